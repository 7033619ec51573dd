// Single-shape detection (issue 4): robustness as in paper Fig. 4, and speed by mesh size.
//   bench_symmetry robustness MODELS_DIR [DATA_FILE]   angular error of the axis found under vertex noise
//                                                      and triangle deletion; DATA_FILE gets a gnuplot table
//   bench_symmetry speed [MAX_TRIANGLES]               detection time and its parts, 10k .. 1M triangles
#include "bench_meshes.hpp"
#include "sample_scenes.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/symmetry.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

using namespace symcompress;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The element of `kind` (and fold, for rotations) whose axis is nearest `axis`: the angle in degrees, or
// -1 when the group has none.
double axisError(const SymmetryGroup& group, Symmetry::Kind kind, int fold, const Eigen::Vector3d& axis) {
    double best = -1;
    for (const Symmetry& s : group.elements) {
        if (s.kind != kind || (kind == Symmetry::Kind::Rotation && s.fold != fold)) continue;
        const double angle = std::acos(std::min(1.0, std::abs(s.axis.dot(axis)))) * 180 / kPi;
        if (best < 0 || angle < best) best = angle;
    }
    return best;
}

TriangleMesh withNoise(TriangleMesh mesh, double amplitude, std::mt19937_64& random) {
    std::normal_distribution<double> normal(0, amplitude / std::sqrt(3.0));  // rms displacement = amplitude
    for (auto& p : mesh.positions) p += samples::drawnVector([&] { return normal(random); });
    return mesh;
}

TriangleMesh withDeletions(TriangleMesh mesh, double share, std::mt19937_64& random) {
    std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), random);
    mesh.triangles.resize(std::size_t(std::llround(double(mesh.triangles.size()) * (1 - share))));
    return mesh;
}

int robustness(const std::string& models, const std::string& dataFile) {
    struct Model {
        const char* name;
        const char* file;
        Symmetry::Kind kind;
        int fold;
    };
    const Model list[] = {
        {"coffee cup (mirror)", "xj3d_coffee_cup/coffeeCup.x3d", Symmetry::Kind::Mirror, 0},
        {"torus knot (3-fold axis)", "vulkan_torusknot/torusknot.gltf", Symmetry::Kind::Rotation, 3},
        {"menger sponge (4-fold axis)", "menger_sponge/Menger_sponge-Binary.stl", Symmetry::Kind::Rotation, 4},
    };
    const double noises[] = {0, 0.0005, 0.001, 0.002, 0.005, 0.01};
    const double deletions[] = {0, 0.01, 0.02, 0.03, 0.05};
    SymmetryOptions options;
    options.tolerance = 0.03;  // loose: the perturbed shapes are symmetric only approximately
    std::ofstream data;
    if (!dataFile.empty()) data.open(dataFile);
    std::printf("Angular error (degrees) of the axis found, at --tolerance %g; '-' when not found.\n\n", options.tolerance);
    std::printf("| model | perturbation | %s |\n", "error (deg) for each level");
    for (const Model& model : list) {
        const TriangleMesh mesh = worldMesh(readScene(models + "/" + model.file));
        // The exact axis: from the unperturbed shape at the default tolerance.
        const SymmetryGroup exact = detectSymmetries(mesh);
        Eigen::Vector3d axis = Eigen::Vector3d::Zero();
        for (const Symmetry& s : exact.elements)
            if (s.kind == model.kind && (model.kind != Symmetry::Kind::Rotation || s.fold == model.fold)) axis = s.axis;
        if (axis.isZero()) {
            std::printf("| %s | the unperturbed shape lacks the symmetry | |\n", model.name);
            continue;
        }
        auto row = [&](const char* what, const double* levels, std::size_t count, bool noise) {
            std::printf("| %s | %s |", model.name, what);
            if (data.is_open()) data << "# " << model.name << ", " << what << "\n";
            for (std::size_t i = 0; i < count; ++i) {
                std::mt19937_64 random(1234 + i);
                Eigen::AlignedBox3d box;
                for (const auto& p : mesh.positions) box.extend(p);
                const TriangleMesh perturbed = noise ? withNoise(mesh, levels[i] * box.diagonal().norm(), random)
                                                     : withDeletions(mesh, levels[i], random);
                const double error = axisError(detectSymmetries(perturbed, options), model.kind, model.fold, axis);
                if (error < 0) std::printf(" %g%%: - |", 100 * levels[i]);
                else std::printf(" %g%%: %.2e |", 100 * levels[i], error);
                if (data.is_open() && error >= 0) data << 100 * levels[i] << " " << error << "\n";
                std::fflush(stdout);
            }
            std::printf("\n");
            if (data.is_open()) data << "\n\n";
        };
        row("vertex noise (rms, % of diagonal)", noises, std::size(noises), true);
        row("triangles deleted (%)", deletions, std::size(deletions), false);
    }
    return 0;
}

// A torus with 8 bumps around its axis (group D8h), as a grid of about `triangles` triangles.
TriangleMesh bumpyTorus(std::size_t triangles) {
    return bench::torusGrid(triangles, 8, [](double u, double v) { return 0.4 + 0.05 * std::cos(8 * u) * std::cos(v); });
}

int speed(std::size_t largest) {
    std::printf("| triangles | group | total s | moments s | axes s | verification s |\n");
    std::printf("| ---: | :---: | ---: | ---: | ---: | ---: |\n");
    for (std::size_t triangles : {10000, 100000, 233000, 1000000}) {
        if (triangles > largest) break;
        TriangleMesh mesh = bumpyTorus(triangles);
        for (auto& p : mesh.positions) p = p.cast<float>().cast<double>();
        const auto start = std::chrono::steady_clock::now();
        const SymmetryGroup group = detectSymmetries(mesh);
        const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("| %zu | %s (%d) | %.3f | %.3f | %.3f | %.3f |\n", mesh.triangles.size(), group.name.c_str(), group.order(),
                    total, group.seconds.moments, group.seconds.axes, group.seconds.verification);
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "robustness" && argc > 2) return robustness(argv[2], argc > 3 ? argv[3] : "");
    if (mode == "speed") return speed(argc > 2 ? std::stoul(argv[2]) : 1000000);
    std::fprintf(stderr, "usage: bench_symmetry robustness MODELS_DIR [DATA_FILE] | bench_symmetry speed [MAX_TRIANGLES]\n");
    return 2;
}
