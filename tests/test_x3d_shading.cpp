// X3D shading as a browser does it and as glTF draws it (issue 15): a face set without a Normal node gets
// the normals an X3D browser makes (creaseAngle, normalPerVertex), and a mesh without normals is written
// to X3D flat, as glTF draws it.
#include "io/x3d_crease_normals.hpp"
#include "io/x3d_polygons.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// An octagonal prism's side, 8 quads around the z axis (45 degrees between neighbours), as an IndexedFaceSet.
std::string prism(const std::string& fields) {
    std::string points, index;
    for (int k = 0; k < 8; ++k) {
        const double angle = k * M_PI / 4;
        points += std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0 " +
                  std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 1 ";
        const int a = 2 * k, b = 2 * k + 1, c = 2 * ((k + 1) % 8) + 1, d = 2 * ((k + 1) % 8);
        index += std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + " " + std::to_string(b) + " -1 ";
    }
    return "<X3D><Scene><Shape><IndexedFaceSet " + fields + " coordIndex='" + index + "'><Coordinate point='" + points +
           "'/></IndexedFaceSet></Shape></Scene></X3D>";
}

Primitive readOnly(const std::filesystem::path& file) {
    const Scene scene = readScene(file);
    REQUIRE(scene.meshes.size() == 1);
    REQUIRE(scene.meshes[0].primitives.size() == 1);
    return scene.meshes[0].primitives[0];
}

}  // namespace

TEST_CASE("Creased normals equal the mean of the faces within the angle, where many faces share a normal",
          "[io][x3d]") {
    // A folded fan: 24 triangles about a centre, the first 12 in the plane z = 0 and the rest bent up along a fold
    // (many faces of one normal at the centre and on the fold), with a few quads; checked against the definition,
    // summed face by face.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    std::vector<double> points = {0, 0, 0};
    constexpr int kRim = 24;
    for (int k = 0; k <= kRim; ++k) {
        const double angle = 2 * M_PI * k / kRim;
        points.insert(points.end(), {std::cos(angle), std::sin(angle), k > kRim / 2 ? 0.4 + jitter(random) : 0.0});
    }
    std::vector<std::vector<std::int64_t>> faces;
    for (int k = 1; k <= kRim; ++k) faces.push_back({0, k, k + 1});
    faces.push_back({1, 3, 5, 7});
    faces.push_back({13, 15, 17, 19});
    auto point = [&](std::int64_t p) { return Eigen::Vector3d(points[3 * p], points[3 * p + 1], points[3 * p + 2]); };
    std::vector<Eigen::Vector3d> unit;
    for (const auto& face : faces) {
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < face.size(); ++k) normal += point(face[k]).cross(point(face[(k + 1) % face.size()]));
        unit.push_back(normal.normalized());
    }
    for (const double creaseAngle : {0.0, 0.01, 0.3, 0.8, 1.6, 3.2}) {
        const auto [normals, cornerNormal] = creasedNormals(faces, points, creaseAngle, true);
        std::size_t corner = 0;
        for (std::size_t f = 0; f < faces.size(); ++f)
            for (const std::int64_t p : faces[f]) {
                Eigen::Vector3d sum = Eigen::Vector3d::Zero();
                for (std::size_t g = 0; g < faces.size(); ++g)
                    if (std::count(faces[g].begin(), faces[g].end(), p) &&
                        (g == f || unit[f].dot(unit[g]) > std::cos(creaseAngle)))
                        sum += unit[g];
                const std::int64_t n = cornerNormal[corner++];
                const Eigen::Vector3d made(normals[std::size_t(3 * n)], normals[std::size_t(3 * n + 1)],
                                           normals[std::size_t(3 * n + 2)]);
                CHECK((made - sum.normalized()).norm() < 1e-12);
            }
        CHECK(corner == cornerNormal.size());
    }
}

