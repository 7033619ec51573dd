// The one step that turns a plan into a Scene: what is kept as it is (the author's shared meshes, animated
// subtrees, cameras and lights), every shared part with its nodes, the tiles stored as they are merged into
// one mesh per material, and the stats counted from the plan.
#include "geometry/bounds.hpp"
#include "plan/planners.hpp"
#include "plan/primitives_by_kind.hpp"
#include "symcompress/detail/compression_plan.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

// What a joined material adds to a glTF file ({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":0.5}}
// and the like), for the join to weigh (joinByBaseColor).
constexpr double kMaterialBytes = 80;

// A root node drawing `mesh`, with the name and extras of the input node `source` stands for (if any).
int addRootNode(Scene& out, int mesh, const Eigen::Matrix4d& transform, const Node* source) {
    Node node;
    if (source) copyNodeNotes(*source, node);
    node.mesh = mesh;
    node.transform = transform;
    out.roots.push_back(int(out.nodes.size()));
    out.nodes.push_back(std::move(node));
    return out.roots.back();
}

// Input nodes by their notes (copyNodeNotes): nodes of the same name, extras and extensions count once, as one node
// of the output can keep them for all.
using NodesByNotes = std::map<std::tuple<std::string, std::string, std::string>, const Node*>;
void addByNotes(NodesByNotes& nodes, const Node& node) {
    nodes.try_emplace({node.name, node.extrasJson, node.extensionsJson}, &node);
}

// The start of a warning about input nodes whose notes are not kept: how many, and one's name.
std::string nodeNotesLost(const NodesByNotes& nodes) {
    const auto named = std::find_if(nodes.begin(), nodes.end(), [](const auto& n) { return !n.second->name.empty(); });
    return std::to_string(nodes.size()) + " node names, extras or extensions" +
           (named != nodes.end() ? " (e.g. '" + named->second->name + "')" : "") + " not kept";
}

// Every node with a camera or a light, outside the animated subtrees (which keep theirs), as a root node at
// its world placement: the tiles are rebuilt elsewhere, the viewpoints and lights stay where they were.
void keepCamerasAndLights(const Scene& input, const SceneAnalysis& analysis, Scene& out, CompressionStats& stats) {
    out.cameras = input.cameras;
    out.lights = input.lights;
    const std::vector<int>& animated = analysis.animatedSubtrees;  // their tops, sorted: a subtree is skipped whole
    std::vector<std::pair<int, Eigen::Matrix4d>> stack;            // node, its parent's world transform
    for (auto root = input.roots.rbegin(); root != input.roots.rend(); ++root)
        stack.push_back({*root, Eigen::Matrix4d::Identity()});
    while (!stack.empty()) {
        const auto [node, parentWorld] = stack.back();
        stack.pop_back();
        const Node& from = input.nodes[std::size_t(node)];
        if (std::binary_search(animated.begin(), animated.end(), node)) continue;
        const Eigen::Matrix4d world = parentWorld * from.transform;
        if (from.camera >= 0 || from.light >= 0) {
            const int kept = addRootNode(out, -1, world, &from);
            out.nodes[std::size_t(kept)].camera = from.camera;
            out.nodes[std::size_t(kept)].light = from.light;
            ++stats.camerasAndLightsKept;
        }
        for (auto child = from.children.rbegin(); child != from.children.rend(); ++child)
            stack.push_back({*child, world});
    }
}

// The input nodes outside the animated subtrees that draw nothing but group others and carry notes (copyNodeNotes):
// the tiles are rebuilt under nodes of their own, so these are not kept.
NodesByNotes flattenedGroupsWithNotes(const Scene& input, const SceneAnalysis& analysis) {
    NodesByNotes out;
    std::vector<int> stack(input.roots.begin(), input.roots.end());
    while (!stack.empty()) {
        const Node& node = input.nodes[std::size_t(stack.back())];
        const bool animated =
            std::binary_search(analysis.animatedSubtrees.begin(), analysis.animatedSubtrees.end(), stack.back());
        stack.pop_back();
        if (animated) continue;
        if (node.mesh < 0 && node.camera < 0 && node.light < 0 && hasNodeNotes(node)) addByNotes(out, node);
        stack.insert(stack.end(), node.children.begin(), node.children.end());
    }
    return out;
}

