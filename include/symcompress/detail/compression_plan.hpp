// The stages of compression, for tests and benchmarks that look inside the job compressFile runs
// (docs/ARCHITECTURE.md): the analysis (tiles and classes, once), the plan (decisions as data: which tiles
// each stored mesh draws, and where), and the scene a plan draws.
#pragma once

#include "symcompress/compress.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/scene.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/tiles.hpp"
#include "symcompress/verify.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace symcompress {

// What storing parts costs in the output, in bytes: measured by the writer where it gives a measure
// (meshBytes, nodeBytes), else the constants (a rough Draco glTF of bare positions).
struct StorageCostModel {
    double bytesPerTriangle = 1.5;
    double bytesPerInstance = 120;
    double bytesPerMesh = 500;
    // What a part costs as a mesh of its own, as written: it takes the place of bytesPerTriangle and
    // bytesPerMesh, which cannot tell a part with normals and texture coordinates (Draco: 8 bytes a
    // triangle) from a bare one (2 to 4). Parts merged with others are then measured on a sample of the
    // scene's parts stored together.
    std::function<double(const Primitive&)> meshBytes;
    // The same without the writer's trials of settings (WriteOptions::encodingTrials), for comparing two ways of
    // storing one part; else meshBytes.
    std::function<double(const Primitive&)> quickMeshBytes;
    // What a node drawing a shared mesh costs (its transform and name): a rigid placement costs less than
    // a mirrored or scaled one. Else bytesPerInstance.
    std::function<double(const Node&)> nodeBytes;
    // What nodes drawing one shared mesh cost together (glTF: batched through EXT_mesh_gpu_instancing where the
    // writer would batch them, a few bytes an instance). Else nodeBytes each.
    std::function<double(const std::vector<Node>&)> nodesBytes;
    // Draco's position bits when the output is quantized, else 0. A fundamental region whose instances are
    // signed permutations in its frame is then stored on a power-of-two grid through its centre
    // (seamPreservingGrid), in units of the grid's step, so that its seams stay closed.
    int seamGridBits = 0;
    // WriteOptions::maxRelativePositionError: the seam grid moves no corner farther than this fraction of its
    // tile's diagonal either.
    double seamGridRelativeError = 0;
    // Where the writer stores a part's geometry once for every material it is drawn in (glTF: meshes whose
    // primitives name the same accessors): what drawing the part in one more material costs. Unset: classes of
    // different materials (a family, CongruenceClass::family) are planned apart.
    std::function<double(const Primitive&)> materialVariantBytes;
};

struct AnalysisOptions {
    double tolerance = 1e-5;  // relative to the diagonal of the tiles' bounding box
    bool classify = true;     // false: tiles only (every plan will store every tile as it is)
    bool keepInputInstances = true;
    bool elementDeviations = true;  // of the classes' groups (SymmetryOptions::elementDeviations): for reports
    int threads = 0;
    ProgressCallback progress;
    // When set, what the plans will price storage with: a class of one tile too small for any fundamental
    // region of it to pay (a mesh of its own and two nodes cost more than its triangles among others) gets no
    // symmetry group, the detector being most of the classification's time (TileShape::symmetrySkipped).
    std::optional<StorageCostModel> groupCosts;
};

// A node of the input that draws a mesh several nodes draw, one of them scaling or shearing it (the author's
// own instancing of copies that are not congruent), or a mesh with attributes that tiles do not carry
// (Primitive::attributes, morph targets): kept as it is.
struct KeptInstance {
    int mesh = -1;                                            // in the input
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // world
    const Node* source = nullptr;  // in the input scene: the instance node keeps its name and extras
};

