// X3D's geometry nodes that do not list their faces one by one (triangle strips and fans, quads, ElevationGrid,
// Extrusion) are read as the browser draws them (issue 15: never lossier): checked against what each node's
// definition gives independently (triangles by point, a surface's area and enclosed volume, a tube's radius),
// and rendered against the input in X_ITE.
#include "symcompress/io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

std::string sceneX3d(const std::string& shapes) {
    // The Full profile: X_ITE loads the CADGeometry component (the quad sets) only where the file asks for it.
    return "<X3D profile='Full' version='3.3'><Scene>" + shapes + "</Scene></X3D>";
}

std::string shapeX3d(const std::string& geometry, const std::string& appearance = "") {
    return "<Shape>" + appearance + geometry + "</Shape>";
}

std::string joinedWarnings(const std::vector<std::string>& warnings) {
    std::string out;
    for (const std::string& warning : warnings) out += warning + "\n";
    return out;
}

Primitive readOne(const TemporaryFolder& folder, const std::string& geometry) {
    writeTextFile(folder / "node.x3d", sceneX3d(shapeX3d(geometry)));
    const Scene scene = readScene(folder / "node.x3d");
    INFO(joinedWarnings(scene.warnings));
    REQUIRE(scene.meshes.size() == 1);
    REQUIRE(scene.meshes[0].primitives.size() == 1);
    return scene.meshes[0].primitives[0];
}

// The triangles as the indices of the points they join (`points` in the file's order), each turned to start at
// its least index, so that the order of corners within a triangle is compared, not where it starts.
std::multiset<std::array<int, 3>> trianglesByPoint(const Primitive& primitive,
                                                   const std::vector<Eigen::Vector3d>& points) {
    std::multiset<std::array<int, 3>> out;
    for (const Triangle& t : primitive.triangles) {
        std::array<int, 3> corners{};
        for (std::size_t k = 0; k < 3; ++k)
            corners[k] = int(
                std::find_if(points.begin(), points.end(),
                             [&](const Eigen::Vector3d& p) { return (p - primitive.positions[t[k]]).norm() < 1e-12; }) -
                points.begin());
        std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
        out.insert(corners);
    }
    return out;
}

// The area of the surface, and the volume it encloses (the divergence theorem: positive where the triangles
// turn counter-clockwise seen from outside).
std::pair<double, double> areaAndVolume(const Primitive& primitive) {
    double area = 0, volume = 0;
    for (const Triangle& t : primitive.triangles) {
        const Eigen::Vector3d &a = primitive.positions[t[0]], &b = primitive.positions[t[1]],
                              &c = primitive.positions[t[2]];
        area += (b - a).cross(c - a).norm() / 2;
        volume += a.dot(b.cross(c)) / 6;
    }
    return {area, volume};
}

std::string numbersText(const std::vector<double>& values) {
    std::ostringstream text;
    text.precision(17);
    for (double v : values) text << v << ' ';
    return text.str();
}

// The points of a regular polygon of `corners` corners and radius `radius` in the plane, closed (its first point
// again at the end), as an Extrusion's crossSection: clockwise, as X3D's default square runs, so that the
// surface faces out.
std::string circleText(int corners, double radius) {
    std::vector<double> values;
    for (int i = 0; i <= corners; ++i) {
        const double angle = -2 * M_PI * (i % corners) / corners;
        values.insert(values.end(), {radius * std::cos(angle), radius * std::sin(angle)});
    }
    return numbersText(values);
}

// The area of a regular polygon of `corners` corners on a circle of radius `radius`.
double polygonArea(int corners, double radius) { return corners * radius * radius * std::sin(2 * M_PI / corners) / 2; }

// `input` compressed to `output` by the command-line tool, which must succeed; what it printed.
std::string compressWithTool(const fs::path& input, const fs::path& output) {
    const CommandResult compressed =
        runCommand(quoted(SYMCOMPRESS_CLI) + " -q " + quoted(input) + " -o " + quoted(output));
    INFO(compressed.output);
    REQUIRE(compressed.status == 0);
    return compressed.output;
}

// `output` renders as `reference` in one `mode` (render_compare.sh, views a, b and c).
void checkRendersIn(const std::string& mode, const fs::path& reference, const fs::path& output) {
    const CommandResult result = renderCompare(reference, output, mode, "abc");
    INFO(mode << ": " << result.output);
    CHECK(result.status == 0);
}

}  // namespace

