// The compression plan (paper 7.1, ALGORITHM.md 8): tiles that recur together are stored once per group
// and drawn by one node per copy; every congruence class whose members reproduce the prototype (geometry
// and attributes) is stored once and drawn by one node per member; the rest is stored as it is. And the check a decoder makes: the rebuilt surface against the original or its digest.
#pragma once

#include "symcompress/congruence.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene.hpp"
#include "symcompress/scene_ops.hpp"

#include <functional>
#include <string>

namespace symcompress {

struct CompressOptions {
    double tolerance = 1e-5;    // relative to the scene's bounding-box diagonal
    bool instancing = true;     // false: every tile stored as it is (Draco alone)
    bool geometryOnly = false;  // instance members whose normals, texture coordinates or colours differ
    bool regions = true;        // store symmetric tiles as their fundamental regions where that pays
    bool assemblies = true;     // store tiles that recur together once per group, drawn by one node per copy
    bool keepInputInstances = true;  // meshes the input draws from several nodes, scaled, stay shared as they are
    // Draco's position bits when the output is quantized (Draco glTF), else 0. A fundamental region whose
    // instances are signed permutations in its frame is then stored on a power-of-two grid through its
    // centre (seamPreservingGrid), in units of the grid's step, so that its seams stay closed.
    int seamGridBits = 0;
    int threads = 0;
    // Called as each stage starts, with what it works on (e.g. "classifying", 873 tiles); may be empty.
    std::function<void(const char* stage, std::size_t count, const char* unit)> progress;
    // The cost model of the output format, in bytes: a stored triangle with its attributes, a node
    // drawing a shared mesh, a shared mesh's own overhead. The constants are a rough Draco glTF (bare
    // positions).
    double bytesPerTriangle = 1.5;
    double bytesPerInstance = 120;
    double bytesPerMesh = 500;
    // When set, what a part costs as a mesh of its own, measured by the output's writer (useGltfCosts,
    // useX3dCosts): it takes the place of bytesPerTriangle and bytesPerMesh, which cannot tell a part with
    // normals and texture coordinates (Draco: 8 bytes a triangle) from a bare one (2 to 4). Parts merged
    // with others are then measured on a sample of the scene's parts stored together.
    std::function<double(const Primitive&)> meshBytes;
    // When set, what a node drawing a shared mesh costs, measured by the writer (its transform and name):
    // a rigid placement costs less than a mirrored or scaled one. Else bytesPerInstance.
    std::function<double(const Node&)> nodeBytes;
};

struct CompressionStats {
    std::size_t trianglesIn = 0, trianglesStored = 0;
    std::size_t tiles = 0, classes = 0;
    std::size_t instancedClasses = 0;  // classes stored once and drawn several times
    std::size_t instances = 0;         // nodes drawing a shared mesh
    std::size_t symmetricClasses = 0;  // classes whose prototype has a symmetry group of order > 1
    std::size_t attributeMismatches = 0;  // congruent members stored apart because their attributes differ
    std::size_t notWorthInstancing = 0;   // members of classes too small for a node each to pay
    std::size_t regionClasses = 0;        // classes stored as their fundamental region
    std::size_t assemblies = 0;           // repeated assemblies stored once (tiles that recur together)
    std::size_t assemblyCopies = 0;       // nodes drawing them
    std::size_t tilesInAssemblies = 0;    // tiles those nodes draw
    std::string sceneGroup = "C1";        // the scene's symmetry group, where one part of the scene is stored for all
    std::size_t tilesInSceneSymmetry = 0; // tiles drawn by that part's nodes
    std::size_t inputInstancesKept = 0;   // nodes of the input's own shared meshes, kept (KeptInstance)
    std::size_t animatedNodesKept = 0;    // nodes of animated subtrees, kept with their animations
    std::size_t camerasAndLightsKept = 0; // other nodes with a camera or a light, kept at their world placement
    double maxDeviation = 0;              // of the placements used, relative to the diagonal
    double secondsTiles = 0, secondsClasses = 0, secondsPlan = 0;
};

// The digest of the original surface that a decoder checks the rebuilt one against.
struct SurfaceDigest {
    std::size_t triangles = 0;
    double area = 0;
    Eigen::AlignedBox3d bounds;
    double tolerance = 0;  // relative to the bounds' diagonal
    std::string json() const;                              // {"symcompress_digest": {...}}
    static bool fromJson(const std::string& text, SurfaceDigest& digest);  // false when absent
};

SurfaceDigest digestOf(const TriangleMesh& surface, double tolerance);

// The cost model for X3D output written with `write`: every part measured by the writer itself
// (x3dMeshBytes), a Transform with a USE per instance.
inline void useX3dCosts(CompressOptions& options, const WriteOptions& write) {
    options.bytesPerInstance = 150;
    options.meshBytes = [write](const Primitive& part) { return double(x3dMeshBytes(part, write)); };
    options.nodeBytes = [](const Node& node) { return double(x3dNodeBytes(node)); };
}

// The cost model and the seams' grid for glTF output written with `write`: every part measured by the
// writer itself (gltfMeshBytes), Draco's positions on the grid its quantization uses.
inline void useGltfCosts(CompressOptions& options, const WriteOptions& write) {
    options.seamGridBits = write.draco ? write.positionBits : 0;
    options.meshBytes = [write](const Primitive& part) { return double(gltfMeshBytes(part, write)); };
    options.nodeBytes = [](const Node& node) { return double(gltfNodeBytes(node)); };
}

struct CompressedScene {
    Scene scene;
    CompressionStats stats;
    SurfaceDigest digest;
};

// What the plan is made from: the tiles and their congruence classes (the expensive part), computed once
// for any number of plans (the size report's ablation makes three).
// A node of the input that draws a mesh several nodes draw, one of them scaling or shearing it: the
// author's own instancing of copies that are not congruent, kept as it is.
struct KeptInstance {
    int mesh = -1;  // in the input
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // world
    std::string name;
};

struct SceneAnalysis {
    std::vector<KeptInstance> keptInstances;  // not in the soup: their meshes are stored as they are
    // The input's animated nodes that have no animated ancestor: kept with their subtrees as they are
    // (nodes, transforms, meshes) and their animations, so that the animations still drive them; what
    // they draw is not in the soup.
    std::vector<int> animatedSubtrees;
    std::vector<WorldPrimitive> soup;
    std::vector<Tile> tiles;
    TileClassification classification;
    SurfaceDigest digest;
    double secondsTiles = 0, secondsClasses = 0;
};

SceneAnalysis analyzeScene(const Scene& input, const CompressOptions& options = {});

// The input's materials, textures and animations are kept. Apart from animated subtrees (kept as they are
// under a node holding their parent's world transform), the output is one level of nodes: an instance node takes
// the name of the input node its tile came from; tiles stored as they are share one mesh per material,
// and the names of their nodes are reported as not kept (CompressedScene::scene.warnings), as is the
// input's hierarchy. `options.tolerance` and `threads` must be those the analysis was made with.
CompressedScene planCompression(const Scene& input, const SceneAnalysis& analysis, const CompressOptions& options = {});

// analyzeScene, then planCompression.
CompressedScene compressScene(const Scene& input, const CompressOptions& options = {});

struct SurfaceComparison {
    double maxDeviation = 0;  // two-sided vertex-to-surface distance, relative to the reference's diagonal
    double areaRatio = 0;     // rebuilt area / reference area
    bool sameBounds = false;  // within maxDeviation's tolerance
    // Share of the rebuilt area turned over: triangles with no reference triangle facing their way
    // within the tolerance of their centroid (a copy placed upside down, a mirror drawn inside out).
    double flippedArea = 0;
};

// The rebuilt surface against the reference: vertex-to-surface both ways (d_A), area, bounds, orientation.
SurfaceComparison compareSurfaces(const TriangleMesh& rebuilt, const TriangleMesh& reference, double boundsTolerance);

}  // namespace symcompress