TEST_CASE("X3D face sets without normals are shaded as the browser would: creaseAngle and normalPerVertex", "[io][x3d]") {
    TemporaryFolder folder;
    SECTION("creaseAngle 0 (the default) is flat: no normals, as glTF draws a mesh without them") {
        writeTextFile(folder / "flat.x3d", prism(""));
        const Primitive flat = readOnly(folder / "flat.x3d");
        CHECK(flat.normals.empty());
        CHECK(flat.positions.size() == 16);
    }
    SECTION("a creaseAngle above the 45 degrees between faces is smooth: each point's normal points away from the axis") {
        writeTextFile(folder / "smooth.x3d", prism("creaseAngle='1'"));
        const Primitive smooth = readOnly(folder / "smooth.x3d");
        REQUIRE(smooth.normals.size() == smooth.positions.size());
        CHECK(smooth.positions.size() == 16);  // one vertex a point: the normals are shared
        for (std::size_t v = 0; v < smooth.positions.size(); ++v) {
            const Eigen::Vector3d radial(smooth.positions[v].x(), smooth.positions[v].y(), 0);
            CHECK((smooth.normals[v] - radial.normalized()).norm() < 1e-6);
        }
    }
    SECTION("a creaseAngle below it keeps the edges: each corner has its face's normal") {
        writeTextFile(folder / "creased.x3d", prism("creaseAngle='0.5'"));
        const Primitive creased = readOnly(folder / "creased.x3d");
        REQUIRE(creased.normals.size() == creased.positions.size());
        CHECK(creased.positions.size() == 32);  // each point on two faces, with two normals
        for (const Triangle& t : creased.triangles) {
            const Eigen::Vector3d face =
                (creased.positions[t[1]] - creased.positions[t[0]]).cross(creased.positions[t[2]] - creased.positions[t[0]]).normalized();
            for (std::uint32_t v : t) CHECK((creased.normals[v] - face).norm() < 1e-6);
        }
    }
    SECTION("normalPerVertex='false' is flat whatever the creaseAngle") {
        writeTextFile(folder / "faces.x3d", prism("creaseAngle='3' normalPerVertex='false'"));
        CHECK(readOnly(folder / "faces.x3d").normals.empty());
    }
    SECTION("an IndexedTriangleSet is smooth across its shared points, flat with normalPerVertex='false'") {
        const std::string triangles = "<Coordinate point='0 0 0 1 0 0 0 1 0 0 0 1'/></IndexedTriangleSet></Shape></Scene></X3D>";
        writeTextFile(folder / "its.x3d", "<X3D><Scene><Shape><IndexedTriangleSet index='0 2 1 0 1 3'>" + triangles);
        const Primitive its = readOnly(folder / "its.x3d");
        REQUIRE(its.normals.size() == 4);
        CHECK((its.normals[0] - Eigen::Vector3d(0, -1, -1).normalized()).norm() < 1e-6);  // between -z and -y
        writeTextFile(folder / "its_flat.x3d",
                      "<X3D><Scene><Shape><IndexedTriangleSet normalPerVertex='false' index='0 2 1 0 1 3'>" + triangles);
        CHECK(readOnly(folder / "its_flat.x3d").normals.empty());
    }
}

TEST_CASE("A mesh without normals is written to X3D flat, as glTF draws it", "[io][x3d]") {
    TemporaryFolder folder;
    writeTextFile(folder / "flat.x3d", prism(""));
    const Scene scene = readScene(folder / "flat.x3d");
    writeScene(scene, folder / "again.x3d");
    const std::string text = readTextFile(folder / "again.x3d");
    CHECK_THAT(text, Catch::Contains("normalPerVertex='false'"));
    CHECK(readOnly(folder / "again.x3d").normals.empty());  // and read back flat
    writeTextFile(folder / "smooth.x3d", prism("creaseAngle='1'"));
    writeScene(readScene(folder / "smooth.x3d"), folder / "smooth_again.x3d");
    CHECK_THAT(readTextFile(folder / "smooth_again.x3d"), !Catch::Contains("normalPerVertex='false'"));
}