TEST_CASE("X3D's triangle strips and fans and quad sets are cut as X_ITE cuts them", "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0},
                                                 {2, 0, 0}, {2, 1, 0}, {3, 0, 0}};
    const std::string coordinate = "<Coordinate point='0 0 0 0 1 0 1 0 0 1 1 0 2 0 0 2 1 0 3 0 0'/>";
    using Triangles = std::multiset<std::array<int, 3>>;
    SECTION("a strip's every second triangle turned back, so that all face the same way") {
        // 0 2 4 6 along the bottom, 1 3 5 along the top: the strip 0 1 2 3 4 5 faces -z.
        const Triangles expected = {{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}};
        CHECK(trianglesByPoint(readOne(folder, "<IndexedTriangleStripSet index='0 1 2 3 4 5'>" + coordinate +
                                                   "</IndexedTriangleStripSet>"),
                               points) == expected);
        CHECK(trianglesByPoint(
                  readOne(folder, "<TriangleStripSet stripCount='6'>" + coordinate + "</TriangleStripSet>"), points) ==
              expected);
        // Strips end at -1; one of two corners draws nothing.
        CHECK(trianglesByPoint(readOne(folder, "<IndexedTriangleStripSet index='0 1 2 -1 5 6 -1 3 4 5 6 -1'>" +
                                                   coordinate + "</IndexedTriangleStripSet>"),
                               points) == Triangles{{0, 1, 2}, {3, 4, 5}, {4, 6, 5}});
    }
    SECTION("a fan from its first corner, by index or by count") {
        CHECK(trianglesByPoint(readOne(folder, "<IndexedTriangleFanSet index='0 2 3 1 -1 4 6 5'>" + coordinate +
                                                   "</IndexedTriangleFanSet>"),
                               points) == Triangles{{0, 2, 3}, {0, 3, 1}, {4, 6, 5}});
        CHECK(trianglesByPoint(readOne(folder, "<TriangleFanSet fanCount='4 3'>" + coordinate + "</TriangleFanSet>"),
                               points) == Triangles{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}});
    }
    SECTION("quads cut from their first corner; a QuadSet's leftover corners draw nothing") {
        CHECK(trianglesByPoint(
                  readOne(folder, "<IndexedQuadSet index='0 2 3 1 2 4 5 3 6'>" + coordinate + "</IndexedQuadSet>"),
                  points) == Triangles{{0, 2, 3}, {0, 3, 1}, {2, 4, 5}, {2, 5, 3}});
        CHECK(trianglesByPoint(readOne(folder, "<QuadSet>" + coordinate + "</QuadSet>"), points) ==
              Triangles{{0, 1, 2}, {0, 2, 3}});
    }
    SECTION("ccw='false' turns every triangle") {
        CHECK(trianglesByPoint(
                  readOne(folder, "<TriangleFanSet ccw='false' fanCount='3'>" + coordinate + "</TriangleFanSet>"),
                  points) == Triangles{{0, 2, 1}});
    }
    SECTION("colours per face are per triangle of a strip or fan, per quad of a quad set") {
        const std::string colors = "<Color color='1 0 0 0 1 0 0 0 1 1 1 0'/>";
        const Primitive strip = readOne(folder, "<TriangleStripSet stripCount='6' colorPerVertex='false'>" +
                                                    coordinate + colors + "</TriangleStripSet>");
        const Primitive quad = readOne(folder, "<IndexedQuadSet index='0 2 3 1 2 4 5 3' colorPerVertex='false'>" +
                                                   coordinate + colors + "</IndexedQuadSet>");
        auto colorsOfTriangles = [](const Primitive& primitive) {
            std::vector<Eigen::Vector3d> out;
            for (const Triangle& t : primitive.triangles) {
                for (std::uint32_t v : t) CHECK(primitive.colors[v] == primitive.colors[t[0]]);
                out.push_back(primitive.colors[t[0]].head<3>());
            }
            return out;
        };
        // Red, green, blue, yellow, decoded from sRGB (glTF's COLOR_0 is linear): only the pattern matters here.
        const std::vector<Eigen::Vector3d> stripColors = colorsOfTriangles(strip);
        REQUIRE(stripColors.size() == 4);
        CHECK(std::set<std::vector<double>>{{stripColors[0].x(), stripColors[0].y(), stripColors[0].z()},
                                            {stripColors[1].x(), stripColors[1].y(), stripColors[1].z()},
                                            {stripColors[2].x(), stripColors[2].y(), stripColors[2].z()},
                                            {stripColors[3].x(), stripColors[3].y(), stripColors[3].z()}}
                  .size() == 4);
        const std::vector<Eigen::Vector3d> quadColors = colorsOfTriangles(quad);
        REQUIRE(quadColors.size() == 4);
        CHECK(quadColors[0] == quadColors[1]);
        CHECK(quadColors[2] == quadColors[3]);
        CHECK(quadColors[0] != quadColors[2]);
    }
    SECTION("counts beyond the points: the rest left out, with a warning naming the node") {
        writeTextFile(folder / "long.x3d",
                      sceneX3d(shapeX3d("<TriangleStripSet stripCount='5 4'>" + coordinate + "</TriangleStripSet>")));
        const Scene scene = readScene(folder / "long.x3d");
        REQUIRE(scene.meshes.size() == 1);
        CHECK(scene.meshes[0].primitives[0].triangles.size() == 3);
        CHECK_THAT(joinedWarnings(scene.warnings), Catch::Contains("long.x3d") && Catch::Contains("TriangleStripSet") &&
                                                       Catch::Contains("names 9 points, its Coordinate has 7"));
    }
}

