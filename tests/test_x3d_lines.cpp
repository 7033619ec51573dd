// X3D's line and point sets (IndexedLineSet, LineSet, PointSet): read into Lines and Points primitives, drawn
// unlit in their Material's emissive colour (or their Color's), written back as line and point sets whose
// emissive colour is the base colour, and carried through the compressor.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// sRGB 0.5 decoded (IEC 61966-2-1): ((0.5 + 0.055) / 1.055)^2.4.
constexpr double kHalfDecoded = 0.21404114048223255;

using Point = std::array<double, 3>;
using PositionSegment = std::pair<Point, Point>;

Point pointOf(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// A primitive's segments by the positions of their ends, each pair in order: equal as sets whatever the
// vertices' order and the segments' direction.
std::set<PositionSegment> segmentsOf(const Primitive& primitive, int decimals = 9) {
    const auto rounded = [&](const Eigen::Vector3d& p) {
        const double scale = std::pow(10.0, decimals);
        return Point{std::round(p.x() * scale) / scale, std::round(p.y() * scale) / scale,
                     std::round(p.z() * scale) / scale};
    };
    std::set<PositionSegment> out;
    for (const Segment& s : primitive.lines) {
        const Point a = rounded(primitive.positions[s[0]]), b = rounded(primitive.positions[s[1]]);
        out.insert(std::minmax(a, b));
    }
    return out;
}

// The colour of the vertex at `position` (the first found).
Eigen::Vector4d colorAt(const Primitive& primitive, const Eigen::Vector3d& position) {
    for (std::size_t v = 0; v < primitive.positions.size(); ++v)
        if ((primitive.positions[v] - position).norm() < 1e-9) return primitive.colors.at(v);
    FAIL("no vertex at " << position.transpose());
    return {};
}

const Primitive& onlyPrimitive(const Scene& scene, std::size_t mesh) {
    REQUIRE(scene.meshes.size() > mesh);
    REQUIRE(scene.meshes[mesh].primitives.size() == 1);
    return scene.meshes[mesh].primitives[0];
}

std::string x3dScene(const std::string& shapes) { return "<X3D version='3.3'><Scene>" + shapes + "</Scene></X3D>"; }

}  // namespace

