// The planners, one per mechanism: each returns its decisions as data (SharedPart: which tiles, which
// stored mesh, which placements, the deviation), in the order planCompression runs them.
#pragma once

#include "plan/storage_costs.hpp"
#include "symcompress/detail/compression_plan.hpp"

#include <optional>
#include <string>
#include <vector>

namespace symcompress {

// The input node that draws tile t (nullptr when it has none): instance nodes keep its name and extras.
const Node* sourceNode(const Scene& input, const SceneAnalysis& analysis, std::size_t t);

// The input mesh all the tiles came from, if one, with a name or extras: the mesh storing them keeps those.
const Mesh* commonSourceMesh(const Scene& input, const SceneAnalysis& analysis, const std::vector<std::size_t>& tiles);

// What every planner reads.
struct PlanContext {
    const Scene& input;
    const SceneAnalysis& analysis;
    const PlanOptions& options;
    StorageCosts& costs;
    double tolerance() const { return analysis.absoluteTolerance; }
    const Node* sourceOf(std::size_t t) const { return sourceNode(input, analysis, t); }
    // Whether tile `from` placed by `map` reproduces tile `to` (the member check, as the options ask); with
    // `deviation`, the largest distance of a vertex from its match, relative to the diagonal.
    bool reproduces(std::size_t from, std::size_t to, const Isometry& map, double* deviation = nullptr) const;
};

// The scene's own symmetry (paper 6.3): one part of the scene stored once, drawn by a node per element of
// the scene's group, where that costs less than storing its copies apart.
std::optional<SharedPart> planSceneSymmetry(const PlanContext& context);

// The free orbits of an assembly's group (assemblySymmetries) among its tiles: those the group moves onto |G|
// distinct tiles, each verified (every element's copy of its representative reproduces the tile it lands on).
// The representatives, the tiles nearest a point no element fixes, are one Dirichlet domain of G: a compact
// part. Tiles on G's planes and axes are in no free orbit.
struct FreeOrbits {
    std::vector<std::size_t> part;        // a representative of each orbit
    std::vector<std::size_t> orbitTiles;  // every tile of those orbits
    double deviation = 0;                 // of the verified copies' vertices, relative to the diagonal
};
FreeOrbits freeOrbits(const PlanContext& context, const SymmetryGroup& group, const std::vector<std::size_t>& tiles);
// Element e of the group, about the group's centroid.
Isometry aboutCentroid(const SymmetryGroup& group, std::size_t e);
// A node per element of the group, each drawing a mesh stored about the group's centroid.
std::vector<PlacedCopy> elementNodes(const SymmetryGroup& group);
// The tiles merged into one mesh (a primitive per material and attributes), about `center`.
Mesh partAbout(const SceneAnalysis& analysis, const std::vector<std::size_t>& part, const Eigen::Vector3d& center);

// The repeated assemblies worth storing once, none with a tile already `drawn`; marks the tiles they draw.
std::vector<SharedPart> planAssemblies(const PlanContext& context, std::vector<bool>& drawn);

// Every class: the members the prototype reproduces drawn from one mesh (the tile, or its fundamental
// region) where that pays, the rest stored as they are (CompressionPlan::tilesAsTheyAre). Tiles already
// `drawn` are left out.
CompressionPlan planClasses(const PlanContext& context, const std::vector<bool>& drawn);

// The tiles stored as they are that are worth storing in the frame of the input node that drew them (a node
// that turns them off the world's axes; FramedTiles), measured both ways by the writer: plan.framedTiles; and
// the shared meshes worth writing in the frame their tiles' nodes share (SharedPart::frame).
void planSourceFrames(const Scene& input, const SceneAnalysis& analysis, StorageCosts& costs, CompressionPlan& plan);

// The scale of `linear` where it scales alike on every axis (L^T L = s^2 I within 1e-6): a rotation or a
// mirror times s. Nothing otherwise.
std::optional<double> uniformScaleOf(const Eigen::Matrix3d& linear);

// The largest factor by which `transform` stretches a length (its linear part's largest singular value).
double largestStretch(const Eigen::Matrix4d& transform);

// `mesh` (in the world's frame) written in the frame whose world transform is `frame`, each primitive's close-up
// bound (Primitive::closeUpDiagonal) no tighter than its world box's.
Mesh meshInFrame(const Mesh& mesh, const Eigen::Matrix4d& frame);

// The tiles merged into one mesh (a primitive per material and attributes) in the frame whose world transform
// is `frame`.
Mesh tilesInFrame(const SceneAnalysis& analysis, const std::vector<std::size_t>& tiles, const Eigen::Matrix4d& frame);

// The translation taking a mesh stored about `center` to where it was.
Eigen::Matrix4d translationTo(const Eigen::Vector3d& center);

}  // namespace symcompress
