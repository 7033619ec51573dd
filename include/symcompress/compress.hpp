// symcompress's job: a scene read, split into tiles, its repetitions and symmetries found, and written
// with every repeated part stored once and drawn by a node per copy; the plans tried, each measured as
// written, the smallest kept, and the size report. docs/ARCHITECTURE.md describes the stages.
#pragma once

#include "symcompress/io.hpp"
#include "symcompress/optimize.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace symcompress {

// Called as each stage starts, with what it works on (e.g. "classifying", 873 tiles).
using ProgressCallback = std::function<void(const char* stage, std::size_t count, const char* unit)>;

struct CompressOptions {
    // The error budget: how far the rebuilt surface may lie from the input's, relative to the scene's
    // bounding-box diagonal (what symdecompress verifies). The congruence and symmetry tolerance takes
    // `tolerance` of it (half when 0); each stored mesh's position quantization takes what the deviation of
    // the copies it draws leaves (the bits chosen per mesh), unless fixedPositionBits.
    double maxError = 5e-5;
    double tolerance = 0;              // congruence and symmetry, relative to the diagonal; 0: maxError / 2
    // How much farther than maxError the rounding and dropping of animation keys may move a vertex in a pose,
    // relative to the diagonal (glTF output), beside the budget, which the rest pose and the meshes keep whole
    // (symdecompress verifies the poses against the sum). 0: the keys take a share of maxError.
    double animationError = 0;
    bool fixedPositionBits = false;    // write.positionBits for every mesh (--position-bits), not the budget
    // Quantization also moves no corner of a stored primitive farther than closeUpError * maxError of the
    // primitive's own diagonal (0: no such bound): the budget holds for a part seen on its own, as a viewer
    // zoomed in on it sees it, as the peers' quantization of each mesh in its own box does. A part small in
    // the scene would otherwise take few bits: 500 blobs of a hundredth of the diagonal at 8 bits rendered
    // 1.2% of their pixels otherwise (at that size most are on an edge), the bolts' threads 0.9% of their
    // normals; within this bound 0.1% and 0.3%. Twice the budget was at the limit (0.5%).
    double closeUpError = 1;
    bool instancing = true;            // false: every tile stored as it is (Draco alone)
    bool geometryOnly = false;         // instance members whose normals, texture coordinates or colours differ
    bool regions = true;               // store symmetric tiles as their fundamental regions where that pays
    // Let a region cut the triangles its planes cross, where the group does not map the tile's triangles onto
    // one another (an asymmetric tessellation of a symmetric surface): smaller, but the copies draw other
    // triangles than the input's. Off: a region keeps the tile's triangles whole, or is not made.
    bool cutTriangles = false;
    bool assemblies = true;            // store tiles that recur together once per group, drawn by one node per copy
    bool keepInputInstances = true;    // meshes the input draws from several nodes, scaled, stay shared
    OptimizeOptions optimize;          // pruning and deduplication before the scene is split into tiles
    int threads = 0;                   // 0: all cores
    WriteOptions write;                // the output's writer (Draco, quantization)
    ProgressCallback progress;         // may be empty
    // When set, compressToFile also writes the HTML report of the plan it kept there (html_report.hpp), once
    // the size report is complete.
    std::filesystem::path htmlReport;

    double congruenceTolerance() const { return tolerance > 0 ? tolerance : maxError / 2; }
};