TEST_CASE("X3D output leaves a mesh's normals to the browser where a creaseAngle makes them, and writes them where "
          "none does",
          "[io][x3d]") {
    TemporaryFolder folder;
    auto normalsAgree = [](const Primitive& a, const Primitive& b) {
        REQUIRE(a.triangles.size() == b.triangles.size());
        double worst = 0;
        for (std::size_t t = 0; t < a.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, (a.normals[a.triangles[t][k]] - b.normals[b.triangles[t][k]]).norm());
        return worst;
    };
    SECTION("the creased prism, the teapot's patches at 0.5") {
        writeTextFile(folder / "prism.x3d", prism("creaseAngle='0.5'"));
        const Scene scene = readScene(folder / "prism.x3d");
        writeScene(scene, folder / "again.x3d");
        CHECK_THAT(readTextFile(folder / "again.x3d"), !Catch::Contains("<Normal"));
        CHECK(normalsAgree(scene.meshes[0].primitives[0], readOnly(folder / "again.x3d")) < 3.5e-3);
        const Scene teapot = readScene(modelPath("xj3d_cad_teapot/teapot.x3d"));
        writeScene(teapot, folder / "teapot.x3d");
        const std::string text = readTextFile(folder / "teapot.x3d");
        CHECK_THAT(text, Catch::Contains("creaseAngle='0.5'"));
        CHECK_THAT(text, !Catch::Contains("<Normal"));
        // Its triangles of zero area (32, at its poles) are written in shapes of their own, without normals.
        auto drawing = [](const Scene& scene) {
            std::vector<Primitive> primitives;
            for (const Mesh& mesh : scene.meshes)
                for (const Primitive& primitive : mesh.primitives) {
                    const auto split = withoutZeroAreaTriangles(primitive);
                    if (!split || !split->first.triangles.empty())
                        primitives.push_back(split ? split->first : primitive);
                }
            return primitives;
        };
        const std::vector<Primitive> before = drawing(teapot), after = drawing(readScene(folder / "teapot.x3d"));
        REQUIRE(after.size() == before.size());
        for (std::size_t p = 0; p < before.size(); ++p) CHECK(normalsAgree(before[p], after[p]) < 3.5e-3);
    }
    SECTION("normals of quads: the quads written again; normals no creaseAngle gives: written") {
        // The smooth prism's normals are the means of its quads', which its triangles would weight otherwise:
        // the triangles are joined into the quads they fan over again (x3d_polygons.hpp).
        writeTextFile(folder / "prism.x3d", prism("creaseAngle='1'"));
        Scene scene = readScene(folder / "prism.x3d");
        writeScene(scene, folder / "smooth.x3d");
        const std::string smooth = readTextFile(folder / "smooth.x3d");
        CHECK_THAT(smooth, !Catch::Contains("<Normal"));
        CHECK_THAT(smooth, Catch::Contains("<IndexedFaceSet solid='true' creaseAngle='4' coordIndex='14 12 13 15 -1 "));
        CHECK(normalsAgree(scene.meshes[0].primitives[0], readOnly(folder / "smooth.x3d")) < 3.5e-3);
        // Normals a modeller tilted.
        for (Eigen::Vector3d& n : scene.meshes[0].primitives[0].normals) n = (n + Eigen::Vector3d(0, 0, 0.3)).normalized();
        writeScene(scene, folder / "tilted.x3d");
        CHECK_THAT(readTextFile(folder / "tilted.x3d"), Catch::Contains("<Normal"));
        CHECK(normalsAgree(scene.meshes[0].primitives[0], readOnly(folder / "tilted.x3d")) < 1e-3);
    }
}

