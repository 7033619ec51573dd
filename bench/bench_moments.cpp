// Throughput of the exact moment coefficients (issue 3): seconds and triangles per second for meshes of
// 10k to 10M triangles, orders 2..8 and 2..16, on 1 and 2 threads.
//   bench_moments [max-triangles]      (default 10000000)
#include "bench_meshes.hpp"
#include "symcompress/detail/moments.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

using namespace symcompress;

namespace {

// A bumpy torus: no symmetry in the bumps.
TriangleMesh bumpyTorus(std::size_t triangles) {
    return bench::torusGrid(triangles, 1, [](double u, double v) { return 0.4 + 0.02 * std::sin(7 * u + 3 * v) * std::cos(5 * v); });
}

double secondsFor(const TriangleMesh& mesh, const MomentOptions& options) {
    double best = 1e300;
    // The best of a few runs for small meshes, one run for the large ones.
    const int runs = mesh.triangles.size() < 2000000 ? 3 : 1;
    for (int run = 0; run < runs; ++run) {
        const auto start = std::chrono::steady_clock::now();
        const MomentCoefficients coefficients = computeMomentCoefficients(mesh, options);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!(coefficients.area > 0)) std::abort();  // keeps the work observable
        best = std::min(best, seconds);
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    const std::size_t largest = argc > 1 ? std::stoul(argv[1]) : 10000000;
    std::printf("| triangles | orders | threads | seconds | triangles/s |\n");
    std::printf("| ---: | :---: | ---: | ---: | ---: |\n");
    for (std::size_t triangles = 10000; triangles <= largest; triangles *= 10) {
        const TriangleMesh mesh = bumpyTorus(triangles);
        for (int maxOrder : {8, 16})
            for (int threads : {1, 2}) {
                MomentOptions options;
                options.maxOrder = maxOrder;
                options.threads = threads;
                const double seconds = secondsFor(mesh, options);
                std::printf("| %zu | 2..%d | %d | %.4f | %.3g |\n", mesh.triangles.size(), maxOrder, threads, seconds,
                            double(mesh.triangles.size()) / seconds);
                std::fflush(stdout);
            }
    }
}
