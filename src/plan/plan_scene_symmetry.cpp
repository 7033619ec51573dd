// The scene's own symmetry: the group G of the whole assembly of tiles (paper 6.3). The tiles of G's free
// orbits (which G moves onto |G| distinct tiles) are stored once, for one fundamental part of the scene, as
// one mesh drawn by a node per element of G: a room of mirrored quadrants costs one quadrant. From each
// orbit the tile nearest a point that no element fixes is taken: the part is the tiles of one Dirichlet
// domain of G, a compact region. Tiles on G's planes and axes are left to the other mechanisms.
#include "plan/planners.hpp"
#include "plan/primitives_by_kind.hpp"
#include "symcompress/assembly.hpp"

#include <algorithm>
#include <set>

namespace symcompress {

FreeOrbits freeOrbits(const PlanContext& context, const SymmetryGroup& group, const std::vector<std::size_t>& tiles) {
    const TileClassification& classification = context.analysis.classification;
    const std::size_t order = group.elements.size(), none = classification.shapes.size();
    const std::vector<std::vector<std::size_t>> images = tileImages(classification, group, tiles);
    const Eigen::Vector3d generic =
        group.centroid + classification.sceneDiagonal * Eigen::Vector3d(0.5377, 0.8314, 0.1403);
    FreeOrbits found;
    std::vector<bool> seen(none, false);
    for (std::size_t t : tiles) {
        if (seen[t]) continue;
        std::set<std::size_t> orbit;
        for (std::size_t e = 0; e < order; ++e) orbit.insert(images[e][t]);
        for (std::size_t u : orbit)
            if (u < none) seen[u] = true;
        if (orbit.size() < order || *orbit.rbegin() >= none) continue;  // on a plane or axis of G
        if (std::any_of(orbit.begin(), orbit.end(), [&](std::size_t u) { return context.analysis.drawnAlone(u); }))
            continue;  // a copy drawn alone
        const std::size_t representative =
            *std::min_element(orbit.begin(), orbit.end(), [&](std::size_t a, std::size_t b) {
                return (classification.shapes[a].moments.centroid - generic).norm() <
                       (classification.shapes[b].moments.centroid - generic).norm();
            });
        bool verified = true;
        double deviation = 0;
        for (std::size_t e = 1; e < order && verified; ++e) {
            double copyDeviation = 0;
            verified =
                context.reproduces(representative, images[e][representative], aboutCentroid(group, e), &copyDeviation);
            deviation = std::max(deviation, copyDeviation);
        }
        if (!verified) continue;
        found.part.push_back(representative);
        found.orbitTiles.insert(found.orbitTiles.end(), orbit.begin(), orbit.end());
        found.deviation = std::max(found.deviation, deviation);
    }
    return found;
}

Isometry aboutCentroid(const SymmetryGroup& group, std::size_t e) {
    Isometry map;
    map.linear = group.elements[e].linear;
    map.translation = group.centroid - map.linear * group.centroid;
    return map;
}

std::vector<PlacedCopy> elementNodes(const SymmetryGroup& group) {
    std::vector<PlacedCopy> nodes;
    for (const Symmetry& element : group.elements) {
        PlacedCopy node;
        node.transform.topLeftCorner<3, 3>() = element.linear;
        node.transform.topRightCorner<3, 1>() = group.centroid;
        nodes.push_back(std::move(node));
    }
    return nodes;
}

Mesh partAbout(const SceneAnalysis& analysis, const std::vector<std::size_t>& part, const Eigen::Vector3d& center) {
    PrimitivesByKind parts;
    for (std::size_t t : part) {
        Primitive local = tilePrimitive(analysis.tiles[t], analysis.soup);
        for (auto& p : local.positions) p -= center;
        parts.add(local);
    }
    Mesh mesh;
    parts.moveInto(mesh);
    return mesh;
}

std::optional<SharedPart> planSceneSymmetry(const PlanContext& context) {
    const SceneAnalysis& analysis = context.analysis;
    const SymmetryGroup group = assemblySymmetries(analysis.classification);
    const std::size_t order = group.elements.size();
    if (order < 2) return std::nullopt;
    std::vector<std::size_t> all(analysis.tiles.size());
    for (std::size_t t = 0; t < all.size(); ++t) all[t] = t;
    FreeOrbits orbits = freeOrbits(context, group, all);
    double apart = 0;
    for (std::size_t t : orbits.part) apart += double(order) * context.costs.apart(t);
    // Once with a node per element, against storing every tile apart; a mesh of its own costs extra only
    // when some tiles are left for another mesh.
    SharedPart shared;
    shared.mechanism = SharedPart::Mechanism::SceneSymmetry;
    shared.nodes = elementNodes(group);
    const double nodes = context.costs.nodes(shared.nodes);
    if (orbits.part.empty() ||
        context.costs.meshOf(orbits.part, orbits.orbitTiles.size() < all.size()) + nodes >= apart)
        return std::nullopt;
    shared.mesh = partAbout(analysis, orbits.part, group.centroid);
    shared.mesh.name = "1/" + std::to_string(order) + " of the scene (" + group.name + ")";
    shared.tiles = std::move(orbits.orbitTiles);
    shared.copies = order;
    shared.group = group.name;
    shared.deviation = orbits.deviation;  // of a copy's vertices from their matches
    return shared;
}

}  // namespace symcompress