// What the plan did, counted from its decisions.
struct CompressionStats {
    std::size_t trianglesIn = 0, trianglesStored = 0;
    std::size_t tiles = 0, classes = 0;
    std::size_t instancedClasses = 0;      // classes stored once and drawn several times
    std::size_t instances = 0;             // nodes drawing a shared mesh
    std::size_t symmetricClasses = 0;      // classes whose prototype has a symmetry group of order > 1
    std::size_t groupsSkipped = 0;         // classes of one tile too small for a region to pay: no group sought
    std::size_t attributeMismatches = 0;   // congruent members stored apart because their attributes differ
    std::size_t notWorthInstancing = 0;    // members of classes too small for a node each to pay
    std::size_t regionClasses = 0;         // classes stored as their fundamental region
    std::size_t assemblies = 0;            // repeated assemblies stored once (tiles that recur together)
    std::size_t assemblyCopies = 0;        // nodes drawing them
    std::size_t tilesInAssemblies = 0;     // tiles those nodes draw
    std::string sceneGroup = "C1";         // the scene's symmetry group, where one part of the scene is stored for all
    std::size_t tilesInSceneSymmetry = 0;  // tiles drawn by that part's nodes
    std::size_t inputInstancesKept = 0;    // nodes of the input's own shared meshes, kept
    // Meshes drawing a shared part's geometry in another material (a family of classes), the geometry stored once.
    std::size_t materialVariants = 0;
    // Meshes written in the frame of the input nodes their tiles came from, which turned them off the world's
    // axes (CompressionPlan::framedTiles, SharedPart::frame), and the tiles they draw.
    std::size_t nodeFrames = 0, tilesInNodeFrames = 0;
    std::size_t animatedNodesKept = 0;     // nodes of animated subtrees, kept with their animations
    std::size_t camerasAndLightsKept = 0;  // other nodes with a camera or a light, kept at their world placement
    std::size_t lineSegmentsKept = 0, pointsKept = 0;  // stored as they are (Topology::Lines, Points)
    BaseColorJoins baseColorJoins;                     // PlanOptions::joinByBaseColor
    double maxDeviation = 0;               // of the placements used, relative to the diagonal
    double secondsTiles = 0, secondsClasses = 0, secondsPlan = 0;
};

// The size report (symcompress --report): what was read and written, and what each plan's file measured.
struct CompressionReport {
    std::filesystem::path input, output;
    std::uintmax_t inputBytes = 0;   // with a .gltf's buffers and images, and the images OBJ, PLY, STL and X3D name
    std::uintmax_t outputBytes = 0;  // the output as kept, with a .gltf's .bin
    double ratio = 0;                // inputBytes / outputBytes
    std::string plan = "final";      // whose file is the output: final, instancing (no regions), draco_alone
    double tolerance = 0;  // the congruence and symmetry tolerance used, relative to the diagonal
    double maxError = 0;   // the error budget, relative; 0 with fixed position bits
    // Of the budget, the shares for the rounding of animations' key values and of skin weights (relative); the
    // keys' allowance beside the budget, where CompressOptions::animationError gave one.
    double animationKeyShare = 0, skinWeightShare = 0, animationError = 0;
    CompressionStats stats;                               // of the plan kept
    std::size_t animations = 0, cameras = 0, lights = 0;  // in the output
    // The bytes a node drawing a shared mesh costs in the output, on average over its instance nodes, by
    // the writer's measure (its transform and name); 0 without instances.
    double bytesPerInstance = 0;
    // glTF: the EXT_mesh_gpu_instancing batches of the output and the instances they draw (each would be a node
    // without them, as with --no-gpu-instancing).
    GpuInstancingCount gpuInstancing;
    OptimizeReport optimizations;               // what was pruned and merged before tiling
    double secondsRead = 0, secondsWrite = 0;  // the other stages' are in stats
    // The file of each plan tried (empty where a plan was not tried, as with --no-instancing).
    struct Ablation {
        std::optional<std::uintmax_t> dracoAlone, instancing, instancingAndRegions;
    } ablation;
    std::vector<std::string> warnings;  // the reader's first, then what the plan could not carry through
    std::size_t readerWarnings = 0;     // how many of `warnings` are the reader's
    std::string json() const;           // the report's JSON object, the keys the README lists
};

// Reads `input`, compresses it and writes `output` (its extension picks the format) atomically. Throws
// FileError for a file it cannot read or write (`output` may not be `input`).
CompressionReport compressFile(const std::filesystem::path& input, const std::filesystem::path& output,
                               const CompressOptions& options = {});

// The same for a scene in memory; `inputs` are the files it was read from (never overwritten; the first,
// when given, is what the report's input_bytes measure).
CompressionReport compressToFile(Scene scene, const std::filesystem::path& output, const CompressOptions& options = {},
                                 const std::vector<std::filesystem::path>& inputs = {});

}  // namespace symcompress