TEST_CASE("An ElevationGrid is its heights over a grid, each square cut along one diagonal",
          "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    // y = 0.5 x - 0.25 z over 4 by 3 points, spaced 2 and 3: a plane.
    std::vector<double> heights;
    std::vector<Eigen::Vector3d> points;
    for (int z = 0; z < 3; ++z)
        for (int x = 0; x < 4; ++x) {
            heights.push_back(0.5 * (2 * x) - 0.25 * (3 * z));
            points.emplace_back(2 * x, heights.back(), 3 * z);
        }
    const std::string grid =
        "<ElevationGrid xDimension='4' zDimension='3' xSpacing='2' zSpacing='3' height='" + numbersText(heights) + "'";
    SECTION("the triangles, facing up, along the diagonal from (x, z) to (x + 1, z + 1); texture coordinates") {
        const Primitive primitive = readOne(folder, grid + "/>");
        std::multiset<std::array<int, 3>> expected;
        for (int z = 0; z < 2; ++z)
            for (int x = 0; x < 3; ++x) {
                const int p1 = z * 4 + x, p2 = p1 + 4, p3 = p2 + 1, p4 = p1 + 1;
                expected.insert({p1, p2, p3});
                expected.insert({p1, p3, p4});
            }
        CHECK(trianglesByPoint(primitive, points) == expected);
        const Eigen::Vector3d up = Eigen::Vector3d(-0.5, 1, 0.25).normalized();  // the plane's normal
        for (const Triangle& t : primitive.triangles) {
            const Eigen::Vector3d& a = primitive.positions[t[0]];
            CHECK((primitive.positions[t[1]] - a).cross(primitive.positions[t[2]] - a).normalized().dot(up) ==
                  Approx(1));
        }
        // Flat by default (creaseAngle 0): no normals, as glTF draws a mesh without them.
        CHECK(primitive.normals.empty());
        // s = x / 3, t = z / 2 in X3D (t up): glTF's v = 1 - t.
        REQUIRE(primitive.texcoords.size() == primitive.positions.size());
        for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
            CHECK(primitive.texcoords[v].x() == Approx(primitive.positions[v].x() / 2 / 3));
            CHECK(primitive.texcoords[v].y() == Approx(1 - primitive.positions[v].z() / 3 / 2));
        }
    }
    SECTION("smoothed where creaseAngle asks: on a plane every normal is the plane's") {
        const Primitive primitive = readOne(folder, grid + " creaseAngle='3'/>");
        REQUIRE(primitive.normals.size() == primitive.positions.size());
        for (const Eigen::Vector3d& normal : primitive.normals)
            CHECK((normal - Eigen::Vector3d(-0.5, 1, 0.25).normalized()).norm() < 1e-12);
    }
    SECTION("colours per square: both its triangles") {
        const Primitive primitive = readOne(
            folder, grid + " colorPerVertex='false'><Color color='" +
                        numbersText({1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0, 0, 1, 1, 1, 0, 1}) + "'/></ElevationGrid>");
        REQUIRE(primitive.colors.size() == primitive.positions.size());
        std::map<std::pair<int, int>, std::set<std::vector<double>>> colorsOfSquare;
        for (const Triangle& t : primitive.triangles) {
            const Eigen::Vector3d centre =
                (primitive.positions[t[0]] + primitive.positions[t[1]] + primitive.positions[t[2]]) / 3;
            for (std::uint32_t v : t)
                colorsOfSquare[{int(centre.x() / 2), int(centre.z() / 3)}].insert(
                    {primitive.colors[v].x(), primitive.colors[v].y(), primitive.colors[v].z()});
        }
        REQUIRE(colorsOfSquare.size() == 6);
        std::set<std::vector<double>> distinct;
        for (const auto& [square, colors] : colorsOfSquare) {
            CHECK(colors.size() == 1);
            distinct.insert(*colors.begin());
        }
        CHECK(distinct.size() == 6);
    }
    SECTION("a grid of one row draws nothing; missing heights are 0, with a warning") {
        CHECK(readOne(folder, "<ElevationGrid xDimension='1' zDimension='5' height='1 2 3 4 5'/>").triangles.empty());
        writeTextFile(folder / "short.x3d",
                      sceneX3d(shapeX3d("<ElevationGrid xDimension='2' zDimension='2' height='1 1'/>")));
        const Scene scene = readScene(folder / "short.x3d");
        REQUIRE(scene.meshes.size() == 1);
        const Primitive& primitive = scene.meshes[0].primitives[0];
        CHECK(primitive.triangles.size() == 2);
        for (const Eigen::Vector3d& p : primitive.positions) CHECK(p.y() == (p.z() == 0 ? 1 : 0));
        CHECK_THAT(joinedWarnings(scene.warnings), Catch::Contains("short.x3d") && Catch::Contains("ElevationGrid") &&
                                                       Catch::Contains("2 heights for 4 points"));
    }
}

