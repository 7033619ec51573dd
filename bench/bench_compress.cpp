// Compression (issue 6): time per stage and peak memory for a generated scene of about N triangles, baked
// into one mesh: 70% of them bolts (1248 triangles, group C6; every fourth mirrored) at random rotations on
// a grid, 30% distinct random convex parts (about 28 triangles each, on ellipsoids of random axes: nothing
// to share). Writes a Draco GLB.
//   bench_compress N OUT.glb      one row of the table (run each N in its own process for its peak memory)
#include "sample_scenes.hpp"
#include "symcompress/detail/compression_plan.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/io.hpp"
#include "symcompress/optimize.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <sys/resource.h>

using namespace symcompress;

namespace {

double peakMemoryMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

void appendPlaced(Primitive& out, const Primitive& part, const Eigen::Matrix3d& linear, const Eigen::Vector3d& at) {
    const auto base = std::uint32_t(out.positions.size());
    const Eigen::Matrix3d normalMatrix = linear.inverse().transpose();
    for (std::size_t v = 0; v < part.positions.size(); ++v) {
        out.positions.push_back((linear * part.positions[v] + at).cast<float>().cast<double>());
        out.normals.push_back((normalMatrix * part.normals[v]).normalized());
    }
    for (Triangle t : part.triangles) {
        if (linear.determinant() < 0) std::swap(t[1], t[2]);
        out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
}

// A random convex part with flat normals, about 28 triangles: 16 points on an ellipsoid of random axes.
Primitive randomPart(std::mt19937_64& random) {
    const TriangleMesh mesh = samples::randomConvexPart(random);
    Primitive part;
    for (const Triangle& t : mesh.triangles) {
        const Eigen::Vector3d n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).normalized();
        const auto base = std::uint32_t(part.positions.size());
        for (int k = 0; k < 3; ++k) part.positions.push_back(0.8 * mesh.positions[t[k]]), part.normals.push_back(n);
        part.triangles.push_back({base, base + 1, base + 2});
    }
    return part;
}

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_compress N OUT.glb\n");
        return 2;
    }
    const double target = std::stod(argv[1]);
    const std::filesystem::path output = argv[2];
    try {
        std::mt19937_64 random(2026);
        std::normal_distribution<double> normal;
        const Primitive bolt = samples::makeBolt();
        const auto bolts = std::size_t(std::ceil(0.7 * target / double(bolt.triangles.size())));
        const auto parts = std::size_t(std::ceil(0.3 * target / 28));
        const auto side = std::size_t(std::ceil(std::cbrt(double(bolts + parts))));
        // Reserved as a reader does (at most 28 triangles a random part, three vertices each): grown by doubling,
        // the arrays would take up to twice the input's memory.
        Primitive baked;
        baked.positions.reserve(bolts * bolt.positions.size() + parts * 28 * 3);
        baked.normals.reserve(baked.positions.capacity());
        baked.triangles.reserve(bolts * bolt.triangles.size() + parts * 28);
        for (std::size_t k = 0; k < bolts + parts; ++k) {
            Eigen::Matrix3d linear =
                samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
            if (k % 4 == 3) linear.col(0) *= -1;
            const Eigen::Vector3d at = 6.0 * Eigen::Vector3d(double(k % side), double(k / side % side), double(k / side / side));
            appendPlaced(baked, k < bolts ? bolt : randomPart(random), linear, at);
        }
        Scene scene = samples::singleMeshScene("bench", std::move(baked), {0.7, 0.7, 0.7, 1});
        const std::size_t triangles = scene.meshes[0].primitives[0].triangles.size();

        // The stages of compressFile's full plan, for a Draco GLB (without the trial of the simpler plans), after
        // the optimizations it makes first.
        WriteOptions write;
        const CompressOptions options;
        PlanOptions planOptions = planOptionsOf(options);
        planOptions.costs = costModelFor(FileFormat::Glb, write);
        auto start = std::chrono::steady_clock::now();
        optimizeScene(scene, options.optimize);  // as compressFile does first: the bolts' flat normals go
        AnalysisOptions analysisOptions = analysisOptionsOf(options);
        analysisOptions.groupCosts = costModelFor(FileFormat::Glb, write);  // as compressFile sets it
        const SceneAnalysis analysis = analyzeSceneTakingGeometry(scene, analysisOptions);
        const double analyzeSeconds = since(start);
        start = std::chrono::steady_clock::now();
        const CompressedScene compressed = compressAnalyzed(scene, analysis, planOptions);
        const double planSeconds = since(start);
        start = std::chrono::steady_clock::now();
        write.extrasJson = compressed.digest.json();
        writeScene(compressed.scene, output, write);
        const double writeSeconds = since(start);
        const CompressionStats& stats = compressed.stats;
        std::printf("| %zu | %zu | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %ju |\n", triangles, stats.tiles, stats.classes,
                    analysis.secondsTiles, analysis.secondsClasses, planSeconds, writeSeconds,
                    analyzeSeconds + planSeconds + writeSeconds, peakMemoryMiB(), std::filesystem::file_size(output));
    } catch (const std::exception& error) {
        std::fprintf(stderr, "bench_compress: %s\n", error.what());
        return 1;
    }
    return 0;
}