// What a shared part adds to the stats.
void count(const SharedPart& part, CompressionStats& stats) {
    stats.instances += part.nodes.size();
    stats.maxDeviation = std::max(stats.maxDeviation, part.deviation);
    switch (part.mechanism) {
    case SharedPart::Mechanism::SceneSymmetry: stats.tilesInSceneSymmetry += part.tiles.size(); break;
    case SharedPart::Mechanism::Assembly:
        ++stats.assemblies;
        stats.assemblyCopies += part.copies;
        stats.tilesInAssemblies += part.tiles.size();
        break;
    case SharedPart::Mechanism::Region: ++stats.regionClasses; [[fallthrough]];
    case SharedPart::Mechanism::Class:
        if (part.copies > 1) ++stats.instancedClasses;
        break;
    }
}

// The triangles stored, a mesh of `variants` (another material over a stored geometry, emitScene) counted once
// with its geometry. Those with two corners at one point (zero area) stay: they draw nothing, and viewers count
// them (the glTF writer keeps them at one point, where Draco's edgebreaker would drop them).
void countStoredTriangles(const Scene& out, const std::vector<std::vector<int>>& variants, CompressionStats& stats) {
    std::vector<char> counted(out.meshes.size(), 1);
    for (const std::vector<int>& meshes : variants)
        for (std::size_t i = 1; i < meshes.size(); ++i) counted[std::size_t(meshes[i])] = 0;
    for (std::size_t m = 0; m < out.meshes.size(); ++m)
        if (counted[m])
            for (const Primitive& p : out.meshes[m].primitives) stats.trianglesStored += p.triangles.size();
}

// A mesh far from the origin for its size (georeferenced coordinates; the lantern moved 10 km away) loses in
// float32, in which glTF, Draco and X3D store its corners, more than a small share of the budget: it is
// moved to be about its centre, and the translation back returned for the node drawing it (a JSON number, a
// double). Otherwise the identity, the mesh as it is.
Eigen::Matrix4d centredIfFar(Mesh& mesh, double budget) {
    Eigen::AlignedBox3d box;
    for (const Primitive& primitive : mesh.primitives)
        for (const Eigen::Vector3d& p : primitive.positions) box.extend(p);
    Eigen::Matrix4d back = Eigen::Matrix4d::Identity();
    const Eigen::Vector3d centre = centreIfFloat32RoundsBeyond(box, kFloat32RoundingShare * budget);
    if (centre.isZero(0)) return back;
    for (Primitive& primitive : mesh.primitives)
        for (Eigen::Vector3d& p : primitive.positions) p -= centre;
    back.topRightCorner<3, 1>() = centre;
    return back;
}