TEST_CASE("X3D IndexedLineSet, LineSet and PointSet are read as lines and points with their colours", "[io][x3d]") {
    TemporaryFolder folder;
    const std::string text = x3dScene(
        // Two polylines, a colour per vertex; the Material's emissive colour is not drawn where Color is.
        "<Shape><Appearance><Material emissiveColor='0 0 0'/></Appearance>"
        "<IndexedLineSet coordIndex='0 1 2 -1 3 4 -1'>"
        "<Coordinate point='0 0 0 1 0 0 1 1 0 0 0 2 0 3 2'/>"
        "<Color color='1 0 0 0 1 0 0 0 1 0.5 0.5 0.5 1 1 1'/></IndexedLineSet></Shape>"
        // vertexCount polylines, drawn in the emissive colour.
        "<Shape><Appearance><Material diffuseColor='0.2 0.2 0.2' emissiveColor='0 0.5 1' transparency='0.25'/>"
        "</Appearance><LineSet vertexCount='2 3'><Coordinate point='0 0 5 1 0 5 2 0 5 2 1 5 2 2 5'/></LineSet></Shape>"
        "<Shape><PointSet><Coordinate point='0 0 9 1 0 9 0 1 9'/>"
        "<ColorRGBA color='1 0 0 1 0 1 0 0.5 0.5 0.5 0.5 1'/></PointSet></Shape>");
    writeTextFile(folder / "lines.x3d", text);
    const Scene scene = readScene(folder / "lines.x3d");
    INFO(scene.warnings.size() << " warnings");
    CHECK(scene.warnings.empty());
    REQUIRE(scene.meshes.size() == 3);

    const Primitive& indexed = onlyPrimitive(scene, 0);
    CHECK(indexed.topology == Topology::Lines);
    CHECK(indexed.triangles.empty());
    const std::set<PositionSegment> expected = {{{0, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {1, 1, 0}}, {{0, 0, 2}, {0, 3, 2}}};
    CHECK(segmentsOf(indexed) == expected);
    REQUIRE(indexed.colors.size() == indexed.positions.size());
    // sRGB-encoded in X3D, linear in the model; the base colour white, the Color taking the emissive's place.
    CHECK(colorAt(indexed, {1, 0, 0}).isApprox(Eigen::Vector4d(0, 1, 0, 1)));
    CHECK(colorAt(indexed, {1, 1, 0}).isApprox(Eigen::Vector4d(0, 0, 1, 1)));
    CHECK(colorAt(indexed, {0, 0, 2}).isApprox(Eigen::Vector4d(kHalfDecoded, kHalfDecoded, kHalfDecoded, 1)));
    REQUIRE(indexed.material >= 0);
    CHECK(scene.materials[std::size_t(indexed.material)].baseColorFactor.isApprox(Eigen::Vector4d(1, 1, 1, 1)));

    const Primitive& counted = onlyPrimitive(scene, 1);
    CHECK(counted.topology == Topology::Lines);
    const std::set<PositionSegment> countedExpected = {
        {{0, 0, 5}, {1, 0, 5}}, {{2, 0, 5}, {2, 1, 5}}, {{2, 1, 5}, {2, 2, 5}}};
    CHECK(segmentsOf(counted) == countedExpected);
    CHECK(counted.colors.empty());
    REQUIRE(counted.material >= 0);
    // The emissive colour is what X3D draws lines in: glTF's base colour, decoded from sRGB; alpha 1 - transparency.
    const Material& emissive = scene.materials[std::size_t(counted.material)];
    CHECK(emissive.baseColorFactor.isApprox(Eigen::Vector4d(0, kHalfDecoded, 1, 0.75)));
    CHECK(emissive.alphaMode == Material::AlphaMode::Blend);

    const Primitive& points = onlyPrimitive(scene, 2);
    CHECK(points.topology == Topology::Points);
    REQUIRE(points.positions.size() == 3);
    CHECK(points.positions[1].isApprox(Eigen::Vector3d(1, 0, 9)));
    REQUIRE(points.colors.size() == 3);
    CHECK(points.colors[0].isApprox(Eigen::Vector4d(1, 0, 0, 1)));
    CHECK(points.colors[1].isApprox(Eigen::Vector4d(0, 1, 0, 0.5)));
    CHECK(points.colors[2].isApprox(Eigen::Vector4d(kHalfDecoded, kHalfDecoded, kHalfDecoded, 1)));
    // No Appearance: unlit white (a material of its own), blended where a colour is translucent, as X_ITE blends
    // a ColorRGBA.
    REQUIRE(points.material >= 0);
    const Material& white = scene.materials[std::size_t(points.material)];
    CHECK(white.baseColorFactor == Eigen::Vector4d(1, 1, 1, 1));
    CHECK(white.alphaMode == Material::AlphaMode::Blend);
}

TEST_CASE("An IndexedLineSet's colour per polyline and colorIndex: a point on two polylines gets two vertices",
          "[io][x3d]") {
    TemporaryFolder folder;
    SECTION("colorPerVertex='false': colorIndex names each polyline's colour") {
        writeTextFile(folder / "per-line.x3d",
                      x3dScene("<Shape><IndexedLineSet colorPerVertex='false' colorIndex='1 0' coordIndex='0 1 -1 1 2'>"
                               "<Coordinate point='0 0 0 1 0 0 2 0 0'/><Color color='1 0 0 0 0 1'/></IndexedLineSet>"
                               "</Shape>"));
        const Scene scene = readScene(folder / "per-line.x3d");
        const Primitive& lines = onlyPrimitive(scene, 0);
        CHECK(lines.positions.size() == 4);  // the middle point twice, once in each colour
        REQUIRE(lines.lines.size() == 2);
        for (const Segment& s : lines.lines) {
            const Eigen::Vector4d expected = lines.positions[s[0]].x() + lines.positions[s[1]].x() == 1
                                                 ? Eigen::Vector4d(0, 0, 1, 1)
                                                 : Eigen::Vector4d(1, 0, 0, 1);
            CHECK(lines.colors[s[0]] == expected);
            CHECK(lines.colors[s[1]] == expected);
        }
    }
    SECTION("colorPerVertex (the default) with a colorIndex laid out as coordIndex") {
        writeTextFile(folder / "indexed-colors.x3d",
                      x3dScene("<Shape><IndexedLineSet colorIndex='1 1 -1 0 0' coordIndex='0 1 -1 1 2'>"
                               "<Coordinate point='0 0 0 1 0 0 2 0 0'/><Color color='1 0 0 0 0 1'/></IndexedLineSet>"
                               "</Shape>"));
        const Primitive lines = onlyPrimitive(readScene(folder / "indexed-colors.x3d"), 0);
        CHECK(lines.positions.size() == 4);
        CHECK(colorAt(lines, {0, 0, 0}) == Eigen::Vector4d(0, 0, 1, 1));
        CHECK(colorAt(lines, {2, 0, 0}) == Eigen::Vector4d(1, 0, 0, 1));
    }
}

TEST_CASE("An X3D Appearance drawing both faces and lines gives each its own material: diffuse, emissive",
          "[io][x3d]") {
    TemporaryFolder folder;
    writeTextFile(folder / "both.x3d",
                  x3dScene("<Shape><Appearance DEF='A'><Material diffuseColor='1 0 0' emissiveColor='0 0 1'/>"
                           "</Appearance><IndexedFaceSet coordIndex='0 1 2'><Coordinate point='0 0 0 1 0 0 0 1 0'/>"
                           "</IndexedFaceSet></Shape>"
                           "<Shape><Appearance USE='A'/><IndexedLineSet coordIndex='0 1'>"
                           "<Coordinate point='0 0 0 1 0 0'/></IndexedLineSet></Shape>"));
    const Scene scene = readScene(folder / "both.x3d");
    const Primitive& faces = onlyPrimitive(scene, 0);
    const Primitive& lines = onlyPrimitive(scene, 1);
    REQUIRE(faces.material >= 0);
    REQUIRE(lines.material >= 0);
    CHECK(faces.material != lines.material);
    CHECK(scene.materials[std::size_t(faces.material)].baseColorFactor == Eigen::Vector4d(1, 0, 0, 1));
    CHECK(scene.materials[std::size_t(lines.material)].baseColorFactor == Eigen::Vector4d(0, 0, 1, 1));
}

TEST_CASE("Bad X3D line and point sets are read with a warning naming the file and the node, never a failure",
          "[io][x3d]") {
    TemporaryFolder folder;
    writeTextFile(folder / "bad.x3d",
                  x3dScene("<Shape><IndexedLineSet DEF='far' coordIndex='0 1 7 2'>"
                           "<Coordinate point='0 0 0 1 0 0 2 0 0 3'/></IndexedLineSet></Shape>"
                           "<Shape><LineSet DEF='long' vertexCount='2 9'><Coordinate point='0 0 0 1 0 0 2 0 0'/>"
                           "<Color color='1 0 0'/></LineSet></Shape>"
                           "<Shape><PointSet DEF='few'><Coordinate point='0 0 0 1 0 0'/><Color color='1 0 0'/>"
                           "</PointSet></Shape>"));
    const Scene scene = readScene(folder / "bad.x3d");
    const auto warned = [&](const std::string& node) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(), [&](const std::string& warning) {
            return warning.find("bad.x3d") != std::string::npos && warning.find(node) != std::string::npos;
        });
    };
    CHECK(warned("IndexedLineSet 'far'"));
    CHECK(warned("LineSet 'long'"));
    CHECK(warned("PointSet 'few'"));
    // The index beyond the points breaks its polyline: 0-1 is drawn, 1-7 and 7-2 are not.
    CHECK(segmentsOf(onlyPrimitive(scene, 0)) == std::set<PositionSegment>{{{0, 0, 0}, {1, 0, 0}}});
    const Primitive& counted = onlyPrimitive(scene, 1);
    CHECK(segmentsOf(counted) == std::set<PositionSegment>{{{0, 0, 0}, {1, 0, 0}}});
    CHECK(counted.colors.empty());  // one colour for three points
    const Primitive& points = onlyPrimitive(scene, 2);
    CHECK(points.positions.size() == 2);
    CHECK(points.colors.empty());
    validateScene(scene);
}

