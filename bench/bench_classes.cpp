// Congruence classification (issue 5): time and peak memory for a generated scene of N tiles: 40 distinct
// small parts (random convex solids of about 30 triangles, 8 of them 1% larger copies of others, which
// must stay apart) placed at random rotations, mirrors and positions on a grid, baked into one mesh.
//   bench_classes N        one row of the table (run each N in its own process for its peak memory)
#include "sample_scenes.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/detail/solids.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <sys/resource.h>

using namespace symcompress;

namespace {

std::vector<TriangleMesh> distinctParts(std::mt19937_64& random) {
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<TriangleMesh> parts;
    for (int k = 0; k < 32; ++k) {
        std::vector<Eigen::Vector3d> points;
        while (points.size() < 16) {
            const Eigen::Vector3d p = samples::drawnVector([&] { return uniform(random); });
            if (p.norm() > 0.5 && p.norm() < 1) points.push_back(p.normalized());  // on the sphere: convex position
        }
        parts.push_back(triangulateFaces(makeConvexPolyhedron(points)));
    }
    for (int k = 0; k < 8; ++k) {  // scaled copies: not congruent to their originals
        TriangleMesh scaled = parts[k];
        for (auto& p : scaled.positions) p *= 1.01;
        parts.push_back(scaled);
    }
    return parts;
}

double peakMemoryMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_classes N\n");
        return 2;
    }
    const std::size_t tileCount = std::stoul(argv[1]);
    std::mt19937_64 random(2026);
    const std::vector<TriangleMesh> parts = distinctParts(random);
    std::normal_distribution<double> normal;
    std::uniform_int_distribution<std::size_t> pick(0, parts.size() - 1);

    WorldPrimitive soup;
    soup.primitive.material = 0;
    const auto side = std::size_t(std::ceil(std::cbrt(double(tileCount))));
    for (std::size_t t = 0; t < tileCount; ++t) {
        const TriangleMesh& part = parts[pick(random)];
        Eigen::Matrix3d linear =
            samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
        const bool mirror = t % 4 == 3;
        if (mirror) linear.col(0) *= -1;
        const Eigen::Vector3d cell(double(t % side), double(t / side % side), double(t / side / side));
        const auto offset = std::uint32_t(soup.primitive.positions.size());
        for (const auto& p : part.positions) soup.primitive.positions.push_back((linear * p + 3.0 * cell).cast<float>().cast<double>());
        for (auto tri : part.triangles) {
            if (mirror) std::swap(tri[1], tri[2]);
            soup.primitive.triangles.push_back({tri[0] + offset, tri[1] + offset, tri[2] + offset});
        }
    }
    const std::vector<WorldPrimitive> scene{std::move(soup)};

    const auto start = std::chrono::steady_clock::now();
    const std::vector<Tile> tiles = splitIntoTiles(scene);
    const auto split = std::chrono::steady_clock::now();
    const TileClassification classification = classifyTiles(tiles);
    const auto end = std::chrono::steady_clock::now();
    std::size_t repeated = 0;
    for (const auto& c : classification.classes) repeated += c.members.size() > 1 ? c.members.size() : 0;
    std::printf("| %zu | %zu | %zu | %.2f | %.2f | %.0f |\n", tiles.size(), scene[0].primitive.triangles.size(),
                classification.classes.size(), std::chrono::duration<double>(split - start).count(),
                std::chrono::duration<double>(end - split).count(), peakMemoryMiB());
    return classification.classes.size() == parts.size() || tileCount < 200 ? 0 : 1;
}