// Each stored mesh's share of the error budget (a distance): what the deviation of the copies it draws
// leaves of it (`deviation`, by mesh), less `instanceShare` where several nodes draw it (a GPU batch may round
// their rotations and translations), in the mesh's frame: divided by the largest stretch of a node that draws it, since
// a corner moved by e in the mesh moves by s e in the world. Meshes of one geometry in several materials (`variants`)
// take the least share of any of them: equal, the writer stores their geometry once.
void shareErrorBudget(Scene& out, double budget, double instanceShare, const std::vector<double>& deviation,
                      const std::vector<std::vector<int>>& variants) {
    std::vector<double> stretch(out.meshes.size(), 0);
    std::vector<int> drawers(out.meshes.size(), 0);
    std::vector<std::pair<int, Eigen::Matrix4d>> stack;  // node, its parent's world transform
    for (int root : out.roots) stack.push_back({root, Eigen::Matrix4d::Identity()});
    while (!stack.empty()) {
        const auto [n, parentWorld] = stack.back();
        stack.pop_back();
        const Node& node = out.nodes[std::size_t(n)];
        const Eigen::Matrix4d world = parentWorld * node.transform;
        if (node.mesh >= 0) {
            stretch[std::size_t(node.mesh)] = std::max(stretch[std::size_t(node.mesh)], largestStretch(world));
            ++drawers[std::size_t(node.mesh)];
        }
        for (int child : node.children) stack.push_back({child, world});
    }
    for (std::size_t m = 0; m < out.meshes.size(); ++m) {
        const double share =
            (budget - deviation[m] - (drawers[m] > 1 ? instanceShare : 0)) / std::max(stretch[m], 1e-300);
        for (Primitive& primitive : out.meshes[m].primitives) primitive.maxPositionError = std::max(share, 0.0);
    }
    for (const std::vector<int>& meshes : variants) {
        double least = std::numeric_limits<double>::infinity();
        for (int m : meshes) least = std::min(least, out.meshes[std::size_t(m)].primitives.front().maxPositionError);
        for (int m : meshes)
            for (Primitive& primitive : out.meshes[std::size_t(m)].primitives) primitive.maxPositionError = least;
    }
}

}  // namespace