// What every plan is made from: the tiles and their congruence classes (the expensive part), computed once
// for any number of plans (the job tries three).
struct SceneAnalysis {
    AnalysisOptions options;  // those it was made with
    // options.tolerance as a distance (times the diagonal of the tiles' bounds): the one every stage uses.
    double absoluteTolerance = 0;
    double diagonal = 0;  // of the tiles' bounding box: the unit of relative tolerances and error bounds
    std::vector<KeptInstance> keptInstances;  // not in the soup: their meshes are stored as they are
    // The input's animated nodes that have no animated ancestor: kept with their subtrees as they are
    // (nodes, transforms, meshes) and their animations, so that the animations still drive them; what
    // they draw is not in the soup. Animated: the target of an animation channel, a skin's joint, a node
    // drawing a skinned mesh or one with morph targets.
    std::vector<int> animatedSubtrees;
    std::vector<WorldPrimitive> soup;
    // The soup's triangles of zero area, which no tile holds: each primitive's as many at one of its vertices,
    // without a material or other attributes, stored as they are.
    std::vector<WorldPrimitive> zeroArea;
    std::vector<Tile> tiles;
    // By material: drawn blended (drawnBlended), so that each primitive in it is one tile (TileOptions::
    // wholePrimitiveMaterials), drawn alone: by a mesh and node of its own, or by its class's mesh under a node of
    // its own; never merged with other tiles, cut into a fundamental region, part of an assembly or batched.
    std::vector<bool> blendedMaterials;
    bool blended(int m) const {
        return m >= 0 && std::size_t(m) < blendedMaterials.size() && blendedMaterials[std::size_t(m)];
    }
    bool drawnAlone(std::size_t t) const { return blended(tiles[t].material); }
    TileClassification classification;  // empty unless options.classify
    SurfaceDigest digest;
    double secondsTiles = 0, secondsClasses = 0;
};

SceneAnalysis analyzeScene(const Scene& input, const AnalysisOptions& options = {});
// The same for a job that needs the input's geometry no more than the analysis does: the arrays of every mesh
// that only tiles draw move into the soup instead of being copied (flattenSceneTaking), and those meshes keep
// their primitives' materials only. The meshes kept as they are (KeptInstance, animated subtrees) stay whole.
SceneAnalysis analyzeSceneTakingGeometry(Scene& input, const AnalysisOptions& options = {});

// Whether tiles can carry everything the mesh's primitives hold where `placement` (the linear part of a node's
// world transform) draws it: not lines or points, morph targets or skin joints and weights (a mesh that moves is
// kept as it is), tangents only under a placement that scales alike on every axis, and no primitive that X3D output
// writes as the node it was read from (Primitive::x3dSource).
bool tilesCanCarry(const Mesh& mesh, const Eigen::Matrix3d& placement);

// The cost model of a file written with `write`: every part measured by the format's writer (gltfMeshBytes,
// x3dMeshBytes and their node measures), and for Draco glTF the seams' grid.
StorageCostModel costModelFor(FileFormat format, const WriteOptions& write);

struct CompressionPlan;

struct PlanOptions {
    bool instancing = true;     // false: every tile stored as it is (Draco alone)
    bool geometryOnly = false;  // instance members whose normals, texture coordinates or colours differ
    bool regions = true;        // fundamental regions where they pay
    bool cutTriangles = false;  // CompressOptions::cutTriangles
    bool assemblies = true;     // the scene's symmetry and repeated assemblies
    // > 0: the error budget (relative to the diagonal) that each stored mesh's quantization shares with the
    // deviation of the copies it rebuilds (CompressOptions::maxError); 0: the writer's fixed bits.
    double maxError = 0;
    // Of maxError, the share kept for the rounding of GPU-instanced rotations, translations and scales
    // (WriteOptions::instanceRotationDeviation, instanceTranslationDeviation): taken only from the meshes that
    // several nodes draw, the ones a batch can hold.
    double instanceShare = 0;
    // Primitives of one mesh in materials that differ only in base colour joined, each vertex given its colour,
    // where costs' quick measure finds it smaller (joinByBaseColor; glTF with Draco, which codes a colour that
    // holds over a part in a few bytes).
    bool joinByBaseColor = false;
    StorageCostModel costs;
    ProgressCallback progress;
    // A plan made from the same analysis with the same costs (and assemblies on): its scene symmetry and
    // repeated assemblies are taken as they are instead of sought again (they do not depend on `regions`, the
    // option the job's other plans change).
    const CompressionPlan* sharedPartsFrom = nullptr;
};

// A node drawing a stored mesh.
struct PlacedCopy {
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // world
    const Node* source = nullptr;  // the input node whose tile it draws (its name and extras are kept), if any
    // The material it draws the mesh in, where that may differ from the mesh's own (a member of a family of
    // classes): emitScene gives it a mesh of that material over the same geometry, which the writer stores once.
    std::optional<int> material;
};

