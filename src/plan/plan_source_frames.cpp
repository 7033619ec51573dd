#include "geometry/bounds.hpp"
#include "plan/planners.hpp"
#include "plan/primitives_by_kind.hpp"
#include "symcompress/scene_ops.hpp"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

// At most about this share of a part's Draco bytes is what its own frame can spare (a UV sphere turned off
// the axes: 1656 -> 1912 bytes in world space, 15%): a group whose estimate is below the node's cost over it
// is not measured.
constexpr double kMostAFrameSpares = 0.3;

// A group is stored in its node's frame only where the quick measure finds that smaller by this share: less
// is within what the writer's trials of Draco settings change, and the job then writes the plan twice to know.
// (Printed coordinates have no trials: any saving counts.)
constexpr double kLeastWorthFraming = 0.01;

// Of a shared mesh's copies turned each their own way, the frames of this many nodes are tried.
constexpr std::size_t kTurnsTried = 3;

// Whether `linear` keeps the axes as axes (a signed permutation with scales): Draco's grid is then the same
// in the world as in the node's frame, up to a scale per axis, and the frame spares nothing. A transform that
// flattens has no frame to go back to: it keeps the world's.
bool keepsAxes(const Eigen::Matrix3d& linear) {
    if (!(std::abs(linear.determinant()) > 1e-12 * std::pow(linear.norm(), 3))) return true;
    for (int column = 0; column < 3; ++column) {
        const Eigen::Vector3d c = linear.col(column).cwiseAbs();
        if ((c.array() > 1e-9 * c.maxCoeff()).count() != 1) return false;
    }
    return true;
}

// The input node all of tile t's triangles come from, or -1.
int onlyNodeOf(const SceneAnalysis& analysis, std::size_t t) {
    const Tile& tile = analysis.tiles[t];
    if (tile.sources.empty()) return -1;
    const int node = analysis.soup[tile.sources.front().primitive].node;
    for (const TriangleSource& source : tile.sources)
        if (analysis.soup[source.primitive].node != node) return -1;
    return node;
}

// The primitive tile t joins when merged (PrimitivesByKind): its material and which attributes it has.
using TileKind = std::tuple<int, bool, bool, bool, std::string>;
TileKind kindOf(const SceneAnalysis& analysis, std::size_t t) {
    const Primitive& from = analysis.soup[analysis.tiles[t].sources.front().primitive].primitive;
    return {analysis.tiles[t].material, !from.normals.empty(), !from.texcoords.empty(), !from.colors.empty(),
            attributeSignature(from)};
}

// The turn that the world transforms of the nodes all of `tiles` come from share, where they share one (scaled
// alike on every axis at most, without a mirror) that turns them off the world's axes: the frame their author
// modelled them in.
std::optional<Eigen::Matrix3d> sharedTurn(const SceneAnalysis& analysis, const std::vector<Eigen::Matrix4d>& world,
                                          const std::vector<std::size_t>& tiles) {
    std::optional<Eigen::Matrix3d> linear;
    for (std::size_t t : tiles) {
        const int node = onlyNodeOf(analysis, t);
        if (node < 0) return std::nullopt;
        const Eigen::Matrix3d l = world[std::size_t(node)].topLeftCorner<3, 3>();
        if (!linear) linear = l;
        if ((l - *linear).norm() > 1e-9 * linear->norm()) return std::nullopt;
    }
    if (!linear || keepsAxes(*linear) || linear->determinant() < 0) return std::nullopt;
    const std::optional<double> scale = uniformScaleOf(*linear);
    if (!scale) return std::nullopt;
    return Eigen::Matrix3d(*linear / *scale);
}

// The turns (scaled alike on every axis at most, without a mirror, off the world's axes) of the nodes the first
// of `tiles` come from, at most `most` distinct ones: copies turned each their own way share none, but the
// stored copy is one of them, and its node's turn is the frame its author modelled it in.
std::vector<Eigen::Matrix3d> turnsOfNodes(const SceneAnalysis& analysis, const std::vector<Eigen::Matrix4d>& world,
                                          const std::vector<std::size_t>& tiles, std::size_t most) {
    std::vector<Eigen::Matrix3d> turns;
    for (std::size_t t : tiles) {
        if (turns.size() == most) break;
        const int node = onlyNodeOf(analysis, t);
        if (node < 0) continue;
        const Eigen::Matrix3d linear = world[std::size_t(node)].topLeftCorner<3, 3>();
        const std::optional<double> scale = uniformScaleOf(linear);
        if (keepsAxes(linear) || linear.determinant() < 0 || !scale) continue;
        const Eigen::Matrix3d turn = linear / *scale;
        if (std::none_of(turns.begin(), turns.end(),
                         [&](const Eigen::Matrix3d& other) { return (other - turn).norm() <= 1e-9; }))
            turns.push_back(turn);
    }
    return turns;
}

