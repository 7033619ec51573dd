// X3D materials (issue 15): X3D 4's PhysicalMaterial and Material texture fields read into glTF's slots and
// written back, the colour spaces between glTF's linear factors and Phong's sRGB-encoded colours, X3D 3.3 output
// kept where nothing needs X3D 4, and broken material nodes warned about.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

// IEC 61966-2-1, written out here so that the test does not check the code against itself.
double expectedLinear(double srgb) { return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4); }

bool warned(const Scene& scene, const std::string& text) {
    return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                       [&](const std::string& warning) { return warning.find(text) != std::string::npos; });
}

// A quad with two texture coordinate sets, mapped 'uvA' and 'uvB', and `appearance` (XML) on it.
std::string quadWith(const std::string& appearance, const std::string& version = "4.0") {
    return "<X3D version='" + version + "'><Scene><Shape>" + appearance +
           "<IndexedFaceSet solid='false' coordIndex='0 1 2 3 -1'><Coordinate point='0 0 0 1 0 0 1 1 0 0 1 0'/>"
           "<MultiTextureCoordinate><TextureCoordinate mapping='uvA' point='0 0 1 0 1 1 0 1'/>"
           "<TextureCoordinate mapping='uvB' point='0.5 0.5 0.75 0.5 0.75 0.75 0.5 0.75'/></MultiTextureCoordinate>"
           "</IndexedFaceSet></Shape></Scene></X3D>";
}

// Three small "images" (PNG signatures and a byte each: the reader keeps bytes, it does not decode them).
const std::string kImageA = "data:image/png;base64,iVBORw0KGgoAAAAB",
                  kImageB = "data:image/png;base64,iVBORw0KGgoAAAAC",
                  kImageC = "data:image/png;base64,iVBORw0KGgoAAAAD";

// A scene of one textured quad whose material fills every core slot: the base colour on TEXCOORD_0, the
// emissive texture on TEXCOORD_1, a normal scale and an occlusion strength; two images, one of them used thrice.
Scene everySlotScene() {
    Scene scene;
    Texture a, b;
    a.bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1};
    a.mimeType = "image/png";
    b.bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 2};
    b.mimeType = "image/png";
    b.sampler = {9728, 9986, 33071, 33648, ""};  // as X3D's TextureProperties
    scene.textures = {a, b};
    Material material;
    material.name = "pbr";
    material.baseColorFactor = {0.5, 0.25, 0.125, 1};
    material.metallicFactor = 0.75;
    material.roughnessFactor = 0.375;
    material.emissiveFactor = {0.25, 0.5, 1};
    material.baseColorTexture.texture = 0;
    material.metallicRoughnessTexture.texture = 1;
    material.normalTexture = {1, 0, 0.75, std::nullopt};
    material.occlusionTexture = {1, 0, 0.5, std::nullopt};
    material.emissiveTexture = {0, 1, 1, std::nullopt};
    material.alphaMode = Material::AlphaMode::Mask;
    material.alphaCutoff = 0.25;
    scene.materials = {material};
    Primitive quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.normals.assign(4, Eigen::Vector3d::UnitZ());
    quad.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    quad.attributes = {{"TEXCOORD_1", 2, {0.5, 0.5, 0.75, 0.5, 0.75, 0.25, 0.5, 0.25}}};
    quad.triangles = {{0, 1, 2}, {0, 2, 3}};
    quad.material = 0;
    scene.meshes.push_back({"quad", {quad}, "", {}});
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    validateScene(scene);
    return scene;
}

// A texture use by value: the image's bytes (indices differ between files), its sampler, the set and the scale.
std::string describeUse(const Scene& scene, const TextureRef& use) {
    if (use.texture < 0) return "-";
    const Texture& texture = scene.textures[std::size_t(use.texture)];
    const TextureSampler& s = texture.sampler;
    return std::string(texture.bytes.begin(), texture.bytes.end()) + " sampler " + std::to_string(s.magFilter) + "," +
           std::to_string(s.minFilter) + "," + std::to_string(s.wrapS) + "," + std::to_string(s.wrapT) + " set " +
           std::to_string(use.texCoord) + " scale " + std::to_string(use.scale);
}

std::vector<std::string> describeSlots(const Scene& scene, const Material& m) {
    std::vector<std::string> out;
    const auto refs = m.textureRefs();
    for (int s = 0; s < 5; ++s) out.push_back(describeUse(scene, *refs[std::size_t(s)]));
    return out;
}

}  // namespace

