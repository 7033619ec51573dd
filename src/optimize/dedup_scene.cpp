// Deduplication: materials and textures equal by content stored once (docs/optimizations.md).
#include "optimize/first_equivalent.hpp"
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <optional>
#include <tuple>

namespace symcompress {
namespace {

// For each material, the first one equal to it but for its name (itself when none is earlier). Compared only
// within a texture and base colour, so a scene of thousands of distinct materials costs a sort, not all pairs.
std::vector<int> firstEqualMaterial(const std::vector<Material>& materials) {
    return firstEquivalent(
        materials.size(),
        [&](std::size_t i) {
            const Material& m = materials[i];
            return std::optional(std::tuple(m.baseColorTexture.texture, m.baseColorFactor.x(), m.baseColorFactor.y(),
                                            m.baseColorFactor.z(), m.baseColorFactor.w()));
        },
        [&](std::size_t earlier, std::size_t i) { return materials[earlier].sameButName(materials[i]); });
}

}  // namespace

std::pair<std::size_t, std::size_t> mergeDuplicateMaterialsAndTextures(Scene& scene) {
    std::size_t texturesMerged = 0, materialsMerged = 0;
    // Textures of the same image (bytes and type, or the same URL where the image could not be read) and the
    // same sampler.
    const std::vector<int> sameImage = firstTextureOfSameImage(scene.textures);
    std::vector<int> sameTexture(scene.textures.size());
    for (std::size_t t = 0; t < sameTexture.size(); ++t) {
        sameTexture[t] = int(t);
        for (std::size_t u = 0; u < t; ++u)
            if (sameImage[u] == sameImage[t] && scene.textures[u].sampler == scene.textures[t].sampler) {
                sameTexture[t] = int(u);
                break;
            }
        texturesMerged += sameTexture[t] != int(t);
    }
    renumberTextures(scene, sameTexture);
    const std::vector<int> sameMaterial = firstEqualMaterial(scene.materials);
    for (std::size_t m = 0; m < sameMaterial.size(); ++m) materialsMerged += sameMaterial[m] != int(m);
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) primitive.material = sameMaterial[std::size_t(primitive.material)];
    renumberVariantMaterials(scene, sameMaterial);
    return {materialsMerged, texturesMerged};
}

OptimizeReport optimizeScene(Scene& scene, const OptimizeOptions& options) {
    OptimizeReport report;
    if (options.dedup)
        std::tie(report.materialsMerged, report.texturesMerged) = mergeDuplicateMaterialsAndTextures(scene);
    if (options.pruneAttributes) report.unreadAttributesDropped = dropUnreadAttributes(scene);
    if (options.dropFlatNormals) report.flatNormalsDropped = dropFlatNormals(scene);
    // Merged materials and textures are left unused, for pruning to remove (with --no-prune they stay).
    if (options.prune) {
        std::tie(report.materialsRemoved, report.texturesRemoved) = pruneUnused(scene);
        report.stillChannelsRemoved = removeStillChannels(scene);
    }
    return report;
}

std::vector<std::string> OptimizeReport::lines() const {
    std::vector<std::string> out;
    auto say = [&](std::size_t count, const std::string& what) {
        if (count) out.push_back(std::to_string(count) + " " + what);
    };
    say(materialsMerged, "materials equal to another but for their names merged into it (--no-dedup keeps them)");
    say(texturesMerged, "textures showing the same image as another merged into it (--no-dedup keeps them)");
    say(unreadAttributesDropped,
        "primitives' texture coordinates or tangents dropped: no material reads them (--keep-unused-attributes "
        "keeps them)");
    say(flatNormalsDropped,
        "primitives' normals dropped: each was its triangle's own, as the viewer shades without them "
        "(--keep-flat-normals keeps them)");
    say(materialsRemoved, "materials that no primitive uses (merged ones included) removed (--no-prune keeps them)");
    say(texturesRemoved, "textures that no material uses (merged ones included) removed (--no-prune keeps them)");
    say(stillChannelsRemoved, "animation channels that hold their node where it rests removed (--no-prune keeps them)");
    say(animationKeysDropped,
        "animation keys dropped: interpolation gives them back within the budget (--keep-animation-keys keeps them)");
    say(animationChannelsRemoved,
        "animation channels removed: their node stays within the budget of where it rests without them "
        "(--keep-animation-keys keeps them)");
    if (primitivesJoinedByColor)
        out.push_back(std::to_string(primitivesJoinedByColor) +
                      " primitives in materials that differ only in base colour drawn as " +
                      std::to_string(joinedPrimitives) + ", the colour per vertex (--no-color-join keeps them apart)");
    return out;
}

}  // namespace symcompress
