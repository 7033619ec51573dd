// Our output checked by independent implementations: the Khronos glTF validator, glTF Transform's
// Draco decoder (../shared/bench/decode_check.mjs) and the X_ITE X3D browser (x3d_count.js).
// Skipped (with a note) when Node.js or the peers are not installed, or SYMCOMPRESS_SKIP_INTEROP is set.
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// symcompress convert: the scene as read, written (with Draco or plain accessors).
void convert(const std::filesystem::path& input, const std::filesystem::path& output, bool draco = true) {
    WriteOptions options;
    options.draco = draco;
    writeScene(readScene(input), output, options, {input});
}

// decode_check exits with 1 when the triangle counts differ: allowed where symcompress leaves out
// zero-area triangles (it says so), which draw nothing.
nlohmann::json decodeCheck(const std::filesystem::path& file, const std::filesystem::path& reference,
                           bool countsMayDiffer = false) {
    const std::string commandLine =
        "node " + quoted(sharedDir() / "bench/decode_check.mjs") + " " + quoted(file) + " --ref " + quoted(reference) + " --json";
    if (!countsMayDiffer) return runJson(commandLine);
    const CommandResult result = runCommand(commandLine);
    INFO(commandLine << "\n" << result.output);
    REQUIRE((result.status == 0 || result.status == 1));
    const auto start = result.output.rfind("\n{");
    return nlohmann::json::parse(start == std::string::npos ? result.output : result.output.substr(start + 1));
}