TEST_CASE("An X3D 4 PhysicalMaterial with its textures is read into glTF's slots", "[io][x3d][materials]") {
    TemporaryFolder folder;
    writeTextFile(folder / "pbr.x3d",
                  quadWith("<Appearance><PhysicalMaterial DEF='P' baseColor='0.5 0.25 0.125' metallic='0.3' "
                           "roughness='0.6' emissiveColor='0.1 0.2 0.3' transparency='0.25' normalScale='0.75' "
                           "occlusionStrength='0.5' baseTextureMapping='uvA' emissiveTextureMapping='uvB'>"
                           "<ImageTexture DEF='A' containerField='baseTexture' url='\"" +
                           kImageA +
                           "\"'/>"
                           "<ImageTexture USE='A' containerField='metallicRoughnessTexture'/>"
                           "<ImageTexture containerField='normalTexture' url='\"" +
                           kImageB +
                           "\"'/>"
                           "<ImageTexture containerField='occlusionTexture' url='\"" +
                           kImageC +
                           "\"'/>"
                           "<ImageTexture USE='A' containerField='emissiveTexture'/>"
                           "</PhysicalMaterial></Appearance>"));
    const Scene scene = readScene(folder / "pbr.x3d");
    INFO(scene.warnings.size());
    REQUIRE(scene.materials.size() == 1);
    const Material& m = scene.materials[0];
    // PhysicalMaterial's colours are linear, as glTF's: taken as they are.
    CHECK(m.baseColorFactor == Eigen::Vector4d(0.5, 0.25, 0.125, 0.75));
    CHECK(m.metallicFactor == 0.3);
    CHECK(m.roughnessFactor == 0.6);
    CHECK(m.emissiveFactor == Eigen::Vector3d(0.1, 0.2, 0.3));
    CHECK(m.alphaMode == Material::AlphaMode::Blend);
    CHECK_FALSE(m.phong);
    CHECK(scene.textures.size() == 3);  // A once, however often it is USEd
    CHECK(m.baseColorTexture == TextureRef{0, 0, 1, std::nullopt});
    CHECK(m.metallicRoughnessTexture == TextureRef{0, 0, 1, std::nullopt});
    CHECK(m.normalTexture == TextureRef{1, 0, 0.75, std::nullopt});
    CHECK(m.occlusionTexture == TextureRef{2, 0, 0.5, std::nullopt});
    CHECK(m.emissiveTexture == TextureRef{0, 1, 1, std::nullopt});  // mapped to 'uvB', the second set
    const Primitive& quad = scene.meshes.at(0).primitives.at(0);
    REQUIRE(quad.attributes.size() == 1);
    CHECK(quad.attributes[0].name == "TEXCOORD_1");
    const auto corner =
        std::find(quad.positions.begin(), quad.positions.end(), Eigen::Vector3d(1, 1, 0)) - quad.positions.begin();
    CHECK(quad.texcoords[std::size_t(corner)] == Eigen::Vector2d(1, 0));  // v flipped to glTF's
    CHECK(quad.attributes[0].values[2 * std::size_t(corner)] == 0.75);
    CHECK(quad.attributes[0].values[2 * std::size_t(corner) + 1] == 0.25);

    SECTION("X3D 4's Material: its diffuse, normal and emissive textures fill the same slots") {
        writeTextFile(folder / "phong.x3d",
                      quadWith("<Appearance><Material diffuseColor='1 1 1' normalScale='2' diffuseTextureMapping='uvB'>"
                               "<ImageTexture containerField='diffuseTexture' url='\"" +
                               kImageA +
                               "\"'/>"
                               "<ImageTexture containerField='normalTexture' url='\"" +
                               kImageB +
                               "\"'/>"
                               "<ImageTexture containerField='specularTexture' url='\"" +
                               kImageC +
                               "\"'/>"
                               "</Material></Appearance>"));
        const Scene phong = readScene(folder / "phong.x3d");
        REQUIRE(phong.materials.size() == 1);
        CHECK(phong.materials[0].baseColorTexture == TextureRef{0, 1, 1, std::nullopt});
        CHECK(phong.materials[0].normalTexture == TextureRef{1, 0, 2, std::nullopt});
        CHECK(phong.materials[0].phong);
        CHECK(warned(phong, "phong.x3d: Material: specularTexture not carried through"));
        // Written back as X3D 4's Material with its texture fields and its Phong fields as they were.
        writeScene(phong, folder / "phong_out.x3d");
        const std::string text = readTextFile(folder / "phong_out.x3d");
        CHECK_THAT(text, Catch::Contains("version='4.0'"));
        CHECK_THAT(text, Catch::Contains("<Material diffuseColor='1 1 1' "
                                         "diffuseTextureMapping='TEXCOORD_1' normalTextureMapping='TEXCOORD_0' "
                                         "normalScale='2'><ImageTexture containerField='diffuseTexture'"));
        CHECK_THAT(text, !Catch::Contains("PhysicalMaterial"));
        const Scene again = readScene(folder / "phong_out.x3d");
        CHECK(again.materials.at(0).sameButName(phong.materials[0]));
    }
}

