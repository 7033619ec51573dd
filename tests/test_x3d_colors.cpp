// X3D vertex colours (issue 15): glTF's COLOR_0 is linear and multiplies the base colour; X3D's Color and
// ColorRGBA take the place of Phong's (and UnlitMaterial's) colour, sRGB-encoded as that colour is, and multiply
// PhysicalMaterial's base colour, linear as it is (docs/scene-model.md, "Colour spaces").
#include "symcompress/io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

// IEC 61966-2-1, written out here so that the test does not check the code against itself.
double expectedLinear(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

// `mesh` as the scene's only mesh, drawn by one root node.
void drawOnce(Scene& scene, Mesh mesh) {
    scene.meshes = {std::move(mesh)};
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
}

// Two quads side by side with vertex colours (one alpha below 1), the first on `phong` (not metal: written as
// Phong's Material), the second on `physical` (metal: written as PhysicalMaterial).
Scene colouredQuads(const Eigen::Vector4d& phongBase) {
    Scene scene;
    Material phong, physical;
    phong.baseColorFactor = phongBase;
    phong.metallicFactor = 0;
    physical.metallicFactor = 1;
    physical.baseColorFactor = {0.5, 0.5, 0.5, 1};
    scene.materials = {phong, physical};
    Mesh mesh;
    for (int k = 0; k < 2; ++k) {
        Primitive quad;
        const double x = 1.1 * k;
        quad.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
        quad.normals.assign(4, Eigen::Vector3d::UnitZ());
        quad.colors = {{0.21404114, 0.02, 1, 1}, {0.6, 0.8, 0.001, 1}, {1, 1, 1, 0.5}, {0, 0.05, 0.3, 1}};
        quad.triangles = {{0, 1, 2}, {0, 2, 3}};
        quad.material = k;
        mesh.primitives.push_back(quad);
    }
    drawOnce(scene, std::move(mesh));
    return scene;
}

std::string quadX3d(const std::string& appearance, const std::string& color) {
    return "<X3D version='4.0'><Scene><Shape>" + appearance +
           "<IndexedFaceSet coordIndex='0 1 2 3 -1'><Coordinate point='0 0 0 1 0 0 1 1 0 0 1 0'/>" + color +
           "</IndexedFaceSet></Shape></Scene></X3D>";
}

}  // namespace

TEST_CASE(
    "Vertex colours: glTF -> X3D -> glTF gives COLOR_0 back, sRGB-encoded for Phong, linear for "
    "PhysicalMaterial",
    "[io][x3d][colors]") {
    TemporaryFolder folder;
    for (const Eigen::Vector4d base : {Eigen::Vector4d(1, 1, 1, 1), Eigen::Vector4d(0.5, 0.25, 1, 0.75)}) {
        INFO("Phong base colour " << base.transpose());
        WriteOptions plain;
        plain.draco = false;  // float COLOR_0, as read
        writeScene(colouredQuads(base), folder / "quads.glb", plain);
        const Scene input = readScene(folder / "quads.glb");
        writeScene(input, folder / "quads.x3d");
        const std::string text = readTextFile(folder / "quads.x3d");
        CHECK_THAT(text, Catch::Contains("<PhysicalMaterial"));
        CHECK_THAT(text, Catch::Contains("<Material"));
        // Phong's colours: sRGB-encoded, the base colour multiplied in (Color takes its place). Linear 0.21404114
        // is sRGB 0.5; PhysicalMaterial's are the linear values, as they are.
        if (base[0] == 1) CHECK_THAT(text, Catch::Contains("color='0.5 "));
        CHECK_THAT(text, Catch::Contains("color='0.21404114 0.02 1 1"));
        writeScene(readScene(folder / "quads.x3d"), folder / "back.glb", plain);
        const Scene back = readScene(folder / "back.glb");
        REQUIRE(back.meshes.size() == 2);  // a Shape each
        for (int k = 0; k < 2; ++k) {
            const Primitive &a = input.meshes[0].primitives[std::size_t(k)],
                            &b = back.meshes[std::size_t(k)].primitives[0];
            REQUIRE(b.colors.size() == a.colors.size());
            // Each vertex at its place (the reader may order them otherwise).
            for (std::size_t v = 0; v < a.positions.size(); ++v)
                for (std::size_t w = 0; w < b.positions.size(); ++w)
                    if ((a.positions[v] - b.positions[w]).norm() < 1e-6) {
                        INFO("primitive " << k << " vertex " << v);
                        CHECK((a.colors[v] - b.colors[w]).cwiseAbs().maxCoeff() < 1e-6);
                    }
        }
        const Material& phong = back.materials[std::size_t(back.meshes[0].primitives[0].material)];
        CHECK((phong.baseColorFactor - input.materials[0].baseColorFactor).cwiseAbs().maxCoeff() < 1e-6);
    }
}

