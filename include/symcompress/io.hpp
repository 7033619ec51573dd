// Reading and writing scenes. The format follows the file name's extension.
#pragma once

#include "symcompress/scene.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace symcompress {

// A file that cannot be read or written. what() names the file and the problem, ready for the user.
class FileError : public std::runtime_error {
public:
    FileError(const std::filesystem::path& file, const std::string& problem)
        : std::runtime_error(file.string() + ": " + problem) {}
};

enum class FileFormat { Gltf, Glb, X3d, Obj, Ply, Stl };

// Draco encodings kept for reuse (WriteOptions::encodings): thread-safe, and made by makePrimitiveEncodings.
class PrimitiveEncodings;
std::shared_ptr<PrimitiveEncodings> makePrimitiveEncodings();

// The format named by the extension (case-insensitive); throws FileError for an unknown one.
FileFormat formatFromExtension(const std::filesystem::path& file);

// Reads any supported scene file. Throws FileError for anything it cannot read; what it can read
// but not carry through is listed in Scene::warnings. The result satisfies the invariants of
// scene.hpp (validateScene).
Scene readScene(const std::filesystem::path& file);

Scene readGltf(const std::filesystem::path& file);  // .gltf and .glb
Scene readX3d(const std::filesystem::path& file);
Scene readObj(const std::filesystem::path& file);
Scene readPly(const std::filesystem::path& file);
Scene readStl(const std::filesystem::path& file);

struct WriteOptions {
    bool draco = true;       // glTF: compress geometry with KHR_draco_mesh_compression
    int positionBits = 14;   // Draco position quantization, where no error bound is given
    // > 0: each primitive's position bits are the fewest that keep its corners within this distance
    // (Primitive::maxPositionError, where set, in its place; positionBitsFor).
    double maxPositionError = 0;
    // > 0: nor farther than this fraction of its own primitive's bounding-box diagonal, so that a part small in
    // the scene keeps its shape when a viewer zooms in on it (positionErrorBound).
    double maxRelativePositionError = 0;
    int normalBits = 10;
    int texcoordBits = 12;
    // > 0: TEXCOORD_0's Draco step (in texture coordinates) where texcoordBits over the coordinates' span would be
    // finer: their grid is stretched to it (the glTF writer sets it to 1/16 of a texel of the largest texture read).
    double texcoordStep = 0;
    int colorBits = 8;
    // > 0: how far (a distance) the rounding of a skin's weights may move a vertex in any pose; the glTF writer
    // sets each skinned primitive's weightBits from it. 0: weights kept as read (float32).
    double skinWeightError = 0;
    int weightBits = 0;  // Draco's quantization of WEIGHTS_n; 0: none (float32 as read)
    // Draco's sequential coding, which keeps the triangles in their order (edgebreaker reorders them): the glTF
    // writer sets it for each blended, double-sided primitive, whose triangles viewers draw over each other in
    // their order (drawnBlended).
    bool keepTriangleOrder = false;
    // > 0: how far (a distance) the rounding of animations' key values may move a vertex in any pose (glTF with
    // meshopt: its filters, gltf_animation_keys.hpp). 0: key values kept as read (float32).
    double animationKeyError = 0;
    int compressionLevel =
        10;  // Draco speed 10 - compressionLevel; 10: the smallest of several (dracoSpeedsWorthTrying)
    // false: each primitive encoded once, at the speed compressionLevel asks first and the fewest position bits,
    // without the trials of other speeds and bits: a quick measure, for comparing two ways of storing a part.
    bool encodingTrials = true;
    // glTF: leaves drawing one mesh written as one node with EXT_mesh_gpu_instancing where that is smaller, and
    // animation, skin and morph data coded by EXT_meshopt_compression where that is (--no-gpu-instancing: a node
    // each and no meshopt, for viewers without the extensions).
    bool gpuInstancing = true;
    // How far, relative to the scene's bounding-box diagonal, the rounding of an instance's rotation (to
    // normalized SHORT, or through meshopt's filters) may move a vertex (else the batch keeps FLOAT rotations):
    // a 16th of the quantization allowance symdecompress verifies with (2^-13).
    double instanceRotationDeviation = 1.0 / (1 << 17);
    // The same for the rounding of an instance's translation and scale together (meshopt's exponential filter,
    // with Draco; else they stay float32): what the budget keeps for them apart from the rotations' share.
    double instanceTranslationDeviation = 1.0 / (1 << 17);
    // Written as glTF asset.extras / X3D MetadataSet, e.g. the digest of the original scene.
    std::string extrasJson;
    int threads = 0;  // glTF: the primitives' Draco encodings on this many threads (0: all cores)
    // Where set, the glTF writer keeps each primitive's Draco encoding here and reuses it for the same primitive
    // written with the same options (a compression job writes the same primitives in every plan it measures).
    std::shared_ptr<PrimitiveEncodings> encodings;
};

// Throws FileError unless `file` can be written: a type the writers write (.glb, .gltf, .x3d, .x3dz, .obj, .ply),
// in a folder that exists, none of `inputs`.
void checkOutputFile(const std::filesystem::path& file, const std::vector<std::filesystem::path>& inputs = {});

// Writes atomically (temporary file in the same folder, then rename). Refuses to overwrite any of
// `inputs` (the files the scene was read from). Throws FileError.
void writeScene(const Scene& scene, const std::filesystem::path& file, const WriteOptions& options = {},
                const std::vector<std::filesystem::path>& inputs = {});

