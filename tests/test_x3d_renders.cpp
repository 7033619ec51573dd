// X3D output renders as its X3D input (issue 15): faces cut as the browser cuts them, double-sidedness kept per
// shape, X3D 4's tangents kept where a normal texture reads them. Each fix has a test where it must act and one
// where it must not, and the shared model it was found on is rendered against its input (render_compare.sh).
#include "symcompress/io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

std::string shapeX3d(const std::string& appearance, const std::string& geometry) {
    return "<X3D version='4.0'><Scene><Shape>" + appearance + geometry + "</Shape></Scene></X3D>";
}

// The triangles by the points of the file (the reader's vertices mapped back through their positions).
std::vector<std::array<int, 3>> trianglesByPoint(const Primitive& primitive,
                                                 const std::vector<Eigen::Vector3d>& points) {
    std::vector<std::array<int, 3>> out;
    for (const Triangle& t : primitive.triangles) {
        std::array<int, 3> corners{};
        for (int k = 0; k < 3; ++k)
            corners[std::size_t(k)] =
                int(std::find_if(points.begin(), points.end(),
                                 [&](const Eigen::Vector3d& p) {
                                     return (p - primitive.positions[t[std::size_t(k)]]).norm() < 1e-12;
                                 }) -
                    points.begin());
        out.push_back(corners);
    }
    return out;
}

void compressAndCompare(const std::string& model) {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    // The model's folder copied, so that the output refers to its textures as the input does (the render
    // server serves the two files' folders only).
    TemporaryFolder folder;
    const fs::path input = modelPath(model);
    for (const auto& entry : fs::recursive_directory_iterator(input.parent_path())) {
        const fs::path target = folder.path() / fs::relative(entry.path(), input.parent_path());
        if (entry.is_directory())
            fs::create_directories(target);
        else
            fs::copy_file(entry.path(), target);
    }
    const fs::path copy = folder / input.filename().string(), output = folder / "out.x3d";
    const CommandResult compressed =
        runCommand(quoted(SYMCOMPRESS_CLI) + " -q " + quoted(copy) + " -o " + quoted(output));
    INFO(compressed.output);
    REQUIRE(compressed.status == 0);
    const CommandResult verified = runCommand(quoted(SYMDECOMPRESS_CLI) + " " + quoted(output) + " -o " +
                                              quoted(folder / "flat.ply") + " --verify " + quoted(copy));
    INFO(verified.output);
    CHECK(verified.status == 0);
    checkRendersSame(copy, output);
}

}  // namespace

TEST_CASE("A convex face of an IndexedFaceSet is cut as the browser cuts it: a fan from its first corner",
          "[io][x3d][renders]") {
    TemporaryFolder folder;
    // A quad bent along one diagonal: ear clipping may cut it along the other, which bends it otherwise.
    const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 0.2}, {1, 1, 0}, {0, 1, 0.2}};
    const std::string coordinate = "<Coordinate point='0 0 0 1 0 0.2 1 1 0 0 1 0.2'/>";
    SECTION("convex (the default): the fan (0 1 2) (0 2 3), whichever corner it starts from") {
        for (const std::string& index : {"0 1 2 3", "1 2 3 0"}) {
            writeTextFile(folder / "quad.x3d", shapeX3d("", "<IndexedFaceSet coordIndex='" + index + " -1'>" +
                                                                coordinate + "</IndexedFaceSet>"));
            const auto triangles = trianglesByPoint(readScene(folder / "quad.x3d").meshes[0].primitives[0], points);
            const int first = index[0] - '0';
            REQUIRE(triangles.size() == 2);
            for (const auto& t : triangles) CHECK(std::find(t.begin(), t.end(), first) != t.end());
        }
    }
    SECTION("not where the face is concave, nor where convex='false': cut correctly (no triangle outside it)") {
        // An arrow head: a fan from its first corner, the reflex one, would cover the notch.
        const std::string arrow = "<Coordinate point='1 0.4 0 0 0 0 2 0 0 2 0.2 0 1 1 0'/>";
        for (const std::string& convex : {"", " convex='false'"}) {
            writeTextFile(folder / "arrow.x3d", shapeX3d("", "<IndexedFaceSet coordIndex='0 1 2 3 4 -1'" + convex +
                                                                 ">" + arrow + "</IndexedFaceSet>"));
            const Primitive arrowHead = readScene(folder / "arrow.x3d").meshes[0].primitives[0];
            double area = 0;
            for (const Triangle& t : arrowHead.triangles)
                area += 0.5 * (arrowHead.positions[t[1]] - arrowHead.positions[t[0]])
                                  .cross(arrowHead.positions[t[2]] - arrowHead.positions[t[0]])
                                  .z();
            // The shoelace area of the polygon, every triangle counter-clockwise.
            CHECK(area == Approx(0.5 * ((1 * 0 - 0 * 0.4) + (0 * 0 - 2 * 0) + (2 * 0.2 - 2 * 0) + (2 * 1 - 1 * 0.2) +
                                        (1 * 0.4 - 1 * 1))));
            for (const Triangle& t : arrowHead.triangles)
                CHECK((arrowHead.positions[t[1]] - arrowHead.positions[t[0]])
                          .cross(arrowHead.positions[t[2]] - arrowHead.positions[t[0]])
                          .z() > 0);
        }
    }
}