TEST_CASE(
    "X3D vertex colours are read as the browser draws them: decoded with Phong, as they are with "
    "PhysicalMaterial",
    "[io][x3d][colors]") {
    TemporaryFolder folder;
    const std::string color = "<Color color='0.5 0.5 0.5 1 0 0 0 1 0 0.2 0.4 0.6'/>";
    SECTION("Phong's Material: sRGB-decoded, divided by the base colour that glTF multiplies it with") {
        writeTextFile(folder / "phong.x3d",
                      quadX3d("<Appearance><Material diffuseColor='0.5 1 1'/></Appearance>", color));
        const Scene scene = readScene(folder / "phong.x3d");
        const Primitive& quad = scene.meshes[0].primitives[0];
        REQUIRE(quad.colors.size() == 4);
        const Eigen::Vector3d base = scene.materials[0].baseColorFactor.head<3>();
        CHECK(std::abs(base[0] - expectedLinear(0.5)) < 1e-9);
        for (std::size_t v = 0; v < 4; ++v) {
            const Eigen::Vector3d drawn = quad.colors[v].head<3>().cwiseProduct(base);  // what glTF draws
            const double x = quad.positions[v].x(), y = quad.positions[v].y();
            const Eigen::Vector3d expected =
                x == 0 && y == 0   ? Eigen::Vector3d::Constant(expectedLinear(0.5))
                : x == 1 && y == 0 ? Eigen::Vector3d(1, 0, 0)
                : x == 1           ? Eigen::Vector3d(0, 1, 0)
                                   : Eigen::Vector3d(expectedLinear(0.2), expectedLinear(0.4), expectedLinear(0.6));
            CHECK((drawn - expected).cwiseAbs().maxCoeff() < 1e-9);
            CHECK(quad.colors[v][3] == 1);
        }
    }
    SECTION("PhysicalMaterial: linear, multiplying the base colour as glTF's COLOR_0: as they are") {
        writeTextFile(folder / "physical.x3d",
                      quadX3d("<Appearance><PhysicalMaterial baseColor='0.5 1 1'/></Appearance>",
                              "<ColorRGBA color='0.5 0.5 0.5 0.5 1 0 0 1 0 1 0 1 0.2 0.4 0.6 1'/>"));
        const Primitive quad = readScene(folder / "physical.x3d").meshes[0].primitives[0];
        REQUIRE(quad.colors.size() == 4);
        for (std::size_t v = 0; v < 4; ++v)
            if (quad.positions[v].isZero())
                CHECK((quad.colors[v] - Eigen::Vector4d(0.5, 0.5, 0.5, 0.5)).norm() < 1e-12);
    }
}

TEST_CASE("Vertex colours as X3D render in X_ITE as the glTF's in three.js", "[io][x3d][colors][models]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    // Unlit (KHR_materials_unlit: X3D 4's UnlitMaterial), which no light changes, so that the two viewers agree:
    // a strip of quads from dark to light, on a white and on a tinted base colour.
    Scene scene;
    for (const Eigen::Vector4d base : {Eigen::Vector4d(1, 1, 1, 1), Eigen::Vector4d(0.8, 0.5, 1, 1)}) {
        Material unlit;
        unlit.baseColorFactor = base;
        unlit.metallicFactor = 0;
        unlit.doubleSided = true;
        unlit.extensions.push_back({"KHR_materials_unlit", "{}", {}, false});
        scene.materials.push_back(unlit);
    }
    Mesh mesh;
    for (int k = 0; k < 6; ++k) {
        Primitive quad;
        const double x = k % 3, y = k / 3;
        quad.positions = {{x, y, 0}, {x + 0.9, y, 0}, {x + 0.9, y + 0.9, 0}, {x, y + 0.9, 0}};
        quad.normals.assign(4, Eigen::Vector3d::UnitZ());
        // One colour a quad: the viewers interpolate between corners in other spaces (three.js linear, X_ITE
        // in the colour's own), which no conversion of the corners makes equal.
        const double level = 0.02 + 0.3 * (k % 3);
        quad.colors.assign(4, Eigen::Vector4d(level, 0.9 - level, 0.05 + level / 2, 1));
        quad.triangles = {{0, 1, 2}, {0, 2, 3}};
        quad.material = k / 3;
        mesh.primitives.push_back(quad);
    }
    drawOnce(scene, std::move(mesh));
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "colours.glb", plain);
    writeScene(readScene(folder / "colours.glb"), folder / "colours.x3d");
    CHECK_THAT(readTextFile(folder / "colours.x3d"), Catch::Contains("<UnlitMaterial"));
    const CommandResult there = renderCompare(folder / "colours.glb", folder / "colours.x3d", "lit", "d");
    INFO(there.output);
    CHECK(there.status == 0);
}