namespace {

// A scene of lines (a strip, a loop, a separate segment; coloured) and points, and lines drawn in a colour.
Scene linesAndPoints() {
    Scene scene;
    Material red;
    red.name = "red";
    red.baseColorFactor = {1, 0, 0, 1};
    Material half;
    half.name = "half";
    half.baseColorFactor = {kHalfDecoded, 0.5, 0, 0.5};
    half.alphaMode = Material::AlphaMode::Blend;
    scene.materials = {red, half};

    Primitive strip;
    strip.topology = Topology::Lines;
    strip.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.123456789, 2, 0}, {1.5, 2.25, 0.75}};
    strip.lines = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}};
    strip.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {kHalfDecoded, 1, 0, 1}, {1, 1, 1, 1}, {0, 0, 0, 1}};

    Primitive colored = strip;
    colored.material = 0;
    colored.colors.clear();

    Primitive points;
    points.topology = Topology::Points;
    points.positions = {{0, 0, 3}, {1, 0, 3}, {0.5, 0.5, 3.5}};
    points.colors = {{1, 0, 0, 1}, {0, 1, 0, 0.5}, {0, 0, 1, 1}};
    points.material = 1;

    scene.meshes = {{"strip", {strip}, "", {}}, {"red", {colored}, "", {}}, {"points", {points}, "", {}}};
    for (int m = 0; m < 3; ++m) {
        Node node;
        node.mesh = m;
        scene.nodes.push_back(node);
        scene.roots.push_back(m);
    }
    return scene;
}

}  // namespace