TEST_CASE(
    "Double-sidedness is each shape's own: a material shared with solid='false' shapes is not made "
    "double-sided for solid ones",
    "[io][x3d][renders]") {
    TemporaryFolder folder;
    const std::string triangle = "<Coordinate point='0 0 0 1 0 0 0 1 0'/>";
    auto twoShapes = [&](const std::string& firstSolid, const std::string& secondSolid) {
        return "<X3D><Scene><Shape><Appearance DEF='grey'><Material diffuseColor='0.2 0.2 0.2'/></Appearance>"
               "<IndexedFaceSet coordIndex='0 1 2 -1'" +
               firstSolid + ">" + triangle +
               "</IndexedFaceSet></Shape><Transform translation='2 0 0'><Shape><Appearance USE='grey'/>"
               "<IndexedFaceSet coordIndex='0 1 2 -1'" +
               secondSolid + ">" + triangle + "</IndexedFaceSet></Shape></Transform></Scene></X3D>";
    };
    auto sidedness = [](const Scene& scene) {
        std::vector<bool> out;
        for (const Mesh& mesh : scene.meshes)
            out.push_back(scene.materials[std::size_t(mesh.primitives[0].material)].doubleSided);
        return out;
    };
    SECTION("one solid, one not: two materials, the same but for their sidedness") {
        for (const auto& [first, second] : {std::pair<std::string, std::string>{"", " solid='false'"},
                                            std::pair<std::string, std::string>{" solid='false'", ""}}) {
            writeTextFile(folder / "mixed.x3d", twoShapes(first, second));
            const Scene scene = readScene(folder / "mixed.x3d");
            CHECK(sidedness(scene) == std::vector<bool>{first.empty() ? false : true, second.empty() ? false : true});
            REQUIRE(scene.materials.size() == 2);
            Material a = scene.materials[0];
            a.doubleSided = scene.materials[1].doubleSided;
            CHECK(a == scene.materials[1]);
            writeScene(scene, folder / "again.x3d");
            CHECK(sidedness(readScene(folder / "again.x3d")) == sidedness(scene));
        }
    }
    SECTION("both alike: one material, as before") {
        writeTextFile(folder / "solid.x3d", twoShapes("", ""));
        CHECK(readScene(folder / "solid.x3d").materials.size() == 1);
        writeTextFile(folder / "open.x3d", twoShapes(" solid='false'", " solid='false'"));
        const Scene open = readScene(folder / "open.x3d");
        REQUIRE(open.materials.size() == 1);
        CHECK(open.materials[0].doubleSided);
    }
}

