// PLY and OBJ colours (issue 15): the colours of PLY vertices, OBJ vertices and MTL materials are display values,
// sRGB-encoded, as three.js's PLYLoader, OBJLoader and MTLLoader read them; glTF's COLOR_0 and factors are linear
// (docs/scene-model.md, "Colour spaces"). Read as linear, written back as they were.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// IEC 61966-2-1, written out here so that the test does not check the code against itself.
double expectedLinear(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

std::string textOf(const std::filesystem::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    return std::string(bytes.begin(), bytes.end());
}

}  // namespace

TEST_CASE("PLY vertex colours are sRGB-encoded: read as linear COLOR_0, written back byte for byte", "[io]") {
    TemporaryFolder folder;
    writeTextFile(folder / "coloured.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property uchar alpha\nelement face 1\n"
                  "property list uchar int vertex_indices\nend_header\n"
                  "0 0 0 128 0 255 255\n1 0 0 188 64 10 128\n0 1 0 255 255 255 255\n"
                  "3 0 1 2\n");
    const Scene scene = readScene(folder / "coloured.ply");
    const Primitive& read = scene.meshes.at(0).primitives.at(0);
    REQUIRE(read.colors.size() == 3);
    CHECK(read.colors[0][0] == Approx(expectedLinear(128 / 255.0)).epsilon(1e-12));
    CHECK(read.colors[0][2] == Approx(1));
    CHECK(read.colors[1][1] == Approx(expectedLinear(64 / 255.0)).epsilon(1e-12));
    CHECK(read.colors[1][3] == Approx(128 / 255.0).epsilon(1e-12));  // alpha is linear as it is
    writeScene(scene, folder / "written.ply");
    const Primitive back = readScene(folder / "written.ply").meshes.at(0).primitives.at(0);
    REQUIRE(back.colors.size() == 3);
    for (std::size_t v = 0; v < 3; ++v) CHECK(back.colors[v] == read.colors[v]);  // the same bytes read again
}

TEST_CASE("OBJ and MTL colours are sRGB-encoded: read as linear factors and COLOR_0, written back as they were",
          "[io]") {
    TemporaryFolder folder;
    writeTextFile(folder / "part.mtl", "newmtl red\nKd 0.8 0.2 0.1\nKe 0.5 0 0\n");
    writeTextFile(folder / "part.obj",
                  "mtllib part.mtl\nv 0 0 0 0.5 0.25 1\nv 1 0 0 0.5 0.25 1\nv 0 1 0 0 0 0\n"
                  "usemtl red\nf 1 2 3\n");
    const Scene scene = readScene(folder / "part.obj");
    REQUIRE(scene.materials.size() == 1);
    const Material& material = scene.materials[0];
    CHECK(material.baseColorFactor[0] == Approx(expectedLinear(0.8)).epsilon(1e-12));
    CHECK(material.baseColorFactor[2] == Approx(expectedLinear(0.1)).epsilon(1e-12));
    CHECK(material.emissiveFactor[0] == Approx(expectedLinear(0.5)).epsilon(1e-12));
    const Primitive& read = scene.meshes.at(0).primitives.at(0);
    REQUIRE(read.colors.size() == 3);
    CHECK(read.colors[0][0] == Approx(expectedLinear(0.5)).epsilon(1e-12));
    CHECK(read.colors[0][1] == Approx(expectedLinear(0.25)).epsilon(1e-12));

    // Written back: the material's fields as read, the vertex colours re-encoded.
    writeScene(scene, folder / "written.obj");
    CHECK(textOf(folder / "written.mtl").find("Kd 0.8 0.2 0.1\n") != std::string::npos);
    CHECK(textOf(folder / "written.mtl").find("Ke 0.5 0 0\n") != std::string::npos);
    CHECK(textOf(folder / "written.obj").find("v 0 0 0 0.5 0.25 1\n") != std::string::npos);
    const Scene back = readScene(folder / "written.obj");
    const Primitive& again = back.meshes.at(0).primitives.at(0);
    REQUIRE(again.material >= 0);
    CHECK(back.materials.at(std::size_t(again.material)).baseColorFactor.isApprox(material.baseColorFactor, 1e-12));
    REQUIRE(again.colors.size() == 3);
    for (std::size_t v = 0; v < 3; ++v) CHECK(again.colors[v].isApprox(read.colors[v], 1e-7));

    // A glTF material (no Phong fields): its linear factor written as the shortest sRGB value that reads back.
    Scene gltf = scene;
    gltf.materials[0].phong.reset();
    gltf.materials[0].baseColorFactor = {float(expectedLinear(0.5)), 0, 0, 1};
    writeScene(gltf, folder / "from_gltf.obj");
    CHECK(textOf(folder / "from_gltf.mtl").find("Kd 0.5 0 0\n") != std::string::npos);
}