TEST_CASE("Lines and points written as X3D read back the same: segments, points, colours, base colours", "[io][x3d]") {
    TemporaryFolder folder;
    const Scene scene = linesAndPoints();
    writeScene(scene, folder / "lines.x3d");
    const std::string text = readTextFile(folder / "lines.x3d");
    INFO(text);
    // The strip and the loop as one polyline, the separate segment as another.
    CHECK(text.find("<IndexedLineSet coordIndex='0 1 2 3 0 -1 4 5 -1'>") != std::string::npos);
    CHECK(text.find("<PointSet") != std::string::npos);
    // Unlit: the base colour is the emissive colour of a Material reflecting nothing.
    CHECK(text.find("<Material diffuseColor='0 0 0' emissiveColor='1 0 0'/>") != std::string::npos);
    CHECK(text.find("<Material diffuseColor='0 0 0' emissiveColor='0.5 0.735357 0' transparency='0.5'/>") !=
          std::string::npos);

    const Scene back = readScene(folder / "lines.x3d");
    CHECK(back.warnings.empty());
    REQUIRE(back.meshes.size() == 3);
    const Primitive& strip = onlyPrimitive(back, 0);
    CHECK(strip.topology == Topology::Lines);
    CHECK(segmentsOf(strip) == segmentsOf(scene.meshes[0].primitives[0]));
    REQUIRE(strip.colors.size() == strip.positions.size());
    for (std::size_t v = 0; v < scene.meshes[0].primitives[0].positions.size(); ++v)
        CHECK((colorAt(strip, scene.meshes[0].primitives[0].positions[v]) - scene.meshes[0].primitives[0].colors[v])
                  .norm() < 1e-6);

    const Primitive& red = onlyPrimitive(back, 1);
    CHECK(segmentsOf(red) == segmentsOf(scene.meshes[1].primitives[0]));
    CHECK(red.colors.empty());
    REQUIRE(red.material >= 0);
    CHECK((back.materials[std::size_t(red.material)].baseColorFactor - Eigen::Vector4d(1, 0, 0, 1)).norm() < 1e-6);

    const Primitive& points = onlyPrimitive(back, 2);
    CHECK(points.topology == Topology::Points);
    REQUIRE(points.positions.size() == 3);
    REQUIRE(points.colors.size() == 3);
    REQUIRE(points.material >= 0);
    // The Color takes the emissive colour's place: the base colour white, the colours multiplied by it.
    const Eigen::Vector4d base = back.materials[std::size_t(points.material)].baseColorFactor;
    CHECK(base[3] == Approx(0.5));
    for (std::size_t v = 0; v < 3; ++v) {
        CHECK(points.positions[v] == scene.meshes[2].primitives[0].positions[v]);
        const Eigen::Vector4d drawn = points.colors[v].cwiseProduct(Eigen::Vector4d(base[0], base[1], base[2], 1));
        const Eigen::Vector4d expected =
            scene.meshes[2].primitives[0].colors[v].cwiseProduct(Eigen::Vector4d(kHalfDecoded, 0.5, 0, 1));
        CHECK((drawn - expected).norm() < 1e-6);
    }
}

TEST_CASE("Lines written as X3D within a position error keep their corners within it, and share equal geometry",
          "[io][x3d]") {
    TemporaryFolder folder;
    Scene scene = linesAndPoints();
    // The same lines in two materials, without colours: one geometry, DEF'd once and USEd.
    scene.meshes[0].primitives[0].colors.clear();
    scene.meshes[2].primitives[0].colors.clear();
    scene.meshes.push_back({"points again", {scene.meshes[2].primitives[0]}, "", {}});
    scene.meshes.back().primitives[0].material = 0;
    Node node;
    node.mesh = 3;
    scene.nodes.push_back(node);
    scene.roots.push_back(3);
    WriteOptions options;
    options.maxPositionError = 1e-3;
    writeScene(scene, folder / "rounded.x3d", options);
    const std::string text = readTextFile(folder / "rounded.x3d");
    INFO(text);
    CHECK(text.find("<IndexedLineSet USE='") != std::string::npos);
    CHECK(text.find("<PointSet USE='") != std::string::npos);
    CHECK(text.find("0.123456789") == std::string::npos);  // rounded

    const Scene back = readScene(folder / "rounded.x3d");
    CHECK(back.warnings.empty());
    REQUIRE(back.meshes.size() == 4);
    for (std::size_t m = 0; m < 4; ++m) {
        const Primitive& original = scene.meshes[m].primitives[0];
        const Primitive& read = onlyPrimitive(back, m);
        CHECK(read.topology == original.topology);
        REQUIRE(read.positions.size() == original.positions.size());
        for (std::size_t v = 0; v < read.positions.size(); ++v)
            CHECK((read.positions[v] - original.positions[v]).norm() <= 1e-3);
        CHECK(read.lines.size() == original.lines.size());
    }
    const auto rounded = [](const Primitive& primitive) { return segmentsOf(primitive, 2); };
    CHECK(rounded(onlyPrimitive(back, 0)) == rounded(scene.meshes[0].primitives[0]));
}

