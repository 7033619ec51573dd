// Joining by base colour: primitives of one mesh whose materials differ in nothing a glTF viewer draws but the
// red, green and blue of their base colour drawn as one primitive, under one material of base colour white, each
// vertex carrying its material's colour in COLOR_0, which glTF multiplies into the base colour (docs/optimizations.md).
#include "common/color_space.hpp"
#include "geometry/bounds.hpp"
#include "optimize/first_equivalent.hpp"
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

// How far, in steps of an 8-bit sRGB output, the quantization of a joined colour may move it: half what an 8-bit
// texel's rounding moves it (glTF-Transform's palette), so that an output pixel changes by one level at most, and
// only where the colour lies within a quarter of a step of a rounding boundary. (60 random colours, some dark: 16
// bits at a 32nd of a step, 10776 bytes; 13 bits here, 9888; the palette 9980.)
constexpr double kColorStepShare = 1.0 / 4;
constexpr int kMostColorBits = 16;
// The largest ratio of close-up diagonals within one joined primitive: its largest member takes at most two
// position bits more than it would alone.
constexpr double kSizeRatio = 4;

// The material a joined primitive is drawn with: `material`'s base colour with red, green and blue white (its
// alpha is every member's), without a name (it stands for several) or X3D's Phong fields, which glTF does not write.
Material joinedMaterial(Material material) {
    material.baseColorFactor.head<3>().setOnes();
    material.name.clear();
    material.phong.reset();
    return material;
}

// Whether a primitive may be joined: triangles without morph targets (their targets would have to agree) or a
// grid of its own (a fundamental region's seams), in a material of the scene's.
bool joinable(const Primitive& primitive) {
    return primitive.topology == Topology::Triangles && primitive.targets.empty() && !primitive.positionGrid &&
           primitive.material >= 0;
}

// The fewest COLOR_0 bits, up to kMostColorBits, at which Draco's quantization of `colors` (each component from
// its least value, one step for all: its AttributeQuantizationTransform) moves no red, green or blue, encoded to
// sRGB as the viewer's output is, farther than kColorStepShare of an 8-bit step.
int colorBitsKeeping(const std::vector<Eigen::Vector4d>& colors) {
    std::set<std::array<double, 4>> distinct;
    for (const Eigen::Vector4d& color : colors) distinct.insert({color[0], color[1], color[2], color[3]});
    Eigen::Vector4d least = Eigen::Vector4d::Constant(HUGE_VAL), most = -least;
    for (const auto& color : distinct)
        least = least.cwiseMin(Eigen::Vector4d(color.data())), most = most.cwiseMax(Eigen::Vector4d(color.data()));
    const double range = (most - least).maxCoeff();
    if (!(range > 0)) return 1;
    for (int bits = 1; bits < kMostColorBits; ++bits) {
        const double step = range / double((1 << bits) - 1);
        const bool keeps = std::all_of(distinct.begin(), distinct.end(), [&](const std::array<double, 4>& color) {
            for (int c = 0; c < 3; ++c) {
                const double rounded = least[c] + std::round((color[c] - least[c]) / step) * step;
                if (std::abs(linearToSrgb(rounded) - linearToSrgb(color[c])) * 255 > kColorStepShare) return false;
            }
            return true;
        });
        if (keeps) return bits;
    }
    return kMostColorBits;
}

// The diagonal the writer's close-up bound is a fraction of (WriteOptions::maxRelativePositionError).
double closeUpDiagonalOf(const Primitive& primitive) {
    return primitive.closeUpDiagonal > 0 ? primitive.closeUpDiagonal : boundsOf(primitive.positions).diagonal().norm();
}

