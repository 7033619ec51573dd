// Pruning: what nothing draws or reads, removed (docs/optimizations.md).
#include "symcompress/optimize.hpp"

#include <numeric>

namespace symcompress {

std::size_t dropUnreadTexcoords(Scene& scene) {
    // Only the base colour texture is carried through: nothing else reads TEXCOORD_0.
    auto readsTexcoords = [&scene](int material) {
        return material >= 0 && scene.materials[material].baseColorTexture >= 0;
    };
    std::size_t dropped = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives)
            if (!primitive.texcoords.empty() && !readsTexcoords(primitive.material)) {
                primitive.texcoords.clear();
                primitive.texcoords.shrink_to_fit();
                ++dropped;
            }
    return dropped;
}

namespace {

// Keeps the items marked used, in order; returns each old index's new one (-1 for a removed item).
template <typename Item>
std::vector<int> keepUsed(std::vector<Item>& items, const std::vector<bool>& used) {
    std::vector<int> newIndex(items.size(), -1);
    std::vector<Item> kept;
    for (std::size_t i = 0; i < items.size(); ++i)
        if (used[i]) {
            newIndex[i] = int(kept.size());
            kept.push_back(std::move(items[i]));
        }
    items = std::move(kept);
    return newIndex;
}

}  // namespace

std::pair<std::size_t, std::size_t> pruneUnused(Scene& scene) {
    std::vector<bool> materialUsed(scene.materials.size(), false);
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) materialUsed[std::size_t(primitive.material)] = true;
    const std::size_t materials = scene.materials.size();
    const std::vector<int> newMaterial = keepUsed(scene.materials, materialUsed);
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) primitive.material = newMaterial[std::size_t(primitive.material)];

    std::vector<bool> textureUsed(scene.textures.size(), false);
    for (const Material& material : scene.materials)
        if (material.baseColorTexture >= 0) textureUsed[std::size_t(material.baseColorTexture)] = true;
    const std::size_t textures = scene.textures.size();
    const std::vector<int> newTexture = keepUsed(scene.textures, textureUsed);
    for (Material& material : scene.materials)
        if (material.baseColorTexture >= 0)
            material.baseColorTexture = newTexture[std::size_t(material.baseColorTexture)];
    return {materials - scene.materials.size(), textures - scene.textures.size()};
}

}  // namespace symcompress
