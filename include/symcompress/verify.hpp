// The decoder's side: the digest of an original surface that a compressed file carries, the comparison of
// a rebuilt surface with its original, and the whole job of symdecompress (expand, write, verify).
// docs/verification.md explains the checks and their allowances.
#pragma once

#include "symcompress/scene.hpp"
#include "symcompress/scene_ops.hpp"

#include <Eigen/Geometry>

#include <filesystem>
#include <string>
#include <vector>

namespace symcompress {

// The digest of the original surface that a decoder checks the rebuilt one against.
struct SurfaceDigest {
    std::size_t triangles = 0;
    double area = 0;
    Eigen::AlignedBox3d bounds;
    double tolerance = 0;                                                  // relative to the bounds' diagonal
    double maxError = 0;  // the error budget the file was written within (relative), 0 when it had none
    // Where animation keys were given an allowance of their own (--animation-error): the farthest a vertex may lie
    // in a pose (relative), the budget's part and the keys'; else 0 (the budget holds in every pose).
    double poseError = 0;
    // {"symcompress_digest": [triangles, area, max error, tolerance, min, max, pose error where there is one]}
    std::string json() const;
    static bool fromJson(const std::string& text, SurfaceDigest& digest);  // false when absent
};

SurfaceDigest digestOf(const TriangleMesh& surface, double tolerance);
// The same digest (the same sums in the same order) of the primitives one after the other: flattenScene's
// soup, without copying it into one mesh. What they draw as points and lines counts towards the bounds.
SurfaceDigest digestOf(const std::vector<WorldPrimitive>& soup, double tolerance);

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

// What symdecompress found: the rebuilt surface against the original (when given) or the digest stored in
// the file (else nothing to verify against).
struct RebuildReport {
    std::filesystem::path input, output;
    enum class Against { Nothing, Original, Digest } against = Against::Nothing;
    std::filesystem::path original;  // with Against::Original
    std::size_t triangles = 0, trianglesOriginal = 0;
    double maxDeviation = 0;  // Original: d_A; Digest: the bounds' deviation (the digest has no surface)
    double areaRatio = 0;
    bool sameBounds = false;      // Original only
    double flippedArea = 0;       // Original only
    // Original only: the original's animations, each at its keys' times (at most kPosesPerAnimation of them), the
    // moved parts against the original's (posedMesh); relative to the original's diagonal at rest, infinite where
    // the animations differ in number or one draws what the other does not.
    std::size_t posesCompared = 0;
    double posedDeviation = 0;
    // The stored error budget, else (a file written with fixed bits) the stored tolerance plus half a 14-bit
    // quantization step.
    double allowedDeviation = 0;
    double allowedPosedDeviation = 0;  // in the poses: allowedDeviation, or the digest's pose error
    bool verified = false;
    std::vector<std::string> warnings;  // what expanding and writing left out (the input's own are not repeated)
    std::string json() const;
};

// Reads `input`, writes it to `output` with every instance expanded into one flat mesh (plain accessors:
// the reference geometry, exact), and verifies the rebuilt surface against `original` (when not empty) or
// the digest in `input`. Throws FileError for a file it cannot read or write.
RebuildReport decompressFile(const std::filesystem::path& input, const std::filesystem::path& output,
                             const std::filesystem::path& original = {});

}  // namespace symcompress