TEST_CASE("An Extrusion is its cross-section swept along its spine, as X3D defines it", "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    SECTION("the defaults: a closed box 2 by 1 by 2, facing out") {
        const Primitive primitive = readOne(folder, "<Extrusion/>");
        CHECK(primitive.triangles.size() == 12);
        const auto [area, volume] = areaAndVolume(primitive);
        CHECK(area == Approx(4 * 2 + 2 * 4));
        CHECK(volume == Approx(4));
        const Eigen::AlignedBox3d box(Eigen::Vector3d(-1, 0, -1), Eigen::Vector3d(1, 1, 1));
        for (const Eigen::Vector3d& p : primitive.positions) CHECK(box.exteriorDistance(p) < 1e-12);
        CHECK(primitive.normals.empty());  // creaseAngle 0: flat
    }
    SECTION("ccw='false' turns it inside out; no caps: open") {
        CHECK(areaAndVolume(readOne(folder, "<Extrusion ccw='false'/>")).second == Approx(-4));
        const Primitive open = readOne(folder, "<Extrusion beginCap='false' endCap='false'/>");
        CHECK(open.triangles.size() == 8);
        CHECK(areaAndVolume(open).first == Approx(8));
    }
    SECTION("a tube along a bent spine: every point at the cross-section's radius from the spine's arc") {
        // A quarter of a circle of radius 3 in the xy plane, about (3, 0, 0), in 6 steps.
        std::vector<double> spine;
        for (int i = 0; i <= 6; ++i) {
            const double angle = M_PI / 2 * i / 6;
            spine.insert(spine.end(), {3 - 3 * std::cos(angle), 3 * std::sin(angle), 0});
        }
        const Primitive tube =
            readOne(folder, "<Extrusion spine='" + numbersText(spine) + "' crossSection='" + circleText(12, 0.5) +
                                "' beginCap='false' endCap='false' creaseAngle='1'/>");
        CHECK(tube.triangles.size() == 6 * 12 * 2);
        // The cross-sections of the spine's inner points lie across the arc (the spine's own ends take the
        // direction of their one segment, a chord).
        auto inner = [](const Eigen::Vector3d& p) {
            const double angle = std::atan2(p.y(), 3 - p.x());
            return angle > 0.1 && angle < M_PI / 2 - 0.1;
        };
        std::size_t checked = 0;
        for (std::size_t v = 0; v < tube.positions.size(); ++v) {
            const Eigen::Vector3d& p = tube.positions[v];
            if (!inner(p)) continue;
            ++checked;
            // The distance from the arc's circle: from the point to the circle's nearest point.
            const Eigen::Vector3d onArc =
                Eigen::Vector3d(3, 0, 0) + 3 * Eigen::Vector3d(p.x() - 3, p.y(), 0).normalized();
            CHECK((p - onArc).norm() == Approx(0.5));
            // Smooth (creaseAngle 1 rad, above the 30 degrees between neighbouring faces): the normal points from
            // the arc.
            REQUIRE(tube.normals.size() == tube.positions.size());
            CHECK((p - onArc).normalized().dot(tube.normals[v]) > 0.95);
        }
        CHECK(checked == 5 * 13);  // 12 points a cross-section, the seam's twice (texture coordinates 0 and 1)
    }
    SECTION("scale to 0: a cone of the polygon's area times a third of its height") {
        const Primitive cone = readOne(
            folder, "<Extrusion spine='0 0 0 0 2 0' scale='1 1 0 0' crossSection='" + circleText(16, 1) + "'/>");
        const double base = 16 * std::sin(2 * M_PI / 16) / 2;  // a regular 16-gon of radius 1
        CHECK(areaAndVolume(cone).second == Approx(base * 2 / 3));
    }
    SECTION("orientation turns each cross-section in its plane; scale stretches it") {
        const Primitive twisted =
            readOne(folder,
                    "<Extrusion spine='0 0 0 0 1 0' orientation='0 1 0 0 0 1 0 0.5' scale='1 1 2 0.5' "
                    "beginCap='false' endCap='false'/>");
        std::set<std::vector<double>> top, expected;
        for (const Eigen::Vector3d& p : twisted.positions)
            if (p.y() == 1) top.insert({std::round(p.x() * 1e9) / 1e9, std::round(p.z() * 1e9) / 1e9});
        for (const Eigen::Vector2d& c :
             {Eigen::Vector2d(1, 1), Eigen::Vector2d(1, -1), Eigen::Vector2d(-1, -1), Eigen::Vector2d(-1, 1)}) {
            // Scaled first, then turned about y by 0.5 rad (X3D's right hand: x towards -z).
            const Eigen::Vector3d p =
                Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()) * Eigen::Vector3d(2 * c.x(), 0, 0.5 * c.y());
            expected.insert({std::round(p.x() * 1e9) / 1e9, std::round(p.z() * 1e9) / 1e9});
        }
        CHECK(top == expected);
    }
    SECTION("a closed spine joins its last cross-section to its first: a ring") {
        std::vector<double> spine;
        for (int i = 0; i <= 24; ++i) {
            const double angle = 2 * M_PI * (i % 24) / 24;
            spine.insert(spine.end(), {2 * std::cos(angle), 0, 2 * std::sin(angle)});
        }
        const Primitive ring = readOne(folder, "<Extrusion spine='" + numbersText(spine) + "' crossSection='" +
                                                   circleText(8, 0.25) + "' beginCap='false' endCap='false'/>");
        CHECK(ring.triangles.size() == 24 * 8 * 2);
        // Closed: every edge between two triangles (by position).
        std::map<std::pair<std::vector<double>, std::vector<double>>, int> edges;
        auto key = [](const Eigen::Vector3d& p) {
            return std::vector<double>{std::round(p.x() * 1e9), std::round(p.y() * 1e9), std::round(p.z() * 1e9)};
        };
        for (const Triangle& t : ring.triangles)
            for (int k = 0; k < 3; ++k) {
                auto a = key(ring.positions[t[std::size_t(k)]]), b = key(ring.positions[t[std::size_t((k + 1) % 3)]]);
                ++edges[std::minmax(a, b)];
            }
        for (const auto& [edge, count] : edges) CHECK(count == 2);
        // Its volume: the octagon's area swept around the ring's polygon, between the 24-gons of radius 2 - r and
        // 2 + r, as the divergence theorem gives it; positive: facing out.
        CHECK(areaAndVolume(ring).second > 0);
    }
    SECTION("a concave cap where convex='false'") {
        // A star of 5 points, its corners counter-clockwise in the cross-section's plane (X3D's cross-sections
        // run clockwise, as the default square does: this prism faces in). A fan over it would cover more.
        std::vector<double> star;
        std::vector<Eigen::Vector2d> corners;
        for (int i = 0; i <= 10; ++i) {
            const double radius = i % 2 ? 0.4 : 1, angle = 2 * M_PI * (i % 10) / 10;
            corners.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
            star.insert(star.end(), {corners.back().x(), corners.back().y()});
        }
        double area = 0, perimeter = 0;
        for (std::size_t i = 0; i < 10; ++i) {
            area += (corners[i].x() * corners[i + 1].y() - corners[i + 1].x() * corners[i].y()) / 2;
            perimeter += (corners[i + 1] - corners[i]).norm();
        }
        const auto [surface, volume] =
            areaAndVolume(readOne(folder, "<Extrusion convex='false' crossSection='" + numbersText(star) + "'/>"));
        CHECK(volume == Approx(-area));
        CHECK(surface == Approx(perimeter * 1 + 2 * area));
    }
    SECTION("bad fields: a clear error naming the file and the node; empty ones draw nothing") {
        writeTextFile(folder / "bad.x3d", sceneX3d(shapeX3d("<Extrusion DEF='pipe' spine='0 0 0 0 1'/>")));
        CHECK_THROWS_WITH(readScene(folder / "bad.x3d"), Catch::Contains("bad.x3d") &&
                                                             Catch::Contains("Extrusion DEF='pipe'") &&
                                                             Catch::Contains("spine"));
        writeTextFile(folder / "huge.x3d",
                      sceneX3d(shapeX3d("<ElevationGrid xDimension='2000000000' zDimension='2000000000'/>")));
        CHECK_THROWS_WITH(readScene(folder / "huge.x3d"), Catch::Contains("huge.x3d") &&
                                                              Catch::Contains("ElevationGrid") &&
                                                              Catch::Contains("too many"));
        CHECK(readOne(folder, "<Extrusion spine='' crossSection=''/>").triangles.empty());
    }
}