// What writing `scene` to `file` leaves out or changes (animations, cameras and lights in OBJ or PLY; X3D's
// environment nodes outside X3D; cubic splines and light intensities in X3D), one warning each, for the
// caller to show before it writes.
std::vector<std::string> formatLosses(const Scene& scene, const std::filesystem::path& file);

// The position bits Draco quantizes `primitive` with: its grid's, else the fewest that keep every corner
// within its error bound (Primitive::maxPositionError, else options.maxPositionError; Draco's quantization
// simulated), else options.positionBits.
int positionBitsFor(const Primitive& primitive, const WriteOptions& options);

// COLOR_0's quantization bits: options.colorBits, or the primitive's own (Primitive::colorBits) where more.
inline int colorBitsFor(const Primitive& primitive, const WriteOptions& options) {
    return std::max(primitive.colorBits, options.colorBits);
}

// How far quantization may move a corner of `primitive` (a distance in its frame): its error bound
// (Primitive::maxPositionError, else options.maxPositionError) and options.maxRelativePositionError of its own
// diagonal, whichever is smaller; 0 where the first is not set (fixed bits).
double positionErrorBound(const Primitive& primitive, const WriteOptions& options);

// Position bits beyond `fewest` (positionBitsFor's) that also keep every corner within the bound, up to two more, for a
// primitive of at most 20000 triangles without a grid: Draco's size is not monotonic in the bits (merged corners,
// other predictions; the grass cards' scene 19390 bytes at 14 bits, 16578 at 15), so the writer encodes with
// these too and keeps the smallest.
std::vector<int> positionBitsWorthTrying(const Primitive& primitive, const WriteOptions& options, int fewest);
// A grid of `bits` for `primitive`'s positions coarser than Draco's own (its box's largest side cut into
// 2^bits - 1 steps): the same corner, a step 2^(k/8) times as long for the largest k < 8 whose corners stay within
// the bound and that collapses no triangle. The bits are whole, the bound is not: where `bits` keep the corners
// well within it (a bit fewer would not), the longer step leaves Draco's predictions smaller residuals to code,
// some fraction of a bit a coordinate. Nothing where no k holds, for a primitive with a grid of its own or of over
// 20000 triangles, or without a bound (fixed bits).
std::optional<QuantizationGrid> coarserPositionGrid(const Primitive& primitive, const WriteOptions& options, int bits);
// The Draco speeds (encoding and decoding alike) to encode `primitive` with, the smallest result kept: the one
// compressionLevel asks, and where that is the best compression (10, speed 0), for a primitive of at most
// 20000 triangles, others too. Speed 0's predictions cost more than they save on small parts: the chess
// board 5000 bytes at speed 0, 4692 at 8; the sterile room 40460 at 0, 38956 at 5.
std::vector<int> dracoSpeedsWorthTrying(const Primitive& primitive, const WriteOptions& options);

void writeGltf(const Scene& scene, const std::filesystem::path& file, const WriteOptions& options);  // .gltf/.glb
// What storing `primitive` as a mesh of its own adds to a glTF file written with `options`: its data (Draco's
// or plain) and the JSON of its mesh, accessors and buffer views. The measure a compression plan weighs its
// choices with (CompressOptions::meshBytes). Throws FileError where writeGltf would.
std::size_t gltfMeshBytes(const Primitive& primitive, const WriteOptions& options);
// What a node drawing a mesh stored already adds to a glTF file: its transform, name and index (children
// not counted). The measure a plan weighs each instance with (CompressOptions::nodeBytes).
std::size_t gltfNodeBytes(const Node& node);
// What `nodes`, drawing one mesh stored already side by side under one parent, add to a glTF file written
// with `options`: batched through EXT_mesh_gpu_instancing where the writer would batch them (mirrored and
// unmirrored ones apart), else gltfNodeBytes each. The measure a plan weighs a mesh's instances with.
double gltfNodesBytes(const std::vector<Node>& nodes, const WriteOptions& options);
// The EXT_mesh_gpu_instancing batches writeGltf writes for `scene`, and the instances they hold.
struct GpuInstancingCount {
    std::size_t batches = 0, instances = 0;
};
GpuInstancingCount gltfGpuInstancing(const Scene& scene, const WriteOptions& options);
void writeX3d(const Scene& scene, const std::filesystem::path& file, const WriteOptions& options);
// gltfMeshBytes for X3D: the text of a Group holding `primitive`'s Shape (uncompressed, as in .x3d).
std::size_t x3dMeshBytes(const Primitive& primitive, const WriteOptions& options);
// Whether X3D output refers to an image (a texture's, or its fallback) where it was read from (`uri`, a file that
// exists) instead of embedding its `bytes` as a data: URL, a third larger: as an X3D author keeps images beside the
// scene.
bool x3dRefersToImageFile(const std::string& uri, const std::vector<std::uint8_t>& bytes);
// The bytes of the image files an X3D file written from `scene` refers to, each once: part of its size.
std::uintmax_t x3dReferencedImageBytes(const Scene& scene);
// gltfNodeBytes for X3D: a Transform around a USE of the mesh.
std::size_t x3dNodeBytes(const Node& node);
void writeObj(const Scene& scene, const std::filesystem::path& file, const WriteOptions& options);
void writePly(const Scene& scene, const std::filesystem::path& file, const WriteOptions& options);

}  // namespace symcompress