// The input node a group keeps, if it came from one.
const Node* sourceOf(const Scene& input, const FramedTiles& group) {
    return group.node >= 0 ? &input.nodes[std::size_t(group.node)] : nullptr;
}

// `mesh` with the error budget of a mesh that one node draws in the frame `frame`, as emitScene gives it.
Mesh drawnOnce(Mesh mesh, double budget, const Eigen::Matrix4d& frame) {
    if (budget > 0)
        for (Primitive& primitive : mesh.primitives) primitive.maxPositionError = budget / largestStretch(frame);
    return mesh;
}

}  // namespace

std::optional<double> uniformScaleOf(const Eigen::Matrix3d& linear) {
    const double squaredScale = (linear.transpose() * linear).trace() / 3;
    if (!(squaredScale > 0) ||
        !((linear.transpose() * linear / squaredScale - Eigen::Matrix3d::Identity()).norm() < 1e-6))
        return std::nullopt;
    return std::sqrt(squaredScale);
}

double largestStretch(const Eigen::Matrix4d& transform) {
    const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
    return std::sqrt(std::max(
        0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(linear.transpose() * linear).eigenvalues().maxCoeff()));
}

Mesh meshInFrame(const Mesh& mesh, const Eigen::Matrix4d& frame) {
    Mesh out = mesh;
    const Eigen::Matrix4d toFrame = frame.inverse();
    for (Primitive& primitive : out.primitives) {
        const double worldDiagonal = boundsOfCorners(primitive.positions, primitive.triangles).diagonal().norm();
        primitive = transformPrimitive(std::move(primitive), toFrame);
        // A box's diagonal depends on its frame: the larger of the two, so that a frame never tightens the bound.
        primitive.closeUpDiagonal =
            std::max(worldDiagonal / largestStretch(frame),
                     boundsOfCorners(primitive.positions, primitive.triangles).diagonal().norm());
    }
    return out;
}

Mesh tilesInFrame(const SceneAnalysis& analysis, const std::vector<std::size_t>& tiles, const Eigen::Matrix4d& frame) {
    PrimitivesByKind parts;
    for (std::size_t t : tiles) parts.add(tilePrimitive(analysis.tiles[t], analysis.soup));
    Mesh mesh;
    parts.moveInto(mesh);
    return frame.isIdentity() ? mesh : meshInFrame(mesh, frame);
}