TEST_CASE("The new geometry nodes render in X3D output as the input does in X_ITE, and in GLB as three.js draws it",
          "[io][x3d][geometry-nodes][renders]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    TemporaryFolder folder;
    auto placed = [](const std::string& translation, const std::string& color, const std::string& geometry) {
        return "<Transform translation='" + translation + "'>" +
               shapeX3d(geometry, "<Appearance><Material diffuseColor='" + color + "'/></Appearance>") + "</Transform>";
    };
    std::vector<double> spine, heights;
    for (int i = 0; i <= 5; ++i) spine.insert(spine.end(), {0.4 * i * i / 5.0, double(i) / 2, 0.3 * i});
    for (int z = 0; z < 6; ++z)
        for (int x = 0; x < 8; ++x) heights.push_back(0.5 * std::sin(x * 0.7) * std::cos(z * 0.5));
    const std::string scene = sceneX3d(
        "<Viewpoint position='1 0 22'/>" +
        placed("-7 2 0", "1 1 1",
               "<IndexedTriangleStripSet index='0 1 2 3 4 5'><Coordinate point='0 0 0 0 1 0 1 0 0 1 1.2 0.3 2 0 0 2 "
               "1 0.3'/><Color color='1 0 0 0 1 0 0 0 1 1 1 0 0 1 1 1 0 1'/></IndexedTriangleStripSet>") +
        placed("-3 2 0", "0.2 0.6 0.9",
               "<IndexedTriangleFanSet index='0 1 2 3 4 5 6 1'><Coordinate point='0 0 0.3 1 0 0 0.5 0.87 0 -0.5 0.87 "
               "0 -1 0 0 -0.5 -0.87 0 0.5 -0.87 0'/></IndexedTriangleFanSet>") +
        placed("0 2 0", "0.9 0.5 0.1",
               "<TriangleStripSet stripCount='6'><Coordinate point='0 0 0 0 1 0.2 1 0 0.3 1 1 0.5 2 0 0.4 2 1 "
               "0.2'/></TriangleStripSet>") +
        placed("4 2 0", "0.7 0.2 0.7",
               "<QuadSet><Coordinate point='0 0 0 1 0 0 1 1 0.3 0 1 0 1.5 0 0 2.5 0 0 2.5 1 0 1.5 1 0'/></QuadSet>") +
        placed("-8 -3 -2", "0.5 0.7 0.3",
               "<ElevationGrid xDimension='8' zDimension='6' xSpacing='0.6' zSpacing='0.7' creaseAngle='1.5' "
               "height='" +
                   numbersText(heights) + "'/>") +
        placed("-2 -3 0", "0.8 0.3 0.3",
               "<Extrusion crossSection='" + circleText(16, 0.6) + "' spine='" + numbersText(spine) +
                   "' creaseAngle='1.6' scale='1 1 0.5 0.5'/>") +
        placed("4 -3 0", "0.3 0.3 0.8",
               "<Extrusion crossSection='" + circleText(16, 1) +
                   "' spine='0 0 0 0 2 0' scale='1 1 0 0' "
                   "creaseAngle='1.6'/>"));
    writeTextFile(folder / "nodes.x3d", scene);
    for (const char* output : {"out.x3d", "out.glb"}) {
        CHECK(compressWithTool(folder / "nodes.x3d", folder / output).find("skipped") == std::string::npos);
    }
    checkRendersSame(folder / "nodes.x3d", folder / "out.x3d");
    // X_ITE and three.js light a scene otherwise: across them, the normals.
    checkRendersIn("normals", folder / "nodes.x3d", folder / "out.glb");
}

