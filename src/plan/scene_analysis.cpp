// The analysis every plan is made from: the input flattened into world primitives, what is kept as it is
// (animated subtrees, the author's scaled instances) set aside, the rest split into tiles and classified.
#include "symcompress/detail/compression_plan.hpp"

#include "common/with_threads.hpp"
#include "geometry/bounds.hpp"
#include "plan/planners.hpp"
#include "plan/storage_costs.hpp"

#include <tbb/task_group.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <set>

namespace symcompress {
namespace {

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Meshes that tiles do not carry where their nodes draw them (tilesCanCarry), kept as they are there, and left
// out of the soup.
void setAsideMeshesTilesCannotCarry(const Scene& input, SceneAnalysis& analysis) {
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    std::set<std::pair<int, int>> kept;  // mesh, node
    for (const WorldPrimitive& placed : analysis.soup)
        if (placed.mesh >= 0 &&
            !tilesCanCarry(input.meshes[std::size_t(placed.mesh)],
                           world[std::size_t(placed.node)].topLeftCorner<3, 3>()) &&
            kept.insert({placed.mesh, placed.node}).second)
            analysis.keptInstances.push_back(
                {placed.mesh, world[std::size_t(placed.node)], &input.nodes[std::size_t(placed.node)]});
    analysis.soup.erase(std::remove_if(analysis.soup.begin(), analysis.soup.end(),
                                       [&](const WorldPrimitive& placed) {
                                           return kept.count({placed.mesh, placed.node}) > 0;
                                       }),
                        analysis.soup.end());
}

// Whether `nodes` (those that draw one mesh) are two or more, one of them scaling or shearing it.
bool scaledInstances(const std::set<int>& nodes, const std::vector<Eigen::Matrix4d>& world) {
    auto rigid = [&](int node) {
        const Eigen::Matrix3d linear = world[std::size_t(node)].topLeftCorner<3, 3>();
        return (linear.transpose() * linear - Eigen::Matrix3d::Identity()).norm() < 1e-6;
    };
    return nodes.size() > 1 && !std::all_of(nodes.begin(), nodes.end(), rigid);
}

// A mesh drawn by two or more nodes, one of them scaling or shearing it, is the author's instancing of
// copies that are not congruent: kept as it is, and left out of the soup. (Rigid copies are left to the
// classes, which may also find more of them baked elsewhere.)
void setAsideScaledInstances(const Scene& input, SceneAnalysis& analysis) {
    std::map<int, std::set<int>> nodesOfMesh;
    for (const WorldPrimitive& placed : analysis.soup) nodesOfMesh[placed.mesh].insert(placed.node);
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    std::set<int> kept;
    for (const auto& [mesh, nodes] : nodesOfMesh)
        if (mesh >= 0 && scaledInstances(nodes, world)) {
            kept.insert(mesh);
            for (int node : nodes)
                analysis.keptInstances.push_back({mesh, world[std::size_t(node)], &input.nodes[std::size_t(node)]});
        }
    analysis.soup.erase(std::remove_if(analysis.soup.begin(), analysis.soup.end(),
                                       [&](const WorldPrimitive& placed) { return kept.count(placed.mesh) > 0; }),
                        analysis.soup.end());
}

// The diagonal of the tiles' bounding box, as the classification measures it.
double tilesDiagonal(const std::vector<Tile>& tiles) {
    Eigen::AlignedBox3d box;
    for (const Tile& tile : tiles) box.extend(boundsOf(tile.mesh.positions));
    return box.isEmpty() ? 0 : box.diagonal().norm();
}

// The analysis of `soup` (the flattened `input`).
SceneAnalysis analyzeSoup(const Scene& input, std::vector<WorldPrimitive> soup, const AnalysisOptions& options,
                          std::chrono::steady_clock::time_point start) {
    SceneAnalysis analysis;
    analysis.options = options;
    analysis.soup = std::move(soup);
    // The whole drawing, before anything is set aside (what digestOf(worldMesh(input)) measures, without
    // flattening the scene a second time).
    analysis.digest = digestOf(analysis.soup, options.tolerance);
    const std::vector<bool> animated = markAnimatedSubtrees(input, analysis.animatedSubtrees);
    analysis.soup.erase(
        std::remove_if(analysis.soup.begin(), analysis.soup.end(),
                       [&](const WorldPrimitive& placed) { return animated[std::size_t(placed.node)]; }),
        analysis.soup.end());
    setAsideMeshesTilesCannotCarry(input, analysis);
    if (options.keepInputInstances) setAsideScaledInstances(input, analysis);
    // Triangles of zero area belong to no tile (splitIntoTiles): a region keeps one triangle of each orbit, and
    // one fixed by a turn (at a lathe's pole) would deny it. They draw nothing but viewers count them: each
    // primitive's are stored as they are, at one of its points, without a material or attributes, which shade
    // nothing of them (all in one primitive, some 250 bytes of glTF: the spider's in two materials took 472).
    for (const WorldPrimitive& placed : analysis.soup)
        if (const std::optional<ZeroAreaTriangles> zeroArea = zeroAreaTrianglesOf(placed.primitive)) {
            Primitive atOnePoint;
            atOnePoint.positions = {placed.primitive.positions[zeroArea->vertex]};
            atOnePoint.triangles.assign(zeroArea->count, Triangle{0, 0, 0});
            analysis.zeroArea.push_back({std::move(atOnePoint), placed.node, placed.mesh});
        }
    std::size_t triangles = 0;
    for (const WorldPrimitive& placed : analysis.soup) triangles += placed.primitive.triangles.size();
    if (options.progress) options.progress("splitting into tiles", triangles, "triangles");
    for (std::size_t m = 0; m < input.materials.size(); ++m)
        analysis.blendedMaterials.push_back(drawnBlended(input, int(m)));
    TileOptions tileOptions;
    tileOptions.wholePrimitiveMaterials = analysis.blendedMaterials;
    analysis.tiles = splitIntoTiles(analysis.soup, tileOptions);
    analysis.secondsTiles = since(start);
    start = std::chrono::steady_clock::now();
    if (options.classify) {
        if (options.progress) options.progress("classifying", analysis.tiles.size(), "tiles");
        CongruenceOptions congruenceOptions;
        congruenceOptions.tolerance = options.tolerance;
        congruenceOptions.threads = options.threads;
        congruenceOptions.elementDeviations = options.elementDeviations;
        std::optional<StorageCosts> costs;
        if (options.groupCosts) {
            costs.emplace(analysis, *options.groupCosts);
            congruenceOptions.groupUsable = [&](std::size_t tile) { return costs->regionMayPay(tile); };
        }
        analysis.classification = withThreads(options.threads, [&] {
            // The kinds' measures that regionMayPay asks for (the writer on a sample), beside the classification.
            tbb::task_group measuring;
            if (costs) measuring.run([&] { costs->measureKinds(); });
            try {
                TileClassification classification = classifyTiles(analysis.tiles, congruenceOptions);
                measuring.wait();
                return classification;
            } catch (...) {
                measuring.wait();
                throw;
            }
        });
        analysis.absoluteTolerance = analysis.classification.absoluteTolerance;
    } else {
        analysis.absoluteTolerance = options.tolerance * tilesDiagonal(analysis.tiles);
    }
    analysis.diagonal = options.tolerance > 0 ? analysis.absoluteTolerance / options.tolerance : 0;
    // No tiles (every mesh animated or set aside): the whole drawing's diagonal, as the digest (and symdecompress's
    // check) measures it, so that the kept meshes are still written within the budget instead of to every digit.
    if (!(analysis.diagonal > 0) && !analysis.digest.bounds.isEmpty())
        analysis.diagonal = analysis.digest.bounds.diagonal().norm();
    analysis.secondsClasses = since(start);
    return analysis;
}

// The meshes whose every drawing stays in the soup: carried by tiles, drawn by no animated node, not the author's
// instancing of scaled copies (the set-asides below). The job needs their geometry only through the soup.
std::vector<char> meshesOnlyTilesDraw(const Scene& input, const AnalysisOptions& options) {
    std::vector<int> tops;
    const std::vector<bool> animated = markAnimatedSubtrees(input, tops);
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    std::vector<std::set<int>> nodesOfMesh(input.meshes.size());
    std::vector<char> only(input.meshes.size(), 1);
    for (std::size_t n = 0; n < input.nodes.size(); ++n)
        if (const int mesh = input.nodes[n].mesh; mesh >= 0) {
            nodesOfMesh[std::size_t(mesh)].insert(int(n));
            if (animated[n] || !tilesCanCarry(input.meshes[std::size_t(mesh)], world[n].topLeftCorner<3, 3>()))
                only[std::size_t(mesh)] = 0;
        }
    for (std::size_t m = 0; m < input.meshes.size(); ++m)
        if (options.keepInputInstances && scaledInstances(nodesOfMesh[m], world)) only[m] = 0;
    return only;
}

}  // namespace

bool tilesCanCarry(const Mesh& mesh, const Eigen::Matrix3d& placement) {
    // A tangent baked under a placement that scales unevenly is turned by it, as glTF viewers turn it, but X3D
    // browsers turn tangents by the normal matrix (X_ITE does), and the two differ in direction.
    const bool even = uniformScaleOf(placement).has_value();
    auto carried = [&](const VertexAttribute& a) {
        return !a.isJoints() && a.name.rfind("WEIGHTS_", 0) != 0 && (even || a.name != "TANGENT");
    };
    return std::all_of(mesh.primitives.begin(), mesh.primitives.end(), [&](const Primitive& p) {
        return p.topology == Topology::Triangles && p.targets.empty() && !p.x3dSource &&
               std::all_of(p.attributes.begin(), p.attributes.end(), carried);
    });
}

SceneAnalysis analyzeScene(const Scene& input, const AnalysisOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    return analyzeSoup(input, flattenScene(input), options, start);
}

SceneAnalysis analyzeSceneTakingGeometry(Scene& input, const AnalysisOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<WorldPrimitive> soup = flattenSceneTaking(input, meshesOnlyTilesDraw(input, options));
    return analyzeSoup(input, std::move(soup), options, start);
}

}  // namespace symcompress