void planSourceFrames(const Scene& input, const SceneAnalysis& analysis, StorageCosts& costs, CompressionPlan& plan) {
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    // The tiles turned off the axes, grouped by the turn of their nodes (the linear part of their world
    // transforms), in the tiles' order: a group from one node is drawn by a node with its transform and name, one
    // from several (a scene under a turned root) by a node with the turn alone. Where coordinates are printed, the
    // tiles of a node that moves or scales them without turning them too, by node.
    struct Turn {
        Eigen::Matrix3d linear;
        std::set<int> nodes;
        std::vector<std::size_t> tiles;
        int byNode = -1;  // the node of a group of a node that keeps the axes
    };
    std::vector<Turn> turns;
    for (std::size_t t : plan.tilesAsTheyAre) {
        const int node = onlyNodeOf(analysis, t);
        if (node < 0) continue;
        const Eigen::Matrix3d linear = world[std::size_t(node)].topLeftCorner<3, 3>();
        const bool axes = keepsAxes(linear);
        if (axes && (costs.positionsOnGrid() || world[std::size_t(node)].isIdentity(0))) continue;
        const int byNode = axes ? node : -1;
        auto turn = std::find_if(turns.begin(), turns.end(), [&](const Turn& other) {
            return other.byNode == byNode && (other.linear - linear).norm() <= 1e-9 * linear.norm();
        });
        if (turn == turns.end()) turn = turns.insert(turns.end(), Turn{linear, {}, {}, byNode});
        turn->nodes.insert(node);
        turn->tiles.push_back(t);
    }
    std::vector<FramedTiles> candidates;
    for (Turn& turn : turns) {
        FramedTiles group{turn.nodes.size() == 1 ? *turn.nodes.begin() : -1, Eigen::Matrix4d::Identity(),
                          std::move(turn.tiles)};
        if (group.node >= 0)
            group.transform = world[std::size_t(group.node)];
        else
            group.transform.topLeftCorner<3, 3>() = turn.linear;
        if (kMostAFrameSpares * costs.meshOf(group.tiles, false) > costs.node(group.transform, sourceOf(input, group)))
            candidates.push_back(std::move(group));
    }
    // Each group measured both ways as the writer codes it. Merged with the world's parts, it spares the
    // overhead of a primitive of each kind that other tiles stored as they are have too; in its frame, it costs
    // a node.
    std::vector<char> inGroup(analysis.tiles.size(), 0);
    for (const FramedTiles& group : candidates)
        for (std::size_t t : group.tiles) inGroup[t] = 1;
    std::map<TileKind, std::size_t> outside;  // a tile of each kind in no group
    for (std::size_t t : plan.tilesAsTheyAre)
        if (!inGroup[t]) outside.emplace(kindOf(analysis, t), t);
    const double budget = plan.maxError * analysis.diagonal;  // of a mesh one node draws (shareErrorBudget)
    const double leastWorth = costs.positionsOnGrid() ? kLeastWorthFraming : 0;
    std::vector<char> pays(candidates.size(), 0);
    tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
        const FramedTiles& group = candidates[i];
        std::vector<std::size_t> spared;  // a tile of each kind whose primitive merging spares
        for (std::size_t t : group.tiles)
            if (const auto other = outside.find(kindOf(analysis, t)); other != outside.end())
                if (std::find(spared.begin(), spared.end(), other->second) == spared.end())
                    spared.push_back(other->second);
        const double overhead = costs.meshOf(spared, true) - costs.meshOf(spared, false);
        double inWorld = 0, inFrame = 0;
        const Eigen::Matrix4d identity = Eigen::Matrix4d::Identity();
        tbb::parallel_invoke(
            [&] {
                inWorld =
                    costs.meshBytesQuickly(drawnOnce(tilesInFrame(analysis, group.tiles, identity), budget, identity));
            },
            [&] {
                inFrame = costs.meshBytesQuickly(
                    drawnOnce(tilesInFrame(analysis, group.tiles, group.transform), budget, group.transform));
            });
        pays[i] =
            inFrame + costs.node(group.transform, sourceOf(input, group)) < (1 - leastWorth) * (inWorld - overhead);
    });
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (pays[i]) plan.framedTiles.push_back(std::move(candidates[i]));

    // A shared mesh (not a fundamental region, whose grid keeps its seams closed) likewise: turned into the
    // frame its tiles' nodes share, or else into the frame of one of their nodes (its own where the stored copy
    // came from it: 50 wingnuts each turned by its node, stored in the world's turn of one, took 15 bits where
    // its own frame takes 14), and each node drawing it turned back after its transform.
    tbb::parallel_for(std::size_t(0), plan.shared.size(), [&](std::size_t i) {
        SharedPart& part = plan.shared[i];
        if (part.mechanism == SharedPart::Mechanism::Region ||
            std::any_of(part.mesh.primitives.begin(), part.mesh.primitives.end(),
                        [](const Primitive& p) { return p.positionGrid.has_value(); }))
            return;
        const std::optional<Eigen::Matrix3d> shared = sharedTurn(analysis, world, part.tiles);
        const std::vector<Eigen::Matrix3d> frames =
            shared ? std::vector<Eigen::Matrix3d>{*shared} : turnsOfNodes(analysis, world, part.tiles, kTurnsTried);
        // The nodes' turns print about as long either way (and their batches' streams code alike): only the
        // mesh is measured, and the job's world_frame plan measures the whole file.
        double least = frames.empty() ? 0 : (1 - kLeastWorthFraming) * costs.meshBytesQuickly(part.mesh);
        for (const Eigen::Matrix3d& frame : frames) {
            Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
            turn.topLeftCorner<3, 3>() = frame;
            if (const double bytes = costs.meshBytesQuickly(meshInFrame(part.mesh, turn)); bytes < least) {
                least = bytes;
                part.frame = frame;
            }
        }
    });
}

}  // namespace symcompress
