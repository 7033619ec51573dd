// Speed on the cases of issue 18, each a row of a table:
//   bench_level level [PIECES]      a game level of small architectural pieces (boxes, wedges, steps, most
//                                   with several symmetries) in one mesh: split into tiles and classified
//   bench_level uneven [TOLERANCE]  detect on an ellipsoid of revolution tessellated unevenly (2.5e-4)
//   bench_level roller [TOLERANCE]  detect on a roller of 1232 triangles whose tessellation is symmetric
//                                   within 1e-4 of its diagonal but not 1e-5 (a near miss at 1e-5)
//   bench_level mirror [TRIANGLES]  detect on a torus-like shape with one mirror plane, irregular rows,
//                                   a random orientation, float32 (233k triangles by default)
// Every generator is deterministic.
#include "bench_meshes.hpp"
#include "sample_scenes.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/symmetry.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

using namespace symcompress;

namespace {

constexpr double kPi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void addQuad(TriangleMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
}

// An axis-aligned box centred on the origin, each face a grid of quads of about `cell` at most (a level's
// tessellation), counter-clockwise seen from outside.
TriangleMesh gridBox(const Eigen::Vector3d& size, double cell) {
    TriangleMesh box;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int nu = std::max(1, int(std::ceil(size[u] / cell))),
                      nv = std::max(1, int(std::ceil(size[v] / cell)));
            const auto first = std::uint32_t(box.positions.size());
            for (int i = 0; i <= nu; ++i)
                for (int j = 0; j <= nv; ++j) {
                    Eigen::Vector3d p;
                    p[axis] = side * size[axis] / 2;
                    p[u] = size[u] * (double(i) / nu - 0.5);
                    p[v] = size[v] * (double(j) / nv - 0.5);
                    box.positions.push_back(p);
                }
            auto at = [&](int i, int j) { return first + std::uint32_t(i * (nv + 1) + j); };
            for (int i = 0; i < nu; ++i)
                for (int j = 0; j < nv; ++j) {
                    if (side > 0)
                        addQuad(box, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    else
                        addQuad(box, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
                }
        }
    return box;
}

// A closed prism: the polygon `profile` (x, z; counter-clockwise, star-shaped from its first point)
// extruded along y by `length`, the caps fanned from the first point.
TriangleMesh extrudedProfile(const std::vector<Eigen::Vector2d>& profile, double length) {
    TriangleMesh prism;
    const auto n = std::uint32_t(profile.size());
    for (double y : {length / 2, -length / 2})
        for (const Eigen::Vector2d& p : profile) prism.positions.emplace_back(p.x(), y, p.y());
    // Counter-clockwise in (x, z) is clockwise seen from +y: the front cap (y = +length / 2) is reversed.
    for (std::uint32_t i = 1; i + 1 < n; ++i) {
        prism.triangles.push_back({0, i + 1, i});
        prism.triangles.push_back({n, n + i, n + i + 1});
    }
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = (i + 1) % n;
        addQuad(prism, i, j, n + j, n + i);
    }
    return prism;
}

// A wedge (ramp): a right triangle of run x rise, extruded.
TriangleMesh wedge(double run, double rise, double length) {
    return extrudedProfile({{run / 2, -rise / 2}, {run / 2, rise / 2}, {-run / 2, -rise / 2}}, length);
}

// A flight of `count` steps, extruded: star-shaped from its lower back corner.
TriangleMesh steps(int count, double tread, double riser, double width) {
    const double run = count * tread, rise = count * riser;
    std::vector<Eigen::Vector2d> profile{{run / 2, -rise / 2}, {run / 2, rise / 2}};
    for (int k = count - 1; k >= 0; --k) {
        profile.emplace_back(-run / 2 + k * tread, -rise / 2 + (k + 1) * riser);
        profile.emplace_back(-run / 2 + k * tread, -rise / 2 + k * riser);
    }
    return extrudedProfile(profile, width);
}

// The catalogue of a level: distinct pieces of modular sizes (quarter metres), boxes the most.
std::vector<TriangleMesh> levelCatalogue(std::mt19937_64& random, int count) {
    std::uniform_int_distribution<int> quarters(1, 16), kind(0, 9), stepCount(2, 6);
    auto size = [&] { return 0.25 * quarters(random); };
    std::vector<TriangleMesh> pieces;
    for (int k = 0; k < count; ++k) {
        const int which = kind(random);
        if (which < 6) {
            Eigen::Vector3d s(size(), size(), size());
            if (which < 2) s.y() = s.x();                 // square section: D4h
            if (which == 0 && k % 3 == 0) s.z() = s.x();  // a cube now and then: Oh
            pieces.push_back(gridBox(s, 1.0));
        } else if (which < 8) {
            const double run = size();
            pieces.push_back(wedge(run, which == 6 ? run : size(), size()));
        } else {
            pieces.push_back(steps(stepCount(random), 0.25, 0.2, size()));
        }
    }
    return pieces;
}

int level(std::size_t pieceCount) {
    std::mt19937_64 random(18);
    const std::vector<TriangleMesh> catalogue = levelCatalogue(random, int(pieceCount / 4));
    std::uniform_int_distribution<std::size_t> pick(0, catalogue.size() - 1);
    std::uniform_int_distribution<int> quarterTurn(0, 3);
    std::uniform_real_distribution<double> yaw(0, 2 * kPi);
    WorldPrimitive soup;
    soup.primitive.material = 0;
    // On a grid of 6 m cells (no two pieces touch), turned about the vertical, now and then by any angle.
    const auto side = std::size_t(std::ceil(std::sqrt(double(pieceCount))));
    for (std::size_t k = 0; k < pieceCount; ++k) {
        const double angle = k % 10 == 9 ? yaw(random) : quarterTurn(random) * kPi / 2;
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        const Eigen::Vector3d at(6.0 * double(k % side), 6.0 * double(k / side), 0);
        TriangleMesh placed = samples::transformed(catalogue[pick(random)], turn, at);
        for (auto& p : placed.positions) p = p.cast<float>().cast<double>();
        samples::appendMesh(soup.primitive, placed);
    }
    const std::vector<WorldPrimitive> scene{std::move(soup)};
    Clock::time_point start = Clock::now();
    const std::vector<Tile> tiles = splitIntoTiles(scene);
    const double split = secondsSince(start);
    start = Clock::now();
    const TileClassification classification = classifyTiles(tiles);
    const double classify = secondsSince(start);
    std::size_t elements = 0;
    for (const CongruenceClass& c : classification.classes)
        elements += classification.shapes[c.prototype].symmetry.elements.size();
    std::printf("| level | %zu | %zu | %zu | %zu | %.3f | %.3f |\n", tiles.size(), scene[0].primitive.triangles.size(),
                classification.classes.size(), elements, split, classify);
    return 0;
}

// A roller: a cylinder with chamfered ends (16 profile points, 44 sectors: 1232 triangles) whose sector
// angles and ring radii are jittered by about 4e-5 of its diagonal, deterministically.
TriangleMesh roller() {
    const std::vector<Eigen::Vector2d> profile{
        {0, 0},     {0.4, 0},   {0.48, 0.02}, {0.5, 0.08}, {0.5, 0.3},  {0.5, 0.5},   {0.5, 0.7}, {0.5, 0.9},
        {0.5, 1.1}, {0.5, 1.3}, {0.5, 1.5},   {0.5, 1.72}, {0.5, 1.92}, {0.48, 1.98}, {0.4, 2.0}, {0, 2.0}};
    const int sectors = 44;
    TriangleMesh mesh = samples::latheMesh(profile, sectors, Eigen::Vector3d::Zero());
    std::mt19937_64 random(1232);
    std::uniform_real_distribution<double> jitter(-1, 1);
    const double diagonal = std::sqrt(1.0 + 4.0), amount = 4e-5 * diagonal;
    std::vector<double> sectorTurn(sectors);
    for (double& turn : sectorTurn) turn = amount * jitter(random) / 0.5;  // radians at the radius 0.5
    for (std::size_t i = 1; i + 1 < mesh.positions.size(); ++i) {
        Eigen::Vector3d& p = mesh.positions[i];
        const int sector = int((i - 1) % sectors);
        const double radius = std::hypot(p.x(), p.y()) + amount * 0.3 * jitter(random);
        const double angle = std::atan2(p.y(), p.x()) + sectorTurn[std::size_t(sector)];
        p = Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle), p.z());
    }
    return mesh;
}