CompressedScene emitScene(const Scene& input, const SceneAnalysis& analysis, const CompressionPlan& plan,
                          const StorageCostModel& costs) {
    CompressedScene result;
    CompressionStats& stats = result.stats;
    result.digest = analysis.digest;
    stats.trianglesIn = analysis.digest.triangles;
    stats.tiles = analysis.tiles.size();
    stats.secondsTiles = analysis.secondsTiles;
    stats.secondsClasses = analysis.secondsClasses;
    stats.classes = plan.classes;
    stats.symmetricClasses = plan.symmetricClasses;
    stats.groupsSkipped = plan.classes > 0 ? analysis.classification.groupsSkipped : 0;  // a plan with no classes asked none
    stats.attributeMismatches = plan.attributeMismatches;
    stats.notWorthInstancing = plan.notWorthInstancing;
    stats.sceneGroup = plan.sceneGroup;

    Scene& out = result.scene;
    out.textures = input.textures;
    out.materials = input.materials;
    out.materialVariants = input.materialVariants;
    copyFileMetadata(input, out);
    out.x3dEnvironment = input.x3dEnvironment;
    out.warnings = input.warnings;
    std::map<int, int> keptMesh;   // input mesh -> output mesh
    PrimitivesByKind unique;       // what is stored as it is
    // The input nodes with notes (copyNodeNotes) whose parts are merged into `unique`, and those whose tiles nodes
    // without notes draw.
    NodesByNotes merged, dropped;
    for (const KeptInstance& kept : analysis.keptInstances) {
        // Without instancing, a kept mesh the tiles can carry (the author's scaled copies) is stored as it is too.
        const Mesh& source = input.meshes[std::size_t(kept.mesh)];
        if (!plan.shareInputInstances && tilesCanCarry(source, kept.transform.topLeftCorner<3, 3>())) {
            for (const Primitive& primitive : source.primitives)
                unique.add(transformPrimitive(primitive, kept.transform));
            if (kept.source && hasNodeNotes(*kept.source)) addByNotes(merged, *kept.source);
            continue;
        }
        auto [entry, added] = keptMesh.emplace(kept.mesh, int(out.meshes.size()));
        if (added) out.meshes.push_back(input.meshes[std::size_t(kept.mesh)]);
        result.instanceNodes.push_back(addRootNode(out, entry->second, kept.transform, kept.source));
        ++stats.inputInstancesKept;
        ++stats.instances;
    }
    stats.animatedNodesKept += keepAnimatedSubtrees(input, analysis.animatedSubtrees, out, keptMesh);
    keepCamerasAndLights(input, analysis, out, stats);
    std::vector<double> deviation(out.meshes.size(), 0);  // of what each mesh draws, as a distance
    std::vector<std::vector<int>> variantsOf;             // meshes of one geometry in a family's materials
    for (const SharedPart& part : plan.shared) {
        const int mesh = int(out.meshes.size());
        Eigen::Matrix4d frame = Eigen::Matrix4d::Identity();
        if (plan.sharedPartFrames) frame.topLeftCorner<3, 3>() = part.frame;
        out.meshes.push_back(frame.isIdentity() ? part.mesh : meshInFrame(part.mesh, frame));
        if (!frame.isIdentity()) ++stats.nodeFrames, stats.tilesInNodeFrames += part.tiles.size();
        deviation.resize(out.meshes.size(), 0);
        deviation.back() = part.deviation * analysis.diagonal;
        std::map<int, int> inMaterial;  // a family's other materials -> the mesh drawing the geometry in it
        for (const PlacedCopy& node : part.nodes) {
            int drawn = mesh;
            if (node.material && *node.material != part.mesh.primitives.front().material) {
                auto [entry, added] = inMaterial.try_emplace(*node.material, int(out.meshes.size()));
                if (added) {
                    Mesh variant = out.meshes[std::size_t(mesh)];
                    variant.name.clear();  // the first mesh names the part; its name again costs a line each
                    for (Primitive& primitive : variant.primitives) primitive.material = *node.material;
                    out.meshes.push_back(std::move(variant));
                    deviation.push_back(deviation[std::size_t(mesh)]);
                    ++stats.materialVariants;
                }
                drawn = entry->second;
            }
            result.instanceNodes.push_back(addRootNode(out, drawn, node.transform * frame, node.source));
        }
        if (!inMaterial.empty()) {
            std::vector<int> sameGeometry{mesh};
            for (const auto& [material, variant] : inMaterial) sameGeometry.push_back(variant);
            variantsOf.push_back(std::move(sameGeometry));
        }
        if (!part.named)
            for (std::size_t t : part.tiles)
                if (const Node* source = sourceNode(input, analysis, t); source && hasNodeNotes(*source))
                    addByNotes(dropped, *source);
        count(part, stats);
    }
    // The error budget as a distance (with fixed bits, about half a 14-bit step of the diagonal).
    const double budget = analysis.diagonal * (plan.maxError > 0 ? plan.maxError : std::ldexp(1.0, -15));
    // 1: in a group in its node's frame, drawn by a node with that node's name; 2: in a group of several nodes'.
    std::vector<char> framed(analysis.tiles.size(), 0);
    for (const FramedTiles& group : plan.framedTiles)
        for (std::size_t t : group.tiles) framed[t] = group.node >= 0 ? 1 : 2;
    for (const WorldPrimitive& placed : analysis.zeroArea) unique.add(placed.primitive);
    std::vector<std::size_t> uniqueTiles;
    for (std::size_t t : plan.tilesAsTheyAre) {
        if (framed[t] == 1) continue;
        if (const Node* source = sourceNode(input, analysis, t); source && hasNodeNotes(*source))
            addByNotes(merged, *source);
        if (framed[t]) continue;
        unique.add(tilePrimitive(analysis.tiles[t], analysis.soup));
        uniqueTiles.push_back(t);
    }
    // The tiles stored as they are share one mesh per material, drawn by one node (or one per turn of their
    // nodes, below): it takes the name, extras and extensions of the node its tiles came from when that is a single
    // one; otherwise they are lost.
    if (merged.size() > 1)
        out.warnings.push_back(nodeNotesLost(merged) + ": their tiles are stored as they are in one mesh per material");
    if (!unique.empty()) {
        Mesh mesh;
        unique.moveInto(mesh);
        // The name and extras of the input mesh all its tiles came from (triangles of zero area come from any).
        const Mesh* source = analysis.zeroArea.empty() ? commonSourceMesh(input, analysis, uniqueTiles) : nullptr;
        if (source) {
            mesh.name = source->name;
            mesh.extrasJson = source->extrasJson;
        }
        const Eigen::Matrix4d offset = centredIfFar(mesh, budget);
        out.meshes.push_back(std::move(mesh));
        addRootNode(out, int(out.meshes.size()) - 1, offset, merged.size() == 1 ? merged.begin()->second : nullptr);
    }
    for (const FramedTiles& group : plan.framedTiles) {
        const Node* source = group.node >= 0 ? &input.nodes[std::size_t(group.node)] : nullptr;
        Mesh mesh = tilesInFrame(analysis, group.tiles, group.transform);
        if (source && source->mesh >= 0) mesh.name = input.meshes[std::size_t(source->mesh)].name;
        const Eigen::Matrix4d offset = centredIfFar(mesh, budget / largestStretch(group.transform));
        out.meshes.push_back(std::move(mesh));
        addRootNode(out, int(out.meshes.size()) - 1, group.transform * offset, source);
        stats.tilesInNodeFrames += group.tiles.size();
        ++stats.nodeFrames;
    }
    // Each tile drawn alone (a blended primitive, whole) by a mesh and node of its own, in the frame of the input
    // node that drew it: viewers sort it by the centre of its bounds there, as they sorted the input's.
    if (!plan.tilesAlone.empty()) {
        const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
        for (std::size_t t : plan.tilesAlone) {
            const int node = analysis.soup[analysis.tiles[t].sources.front().primitive].node;
            const Node* source = sourceNode(input, analysis, t);
            Eigen::Matrix4d frame = Eigen::Matrix4d::Identity();
            if (source && std::abs(world[std::size_t(node)].topLeftCorner<3, 3>().determinant()) > 0)
                frame = world[std::size_t(node)];
            Mesh mesh = tilesInFrame(analysis, {t}, frame);
            if (source && source->mesh >= 0) mesh.name = input.meshes[std::size_t(source->mesh)].name;
            const Eigen::Matrix4d offset = centredIfFar(mesh, budget / largestStretch(frame));
            out.meshes.push_back(std::move(mesh));
            addRootNode(out, int(out.meshes.size()) - 1, frame * offset, source);
        }
    }
    if (const NodesByNotes groups = flattenedGroupsWithNotes(input, analysis); !groups.empty())
        out.warnings.push_back(nodeNotesLost(groups) + ": they group other nodes, and the output draws the tiles " +
                               "under nodes of their own");
    if (!dropped.empty())
        out.warnings.push_back(nodeNotesLost(dropped) +
                               ": their copies are drawn by instances without names, smaller than storing them as "
                               "they are, which would lose them too");
    deviation.resize(out.meshes.size(), 0);
    if (plan.maxError > 0)
        shareErrorBudget(out, plan.maxError * analysis.diagonal, plan.instanceShare * analysis.diagonal, deviation,
                         variantsOf);
    // After the budget's shares: a joined primitive keeps the least of its members'. (A family's meshes have one
    // primitive each: its geometry stays shared.)
    if (plan.joinByBaseColor) {
        stats.baseColorJoins =
            joinByBaseColor(out, costs.quickMeshBytes ? costs.quickMeshBytes : costs.meshBytes, kMaterialBytes);
        if (const std::vector<std::string>& names = stats.baseColorJoins.namesLost; !names.empty())
            out.warnings.push_back(std::to_string(names.size()) + " material names (e.g. '" + names.front() +
                                   "') not kept: their primitives are drawn as one, each vertex given its base "
                                   "colour (--no-color-join keeps them)");
    }
    countStoredTriangles(out, variantsOf, stats);
    for (const Mesh& mesh : out.meshes)
        for (const Primitive& primitive : mesh.primitives) {
            stats.lineSegmentsKept += primitive.lines.size();
            if (primitive.topology == Topology::Points) stats.pointsKept += primitive.positions.size();
        }
    return result;
}

}  // namespace symcompress