TEST_CASE("X3D output writes the nodes that make their own points again as they were, not their triangles",
          "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    std::vector<double> heights;
    for (int z = 0; z < 60; ++z)
        for (int x = 0; x < 60; ++x) heights.push_back(std::round(300 * std::sin(x * 0.1) * std::cos(z * 0.13)) / 100);
    // The ElevationGrid's Color is a USE of a Color an earlier shape defines: the output's node holds it whole.
    const std::string input = sceneX3d(
        "<Shape><Appearance><Material diffuseColor='1 1 1'/></Appearance><IndexedFaceSet coordIndex='0 1 2'>"
        "<Coordinate point='0 0 0 1 0 0 0 1 0'/><Color DEF='tint' color='1 0 0 0 1 0 0 0 1 1 1 0'/>"
        "</IndexedFaceSet></Shape>"
        "<Transform translation='0 -5 0'><Shape><Appearance><Material diffuseColor='0.4 0.6 0.3'/></Appearance>"
        "<ElevationGrid DEF='ground' xDimension='60' zDimension='60' creaseAngle='1.5' height='" +
        numbersText(heights) +
        "'/></Shape></Transform>"
        "<Transform translation='0 0 70'><Shape><Appearance><Material/></Appearance><ElevationGrid xDimension='2' "
        "zDimension='2' colorPerVertex='true' height='0 1 2 3'><Color USE='tint'/></ElevationGrid></Shape></Transform>"
        "<Transform translation='5 0 0'><Shape><Appearance><Material/></Appearance><Extrusion spine='0 0 0 0 1 0 1 2 "
        "0' crossSection='" +
        circleText(12, 0.5) +
        "' creaseAngle='1'/></Shape></Transform>"
        "<Shape><Appearance><Material/></Appearance><Box size='1 2 3'/></Shape>"
        "<Transform translation='9 0 0'><Shape><Appearance><Material/></Appearance><Cone/></Shape></Transform>");
    writeTextFile(folder / "made.x3d", input);
    compressWithTool(folder / "made.x3d", folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK_THAT(text, Catch::Contains("height=\"" + numbersText(heights).substr(0, 200)));
    CHECK_THAT(text, Catch::Contains("<Extrusion spine=\"0 0 0 0 1 0 1 2 0\""));
    CHECK_THAT(text, Catch::Contains("<Box size=\"1 2 3\"/>"));
    CHECK_THAT(text, Catch::Contains("<Cone/>"));
    CHECK_THAT(text, Catch::Contains("zDimension=\"2\" colorPerVertex=\"true\" height=\"0 1 2 3\"><Color "
                                     "color=\"1 0 0 0 1 0 0 0 1 1 1 0\"/></ElevationGrid>"));
    CHECK_THAT(text, !Catch::Contains("ground"));  // DEFs of their own only
    // The file's one face set stays a face set; the rest is the nodes: far smaller than their triangles.
    std::size_t faceSets = 0;
    for (std::size_t at = text.find("<Indexed"); at != std::string::npos; at = text.find("<Indexed", at + 1))
        ++faceSets;
    CHECK(faceSets == 1);
    CHECK(fs::file_size(folder / "out.x3d") < fs::file_size(folder / "made.x3d") + 1024);
    const CommandResult verified = runCommand(quoted(SYMDECOMPRESS_CLI) + " " + quoted(folder / "out.x3d") + " -o " +
                                              quoted(folder / "flat.ply") + " --verify " + quoted(folder / "made.x3d"));
    INFO(verified.output);
    CHECK(verified.status == 0);
    CHECK_THAT(verified.output, Catch::Contains("max deviation 0.00e+00"));

    SECTION("glTF output cuts them as any mesh; a primitive that changed is written as its triangles") {
        compressWithTool(folder / "made.x3d", folder / "out.glb");
        Scene scene = readScene(folder / "made.x3d");
        std::size_t sources = 0;
        for (Mesh& mesh : scene.meshes)
            for (Primitive& primitive : mesh.primitives)
                if (primitive.x3dSource) {
                    ++sources;
                    primitive.positions[0].x() += 0.5;
                }
        CHECK(sources == 5);
        writeScene(scene, folder / "moved.x3d");
        const std::string moved = readTextFile(folder / "moved.x3d");
        CHECK_THAT(moved, !Catch::Contains("<ElevationGrid") && !Catch::Contains("<Box") &&
                              !Catch::Contains("<Extrusion") && !Catch::Contains("<Cone"));
    }
}

TEST_CASE("Box, Sphere, Cylinder and Cone are cut as X_ITE cuts them", "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    // The area of a regular polygon of n corners on a circle of radius r.
    SECTION("their triangles (X_ITE's counts: 20 sides, a sphere of 32 by 15 points), closed and facing out") {
        const Primitive box = readOne(folder, "<Box size='2 4 6'/>");
        CHECK(box.triangles.size() == 12);
        CHECK(areaAndVolume(box).second == Approx(48));
        const Primitive cylinder = readOne(folder, "<Cylinder radius='2' height='3'/>");
        CHECK(cylinder.triangles.size() == 20 * 2 + 2 * 18);
        CHECK(areaAndVolume(cylinder).second == Approx(polygonArea(20, 2) * 3));
        const Primitive cone = readOne(folder, "<Cone bottomRadius='2' height='3'/>");
        CHECK(cone.triangles.size() == 20 + 18);
        CHECK(areaAndVolume(cone).second == Approx(polygonArea(20, 2) * 3 / 3));
        const Primitive sphere = readOne(folder, "<Sphere radius='2'/>");
        CHECK(sphere.triangles.size() == 32 + 12 * 32 * 2 + 32);
        for (const Eigen::Vector3d& p : sphere.positions) CHECK(p.norm() == Approx(2));
        const double volume = areaAndVolume(sphere).second;
        CHECK(volume < 4 * M_PI * 8 / 3);
        CHECK(volume > 0.97 * 4 * M_PI * 8 / 3);
    }
    SECTION("their normals: the cone's across its slant side, the cylinder's and sphere's from their axis and centre") {
        const Primitive cone = readOne(folder, "<Cone bottomRadius='2' height='3'/>");
        for (std::size_t v = 0; v < cone.positions.size(); ++v) {
            const Eigen::Vector3d &p = cone.positions[v], &n = cone.normals[v];
            CHECK(n.norm() == Approx(1));
            if (n.y() > -0.5)  // the side: along the slant from the rim to the apex, the normal is square to it
                CHECK(std::abs(n.dot(Eigen::Vector3d(-n.x(), 0, -n.z()).normalized() * 2 + Eigen::Vector3d(0, 3, 0))) <
                      1e-9);
            else
                CHECK(p.y() == Approx(-1.5));
        }
        const Primitive sphere = readOne(folder, "<Sphere/>");
        for (std::size_t v = 0; v < sphere.positions.size(); ++v)
            CHECK(sphere.normals[v].dot(sphere.positions[v]) > 0.99);
    }
}

TEST_CASE("The geometric primitives render in GLB output as X_ITE draws them, textures too",
          "[io][x3d][geometry-nodes][renders]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    TemporaryFolder folder;
    fs::copy_file(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"), folder / "logo.png");
    std::string shapes;
    for (const auto& [translation, geometry] :
         std::vector<std::pair<std::string, std::string>>{{"0 0 0", "<Sphere/>"},
                                                          {"3 0 0", "<Cylinder/>"},
                                                          {"-3 0 0", "<Cone/>"},
                                                          {"0 3 0", "<Box size='1 2 3'/>"},
                                                          {"3 3 0", "<Cone bottomRadius='0.5' height='3'/>"}})
        shapes += "<Transform translation='" + translation +
                  "'><Shape><Appearance><Material/><ImageTexture url='\"logo.png\"'/></Appearance>" + geometry +
                  "</Shape></Transform>";
    writeTextFile(folder / "primitives.x3d", sceneX3d(shapes));
    compressWithTool(folder / "primitives.x3d", folder / "out.glb");
    // X_ITE and three.js light a scene otherwise: across them, the normals; the textures through X3D again, which
    // has no node to write again once the shapes are in GLB.
    checkRendersIn("normals", folder / "primitives.x3d", folder / "out.glb");
    const CommandResult back = runCommand(quoted(SYMCOMPRESS_CLI) + " convert " + quoted(folder / "out.glb") + " -o " +
                                          quoted(folder / "back.x3d"));
    REQUIRE(back.status == 0);
    checkRendersIn("lit", folder / "primitives.x3d", folder / "back.x3d");
}

TEST_CASE("X3D's 2D geometry is drawn in the z = 0 plane as X_ITE draws it, its surfaces from both sides",
          "[io][x3d][geometry-nodes]") {
    TemporaryFolder folder;
    auto doubleSided = [&](const std::string& geometry) {
        writeTextFile(folder / "sided.x3d", sceneX3d(shapeX3d(geometry, "<Appearance><Material/></Appearance>")));
        const Scene scene = readScene(folder / "sided.x3d");
        return scene.materials[std::size_t(scene.meshes[0].primitives[0].material)].doubleSided;
    };
    SECTION("surfaces: their areas, facing +z, double-sided unless solid") {
        const Primitive rectangle = readOne(folder, "<Rectangle2D size='3 2'/>");
        CHECK(rectangle.triangles.size() == 2);
        CHECK(areaAndVolume(rectangle).first == Approx(6));
        const Primitive disk = readOne(folder, "<Disk2D outerRadius='2'/>");
        CHECK(disk.triangles.size() == 40);
        CHECK(areaAndVolume(disk).first == Approx(polygonArea(40, 2)));
        const Primitive ring = readOne(folder, "<Disk2D innerRadius='1' outerRadius='2'/>");
        CHECK(ring.triangles.size() == 80);
        CHECK(areaAndVolume(ring).first == Approx(polygonArea(40, 2) - polygonArea(40, 1)));
        const Primitive triangles = readOne(folder, "<TriangleSet2D vertices='0 0 2 0 1 1 0 0 -1 -1 0 -1'/>");
        CHECK(triangles.triangles.size() == 2);
        for (const Primitive* p : {&rectangle, &disk, &ring, &triangles})
            for (const Triangle& t : p->triangles) {
                const Eigen::Vector3d &a = p->positions[t[0]], &b = p->positions[t[1]], &c = p->positions[t[2]];
                CHECK((b - a).cross(c - a).z() > 0);
                CHECK(a.z() == 0);
            }
        // The 2D triangle set's texture across its box's longer side (3 wide, 2 high, from (-1, -1)).
        for (std::size_t v = 0; v < triangles.positions.size(); ++v) {
            CHECK(triangles.texcoords[v].x() == Approx((triangles.positions[v].x() + 1) / 3));
            CHECK(triangles.texcoords[v].y() == Approx(1 - (triangles.positions[v].y() + 1) / 3));
        }
        CHECK(doubleSided("<Rectangle2D/>"));
        CHECK_FALSE(doubleSided("<Rectangle2D solid='true'/>"));
        CHECK_FALSE(doubleSided("<Box/>"));
    }
    SECTION("lines and points: a circle of 40 segments, an arc of its share of them, a polyline, points") {
        const Primitive circle = readOne(folder, "<Circle2D radius='2'/>");
        CHECK(circle.topology == Topology::Lines);
        CHECK(circle.lines.size() == 40);
        for (const Eigen::Vector3d& p : circle.positions) CHECK(p.norm() == Approx(2));
        const Primitive arc = readOne(folder, "<Arc2D radius='1' startAngle='0.5' endAngle='2'/>");
        CHECK(arc.lines.size() == std::size_t(std::floor(1.5 * 40 / (2 * M_PI))));
        CHECK((arc.positions.front() - Eigen::Vector3d(std::cos(0.5), std::sin(0.5), 0)).norm() < 1e-12);
        CHECK((arc.positions.back() - Eigen::Vector3d(std::cos(2.0), std::sin(2.0), 0)).norm() < 1e-12);
        const Primitive polyline = readOne(folder, "<Polyline2D lineSegments='0 0 1 1 2 0 3 1'/>");
        CHECK(polyline.lines.size() == 3);
        const Primitive points = readOne(folder, "<Polypoint2D point='0 0 1 0 2 0'/>");
        CHECK(points.topology == Topology::Points);
        CHECK(points.positions.size() == 3);
    }
    SECTION("ArcClose2D: a pie from the centre, or a fan from the arc's first point closed by its chord") {
        // 3.2 rad: 20 of the 40 steps to the turn (floor(3.2 * 40 / 2 pi)), 20 points from start to end.
        const Primitive pie = readOne(folder, "<ArcClose2D radius='2' startAngle='0' endAngle='3.2'/>");
        CHECK(pie.triangles.size() == 19);
        CHECK(areaAndVolume(pie).first == Approx(19 * 4 * std::sin(3.2 / 19) / 2));
        const Primitive chord =
            readOne(folder, "<ArcClose2D closureType='CHORD' radius='2' startAngle='0' endAngle='3.2'/>");
        CHECK(chord.triangles.size() == 18);
        // The polygon of the arc's points: the pie's sectors and the triangle between the chord and the centre.
        CHECK(areaAndVolume(chord).first == Approx(areaAndVolume(pie).first + 4 * std::sin(-3.2) / 2));
        CHECK(doubleSided("<ArcClose2D/>"));
    }
}

TEST_CASE("X3D's 2D surfaces render in GLB as X_ITE draws them", "[io][x3d][geometry-nodes][renders]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    TemporaryFolder folder;
    std::string shapes = "<Viewpoint position='0 0 12'/>";
    for (const auto& [translation, geometry] : std::vector<std::pair<std::string, std::string>>{
             {"-4 0 0", "<Rectangle2D size='2 1'/>"},
             {"0 0 0", "<Disk2D outerRadius='1'/>"},
             {"4 0 0", "<Disk2D innerRadius='0.5' outerRadius='1.2'/>"},
             {"0 -3 0", "<TriangleSet2D vertices='0 0 2 0 1 1.5 -1 0 -0.5 -1 0 -1'/>"},
             {"4 -3 0", "<ArcClose2D closureType='CHORD' endAngle='4'/>"},
             {"-4 -3 0", "<ArcClose2D startAngle='1' endAngle='5'/>"}})
        shapes += "<Transform translation='" + translation + "'>" +
                  shapeX3d(geometry, "<Appearance><Material diffuseColor='0.8 0.3 0.3'/></Appearance>") +
                  "</Transform>";
    // Turned off the axes: a view along the plane would see nothing.
    writeTextFile(folder / "flat.x3d", sceneX3d("<Transform rotation='1 1 0 0.6'>" + shapes + "</Transform>"));
    for (const char* output : {"out.glb", "out.x3d"}) {
        compressWithTool(folder / "flat.x3d", folder / output);
    }
    checkRendersSame(folder / "flat.x3d", folder / "out.x3d");
    checkRendersIn("normals", folder / "flat.x3d", folder / "out.glb");
}
