// Pruning: what nothing draws or reads, removed (docs/optimizations.md).
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <numeric>

namespace symcompress {

std::size_t dropUnreadTexcoords(Scene& scene) {
    // Only TEXCOORD_0 is carried through, and every texture the reader keeps reads it.
    auto readsTexcoords = [&scene](int material) {
        if (material < 0) return false;
        for (const TextureRef* use : scene.materials[std::size_t(material)].textureRefs())
            if (use->texture >= 0) return true;
        return false;
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
        for (const TextureRef* use : material.textureRefs())
            if (use->texture >= 0) textureUsed[std::size_t(use->texture)] = true;
    const std::size_t textures = scene.textures.size();
    renumberTextures(scene, keepUsed(scene.textures, textureUsed));
    return {materials - scene.materials.size(), textures - scene.textures.size()};
}

}  // namespace symcompress