TEST_CASE("X3D 4's Tangent is read as TANGENT and written where a normal texture reads it", "[io][x3d][renders]") {
    TemporaryFolder folder;
    const std::string image = "data:image/png;base64,iVBORw0KGgoAAAAB";
    const std::string geometry =
        "<IndexedTriangleSet index='0 1 2 0 2 3'><Coordinate point='0 0 0 1 0 0 1 1 0 0 1 0'/>"
        "<Normal vector='0 0 1 0 0 1 0 0 1 0 0 1'/><Tangent vector='1 0 0 1 1 0 0 1 0.6 0.8 0 -1 1 0 0 1'/>"
        "<TextureCoordinate point='0 0 1 0 1 1 0 1'/></IndexedTriangleSet>";
    auto tangentOf = [](const Primitive& primitive) -> const VertexAttribute* {
        for (const VertexAttribute& attribute : primitive.attributes)
            if (attribute.name == "TANGENT") return &attribute;
        return nullptr;
    };
    SECTION("with a normal texture: read, and written back vertex by vertex") {
        writeTextFile(folder / "mapped.x3d",
                      shapeX3d("<Appearance><PhysicalMaterial><ImageTexture containerField='normalTexture' url='\"" +
                                   image + "\"'/></PhysicalMaterial></Appearance>",
                               geometry));
        const Scene scene = readScene(folder / "mapped.x3d");
        const Primitive& quad = scene.meshes[0].primitives[0];
        const VertexAttribute* tangent = tangentOf(quad);
        REQUIRE(tangent);
        REQUIRE(tangent->components == 4);
        REQUIRE(tangent->values.size() == 4 * quad.positions.size());
        for (std::size_t v = 0; v < quad.positions.size(); ++v)
            if (quad.positions[v] == Eigen::Vector3d(1, 1, 0))
                CHECK(Eigen::Map<const Eigen::Vector4d>(tangent->values.data() + 4 * v) ==
                      Eigen::Vector4d(0.6, 0.8, 0, -1));
        writeScene(scene, folder / "again.x3d");
        CHECK_THAT(readTextFile(folder / "again.x3d"), Catch::Contains("<Tangent vector='"));
        const Scene again = readScene(folder / "again.x3d");
        const VertexAttribute* back = tangentOf(again.meshes[0].primitives[0]);
        REQUIRE(back);
        CHECK(back->values == tangent->values);
    }
    SECTION("without a normal texture: nothing reads them, none written") {
        writeTextFile(folder / "plain.x3d", shapeX3d("<Appearance><PhysicalMaterial/></Appearance>", geometry));
        const Scene scene = readScene(folder / "plain.x3d");
        writeScene(scene, folder / "again.x3d");
        CHECK_THAT(readTextFile(folder / "again.x3d"), !Catch::Contains("<Tangent"));
    }
}

TEST_CASE("Meshes no tile can carry (tangents) are still written within the budget, not to every digit",
          "[io][x3d][renders]") {
    TemporaryFolder folder;
    // A quad of 10 digits a coordinate, its tangents read by a normal texture: the tiles cannot carry it yet, so
    // no tile gives the budget its diagonal; the whole drawing's does.
    const std::string image = "data:image/png;base64,iVBORw0KGgoAAAAB";
    const std::string points =
        "0.1234567891 0.2345678912 0 1.3456789123 0.4567891234 0 1.5678912345 1.6789123456 0 "
        "0.7891234567 1.8912345678 0";
    const std::string tangents = "1 0 0 1 1 0 0 1 1 0 0 1 1 0 0 1";
    writeTextFile(folder / "mapped.x3d",
                  shapeX3d("<Appearance><PhysicalMaterial><ImageTexture containerField='normalTexture' url='\"" +
                               image + "\"'/></PhysicalMaterial></Appearance>",
                           "<IndexedTriangleSet index='0 1 2 0 2 3'><Coordinate point='" + points +
                               "'/><Normal vector='0 0 1 0 0 1 0 0 1 0 0 1'/><Tangent vector='" + tangents +
                               "'/><TextureCoordinate point='0 0 1 0 1 1 0 1'/></IndexedTriangleSet>"));
    const CommandResult compressed = runCommand(quoted(SYMCOMPRESS_CLI) + " -q " + quoted(folder / "mapped.x3d") +
                                                " -o " + quoted(folder / "out.x3d"));
    INFO(compressed.output);
    REQUIRE(compressed.status == 0);
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK_THAT(text, Catch::Contains("<Tangent"));
    CHECK_THAT(text, !Catch::Contains("0.1234567891"));  // rounded within the budget
    const CommandResult verified =
        runCommand(quoted(SYMDECOMPRESS_CLI) + " " + quoted(folder / "out.x3d") + " -o " + quoted(folder / "flat.ply") +
                   " --verify " + quoted(folder / "mapped.x3d"));
    INFO(verified.output);
    CHECK(verified.status == 0);
}