// Some models in ../shared come without their textures, and symcompress keeps the references (issue 15):
// glTF Transform refuses a file whose images it cannot open. Such a model is copied into `folder` with a
// one-pixel PNG standing in for each missing image, for the checks of geometry; others are used as they are.
std::filesystem::path withStandInImages(const std::filesystem::path& model, const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    std::vector<std::string> present, missing;
    if (model.extension() == ".x3d") {
        // An X3D file's images are where its reader looked for them, beside it (the cat's PhysicalMaterial
        // textures are not in the shared folder).
        for (const Texture& texture : readScene(model).textures)
            if (texture.bytes.empty() && texture.uri.find("://") == std::string::npos)
                missing.push_back(
                    fs::path(texture.uri).lexically_relative(model.parent_path().lexically_normal()).string());
        if (missing.empty()) return model;
    } else if (model.extension() != ".glb" && model.extension() != ".gltf") {
        return model;
    }
    const nlohmann::json root = model.extension() == ".glb"    ? glbJson(model)
                                : model.extension() == ".gltf" ? nlohmann::json::parse(readTextFile(model))
                                                               : nlohmann::json::object();
    for (const char* list : {"buffers", "images"})
        for (const auto& item : root.value(list, nlohmann::json::array()))
            if (item.contains("uri") && item["uri"].get<std::string>().rfind("data:", 0) != 0)
                (fs::exists(model.parent_path() / item["uri"].get<std::string>()) ? present : missing).push_back(item["uri"]);
    if (missing.empty()) return model;
    static const unsigned char pixel[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
        0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0xfc, 0xcf, 0xc0, 0x50, 0x0f, 0x00, 0x04, 0x85, 0x01, 0x80,
        0x84, 0xa9, 0x8c, 0x21, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    const fs::path copy = folder / "with_stand_ins" / model.filename();
    for (const std::string& uri : present) {
        fs::create_directories((copy.parent_path() / uri).parent_path());
        fs::copy_file(model.parent_path() / uri, copy.parent_path() / uri, fs::copy_options::overwrite_existing);
    }
    for (const std::string& uri : missing) {
        fs::create_directories((copy.parent_path() / uri).parent_path());
        writeTextFile(copy.parent_path() / uri, std::string(reinterpret_cast<const char*>(pixel), sizeof pixel));
    }
    fs::copy_file(model, copy, fs::copy_options::overwrite_existing);
    return copy;
}

nlohmann::json x3dCount(const std::filesystem::path& file) {
    return runJson("node " + quoted(sharedDir() / "bench/x3d_count.js") + " " + quoted(file) + " --json");
}

// Compressed to GLB and X3D, each input is drawn by others as it was (instances, mirrored nodes,
// fundamental regions, assemblies, the scene's symmetry): the GLB decoded by glTF Transform as symdecompress
// expands it, with the input's volume; the X3D loaded by X_ITE with the triangles symdecompress expands (a region
// cut by its planes has more triangles than the part) and the input's volume.
void checkDrawnByOthers(const std::vector<std::filesystem::path>& inputs) {
    if (!interopAvailable() || !x3dInteropAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    for (const auto& model : inputs) {
        INFO(model);
        const std::filesystem::path input = withStandInImages(model, folder.path());
        const auto reference = folder / "reference.glb";
        convert(input, reference, false);
        double referenceVolume = 0;  // as glTF Transform reads the reference (the .glb comes first)
        for (const char* extension : {".glb", ".x3d"}) {
            const auto output = folder / (std::string("small") + extension);
            compressFile(input, output);
            const RebuildReport expanded = decompressFile(output, folder / "flat.glb", input);
            CHECK(expanded.verified);
            if (std::string(extension) == ".glb") {
                CHECK(validatorErrors(output).empty());
                const auto decoded = decodeCheck(output, reference, true);
                CHECK(decoded["tris"] == expanded.triangles);
                // Vertex to vertex against our own expansion: a fundamental region whose planes cut triangles
                // puts vertices mid-edge, far from any vertex of the original though on its surface (which
                // decompressFile measured).
                CHECK(decodeCheck(output, folder / "flat.glb")["dev_rel"].get<double>() < 2e-4);
                // Tiles stored as they are share one mesh per material, quantized over the whole scene: the
                // sterile room's walls move by up to a 14-bit step of its 62 m, 1.1e-3 of its volume; the house's
                // thin parts, quantized on grids that take the whole of their bound (coarserPositionGrid), 2.2e-3.
                referenceVolume = decoded["ref_volume"].get<double>();
                CHECK(decoded["volume"].get<double>() == Approx(referenceVolume).epsilon(3e-3));
            } else {
                const auto drawn = x3dCount(output);
                CHECK(drawn["tris"] == expanded.triangles);
                // Positions written to the places the budget needs: as the GLB's quantization, a little volume.
                CHECK(drawn["volume"].get<double>() == Approx(referenceVolume).epsilon(2e-3));
            }
        }
    }
}

// The shared models whose files end with one of `extensions`.
std::vector<std::filesystem::path> modelsWithExtension(std::initializer_list<const char*> extensions) {
    std::vector<std::filesystem::path> inputs;
    for (const std::string& model : sharedModels())
        for (const char* extension : extensions)
            if (std::filesystem::path(model).extension() == extension) inputs.push_back(modelPath(model));
    return inputs;
}

}  // namespace

TEST_CASE("GLB output passes the Khronos validator and decodes to the same triangles", "[interop][gltf]") {
    if (!interopAvailable()) {
        WARN("skipped: Node.js >= 20 and ../shared/bench/node are needed (scripts/install-deps.sh installs them)");
        return;
    }
    TemporaryFolder folder;
    const std::vector<std::string> models = {
        "cesium_milk_truck/CesiumMilkTruck.gltf", "vulkan_subpass_scene/subpass_scene_opaque.gltf",
        "kenney_racing_forest/decoration-forest.glb", "cge_sterile_room/sterile_room.gltf",
        "khronos_lantern/Lantern.gltf", "vulkan_torusknot/torusknot.gltf", "assimp_spider/spider.obj",
        "savage_chevy_tahoe/ChevyTahoe.x3d", "menger_sponge/Menger_sponge-Binary.stl"};
    for (const std::string& model : models) {
        const std::filesystem::path input = withStandInImages(modelPath(model), folder.path());
        for (const bool draco : {true, false}) {
            INFO(model << (draco ? "" : " --no-draco"));
            const auto output = folder / "out.glb";
            convert(input, output, draco);
            CHECK(validatorErrors(output).empty());
            // Compare with our own uncompressed reading of the input (decode_check reads only glTF).
            const auto reference = folder / "reference.glb";
            convert(input, reference, false);
            const auto decoded = decodeCheck(output, reference);
            CHECK(decoded["tris"] == decoded["ref_tris"]);
            CHECK(decoded["dev_rel"].get<double>() < 2e-4);  // 14-bit quantization: about 1e-4 of the extent at most
            const double volume = decoded["volume"], referenceVolume = decoded["ref_volume"];
            CHECK(std::abs(volume - referenceVolume) <= 1e-3 * std::abs(referenceVolume) + 1e-9);
        }
    }
}

TEST_CASE("glTF input read by us equals the independent decoder's reading", "[interop][gltf]") {
    if (!interopAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    for (const std::string& model :
         {"cesium_milk_truck/CesiumMilkTruck.gltf", "vulkan_subpass_scene/subpass_scene_opaque.gltf",
          "vianney_house_2/scene.gltf", "cge_sterile_room/sterile_room.gltf"}) {
        INFO(model);
        const auto output = folder / "plain.glb";
        convert(modelPath(model), output, false);
        const auto decoded = decodeCheck(output, modelPath(model));
        CHECK(decoded["tris"] == decoded["ref_tris"]);
        CHECK(decoded["dev_rel"].get<double>() < 1e-6);
        CHECK(decoded["volume"].get<double>() == Approx(decoded["ref_volume"].get<double>()).epsilon(1e-6));
    }
}

TEST_CASE("X3D output loads in X_ITE with the same triangles and volume", "[interop][x3d]") {
    if (!x3dInteropAvailable()) {
        WARN("skipped: Node.js >= 20 and ../shared/bench/x3d are needed (scripts/install-deps.sh installs them)");
        return;
    }
    TemporaryFolder folder;
    // X_ITE does not draw CAD component nodes (it counts 0 triangles in xj3d_cad_teapot), so the teapot is left out.
    for (const std::string& model : {"savage_chevy_tahoe/ChevyTahoe.x3d", "xj3d_coffee_cup/coffeeCup.x3d",
                                     "cge_cat_x3d/scene.x3d", "cge_grass_flowers/grass_flowers.x3d"}) {
        INFO(model);
        const auto output = folder / "out.x3d";
        convert(modelPath(model), output);
        const auto before = x3dCount(modelPath(model));
        const auto after = x3dCount(output);
        CHECK(after["tris"] == before["tris"]);
        CHECK(after["volume"].get<double>() ==
              Approx(before["volume"].get<double>()).epsilon(1e-5).margin(1e-9));
    }
    SECTION("glTF with mirrored instances to X3D keeps the orientation") {
        const auto model = modelPath("vulkan_subpass_scene/subpass_scene_opaque.gltf");
        const auto output = folder / "subpass.x3d";
        convert(model, output);
        const auto reference = runJson("node " + quoted(sharedDir() / "bench/decode_check.mjs") + " " + quoted(model) +
                                       " --json");
        const auto after = x3dCount(output);
        CHECK(after["tris"] == reference["tris"]);
        CHECK(after["volume"].get<double>() == Approx(reference["volume"].get<double>()).epsilon(1e-5));
        CHECK(after["distinct"].get<int>() < after["shapes"].get<int>());  // shared meshes stay shared (DEF/USE)
    }
}

// Four test cases, so that CTest runs them side by side.
TEST_CASE("Compressed scans and parts are drawn as they were by independent readers (glTF Transform, X_ITE)",
          "[interop][compress][models]") {
    checkDrawnByOthers(modelsWithExtension({".obj", ".ply", ".stl"}));
}

TEST_CASE("Compressed glTF scenes are drawn as they were by independent readers (glTF Transform, X_ITE)",
          "[interop][compress][models]") {
    checkDrawnByOthers(modelsWithExtension({".gltf", ".glb"}));
}

TEST_CASE("Compressed X3D scenes are drawn as they were by independent readers (glTF Transform, X_ITE)",
          "[interop][compress][models]") {
    checkDrawnByOthers(modelsWithExtension({".x3d"}));
}

TEST_CASE("Compressed samples are drawn as they were by independent readers (glTF Transform, X_ITE)",
          "[interop][compress]") {
    std::vector<std::filesystem::path> inputs;
    for (const char* sample : {"bolts", "chess", "icosahedral", "lamp", "pliers", "room", "three_spheres"})
        inputs.push_back(std::filesystem::path(SYMCOMPRESS_SOURCE_DIR) / "samples" / (std::string(sample) + ".glb"));
    checkDrawnByOthers(inputs);
}

TEST_CASE(
    "Files packed by glTF-Transform (meshopt) and gltfpack (quantized, EXT_ and KHR_meshopt, GPU instancing) read as "
    "the same scene",
    "[interop][gltf]") {
    if (!interopAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    const std::string transform = quoted(sharedDir() / "bench/node/node_modules/.bin/gltf-transform");
    const std::string gltfpack = quoted(sharedDir() / "bench/node/node_modules/.bin/gltfpack");
    for (const char* model : {"cge_grass_flowers/grass_flowers.x3d", "kenney_racing_forest/decoration-forest.glb"}) {
        INFO(model);
        const auto reference = folder / "reference.glb";
        convert(withStandInImages(modelPath(model), folder.path()), reference, false);
        std::vector<std::pair<std::string, std::string>> packers = {
            {"meshopt.glb", transform + " meshopt " + quoted(reference) + " " + quoted(folder / "meshopt.glb")}};
        // -cz: KHR_meshopt_compression, its vertex codec's version 1 (meshopt_vertex_codec.hpp).
        for (const char* flags : {"", "-cc", "-cc -mi", "-cz", "-cz -mi"}) {
            const std::string name = "gltfpack" + std::string(flags) + ".glb";
            packers.push_back({name, gltfpack + " " + flags + " -i " + quoted(reference) + " -o " + quoted(folder / name)});
        }
        const std::vector<WorldPrimitive> original = flattenScene(readScene(reference));
        for (const auto& [name, command] : packers) {
            INFO(name);
            REQUIRE(runCommand(command).status == 0);
            CHECK(decompressFile(folder / name, folder / "flat.glb", reference).verified);
            // The texture coordinates the base colour texture reads span what they did (gltfpack quantizes
            // them and brings them back with KHR_texture_transform, which is kept).
            Eigen::AlignedBox2d before, after;
            for (const WorldPrimitive& p : original)
                for (const Eigen::Vector2d& t : p.primitive.texcoords) before.extend(t);
            const Scene packed = readScene(folder / name);
            for (const WorldPrimitive& p : flattenScene(packed))
                for (std::size_t v = 0; v < p.primitive.texcoords.size(); ++v)
                    after.extend(baseColorTexcoord(packed, p.primitive, v));
            REQUIRE(!before.isEmpty());
            if (after.isEmpty() && name.rfind("gltfpack", 0) == 0) continue;  // dropped: no texture reads them (forest)
            CHECK((before.min() - after.min()).norm() < 1e-3);
            CHECK((before.max() - after.max()).norm() < 1e-3);
        }
    }
}

TEST_CASE("Vertex colours gltfpack -cz codes with meshopt's colour filter read as its -cc ones", "[interop][gltf]") {
    if (!interopAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    const std::string gltfpack = quoted(sharedDir() / "bench/node/node_modules/.bin/gltfpack");
    const std::filesystem::path input = modelPath("pbr/vertex_color/VertexColorTest.gltf");
    for (const char* flags : {"-cc", "-cz"})
        REQUIRE(runCommand(gltfpack + " " + flags + " -i " + quoted(input) + " -o " +
                           quoted(folder / (std::string(flags) + ".glb")))
                    .status == 0);
    REQUIRE_THAT(readTextFile(folder / "-cz.glb"), Catch::Contains("\"filter\":\"COLOR\""));
    const std::vector<WorldPrimitive> ext = flattenScene(readScene(folder / "-cc.glb"));
    const std::vector<WorldPrimitive> khr = flattenScene(readScene(folder / "-cz.glb"));
    REQUIRE(ext.size() == khr.size());
    std::size_t colors = 0;
    for (std::size_t p = 0; p < ext.size(); ++p) {
        REQUIRE(ext[p].primitive.colors.size() == khr[p].primitive.colors.size());
        for (std::size_t v = 0; v < ext[p].primitive.colors.size(); ++v, ++colors)
            CHECK((ext[p].primitive.colors[v] - khr[p].primitive.colors[v]).cwiseAbs().maxCoeff() <= 1.5 / 255);
    }
    CHECK(colors > 0);
    CHECK(decompressFile(folder / "-cz.glb", folder / "flat.glb", input).verified);
}