TEST_CASE("A glTF material with every core texture slot comes back from X3D with the same slots",
          "[io][x3d][materials]") {
    TemporaryFolder folder;
    const Scene scene = everySlotScene();
    writeScene(scene, folder / "in.gltf");
    const Scene gltf = readScene(folder / "in.gltf");
    writeScene(gltf, folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK_THAT(text, Catch::Contains("version='4.0'"));
    CHECK_THAT(text, Catch::Contains("<component name='Shape' level='2'/>"));
    CHECK_THAT(text, Catch::Contains("<PhysicalMaterial"));
    CHECK_THAT(text, Catch::Contains("<MultiTextureCoordinate>"));
    CHECK(occurrences(text, "data:image/png") == 2);  // each image once, then USEd
    CHECK_THAT(text,
               Catch::Contains("<TextureProperties boundaryModeS='CLAMP_TO_EDGE' boundaryModeT='MIRRORED_REPEAT' "
                               "magnificationFilter='NEAREST_PIXEL' minificationFilter='NEAREST_PIXEL_AVG_MIPMAP' "
                               "generateMipMaps='true'/>"));
    const Scene x3d = readScene(folder / "out.x3d");
    REQUIRE(x3d.materials.size() == 1);
    const Material &before = scene.materials[0], &after = x3d.materials[0];
    CHECK(describeSlots(x3d, after) == describeSlots(scene, before));
    CHECK(after.baseColorFactor == before.baseColorFactor);
    CHECK(after.metallicFactor == before.metallicFactor);
    CHECK(after.roughnessFactor == before.roughnessFactor);
    CHECK(after.emissiveFactor == before.emissiveFactor);
    CHECK(after.alphaMode == Material::AlphaMode::Mask);  // X3D 4's Appearance alphaMode and alphaCutoff
    CHECK(after.alphaCutoff == 0.25);
    // The emissive texture's set comes back as TEXCOORD_1, with its coordinates.
    const Primitive& quad = x3d.meshes.at(0).primitives.at(0);
    REQUIRE(quad.attributes.size() == 1);
    CHECK(quad.attributes[0].name == "TEXCOORD_1");
    std::vector<double> values = quad.attributes[0].values,
                        expected = scene.meshes[0].primitives[0].attributes[0].values;
    std::sort(values.begin(), values.end());
    std::sort(expected.begin(), expected.end());
    CHECK(values == expected);
    // And again through X3D: the same material and coordinates, as text.
    writeScene(x3d, folder / "again.x3d");
    const auto between = [](const std::string& in, const std::string& from, const std::string& to) {
        const std::size_t start = in.find(from);
        return start == std::string::npos ? std::string() : in.substr(start, in.find(to, start) - start);
    };
    const std::string again = readTextFile(folder / "again.x3d");
    // The second file's DEFs are unique.
    std::set<std::string> defs;
    for (std::size_t at = again.find("DEF='"); at != std::string::npos; at = again.find("DEF='", at + 1))
        CHECK(defs.insert(again.substr(at + 5, again.find('\'', at + 5) - at - 5)).second);
    CHECK_FALSE(between(text, "<Appearance", "</Appearance>").empty());
    CHECK(between(again, "<Appearance", "</Appearance>") == between(text, "<Appearance", "</Appearance>"));
    const auto unindented = [](std::string in) {  // the second file nests the mesh one Transform deeper
        in.erase(std::remove(in.begin(), in.end(), ' '), in.end());
        return in;
    };
    CHECK(unindented(between(again, "<MultiTextureCoordinate>", "</MultiTextureCoordinate>")) ==
          unindented(between(text, "<MultiTextureCoordinate>", "</MultiTextureCoordinate>")));
}

TEST_CASE("Colours convert between glTF's linear factors and X3D's sRGB-encoded Phong colours, both ways",
          "[io][x3d][materials]") {
    TemporaryFolder folder;
    SECTION("glTF -> X3D -> glTF gives the linear factors back") {
        Scene scene = everySlotScene();
        Material& m = scene.materials[0];
        m = Material{};
        m.metallicFactor = 0;  // drawable by Phong: X3D 3.3's Material
        m.roughnessFactor = 0.3;
        m.baseColorFactor = {0.002, expectedLinear(0.5), 0.9, 0.6};
        m.emissiveFactor = {0.0001, 0.5, 1};
        m.alphaMode = Material::AlphaMode::Blend;
        writeScene(scene, folder / "in.glb");
        writeScene(readScene(folder / "in.glb"), folder / "out.x3d");
        const std::string text = readTextFile(folder / "out.x3d");
        CHECK_THAT(text, Catch::Contains("version='3.3'"));
        CHECK_THAT(text, !Catch::Contains("PhysicalMaterial"));
        // What is 0.5 in sRGB is written as 0.5: the colour X_ITE puts on screen for a Phong Material.
        CHECK_THAT(text, Catch::Contains("diffuseColor='0.02584 0.5 0.9"));
        writeScene(readScene(folder / "out.x3d"), folder / "back.glb");
        const Material back = readScene(folder / "back.glb").materials.at(0);
        for (int c = 0; c < 4; ++c) CHECK(std::abs(back.baseColorFactor[c] - m.baseColorFactor[c]) < 1e-6);
        for (int c = 0; c < 3; ++c) CHECK(std::abs(back.emissiveFactor[c] - m.emissiveFactor[c]) < 1e-6);
        CHECK(std::abs(back.roughnessFactor - m.roughnessFactor) < 1e-6);
        CHECK(back.metallicFactor == 0);
    }
    SECTION("X3D -> glTF -> X3D gives the Phong fields back, the glTF factors linear") {
        writeTextFile(folder / "in.x3d",
                      "<X3D version='3.3'><Scene><Shape><Appearance><Material diffuseColor='0.8 0.4 0.05' "
                      "emissiveColor='0.1 0 0.3' shininess='0.35' transparency='0.3'/></Appearance>"
                      "<Box/></Shape></Scene></X3D>");
        const Scene x3d = readScene(folder / "in.x3d");
        REQUIRE(x3d.materials.size() == 1);
        const Material& read = x3d.materials[0];
        CHECK(read.baseColorFactor[0] == Approx(expectedLinear(0.8)).epsilon(1e-12));
        CHECK(read.baseColorFactor[2] == Approx(expectedLinear(0.05)).epsilon(1e-12));
        CHECK(read.emissiveFactor[2] == Approx(expectedLinear(0.3)).epsilon(1e-12));
        writeScene(x3d, folder / "mid.glb");
        const nlohmann::json root = glbJson(folder / "mid.glb");
        CHECK(root["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][0].get<double>() ==
              Approx(expectedLinear(0.8)).epsilon(1e-6));
        writeScene(readScene(folder / "mid.glb"), folder / "back.x3d");
        const Scene back = readScene(folder / "back.x3d");
        REQUIRE(back.materials.size() == 1);
        REQUIRE(back.materials[0].phong);
        // glTF has no place for specularColor and ambientIntensity: these come back as X3D's defaults, which
        // the input had.
        CHECK(*back.materials[0].phong == *read.phong);
    }
}

TEST_CASE("KHR_materials_unlit is X3D 4's UnlitMaterial, its colour sRGB-encoded, and comes back",
          "[io][x3d][materials]") {
    TemporaryFolder folder;
    Scene scene = everySlotScene();
    Material& m = scene.materials[0];
    m = Material{};
    m.baseColorFactor = {expectedLinear(0.5), 0.02, 1, 1};
    m.baseColorTexture.texture = 0;
    m.extensions.push_back({"KHR_materials_unlit", "{}", {}, false});
    writeScene(scene, folder / "unlit.x3d");
    const std::string text = readTextFile(folder / "unlit.x3d");
    CHECK_THAT(text, Catch::Contains("version='4.0'"));
    CHECK_THAT(text, Catch::Contains("<UnlitMaterial emissiveColor='0.5 0.15170372 1'><ImageTexture "
                                     "containerField='emissiveTexture'"));
    const Scene back = readScene(folder / "unlit.x3d");
    REQUIRE(back.materials.size() == 1);
    const Material& read = back.materials[0];
    for (int c = 0; c < 4; ++c) CHECK(std::abs(read.baseColorFactor[c] - m.baseColorFactor[c]) < 1e-6);
    REQUIRE(read.extensions.size() == 1);
    CHECK(read.extensions[0].name == "KHR_materials_unlit");
    CHECK(describeUse(back, read.baseColorTexture) == describeUse(scene, m.baseColorTexture));
}

TEST_CASE("An X3D 3.3 Phong scene is written as X3D 3.3, as it was", "[io][x3d][materials]") {
    TemporaryFolder folder;
    writeTextFile(folder / "in.x3d",
                  quadWith("<Appearance><Material diffuseColor='0.8 0.2 0.1' specularColor='0.5 0.5 0.5' "
                           "ambientIntensity='0.4' shininess='0.7'/><ImageTexture repeatT='false' url='\"" +
                               kImageA + "\"'/></Appearance>",
                           "3.3"));
    const Scene scene = readScene(folder / "in.x3d");
    writeScene(scene, folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK_THAT(text, Catch::StartsWith(
                         "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile='Interchange' version='3.3'>\n"
                         "<head>\n<meta name='generator' content='symcompress'/>\n</head>"));
    CHECK_THAT(text, Catch::Contains("<Material diffuseColor='0.8 0.2 0.1' specularColor='0.5 0.5 0.5' "
                                     "ambientIntensity='0.4' shininess='0.7'/><ImageTexture "
                                     "url="));
    CHECK_THAT(text, Catch::Contains("repeatT='false'/>"));  // clamped along t: glTF's CLAMP_TO_EDGE
    CHECK(scene.textures.at(0).sampler == TextureSampler{0, 0, 10497, 33071, ""});
    CHECK_THAT(text, !Catch::Contains("PhysicalMaterial"));
    CHECK_THAT(text, !Catch::Contains("containerField"));
    const Scene back = readScene(folder / "out.x3d");
    REQUIRE(back.materials.size() == 1);
    CHECK(back.materials[0].phong == scene.materials[0].phong);
    CHECK(back.materials[0].sameButName(scene.materials[0]));
}

TEST_CASE("Broken X3D material nodes are warned about, naming the file and the node, and read as far as they go",
          "[io][x3d][materials]") {
    TemporaryFolder folder;
    writeTextFile(folder / "broken.x3d", quadWith("<Appearance><PhysicalMaterial DEF='P' baseColor='0.5 0.5 0.5'>"
                                                  "<Box containerField='baseTexture'/>"
                                                  "<ImageTexture USE='nothing' containerField='emissiveTexture'/>"
                                                  "<ImageTexture url='\"" +
                                                  kImageA +
                                                  "\"'/>"
                                                  "<ImageTexture containerField='normalTexture' url='\"" +
                                                  kImageB +
                                                  "\"'/>"
                                                  "</PhysicalMaterial></Appearance>"));
    Scene scene;
    REQUIRE_NOTHROW(scene = readScene(folder / "broken.x3d"));
    CHECK(warned(scene, "broken.x3d: PhysicalMaterial 'P' baseTexture holds a Box, not a texture node; left out"));
    CHECK(warned(scene, "broken.x3d: PhysicalMaterial 'P' emissiveTexture: USE='nothing' refers to no DEF before it"));
    CHECK(warned(scene,
                 "broken.x3d: PhysicalMaterial 'P': a ImageTexture without containerField is in no texture field"));
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].baseColorTexture.texture == -1);
    CHECK(scene.materials[0].emissiveTexture.texture == -1);
    CHECK(scene.materials[0].normalTexture.texture >= 0);  // what is right is read
    CHECK(scene.materials[0].baseColorFactor.head<3>() == Eigen::Vector3d(0.5, 0.5, 0.5));

    SECTION("a USE of an unknown material, and a mapping no coordinates have") {
        writeTextFile(folder / "unknown.x3d",
                      quadWith("<Appearance><PhysicalMaterial USE='missing'/></Appearance>") +
                          "");  // the material is left out: the Appearance has none
        Scene unknown;
        REQUIRE_NOTHROW(unknown = readScene(folder / "unknown.x3d"));
        CHECK(
            warned(unknown, "unknown.x3d: an Appearance's PhysicalMaterial: USE='missing' refers to no DEF before it"));
        writeTextFile(folder / "mapping.x3d",
                      quadWith("<Appearance><PhysicalMaterial baseTextureMapping='elsewhere'><ImageTexture "
                               "containerField='baseTexture' url='\"" +
                               kImageA + "\"'/></PhysicalMaterial></Appearance>"));
        const Scene mapping = readScene(folder / "mapping.x3d");
        CHECK(warned(mapping,
                     "mapping.x3d: PhysicalMaterial: baseTextureMapping 'elsewhere' names no texture coordinates"));
        CHECK(mapping.materials.at(0).baseColorTexture.texCoord == 0);
        // A further set shorter than the first is left out with its mapping, not the file.
        std::string shortSet = quadWith(
            "<Appearance><PhysicalMaterial baseTextureMapping='uvB'><ImageTexture "
            "containerField='baseTexture' url='\"" +
            kImageA + "\"'/></PhysicalMaterial></Appearance>");
        shortSet.replace(shortSet.find("0.5 0.5 0.75 0.5 0.75 0.75 0.5 0.75"), 35, "0.5 0.5 0.75 0.5");
        writeTextFile(folder / "short.x3d", shortSet);
        Scene shortRead;
        REQUIRE_NOTHROW(shortRead = readScene(folder / "short.x3d"));
        CHECK(warned(shortRead,
                     "short.x3d: a MultiTextureCoordinate's TextureCoordinate 'uvB' has 2 points, the first 4"));
        CHECK(warned(shortRead, "short.x3d: PhysicalMaterial: baseTextureMapping 'uvB' names no texture coordinates"));
        CHECK(shortRead.meshes.at(0).primitives.at(0).attributes.empty());
    }
}

TEST_CASE("A glTF with normal and metallic-roughness textures, as X3D, renders in X_ITE as X_ITE draws the glTF",
          "[io][x3d][materials][models]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    // TwoSidedPlane: base colour, metallic-roughness and normal textures on a double-sided plane. The reference
    // is X_ITE's own reading of the glTF (an Inline of it): the same browser and lights, so that what is compared
    // is the conversion. The model is copied beside the output, whose images it refers to.
    TemporaryFolder folder;
    for (const auto& entry : fs::directory_iterator(modelPath("pbr/two_sided_plane")))
        fs::copy_file(entry.path(), folder / entry.path().filename().string());
    writeScene(readScene(folder / "TwoSidedPlane.gltf"), folder / "plane.x3d");
    CHECK_THAT(readTextFile(folder / "plane.x3d"), Catch::Contains("<PhysicalMaterial"));
    writeTextFile(
        folder / "reference.x3d",
        "<X3D profile='Interchange' version='4.0'><Scene><Inline url='\"TwoSidedPlane.gltf\"'/></Scene></X3D>");
    for (const char* mode : {"lit", "normals"}) {
        const CommandResult result = renderCompare(folder / "reference.x3d", folder / "plane.x3d", mode, "abc");
        INFO(mode << ": " << result.output);
        CHECK(result.status == 0);
    }
}

TEST_CASE("Colours as X3D render in X_ITE as the glTF's do in three.js, and back", "[io][x3d][materials][models]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    // Emissive quads on black (no light changes them, and the two pages light differently): a dark, a middle and
    // a light colour, as Phong's Material (not metal) and as PhysicalMaterial (metal).
    Scene scene;
    const std::vector<Eigen::Vector3d> colours = {{0.02, 0.2140411, 0.6}, {0.8, 0.05, 0.3}, {0.5, 0.9, 0.01}};
    Mesh mesh;
    for (std::size_t k = 0; k < 2 * colours.size(); ++k) {
        Material material;
        material.baseColorFactor = {0, 0, 0, 1};
        material.metallicFactor = k < colours.size() ? 0 : 1;
        material.emissiveFactor = colours[k % colours.size()];
        material.doubleSided = true;
        scene.materials.push_back(material);
        Primitive quad;
        const double x = double(k % colours.size()), y = double(k / colours.size());
        quad.positions = {{x, y, 0}, {x + 0.9, y, 0}, {x + 0.9, y + 0.9, 0}, {x, y + 0.9, 0}};
        quad.normals.assign(4, Eigen::Vector3d::UnitZ());
        quad.triangles = {{0, 1, 2}, {0, 2, 3}};
        quad.material = int(k);
        mesh.primitives.push_back(quad);
    }
    scene.meshes = {mesh};
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    TemporaryFolder folder;
    writeScene(scene, folder / "colours.glb");
    writeScene(readScene(folder / "colours.glb"), folder / "colours.x3d");
    const CommandResult there = renderCompare(folder / "colours.glb", folder / "colours.x3d", "lit", "d");
    INFO("glTF -> X3D: " << there.output);
    CHECK(there.status == 0);
    // And an X3D written by hand with Phong colours, as glTF in three.js.
    writeScene(readScene(folder / "colours.x3d"), folder / "back.glb");
    const CommandResult back = renderCompare(folder / "colours.x3d", folder / "back.glb", "lit", "d");
    INFO("X3D -> glTF: " << back.output);
    CHECK(back.status == 0);
}

TEST_CASE("Unlit glTF materials as X3D render in X_ITE as in three.js", "[io][x3d][materials][models]") {
    if (!renderAvailable()) {
        WARN("skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    // UnlitTest: two KHR_materials_unlit colours, which no light changes, so that the two viewers agree.
    TemporaryFolder folder;
    const fs::path input = modelPath("pbr/unlit/UnlitTest.gltf");
    writeScene(readScene(input), folder / "unlit.x3d");
    CHECK_THAT(readTextFile(folder / "unlit.x3d"), Catch::Contains("<UnlitMaterial"));
    const CommandResult there = renderCompare(input, folder / "unlit.x3d", "lit", "abc");
    INFO(there.output);
    CHECK(there.status == 0);
}

namespace {

bool hasUnlitExtension(const Material& m) {
    return std::any_of(m.extensions.begin(), m.extensions.end(),
                       [](const MaterialExtension& e) { return e.name == "KHR_materials_unlit"; });
}

const Material& materialOf(const Scene& scene, const Mesh& mesh) {
    REQUIRE(mesh.primitives.size() == 1);
    REQUIRE(mesh.primitives[0].material >= 0);
    return scene.materials[std::size_t(mesh.primitives[0].material)];
}

// A quad facing +z in X3D with `appearance` (XML) and `colour` (a Color or ColorRGBA node, or nothing), at x.
std::string quadAt(double x, const std::string& appearance, const std::string& colour = "") {
    return "<Transform translation='" + std::to_string(x) + " 0 0'><Shape>" + appearance +
           "<IndexedFaceSet solid='false' coordIndex='0 1 2 3 -1' texCoordIndex='0 1 2 3 -1'>"
           "<Coordinate point='-1 -1 0 1 -1 0 1 1 0 -1 1 0'/><TextureCoordinate point='0 0 1 0 1 1 0 1'/>" +
           colour + "</IndexedFaceSet></Shape></Transform>";
}

// `output` lit as `input` is (render_compare.sh, views a-c), where the renderer is set up.
void checkLitAlike(const fs::path& input, const fs::path& output) {
    if (!renderAvailable()) {
        WARN("render check skipped: needs Node.js, chromium and ../shared/bench/render (npm ci)");
        return;
    }
    const CommandResult rendered = renderCompare(input, output, "lit", "abc");
    INFO(rendered.output);
    CHECK(rendered.status == 0);
}

}  // namespace

TEST_CASE("A Shape without an Appearance, or an Appearance without a material, is unlit white and is written so",
          "[io][x3d][materials]") {
    // X3D 4.0 12.4.1 (as 3.3): no Appearance, or no material in it, turns lighting off; the colour is white, or
    // the texture's. Before, both were glTF's lit default material (and one-sided where solid='false').
    TemporaryFolder folder;
    fs::copy_file(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"), folder / "logo.png");
    writeTextFile(folder / "in.x3d",
                  "<X3D version='3.3'><Scene><Transform><Transform translation='-3 0 0'><Shape><Box/></Shape>"
                  "</Transform>" +
                      quadAt(0, "") +
                      "<Transform translation='3 0 0'><Shape><Appearance><ImageTexture url='\"logo.png\"'/>"
                      "</Appearance><Sphere/></Shape></Transform></Transform></Scene></X3D>");
    const Scene scene = readScene(folder / "in.x3d");
    REQUIRE(scene.meshes.size() == 3);
    for (const Mesh& mesh : scene.meshes) {
        const Material& m = materialOf(scene, mesh);
        CHECK(hasUnlitExtension(m));
        CHECK(m.baseColorFactor == Eigen::Vector4d(1, 1, 1, 1));
        CHECK(m.alphaMode == Material::AlphaMode::Opaque);  // the logo's pixels are all opaque
    }
    const Material& box = materialOf(scene, scene.meshes[0]);
    const Material& quad = materialOf(scene, scene.meshes[1]);
    const Material& sphere = materialOf(scene, scene.meshes[2]);
    CHECK(!box.doubleSided);
    CHECK(quad.doubleSided);
    CHECK(sphere.baseColorTexture.texture >= 0);

    // X3D again: as it was (3.3, no Material, an Appearance for the texture alone), drawn the same by X_ITE.
    writeScene(scene, folder / "out.x3d");
    const std::string text = readTextFile(folder / "out.x3d");
    CHECK_THAT(text, Catch::Contains("version='3.3'"));
    CHECK_THAT(text, !Catch::Contains("Material"));
    CHECK(occurrences(text, "<Appearance") == 1);
    CHECK_THAT(text, Catch::Contains("<Appearance><ImageTexture url="));
    CHECK_THAT(text, Catch::Contains("solid='false'"));
    // glTF: KHR_materials_unlit, double-sided where the quad was.
    writeScene(scene, folder / "out.glb");
    const Scene glb = readScene(folder / "out.glb");
    REQUIRE(glb.materials.size() >= 2);
    for (const Material& m : glb.materials) CHECK(hasUnlitExtension(m));
    CHECK(std::any_of(glb.materials.begin(), glb.materials.end(), [](const Material& m) { return m.doubleSided; }));
    checkLitAlike(folder / "in.x3d", folder / "out.x3d");
}

TEST_CASE(
    "X3D's AUTO alpha mode blends translucent textures and colours, and the writer states a mode where "
    "AUTO would draw another",
    "[io][x3d][materials]") {
    TemporaryFolder folder;
    // The grass's flowers are cut out by their alpha; Cesium's logo is opaque.
    fs::copy_file(modelPath("cge_grass_flowers/textures/flower111.png"), folder / "flower.png");
    fs::copy_file(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"), folder / "logo.png");
    const std::string flower = "<ImageTexture url='\"flower.png\"'/>", logo = "<ImageTexture url='\"logo.png\"'/>";
    SECTION("read: AUTO decides by the texture's pixels and the colours' alpha, X3D 4's alphaMode as it says") {
        writeTextFile(folder / "in.x3d",
                      "<X3D version='4.0'><Scene>" + quadAt(0, "<Appearance><Material/>" + flower + "</Appearance>") +
                          quadAt(3, "<Appearance><Material/>" + logo + "</Appearance>") +
                          quadAt(6, "<Appearance><Material/></Appearance>",
                                 "<ColorRGBA color='1 0 0 0.5 0 1 0 1 0 0 1 1 1 1 1 1'/>") +
                          quadAt(9, "<Appearance><Material/></Appearance>",
                                 "<ColorRGBA color='1 0 0 1 0 1 0 1 0 0 1 1 1 1 1 1'/>") +
                          quadAt(12, "<Appearance alphaMode='OPAQUE'><Material/>" + flower + "</Appearance>") +
                          "</Scene></X3D>");
        const Scene scene = readScene(folder / "in.x3d");
        REQUIRE(scene.meshes.size() == 5);
        const Material::AlphaMode expected[] = {Material::AlphaMode::Blend, Material::AlphaMode::Opaque,
                                                Material::AlphaMode::Blend, Material::AlphaMode::Opaque,
                                                Material::AlphaMode::Opaque};
        for (std::size_t k = 0; k < 5; ++k) {
            INFO("quad " << k);
            CHECK(materialOf(scene, scene.meshes[k]).alphaMode == expected[k]);
        }
    }
    SECTION("written: alphaMode only where AUTO would differ, and X3D 3.3 where none is stated") {
        Scene scene;
        for (const char* image : {"flower.png", "logo.png"}) {
            Texture texture;
            texture.uri = image;
            texture.mimeType = "image/png";
            const std::string bytes = readTextFile(folder / image);
            texture.bytes.assign(bytes.begin(), bytes.end());
            scene.textures.push_back(texture);
        }
        const auto add = [&](Material::AlphaMode mode, int texture, double alpha) {
            Material m;
            m.metallicFactor = 0;
            m.alphaMode = mode;
            m.alphaCutoff = 0.25;
            m.baseColorFactor[3] = alpha;
            m.baseColorTexture.texture = texture;
            scene.materials.push_back(m);
            Primitive quad;
            quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
            quad.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
            quad.triangles = {{0, 1, 2}, {0, 2, 3}};
            quad.material = int(scene.materials.size()) - 1;
            scene.meshes.push_back({"", {quad}, "", {}});
            Node node;
            node.mesh = int(scene.meshes.size()) - 1;
            scene.nodes.push_back(node);
            scene.roots.push_back(int(scene.nodes.size()) - 1);
        };
        add(Material::AlphaMode::Blend, 0, 1);   // AUTO blends the flower: nothing stated
        add(Material::AlphaMode::Opaque, 1, 1);  // AUTO draws the logo opaque: nothing stated
        add(Material::AlphaMode::Blend, -1, 0.5);
        writeScene(scene, folder / "auto.x3d");
        const std::string autoText = readTextFile(folder / "auto.x3d");
        CHECK_THAT(autoText, Catch::Contains("version='3.3'"));
        CHECK_THAT(autoText, !Catch::Contains("alphaMode"));

        add(Material::AlphaMode::Opaque, 0, 1);  // AUTO would blend the flower
        add(Material::AlphaMode::Blend, 1, 1);   // AUTO would draw the logo opaque
        add(Material::AlphaMode::Mask, 0, 1);    // AUTO never cuts out
        writeScene(scene, folder / "stated.x3d");
        const std::string stated = readTextFile(folder / "stated.x3d");
        CHECK_THAT(stated, Catch::Contains("version='4.0'"));
        CHECK(occurrences(stated, "alphaMode=") == 3);
        CHECK_THAT(stated, Catch::Contains("alphaMode='OPAQUE'"));
        CHECK_THAT(stated, Catch::Contains("alphaMode='BLEND'"));
        CHECK_THAT(stated, Catch::Contains("alphaMode='MASK' alphaCutoff='0.25'"));
        const Scene back = readScene(folder / "stated.x3d");
        REQUIRE(back.materials.size() == scene.materials.size());
        for (std::size_t k = 0; k < scene.materials.size(); ++k) {
            INFO("material " << k);
            CHECK(back.materials[k].alphaMode == scene.materials[k].alphaMode);
        }
    }
}

TEST_CASE("An Appearance's TextureTransform is baked into the texture coordinates it applies to, as X_ITE draws it",
          "[io][x3d][materials]") {
    TemporaryFolder folder;
    fs::copy_file(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"), folder / "logo.png");
    SECTION("every set: Tc' = -C S R C T Tc, worked out by hand") {
        // translation (0.25, 0), center (0.5, 0.5), a quarter turn, scale (2, 1). Corner (s, t) = (0, 0): + T + C
        // = (0.75, 0.5); turned, (x, y) -> (-y, x): (-0.5, 0.75); scaled (-1, 0.75); - C: (-1.5, 0.25), glTF's v
        // = 1 - t = 0.75. Corner (1, 0): (1.75, 0.5) -> (-0.5, 1.75) -> (-1, 1.75) -> (-1.5, 1.25), v = -0.25.
        writeTextFile(folder / "in.x3d",
                      "<X3D version='3.3'><Scene><Transform>" +
                          quadAt(0,
                                 "<Appearance><ImageTexture url='\"logo.png\"'/><TextureTransform "
                                 "translation='0.25 0' center='0.5 0.5' rotation='1.5707963267948966' "
                                 "scale='2 1'/></Appearance>") +
                          "<Transform translation='3 0 0'><Shape><Appearance><ImageTexture url='\"logo.png\"'/>"
                          "<TextureTransform rotation='0.3' scale='1 2'/></Appearance><Box/></Shape></Transform>"
                          "</Transform></Scene></X3D>");
        const Scene scene = readScene(folder / "in.x3d");
        REQUIRE(scene.meshes.size() == 2);
        const Primitive& quad = scene.meshes[0].primitives.at(0);
        const auto uvAt = [&](const Eigen::Vector3d& position) {
            for (std::size_t v = 0; v < quad.positions.size(); ++v)
                if (quad.positions[v].isApprox(position)) return quad.texcoords.at(v);
            FAIL("no vertex at " << position.transpose());
            return Eigen::Vector2d();
        };
        CHECK(uvAt({-1, -1, 0}).isApprox(Eigen::Vector2d(-1.5, 0.75), 1e-12));
        CHECK(uvAt({1, -1, 0}).isApprox(Eigen::Vector2d(-1.5, -0.25), 1e-12));
        // X3D again: the box's triangles with their coordinates, not the Box node (which would draw its own).
        writeScene(scene, folder / "out.x3d");
        CHECK_THAT(readTextFile(folder / "out.x3d"), !Catch::Contains("<Box"));
        CHECK_THAT(readTextFile(folder / "out.x3d"), !Catch::Contains("TextureTransform"));
        checkLitAlike(folder / "in.x3d", folder / "out.x3d");
    }
    SECTION("X3D 4's mapping: the set it names alone") {
        writeTextFile(folder / "in.x3d", quadWith("<Appearance><Material/><TextureTransform mapping='uvB' "
                                                  "translation='1 0'/></Appearance>"));
        const Scene scene = readScene(folder / "in.x3d");
        const Primitive& quad = scene.meshes.at(0).primitives.at(0);
        // uvA unchanged: (0, 0) at the first corner, glTF's v = 1 - t.
        CHECK(quad.texcoords.at(0).isApprox(Eigen::Vector2d(0, 1)));
        REQUIRE(quad.attributes.size() == 1);
        CHECK(quad.attributes[0].name == "TEXCOORD_1");
        CHECK(quad.attributes[0].values[0] == Approx(1.5));  // 0.5 + 1
        CHECK(quad.attributes[0].values[1] == Approx(0.5));
    }
}