// `members` (indices into `primitives`) cut into runs whose close-up diagonals lie within kSizeRatio of the
// run's least, each in the primitives' order. A joined primitive keeps every member's close-up bound, its smallest
// member's: a small part beside large ones would hold them all to its precision (the bound is what keeps the
// parts' edges where they were in a render: 60 cylinders in 60 colours quantized in the joined box rendered 0.7%
// of their pixels otherwise, as the peers' joins do, against 0.05% each in its own box).
std::vector<std::vector<std::size_t>> runsOfSimilarSize(const std::vector<Primitive>& primitives,
                                                        const std::vector<std::size_t>& members) {
    std::vector<std::pair<double, std::size_t>> bySize;
    for (std::size_t p : members) bySize.push_back({closeUpDiagonalOf(primitives[p]), p});
    std::sort(bySize.begin(), bySize.end());
    std::vector<std::vector<std::size_t>> runs;
    double least = 0;
    for (const auto& [diagonal, p] : bySize) {
        if (runs.empty() || diagonal > kSizeRatio * least) runs.emplace_back(), least = diagonal;
        runs.back().push_back(p);
    }
    for (std::vector<std::size_t>& run : runs) std::sort(run.begin(), run.end());
    return runs;
}

// `primitive` with its material's base colour in COLOR_0 (multiplied into the colours it has).
Primitive withBaseColorPerVertex(Primitive primitive, const Material& material) {
    const Eigen::Vector3d base = material.baseColorFactor.head<3>();
    if (primitive.colors.empty()) primitive.colors.assign(primitive.positions.size(), Eigen::Vector4d(1, 1, 1, 1));
    for (Eigen::Vector4d& color : primitive.colors) color.head<3>() = color.head<3>().cwiseProduct(base);
    return primitive;
}

// `members` of `primitives` as one primitive, each vertex given its material's base colour (its material left to the
// caller). Every member's bounds hold: the least error bound, and the close-up bound of the smallest member
// (WriteOptions::maxRelativePositionError), which a run of similar sizes keeps near the others'.
Primitive joinedPrimitive(const std::vector<Primitive>& primitives, const std::vector<std::size_t>& members,
                          const std::vector<Material>& materials) {
    Primitive joined;
    double maxPositionError = HUGE_VAL, closeUpDiagonal = HUGE_VAL;
    for (std::size_t p : members) {
        const Primitive& member = primitives[p];
        if (member.maxPositionError > 0) maxPositionError = std::min(maxPositionError, member.maxPositionError);
        closeUpDiagonal = std::min(closeUpDiagonal, closeUpDiagonalOf(member));
        Primitive colored = withBaseColorPerVertex(member, materials[std::size_t(member.material)]);
        if (joined.positions.empty())
            joined = std::move(colored);
        else
            appendPrimitive(joined, colored);
    }
    joined.colorBits = colorBitsKeeping(joined.colors);
    joined.maxPositionError = std::isfinite(maxPositionError) ? maxPositionError : 0;  // 0: the writer's
    joined.closeUpDiagonal = closeUpDiagonal;
    return joined;
}

}  // namespace

std::vector<int> baseColorJoinGroups(const std::vector<Material>& materials) {
    std::vector<Material> joined;
    for (const Material& material : materials) joined.push_back(joinedMaterial(material));
    // Compared only within the same textures and other factors.
    auto keyOf = [&](std::size_t m) {
        const Material& material = materials[m];
        // Specular-glossiness multiplies COLOR_0 into its own diffuse factor, not the core base colour.
        const bool specularGlossiness =
            std::any_of(material.extensions.begin(), material.extensions.end(),
                        [](const MaterialExtension& e) { return e.name == "KHR_materials_pbrSpecularGlossiness"; });
        using Key = std::tuple<int, int, int, double, double, double, int, bool>;
        // Blended primitives are drawn as objects of their own, which viewers sort (drawnBlended).
        if (!material.variants.empty() || specularGlossiness || material.alphaMode == Material::AlphaMode::Blend)
            return std::optional<Key>();
        return std::optional(Key(material.baseColorTexture.texture, material.metallicRoughnessTexture.texture,
                                 material.normalTexture.texture, material.metallicFactor, material.roughnessFactor,
                                 material.baseColorFactor.w(), int(material.alphaMode), material.doubleSided));
    };
    return firstEquivalent(materials.size(), keyOf,
                           [&](std::size_t earlier, std::size_t m) { return joined[earlier] == joined[m]; });
}