// One mesh stored once and the nodes that draw it: a decision of one of the planners.
struct SharedPart {
    enum class Mechanism { SceneSymmetry, Assembly, Class, Region } mechanism = Mechanism::Class;
    Mesh mesh;                       // in its own frame (about a centroid: a small range to quantize)
    std::vector<PlacedCopy> nodes;   // each draws `mesh`
    std::vector<std::size_t> tiles;  // the tiles those nodes rebuild
    std::size_t copies = 0;          // copies of the part (class members, assembly copies, group elements)
    std::string group;               // SceneSymmetry: the scene's symmetry group, whose elements the nodes are
    double deviation = 0;            // the largest of a rebuilt tile from its original, relative to the diagonal
    // false: the nodes leave out the names and extras of the input nodes their tiles came from (stored as they
    // are, merged into one mesh per material, the tiles would lose them too; emitScene warns).
    bool named = true;
    // The rotation of the frame the mesh is written in (emitScene turns it by the inverse, and each node by this
    // after its transform): the frame of the input nodes its tiles came from, where they all share one that
    // turns them off the world's axes and Draco codes the mesh smaller there (planSourceFrames).
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

// Tiles stored as they are in the frame of the input node that drew them, drawn by a node at its placement (its
// name and extras kept): where the node turns them off the world's axes, Draco codes them smaller there (a UV
// sphere's rings each share a coordinate in its frame, none in the world's).
struct FramedTiles {
    int node = -1;  // the input node they all come from, or -1: several, which share the transform's turn
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // its world transform, or the turn they share
    std::vector<std::size_t> tiles;                           // in the order they are merged
};

// A plan: what is stored once and drawn by nodes, and what is stored as it is. Turned into a Scene by
// emitScene.
struct CompressionPlan {
    bool shareInputInstances = true;          // false: the input's own shared meshes stored as they are too
    std::vector<SharedPart> shared;           // in the order they are written
    std::vector<std::size_t> tilesAsTheyAre;  // in the order they are merged (one mesh per material)
    std::vector<std::size_t> tilesAlone;      // stored as they are, each by a mesh and node of its own (drawnAlone)
    std::vector<FramedTiles> framedTiles;     // of tilesAsTheyAre, those stored in their nodes' frames
    // Whether a shared part's mesh is written in its SharedPart::frame (false: every one in the world's).
    bool sharedPartFrames = true;
    std::size_t classes = 0, symmetricClasses = 0, attributeMismatches = 0, notWorthInstancing = 0;
    std::string sceneGroup = "C1";
    double maxError = 0;               // PlanOptions::maxError
    double instanceShare = 0;          // PlanOptions::instanceShare
    bool joinByBaseColor = false;      // PlanOptions::joinByBaseColor
};

// The three planners in turn: the scene's own symmetry, repeated assemblies, then every class.
CompressionPlan planCompression(const Scene& input, const SceneAnalysis& analysis, const PlanOptions& options);

struct CompressedScene {
    Scene scene;
    CompressionStats stats;
    SurfaceDigest digest;
    std::vector<int> instanceNodes;  // the nodes of `scene` that draw a shared mesh
};

// The scene a plan draws. The input's materials, textures and animations are kept. Apart from animated
// subtrees (kept as they are under a node holding their parent's world transform) and cameras and lights
// (on nodes of their own at their world placement), the output is one level of nodes: an instance node
// takes the name of the input node its tile came from; tiles stored as they are share one mesh per
// material, and the names of their nodes are reported as not kept (scene.warnings). Where the plan asks, primitives
// are then joined by base colour, weighed by `costs`.
CompressedScene emitScene(const Scene& input, const SceneAnalysis& analysis, const CompressionPlan& plan,
                          const StorageCostModel& costs);

// planCompression, then emitScene, timed (stats.secondsPlan); the plan is moved into `decisions` when given
// (the HTML report draws it).
CompressedScene compressAnalyzed(const Scene& input, const SceneAnalysis& analysis, const PlanOptions& options,
                                 CompressionPlan* decisions = nullptr);

// The stages' options as the job's options ask (PlanOptions::costs left at the constant model).
AnalysisOptions analysisOptionsOf(const CompressOptions& options);
PlanOptions planOptionsOf(const CompressOptions& options);

// analyzeScene, then compressAnalyzed, with the constant cost model: the plan in memory, no file.
CompressedScene compressInMemory(const Scene& input, const CompressOptions& options = {});

}  // namespace symcompress