TEST_CASE("Lines and points go through the compressor to X3D as they are, beside the triangles", "[io][x3d]") {
    TemporaryFolder folder;
    // Two boxes (a repeated part) and a coloured polyline and points, which are never tiled.
    writeTextFile(
        folder / "input.x3d",
        x3dScene("<Transform translation='-3 0 0'><Shape><Appearance><Material diffuseColor='0.8 0.8 0.8'/>"
                 "</Appearance><Box/></Shape></Transform>"
                 "<Transform translation='3 0 0'><Shape><Appearance><Material diffuseColor='0.8 0.8 0.8'/>"
                 "</Appearance><Box/></Shape></Transform>"
                 "<Transform translation='0 2 0'><Shape><Appearance><Material emissiveColor='0 0.5 1'/></Appearance>"
                 "<IndexedLineSet coordIndex='0 1 2 -1'><Coordinate point='-3 0 0 0 1 0 3 0 0'/>"
                 "<Color color='1 0 0 0 1 0 0 0 1'/></IndexedLineSet></Shape>"
                 "<Shape><Appearance><Material emissiveColor='1 1 0'/></Appearance>"
                 "<PointSet><Coordinate point='0 0 1 0 0 -1'/></PointSet></Shape></Transform>"));
    const CompressionReport report = compressFile(folder / "input.x3d", folder / "output.x3d");
    (void)report;
    const Scene output = readScene(folder / "output.x3d");
    std::vector<Primitive> lines, points;
    for (const WorldPrimitive& world : flattenScene(output)) {
        if (world.primitive.topology == Topology::Lines) lines.push_back(world.primitive);
        if (world.primitive.topology == Topology::Points) points.push_back(world.primitive);
    }
    REQUIRE(lines.size() == 1);
    const std::set<PositionSegment> expected = {{{-3, 2, 0}, {0, 3, 0}}, {{0, 3, 0}, {3, 2, 0}}};
    CHECK(segmentsOf(lines[0], 3) == expected);
    REQUIRE(lines[0].colors.size() == lines[0].positions.size());
    const auto near = [&](const Eigen::Vector3d& at) {
        for (std::size_t v = 0; v < lines[0].positions.size(); ++v)
            if ((lines[0].positions[v] - at).norm() < 1e-2) return lines[0].colors[v];
        return Eigen::Vector4d(-1, -1, -1, -1);
    };
    CHECK((near({-3, 2, 0}) - Eigen::Vector4d(1, 0, 0, 1)).norm() < 1e-3);
    CHECK((near({0, 3, 0}) - Eigen::Vector4d(0, 1, 0, 1)).norm() < 1e-3);
    CHECK((near({3, 2, 0}) - Eigen::Vector4d(0, 0, 1, 1)).norm() < 1e-3);
    REQUIRE(points.size() == 1);
    REQUIRE(points[0].positions.size() == 2);
    std::set<Point> pointSet;
    for (const Eigen::Vector3d& p : points[0].positions)
        pointSet.insert(pointOf(p.unaryExpr([](double x) { return std::round(x * 1000) / 1000; })));
    CHECK(pointSet == std::set<Point>{{0, 2, 1}, {0, 2, -1}});
    REQUIRE(points[0].material >= 0);
    CHECK((output.materials[std::size_t(points[0].material)].baseColorFactor - Eigen::Vector4d(1, 1, 0, 1)).norm() <
          1e-6);
    // The boxes are still drawn: 2 of 6 faces of 2 by 2.
    const TriangleMesh boxes = worldMesh(output);
    double area = 0;
    for (const Triangle& t : boxes.triangles)
        area += (boxes.positions[t[1]] - boxes.positions[t[0]])
                    .cross(boxes.positions[t[2]] - boxes.positions[t[0]])
                    .norm() /
                2;
    CHECK(area == Approx(48).epsilon(1e-3));
}
