// Pruning: what nothing draws or reads, removed (docs/optimizations.md).
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <map>
#include <numeric>

namespace symcompress {

namespace {

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

// Normals within this angle of their triangle's (0.8 degrees, a few steps of Draco's 10-bit normals) shade as
// the viewer's own flat normals do.
constexpr double kFlatNormalCosine = 0.9999;
// Triangles whose normal float32 cannot tell within that angle are excused, unless more than this fraction are.
constexpr double kMostExcused = 0.01;

// Whether every corner's normal is its triangle's geometric normal: what a viewer computes where a mesh has
// none (glTF: flat shading; the X3D writer asks for normals per face), so the normals say nothing. Triangles
// too small to have a direction ask nothing, nor do slivers whose normal float32 cannot tell within the angle
// (a bolt's thread 200 units out), unless more than kMostExcused of the triangles are.
bool normalsAreFlat(const Primitive& primitive) {
    const double flatAngle = std::acos(kFlatNormalCosine);
    std::size_t excused = 0;
    for (const Triangle& t : primitive.triangles) {
        const Eigen::Vector3d &a = primitive.positions[t[0]], &b = primitive.positions[t[1]],
                              &c = primitive.positions[t[2]];
        const Eigen::Vector3d cross = (b - a).cross(c - a);
        const double length = cross.norm();
        if (!(length > 1e-12 * std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), 1e-300}))) continue;
        const bool flat = std::all_of(t.begin(), t.end(), [&](std::uint32_t v) {
            return !(primitive.normals[v].dot(cross) < kFlatNormalCosine * length * primitive.normals[v].norm());
        });
        if (flat) continue;
        // How far float32's rounding of the corners (the file's and the viewer's) may turn the cross product.
        const double rounding =
            std::ldexp(std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff()}), -24);
        const double perimeter = (b - a).norm() + (c - b).norm() + (a - c).norm();
        if (!(2 * std::sqrt(3.0) * rounding * perimeter > flatAngle * length)) return false;
        ++excused;
    }
    return double(excused) <= kMostExcused * double(primitive.triangles.size());
}

// Vertices equal in every attribute merged into the first of them (what splitting by face normals had
// kept apart); triangles renumbered.
void mergeEqualVertices(Primitive& primitive) {
    std::map<std::vector<double>, std::uint32_t> first;
    std::vector<std::uint32_t> newIndex(primitive.positions.size());
    std::vector<std::uint32_t> kept;
    for (std::uint32_t v = 0; v < primitive.positions.size(); ++v) {
        std::vector<double> key(primitive.positions[v].data(), primitive.positions[v].data() + 3);
        if (!primitive.texcoords.empty()) key.insert(key.end(), {primitive.texcoords[v].x(), primitive.texcoords[v].y()});
        if (!primitive.colors.empty())
            key.insert(key.end(), primitive.colors[v].data(), primitive.colors[v].data() + 4);
        for (const VertexAttribute& attribute : primitive.attributes)
            key.insert(key.end(), attribute.values.begin() + std::ptrdiff_t(v) * attribute.components,
                       attribute.values.begin() + std::ptrdiff_t(v + 1) * attribute.components);
        const auto [entry, added] = first.emplace(std::move(key), std::uint32_t(kept.size()));
        if (added) kept.push_back(v);
        newIndex[v] = entry->second;
    }
    if (kept.size() == primitive.positions.size()) return;
    keepVertices(primitive, kept);
    for (Triangle& t : primitive.triangles)
        for (std::uint32_t& v : t) v = newIndex[v];
}

}  // namespace

std::size_t dropFlatNormals(Scene& scene) {
    std::size_t dropped = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives) {
            // Morph targets may displace the normals; tangents, and the normal maps that read them, need them.
            const std::vector<const Material*> materials = materialsDrawnWith(scene, primitive.material);
            const bool needsNormals =
                !primitive.targets.empty() ||
                std::any_of(materials.begin(), materials.end(), [](const Material* m) { return readsTangents(*m); }) ||
                std::any_of(primitive.attributes.begin(), primitive.attributes.end(),
                            [](const VertexAttribute& a) { return a.name == "TANGENT"; });
            // Lines and points have no face for a viewer to take a normal from.
            if (primitive.normals.empty() || needsNormals || primitive.topology != Topology::Triangles ||
                !normalsAreFlat(primitive))
                continue;
            primitive.normals.clear();
            primitive.normals.shrink_to_fit();
            mergeEqualVertices(primitive);
            ++dropped;
        }
    return dropped;
}

std::size_t dropUnreadAttributes(Scene& scene) {
    std::size_t dropped = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives) {
            // Read by the material under any of its variants.
            const std::vector<const Material*> materials = materialsDrawnWith(scene, primitive.material);
            // glTF numbers the sets without a gap (TEXCOORD_1 needs TEXCOORD_0): an unread set below one that is
            // read stays.
            int highestRead = -1;
            for (const Material* m : materials)
                for (const TextureRef* use : m->textureRefs())
                    if (use->texture >= 0) highestRead = std::max(highestRead, use->texCoordSet());
            const auto unread = [&](const VertexAttribute& attribute) {
                if (attribute.name == "TANGENT")
                    return std::none_of(materials.begin(), materials.end(),
                                        [](const Material* m) { return readsTangents(*m); });
                return texcoordSet(attribute.name) > highestRead;
            };
            bool any = false;
            if (!primitive.texcoords.empty() && unread({"TEXCOORD_0", 2, {}})) {
                primitive.texcoords.clear();
                primitive.texcoords.shrink_to_fit();
                any = true;
            }
            const auto end = std::remove_if(primitive.attributes.begin(), primitive.attributes.end(), unread);
            any = any || end != primitive.attributes.end();
            primitive.attributes.erase(end, primitive.attributes.end());
            // A morph target displaces only what its primitive has (and what is unread moves nothing seen).
            for (MorphTarget& target : primitive.targets)
                target.erase(std::remove_if(target.begin(), target.end(), unread), target.end());
            dropped += any;
        }
    return dropped;
}

std::pair<std::size_t, std::size_t> pruneUnused(Scene& scene) {
    std::vector<bool> materialUsed(scene.materials.size(), false);
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives)
            for (const Material* material : materialsDrawnWith(scene, primitive.material))
                materialUsed[std::size_t(material - scene.materials.data())] = true;
    const std::size_t materials = removeMaterials(scene, materialUsed);

    std::vector<bool> textureUsed(scene.textures.size(), false);
    for (const Material& material : scene.materials)
        for (const TextureRef* use : material.textureRefs())
            if (use->texture >= 0) textureUsed[std::size_t(use->texture)] = true;
    const std::size_t textures = scene.textures.size();
    renumberTextures(scene, keepUsed(scene.textures, textureUsed));
    return {materials, textures - scene.textures.size()};
}

}  // namespace symcompress
