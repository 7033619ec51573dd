// symdecompress's job: every instance expanded, written, and the rebuilt surface verified.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace symcompress {
namespace {

// Beyond the symmetry tolerance, the rebuilt surface may differ by Draco's quantization: half a step of
// the position grid, 2^-bits of the largest mesh extent; 14 bits and a mesh as large as the scene bound it.
constexpr double kQuantizationAllowance = 1.0 / (1 << 13);
// A file written within an error budget is checked against it, with room for the float32 rounding of its
// node transforms (a relative 6e-8 of the coordinates).
constexpr double kBudgetSlack = 1e-2;
// Share of the area that may face the other way: slivers that quantization turns over.
constexpr double kFlippedAllowance = 1e-4;

// How far the rebuilt area may be from the original's: a triangle's area changes by at most half its perimeter
// times how far its corners move (to first order), taken twice; at least 10 times the allowed deviation's
// share of the area, as before. `perimeters` is the sum of the triangles' perimeters.
double allowedAreaChange(double area, double perimeters, double allowed, double diagonal) {
    return std::max(10 * allowed * area, perimeters * allowed * diagonal);
}

// The times at which each animation is drawn and compared: its keys', at most this many, spread evenly.
constexpr std::size_t kPosesPerAnimation = 16;

// Every animation of the original drawn at its keys' times, the rebuilt scene's moved parts against the
// original's: an animation, skin or morph target that did not come out as it went in moves them apart. Relative to
// the whole original's diagonal at rest (`diagonal`), as the budget is: the moved parts are a part of the scene.
void comparePoses(const Scene& rebuilt, const Scene& original, double diagonal, RebuildReport& report) {
    // A format without skins or morph targets (X3D) draws those meshes at rest: a loss its writer reported, which
    // the rest pose's check covers; their poses are not compared.
    const auto morphed = [](const Scene& scene) {
        return std::count_if(scene.meshes.begin(), scene.meshes.end(),
                             [](const Mesh& mesh) { return morphTargetCount(mesh) > 0; });
    };
    if (rebuilt.skins.size() < original.skins.size() || morphed(rebuilt) < morphed(original)) {
        report.warnings.push_back(report.input.string() + " has fewer skins or morphed meshes than " +
                                  report.original.string() +
                                  " (its format holds none): its animations are not compared");
        return;
    }
    if (rebuilt.animations.size() != original.animations.size()) {
        report.posedDeviation = std::numeric_limits<double>::infinity();
        return;
    }
    for (std::size_t a = 0; a < original.animations.size(); ++a) {
        const std::vector<double> times = keyTimes(original.animations[a]);
        const std::size_t poses = std::min(times.size(), kPosesPerAnimation);
        for (std::size_t i = 0; i < poses; ++i) {
            const double time = times[poses > 1 ? i * (times.size() - 1) / (poses - 1) : 0];
            const TriangleMesh moved = posedMesh(rebuilt, rebuilt.animations[a], time),
                               reference = posedMesh(original, original.animations[a], time);
            ++report.posesCompared;
            if (moved.triangles.empty() && reference.triangles.empty()) continue;
            const Eigen::AlignedBox3d posed = digestOf(reference, 0).bounds;
            const double deviation = moved.triangles.empty() || reference.triangles.empty() || !(diagonal > 0)
                                         ? std::numeric_limits<double>::infinity()
                                         : compareSurfaces(moved, reference, report.allowedDeviation).maxDeviation *
                                               posed.diagonal().norm() / diagonal;
            report.posedDeviation = std::max(report.posedDeviation, deviation);
        }
    }
}

// The box of what a scene draws as triangles (`surface`), points and lines.
Eigen::AlignedBox3d drawnBounds(const TriangleMesh& surface, const DrawnVertices& drawn) {
    Eigen::AlignedBox3d box = digestOf(surface, 0).bounds;
    for (const TriangleMesh* vertices : {&drawn.points, &drawn.lineEnds})
        for (const Eigen::Vector3d& p : vertices->positions) box.extend(p);
    return box;
}

// How far, relative to `diagonal`, the points or line ends drawn by the rebuilt scene and the original lie from
// each other (both ways); infinite where they differ in number (lines and points are kept as they are).
double vertexDeviation(const TriangleMesh& rebuilt, const TriangleMesh& original, double diagonal) {
    if (rebuilt.positions.size() != original.positions.size()) return std::numeric_limits<double>::infinity();
    if (original.positions.empty()) return 0;
    const Eigen::AlignedBox3d box = digestOf(original, 0).bounds;
    const double own = box.diagonal().norm();
    // compareSurfaces measures relative to the original's own box: a single point has none.
    const double distance = own > 0 ? compareSurfaces(rebuilt, original, 0).maxDeviation * own
                                    : (digestOf(rebuilt, 0).bounds.max() - box.max()).norm();
    return diagonal > 0 ? distance / diagonal : distance > 0 ? std::numeric_limits<double>::infinity() : 0;
}

// Against the original: the surfaces must agree (distance both ways, area, bounds); triangle counts may
// differ, since fundamental regions split the triangles their planes cut. Quantization may turn over a
// sliver or two, not a part. Points and lines (kept as they are) must agree in number and lie within the
// allowance of each other.
void verifyAgainstOriginal(const TriangleMesh& rebuilt, const DrawnVertices& rebuiltVertices, const Scene& rebuiltScene,
                           const Scene& original, RebuildReport& report) {
    const TriangleMesh reference = worldMesh(original);
    const DrawnVertices referenceVertices = worldPointsAndLineEnds(original);
    const double drawnDiagonal = drawnBounds(reference, referenceVertices).diagonal().norm();
    const double vertices =
        std::max(vertexDeviation(rebuiltVertices.points, referenceVertices.points, drawnDiagonal),
                 vertexDeviation(rebuiltVertices.lineEnds, referenceVertices.lineEnds, drawnDiagonal));
    SurfaceComparison comparison = compareSurfaces(rebuilt, reference, report.allowedDeviation);
    if (reference.triangles.empty() && rebuilt.triangles.empty())
        comparison.areaRatio = 1, comparison.sameBounds = true;
    report.against = RebuildReport::Against::Original;
    report.maxDeviation = comparison.maxDeviation;
    report.areaRatio = comparison.areaRatio;
    report.sameBounds = comparison.sameBounds;
    report.flippedArea = comparison.flippedArea;
    report.trianglesOriginal = reference.triangles.size();
    const double allowed = report.allowedDeviation;
    const SurfaceDigest digest = digestOf(reference, 0);
    double perimeters = 0;
    for (const Triangle& t : reference.triangles)
        for (int k = 0; k < 3; ++k) perimeters += (reference.positions[t[k]] - reference.positions[t[(k + 1) % 3]]).norm();
    const double diagonal = digest.bounds.isEmpty() ? 0 : digest.bounds.diagonal().norm();
    comparePoses(rebuiltScene, original, diagonal, report);
    report.maxDeviation = std::max(report.maxDeviation, vertices);
    report.verified = report.maxDeviation <= allowed &&
                      std::abs(comparison.areaRatio - 1) * digest.area <=
                          allowedAreaChange(digest.area, perimeters, allowed, diagonal) &&
                      comparison.sameBounds && comparison.flippedArea <= kFlippedAllowance &&
                      report.posedDeviation <= report.allowedPosedDeviation;
}

// Against the digest: it has no surface, so the bounds and the area are what can be compared.
void verifyAgainstDigest(const SurfaceDigest& rebuilt, const SurfaceDigest& stored, RebuildReport& report) {
    const double diagonal = stored.bounds.isEmpty() ? 0 : stored.bounds.diagonal().norm();
    const double boundsError = diagonal > 0
                                   ? std::max((rebuilt.bounds.min() - stored.bounds.min()).cwiseAbs().maxCoeff(),
                                              (rebuilt.bounds.max() - stored.bounds.max()).cwiseAbs().maxCoeff()) /
                                         diagonal
                                   : 0;
    report.against = RebuildReport::Against::Digest;
    report.areaRatio = stored.area > 0 ? rebuilt.area / stored.area : 0;
    report.maxDeviation = boundsError;
    report.trianglesOriginal = stored.triangles;
    // The digest has no perimeters: theirs as if the triangles were equilateral, sqrt(4 A / sqrt(3)) a side,
    // summed at most as 3 sqrt(4 / sqrt(3)) sqrt(n A) (Cauchy-Schwarz).
    const double perimeters = 3 * std::sqrt(4 / std::sqrt(3.0)) * std::sqrt(double(stored.triangles) * stored.area);
    report.verified = boundsError <= report.allowedDeviation &&
                      std::abs(report.areaRatio - 1) * stored.area <=
                          allowedAreaChange(stored.area, perimeters, report.allowedDeviation, diagonal);
}

}  // namespace