TEST_CASE("Meshes with tangents that one node draws at a rigid placement are merged with what is stored as it is",
          "[io][x3d][renders]") {
    TemporaryFolder folder;
    // Three parts the tiles cannot carry (tangents read by a normal texture), one material: two placed rigidly,
    // merged into one shape; one scaled, kept with its Transform (a viewer may turn its tangents otherwise).
    const std::string image = "data:image/png;base64,iVBORw0KGgoAAAAB";
    auto part = [&](const std::string& transform, const std::string& appearance) {
        return "<Transform " + transform + "><Shape>" + appearance +
               "<IndexedTriangleSet index='0 1 2 0 2 3'><Coordinate point='0 0 0 1 0 0 1 1 0 0 1 0'/>"
               "<Normal vector='0 0 1 0 0 1 0 0 1 0 0 1'/><Tangent vector='1 0 0 1 1 0 0 1 1 0 0 1 1 0 0 1'/>"
               "<TextureCoordinate point='0 0 1 0 1 1 0 1'/></IndexedTriangleSet></Shape></Transform>";
    };
    const std::string appearance =
        "<Appearance DEF='mapped'><PhysicalMaterial><ImageTexture "
        "containerField='normalTexture' url='\"" +
        image + "\"'/></PhysicalMaterial></Appearance>";
    writeTextFile(folder / "parts.x3d",
                  "<X3D version='4.0'><Scene>" + part("translation='2 0 0'", appearance) +
                      part("translation='0 3 0' rotation='0 0 1 0.5'", "<Appearance USE='mapped'/>") +
                      part("translation='5 0 0' scale='2 1 1'", "<Appearance USE='mapped'/>") + "</Scene></X3D>");
    const CommandResult compressed = runCommand(quoted(SYMCOMPRESS_CLI) + " -q " + quoted(folder / "parts.x3d") +
                                                " -o " + quoted(folder / "out.x3d"));
    INFO(compressed.output);
    REQUIRE(compressed.status == 0);
    const std::string text = readTextFile(folder / "out.x3d");
    std::size_t shapes = 0;
    for (std::size_t at = text.find("<Shape"); at != std::string::npos; at = text.find("<Shape", at + 1)) ++shapes;
    CHECK(shapes == 2);
    CHECK_THAT(text, Catch::Contains("scale='2 1 1'"));
    const Scene out = readScene(folder / "out.x3d");
    for (const Mesh& mesh : out.meshes)
        for (const Primitive& primitive : mesh.primitives)
            CHECK(std::any_of(primitive.attributes.begin(), primitive.attributes.end(),
                              [](const VertexAttribute& a) { return a.name == "TANGENT"; }));
    const CommandResult verified =
        runCommand(quoted(SYMDECOMPRESS_CLI) + " " + quoted(folder / "out.x3d") + " -o " + quoted(folder / "flat.ply") +
                   " --verify " + quoted(folder / "parts.x3d"));
    INFO(verified.output);
    CHECK(verified.status == 0);
}

TEST_CASE("X3D texture coordinates are written as float32, as short as they were read", "[io][x3d][renders]") {
    TemporaryFolder folder;
    writeTextFile(folder / "quad.x3d",
                  shapeX3d("<Appearance><Material/><ImageTexture url='\"data:image/png;base64,iVBORw0KGgoAAAAB\"'/>"
                           "</Appearance>",
                           "<IndexedFaceSet coordIndex='0 1 2 3 -1'><Coordinate point='0 0 0 1 0 0 1 1 0 0 1 0'/>"
                           "<TextureCoordinate point='0.2017 0.0015 0.9084 0.0015 0.9084 0.2508 0.2017 0.2508'/>"
                           "</IndexedFaceSet>"));
    writeScene(readScene(folder / "quad.x3d"), folder / "again.x3d");
    const std::string text = readTextFile(folder / "again.x3d");
    CHECK_THAT(text, Catch::Contains("0.2017 0.0015"));  // not 0.0014999999999999458
    CHECK_THAT(text, Catch::Contains("0.9084 0.2508"));
}

TEST_CASE(
    "Compressed X3D renders as its X3D input: the grass (faces cut as fans), the Chevy (sidedness per shape), "
    "the cat (tangents)",
    "[io][x3d][renders][models]") {
    SECTION("grass") { compressAndCompare("cge_grass_flowers/grass_flowers.x3d"); }
    SECTION("Chevy") { compressAndCompare("savage_chevy_tahoe/ChevyTahoe.x3d"); }
    SECTION("cat") { compressAndCompare("cge_cat_x3d/scene.x3d"); }
}