TEST_CASE("Triangles that fan over a convex polygon are joined into it: planar ones where flat, bent where smoothed",
          "[io][x3d]") {
    using x3d::fanPolygons;
    // A regular hexagon cut as a fan from corner 0, then a dart (concave at corner 8) cut the same way.
    std::vector<Eigen::Vector3d> p;
    for (int k = 0; k < 6; ++k) p.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0});
    p.insert(p.end(), {{10, 0, 0}, {12, -1, 0}, {11, 0, 0}, {12, 1, 0}});
    std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {6, 7, 8}, {6, 8, 9}};
    CHECK(fanPolygons(triangles, p, x3d::kMostTurnOfFlatPolygon) ==
          std::vector<std::vector<std::uint32_t>>{{0, 1, 2, 3, 4, 5}, {6, 7, 8}, {6, 8, 9}});
    // Out of order, or not from the first corner: no fan.
    CHECK(fanPolygons({{0, 2, 3}, {0, 1, 2}}, p, x3d::kMostTurnOfFlatPolygon).size() == 2);
    CHECK(fanPolygons({{0, 1, 2}, {2, 3, 0}}, p, x3d::kMostTurnOfFlatPolygon).size() == 2);
    // A quad bent by 0.01 radians about its diagonal: two faces where flat, one where smoothed.
    std::vector<Eigen::Vector3d> bent = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.01 * std::sqrt(2.0)}};
    CHECK(fanPolygons({{0, 1, 2}, {0, 2, 3}}, bent, x3d::kMostTurnOfFlatPolygon).size() == 2);
    CHECK(fanPolygons({{0, 1, 2}, {0, 2, 3}}, bent, x3d::kMostTurnOfSmoothedPolygon).size() == 1);
    // A triangle of zero area (corner 3 on the edge from 0 to 2) joins nothing.
    std::vector<Eigen::Vector3d> flat = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
    CHECK(fanPolygons({{0, 1, 2}, {0, 2, 3}}, flat, x3d::kMostTurnOfSmoothedPolygon).size() == 2);
}

TEST_CASE("X3D face sets of quads come out as quads: smaller than triangles, and the browser's normals as they were",
          "[io][x3d]") {
    TemporaryFolder folder;
    // A ring of 40 x 12 planar quads (trapezoids between meridians at uneven longitudes, no symmetry to find),
    // flat (creaseAngle 0), then smooth (creaseAngle 1: normals the means of the quads', which triangles would
    // weigh otherwise).
    std::string points, index;
    const int around = 40, across = 12;
    for (int i = 0; i < around; ++i) {
        const double u = 2 * M_PI * (i + 0.3 * std::sin(i * 1.7)) / around;
        for (int j = 0; j < across; ++j) {
            const double v = 2 * M_PI * j / across, r = 0.5 * (1 + 0.3 * std::sin(v));
            const double x = (2 + r * std::cos(v)) * std::cos(u), y = (2 + r * std::cos(v)) * std::sin(u);
            points += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(r * std::sin(v)) + " ";
            const int a = i * across + j, b = ((i + 1) % around) * across + j;
            const int c = ((i + 1) % around) * across + (j + 1) % across, d = i * across + (j + 1) % across;
            index += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(d) +
                     " -1 ";
        }
    }
    for (const char* crease : {"0", "1"}) {
        INFO("creaseAngle " << crease);
        const std::string input =
            "<X3D><Scene><Shape><Appearance><Material/></Appearance><IndexedFaceSet creaseAngle='" +
            std::string(crease) + "' coordIndex='" + index + "'><Coordinate point='" + points +
            "'/></IndexedFaceSet></Shape></Scene></X3D>";
        writeTextFile(folder / "ring.x3d", input);
        const Primitive read = readOnly(folder / "ring.x3d");
        compressFile(folder / "ring.x3d", folder / "out.x3d");
        const std::string text = readTextFile(folder / "out.x3d");
        const std::size_t from = text.find("coordIndex='") + 12;
        REQUIRE(from > 12);
        const std::string faces = text.substr(from, text.find('\'', from) - from);
        CHECK(occurrences(faces, "-1") == std::size_t(around * across));  // every quad one face
        CHECK_THAT(text, !Catch::Contains("<Normal"));
        CHECK(text.size() < input.size());
        const Primitive again = readOnly(folder / "out.x3d");
        REQUIRE(again.triangles.size() == read.triangles.size());
        CHECK(again.normals.empty() == read.normals.empty());
        CHECK(decompressFile(folder / "out.x3d", folder / "flat.glb", folder / "ring.x3d").verified);
    }
}