RebuildReport decompressFile(const std::filesystem::path& input, const std::filesystem::path& output,
                             const std::filesystem::path& original) {
    const Scene scene = readScene(input);
    const Scene reference = original.empty() ? Scene() : readScene(original);
    RebuildReport report;
    report.input = input;
    report.output = output;
    report.original = original;
    Scene flat = expandInstances(scene);
    for (std::string& loss : formatLosses(flat, output)) flat.warnings.push_back(std::move(loss));
    report.warnings.assign(flat.warnings.begin() + std::ptrdiff_t(scene.warnings.size()), flat.warnings.end());
    WriteOptions exact;
    exact.draco = false;  // the expanded scene is the reference geometry: keep it exact
    writeScene(flat, output, exact, {input});
    const TriangleMesh rebuilt = worldMesh(flat);
    const DrawnVertices rebuiltVertices = worldPointsAndLineEnds(flat);
    SurfaceDigest rebuiltDigest = digestOf(rebuilt, 0);
    // As the digest of the original holds them: points and lines count towards the bounds.
    rebuiltDigest.bounds = drawnBounds(rebuilt, rebuiltVertices);
    report.triangles = rebuiltDigest.triangles;
    SurfaceDigest stored;
    const bool haveDigest = SurfaceDigest::fromJson(scene.extrasJson, stored);
    report.allowedDeviation = haveDigest && stored.maxError > 0
                                  ? stored.maxError * (1 + kBudgetSlack)
                                  : kQuantizationAllowance + (haveDigest ? stored.tolerance : 0);
    report.allowedPosedDeviation =
        haveDigest && stored.poseError > 0 ? stored.poseError * (1 + kBudgetSlack) : report.allowedDeviation;
    if (!original.empty())
        verifyAgainstOriginal(rebuilt, rebuiltVertices, flat, reference, report);
    else if (haveDigest)
        verifyAgainstDigest(rebuiltDigest, stored, report);
    return report;
}

std::string RebuildReport::json() const {
    nlohmann::json out{{"input", input.string()}, {"output", output.string()}, {"triangles", triangles}};
    switch (against) {
    case Against::Original:
        out["against"] = original.string();
        out["max_deviation"] = maxDeviation;
        out["area_ratio"] = areaRatio;
        out["same_bounds"] = sameBounds;
        out["flipped_area"] = flippedArea;
        out["triangles_original"] = trianglesOriginal;
        out["poses_compared"] = posesCompared;
        out["posed_deviation"] =
            std::isfinite(posedDeviation) ? nlohmann::json(posedDeviation) : nlohmann::json("infinite");
        break;
    case Against::Digest:
        out["against"] = "digest";
        out["area_ratio"] = areaRatio;
        out["bounds_deviation"] = maxDeviation;
        out["max_deviation"] = maxDeviation;
        out["triangles_original"] = trianglesOriginal;
        break;
    case Against::Nothing: out["against"] = nullptr; break;
    }
    out["verified"] = verified;
    out["allowed_deviation"] = allowedDeviation;
    out["allowed_posed_deviation"] = allowedPosedDeviation;
    return out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);  // names from X3D need not be UTF-8
}

}  // namespace symcompress