void printGroupRow(const char* name, const TriangleMesh& mesh, double tolerance, const SymmetryGroup& group,
                   double seconds) {
    std::printf("| %s | %zu | %g | %s (%d) | %.4f | %.4f | %.4f | %.4f |\n", name, mesh.triangles.size(), tolerance,
                group.name.c_str(), group.order(), seconds, group.seconds.moments, group.seconds.axes,
                group.seconds.verification);
}

int detectRow(const char* name, const TriangleMesh& mesh, double tolerance) {
    SymmetryOptions options;
    options.tolerance = tolerance;
    const Clock::time_point start = Clock::now();
    const SymmetryGroup group = detectSymmetries(mesh, options);
    printGroupRow(name, mesh, tolerance, group, secondsSince(start));
    return 0;
}

// A torus of irregular rows (each row's angle jittered by a third of the spacing) whose tube radius varies
// with cos u and sin v: one mirror plane (u -> -u) of the surface, none of the tessellation; randomly
// turned, rounded to float32.
TriangleMesh mirrorShape(std::size_t triangles) {
    const std::size_t columns = 116, rows = triangles / (2 * columns);
    std::mt19937_64 random(233);
    std::uniform_real_distribution<double> jitter(-1.0 / 3, 1.0 / 3);
    std::vector<double> rowAngle(rows);
    for (std::size_t i = 0; i < rows; ++i) rowAngle[i] = 2 * kPi * (double(i) + jitter(random)) / double(rows);
    auto radius = [](double u, double v) {
        return 0.3 + 0.04 * std::cos(u) + 0.02 * std::cos(2 * u) + 0.03 * std::sin(v) +
               0.02 * std::sin(2 * v) * std::cos(u);
    };
    std::normal_distribution<double> normal;
    const Eigen::Matrix3d turn =
        samples::drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
    TriangleMesh mesh = bench::torusOnRows(rowAngle, columns, radius);
    for (Eigen::Vector3d& p : mesh.positions) p = (turn * p).cast<float>().cast<double>();
    return mesh;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "";
    if (which == "level") {
        std::printf("| case | tiles | triangles | classes | group elements (prototypes) | split s | classify s |\n");
        std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        return level(argc > 2 ? std::stoul(argv[2]) : 1200);
    }
    if (which == "roller" || which == "mirror" || which == "uneven") {
        std::printf("| case | triangles | tolerance | group | total s | moments s | axes s | verification s |\n");
        std::printf("| --- | ---: | ---: | :---: | ---: | ---: | ---: | ---: |\n");
        if (which == "roller") {
            const TriangleMesh mesh = roller();
            if (argc > 2) return detectRow("roller", mesh, std::stod(argv[2]));
            for (double tolerance : {1e-5, 3e-5, 1e-4}) detectRow("roller", mesh, tolerance);
            return 0;
        }
        if (which == "uneven") return detectRow("uneven", samples::unevenEllipsoid(68, 64), argc > 2 ? std::stod(argv[2]) : 2.5e-4);
        return detectRow("mirror", mirrorShape(argc > 2 ? std::stoul(argv[2]) : 232000), 1e-5);
    }
    std::fprintf(stderr,
                 "usage: bench_level level [PIECES] | roller [TOLERANCE] | mirror [TRIANGLES] | uneven [TOLERANCE]\n");
    return 2;
}