BaseColorJoins joinByBaseColor(Scene& scene, const std::function<double(const Primitive&)>& bytes,
                               double materialBytes) {
    BaseColorJoins joins;
    std::vector<char> usedBefore(scene.materials.size(), 0);
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) usedBefore[std::size_t(primitive.material)] = 1;
    const std::vector<int> group = baseColorJoinGroups(scene.materials);
    std::map<int, int> made;  // a group's joined material, by the group's first material
    for (Mesh& mesh : scene.meshes) {
        // The mesh's joinable primitives by their materials' group and the attributes they carry but colours,
        // which each gets.
        std::map<std::tuple<int, bool, bool, std::string>, std::vector<std::size_t>> byKind;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const Primitive& primitive = mesh.primitives[p];
            // (A material made by an earlier join is not in a group: its primitive is joined already.)
            if (!joinable(primitive) || std::size_t(primitive.material) >= group.size()) continue;
            byKind[{group[std::size_t(primitive.material)], !primitive.normals.empty(), !primitive.texcoords.empty(),
                    attributeSignature(primitive)}]
                .push_back(p);
        }
        // Each joined primitive takes its first member's place (the order a viewer draws them in); the others go.
        std::vector<std::optional<Primitive>> joinedAt(mesh.primitives.size());
        std::vector<char> joinedAway(mesh.primitives.size(), 0);
        for (const auto& [kind, ofKind] : byKind)
            for (const std::vector<std::size_t>& members : runsOfSimilarSize(mesh.primitives, ofKind)) {
                // Primitives of one material would take a colour each for nothing: a join of several materials only.
                const int first = mesh.primitives[members.front()].material;
                if (std::all_of(members.begin(), members.end(),
                                [&](std::size_t p) { return mesh.primitives[p].material == first; }))
                    continue;
                double apart = 0;
                for (std::size_t p : members) apart += bytes(mesh.primitives[p]);
                Primitive joined = joinedPrimitive(mesh.primitives, members, scene.materials);
                const auto madeAlready = made.find(std::get<0>(kind));
                joined.material = madeAlready != made.end() ? madeAlready->second : int(scene.materials.size());
                if (bytes(joined) + (madeAlready != made.end() ? 0 : materialBytes) >= apart) continue;
                if (madeAlready == made.end()) {
                    made[std::get<0>(kind)] = joined.material;
                    scene.materials.push_back(joinedMaterial(scene.materials[std::size_t(std::get<0>(kind))]));
                }
                for (std::size_t p : members) joinedAway[p] = 1;
                joins.primitivesJoined += members.size();
                ++joins.joinedPrimitives;
                joinedAt[members.front()] = std::move(joined);
            }
        std::vector<Primitive> kept;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
            if (joinedAt[p])
                kept.push_back(std::move(*joinedAt[p]));
            else if (!joinedAway[p])
                kept.push_back(std::move(mesh.primitives[p]));
        mesh.primitives = std::move(kept);
    }
    // The materials the joins left unused go; the input's own unused ones stay for pruning to decide.
    std::vector<bool> keep(scene.materials.size(), true);
    for (std::size_t m = 0; m < usedBefore.size(); ++m) keep[m] = !usedBefore[m];
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives)
            for (const Material* material : materialsDrawnWith(scene, primitive.material))
                keep[std::size_t(material - scene.materials.data())] = true;
    for (std::size_t m = 0; m < keep.size(); ++m)
        if (!keep[m] && !scene.materials[m].name.empty()) joins.namesLost.push_back(scene.materials[m].name);
    joins.materialsRemoved = removeMaterials(scene, keep);
    return joins;
}

}  // namespace symcompress
