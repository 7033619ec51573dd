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

std::optional<SharedPart> planSceneSymmetry(const PlanContext& context) {
    const SceneAnalysis& analysis = context.analysis;
    const std::vector<Tile>& tiles = analysis.tiles;
    const TileClassification& classification = analysis.classification;
    const SymmetryGroup group = assemblySymmetries(classification);
    const std::size_t order = group.elements.size();
    if (order < 2) return std::nullopt;
    const std::vector<std::vector<std::size_t>> images = tileImages(classification, group);
    const Eigen::Vector3d center = group.centroid;
    auto about = [&](std::size_t e) {
        Isometry map;
        map.linear = group.elements[e].linear;
        map.translation = center - map.linear * center;
        return map;
    };
    const Eigen::Vector3d generic = center + classification.sceneDiagonal * Eigen::Vector3d(0.5377, 0.8314, 0.1403);

    std::vector<bool> seen(tiles.size(), false);
    std::vector<std::size_t> part, orbitTiles;
    double apart = 0, deviation = 0;  // deviation: of the verified copies, relative to the diagonal
    for (std::size_t t = 0; t < tiles.size(); ++t) {
        if (seen[t]) continue;
        std::set<std::size_t> orbit;
        for (std::size_t e = 0; e < order; ++e) orbit.insert(images[e][t]);
        for (std::size_t u : orbit)
            if (u < tiles.size()) seen[u] = true;
        if (orbit.size() < order || *orbit.rbegin() >= tiles.size()) continue;  // on a plane or axis of G
        const std::size_t representative =
            *std::min_element(orbit.begin(), orbit.end(), [&](std::size_t a, std::size_t b) {
                return (classification.shapes[a].moments.centroid - generic).norm() <
                       (classification.shapes[b].moments.centroid - generic).norm();
            });
        bool verified = true;
        for (std::size_t e = 1; e < order && verified; ++e) {
            double copyDeviation = 0;
            verified = context.reproduces(representative, images[e][representative], about(e), &copyDeviation);
            deviation = std::max(deviation, copyDeviation);
        }
        if (!verified) continue;
        part.push_back(representative);
        orbitTiles.insert(orbitTiles.end(), orbit.begin(), orbit.end());
        apart += double(order) * context.costs.apart(representative);
    }
    // Once with a node per element, against storing every tile apart; a mesh of its own costs extra only
    // when some tiles are left for another mesh.
    SharedPart shared;
    shared.mechanism = SharedPart::Mechanism::SceneSymmetry;
    for (std::size_t e = 0; e < order; ++e) {
        PlacedCopy node;
        node.transform.topLeftCorner<3, 3>() = group.elements[e].linear;
        node.transform.topRightCorner<3, 1>() = center;
        shared.nodes.push_back(std::move(node));
    }
    const double nodes = context.costs.nodes(shared.nodes);
    if (part.empty() || context.costs.meshOf(part, orbitTiles.size() < tiles.size()) + nodes >= apart)
        return std::nullopt;
    PrimitivesByKind parts;
    for (std::size_t t : part) {
        Primitive local = tilePrimitive(tiles[t], analysis.soup);
        for (auto& p : local.positions) p -= center;
        parts.add(local);
    }
    shared.mesh.name = "1/" + std::to_string(order) + " of the scene (" + group.name + ")";
    parts.moveInto(shared.mesh);
    shared.tiles = std::move(orbitTiles);
    shared.copies = order;
    shared.group = group.name;
    shared.deviation = deviation;  // of a copy's vertices from their matches
    return shared;
}

}  // namespace symcompress
