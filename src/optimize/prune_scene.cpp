// Pruning: what nothing draws or reads, removed (docs/optimizations.md).
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <numeric>

namespace symcompress {

namespace {

// Whether a texture of the material reads TEXCOORD_<set>.
bool readsTexcoords(const Material& material, int set) {
    for (const TextureRef* use : material.textureRefs())
        if (use->texture >= 0 && use->texCoordSet() == set) return true;
    return false;
}

// Whether the material's shading reads tangents: a normal map (core or clear-coat's) or anisotropy.
bool readsTangents(const Material& material) {
    if (material.normalTexture.texture >= 0) return true;
    for (const MaterialExtension& extension : material.extensions) {
        if (extension.name == "KHR_materials_anisotropy") return true;
        for (const auto& [key, use] : extension.textures)
            if (use.texture >= 0 && key.find("ormalTexture") != std::string::npos) return true;
    }
    return false;
}

// The set a TEXCOORD_n attribute holds, or -1 for another attribute.
int texcoordSet(const std::string& name) {
    const std::string prefix = "TEXCOORD_", digits = name.substr(std::min(name.size(), prefix.size()));
    if (name.rfind(prefix, 0) != 0 || digits.empty() || digits.size() > 5 ||
        digits.find_first_not_of("0123456789") != std::string::npos)
        return -1;
    return std::stoi(digits);
}

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

std::size_t dropUnreadAttributes(Scene& scene) {
    std::size_t dropped = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives) {
            if (!primitive.targets.empty()) continue;
            const Material* material =
                primitive.material >= 0 ? &scene.materials[std::size_t(primitive.material)] : nullptr;
            bool any = false;
            if (!primitive.texcoords.empty() && !(material && readsTexcoords(*material, 0))) {
                primitive.texcoords.clear();
                primitive.texcoords.shrink_to_fit();
                any = true;
            }
            const auto unread = [&](const VertexAttribute& attribute) {
                if (attribute.name == "TANGENT") return !(material && readsTangents(*material));
                const int set = texcoordSet(attribute.name);
                return set >= 0 && !(material && readsTexcoords(*material, set));
            };
            const auto end = std::remove_if(primitive.attributes.begin(), primitive.attributes.end(), unread);
            any = any || end != primitive.attributes.end();
            primitive.attributes.erase(end, primitive.attributes.end());
            dropped += any;
        }
    return dropped;
}

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
