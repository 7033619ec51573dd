// The command-line tools as a user runs them: exit status, messages, JSON keys, files written.
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <nlohmann/json.hpp>

#include <unistd.h>

using namespace symcompress::testing;

namespace {
const std::string kSymcompress = SYMCOMPRESS_CLI;
const std::string kSymdecompress = SYMDECOMPRESS_CLI;
}  // namespace

TEST_CASE("symcompress info --json has the documented keys", "[cli]") {
    const auto model = modelPath("vulkan_subpass_scene/subpass_scene_opaque.gltf");
    const CommandResult result = runCommand(kSymcompress + " info --json " + quoted(model));
    REQUIRE(result.status == 0);
    const auto json = nlohmann::json::parse(result.output);
    CHECK(json["triangles"] == 23388);         // MANIFEST.md: drawn, instances expanded
    CHECK(json["triangles_stored"] == 11132);  // MANIFEST.md: stored
    CHECK(json["nodes"] == 72);
    CHECK(json["meshes"] == 12);
    CHECK(json["materials"].is_number());
    CHECK(json["bbox"]["min"].size() == 3);
    CHECK(json["bbox"]["max"].size() == 3);
    CHECK(json["animations"] == 0);
    CHECK(json["warnings"].is_array());
    const CommandResult truck =
        runCommand(kSymcompress + " info --json " + quoted(modelPath("cesium_milk_truck/CesiumMilkTruck.gltf")));
    REQUIRE(truck.status == 0);
    CHECK(nlohmann::json::parse(truck.output)["animations"] == 1);
}

TEST_CASE("symcompress detect --json lists the whole group", "[cli][symmetry]") {
    const auto model = modelPath("menger_sponge/Menger_sponge-Binary.stl");
    const CommandResult result = runCommand(kSymcompress + " detect --json " + quoted(model));
    REQUIRE(result.status == 0);
    const auto json = nlohmann::json::parse(result.output);
    CHECK(json["group"] == "Oh");
    CHECK(json["order"] == 48);
    CHECK(json["centroid"].size() == 3);
    REQUIRE(json["symmetries"].size() == 47);  // every element but the identity
    std::map<std::string, int> kinds;
    for (const auto& s : json["symmetries"]) {
        kinds[s["type"]]++;
        CHECK(s["deviation"].get<double>() <= 1e-5);
        if (s["type"] == "rotation") CHECK(s["fold"].get<int>() >= 2);
        if (s["type"] == "mirror") CHECK(s["normal"].size() == 3);
    }
    // Oh: 9 + 8 + 6 rotations, 9 mirrors, 14 rotoreflections (6 S4 + 8 S6), the inversion.
    CHECK(kinds["rotation"] == 23);
    CHECK(kinds["mirror"] == 9);
    CHECK(kinds["rotoreflection"] == 14);
    CHECK(kinds["inversion"] == 1);

    const CommandResult human = runCommand(kSymcompress + " detect " + quoted(model));
    CHECK(human.status == 0);
    CHECK_THAT(human.output, Catch::Contains("group Oh, order 48"));
    CHECK(runCommand(kSymcompress + " detect --tolerance -1 " + quoted(model)).status == 2);
}

TEST_CASE("symcompress info prints a readable summary", "[cli]") {
    const CommandResult result = runCommand(kSymcompress + " info " + quoted(modelPath("vulkan_rock/rock.gltf")));
    REQUIRE(result.status == 0);
    CHECK_THAT(result.output, Catch::Contains("triangles drawn   180"));
}

TEST_CASE("symcompress convert writes every format and the result reads back", "[cli]") {
    TemporaryFolder folder;
    const auto model = modelPath("kenney_racing_forest/decoration-forest.glb");
    for (const std::string extension : {".glb", ".gltf", ".x3d", ".obj", ".ply"}) {
        const auto output = folder / ("out" + extension);
        const CommandResult convert = runCommand(kSymcompress + " convert " + quoted(model) + " -o " + quoted(output));
        INFO(extension << ": " << convert.output);
        REQUIRE(convert.status == 0);
        const CommandResult info = runCommand(kSymcompress + " info --json " + quoted(output));
        REQUIRE(info.status == 0);
        CHECK(nlohmann::json::parse(info.output)["triangles"] == 2006);
    }
}

TEST_CASE("symcompress reports bad usage and unreadable input with exit status 2", "[cli]") {
    TemporaryFolder folder;
    SECTION("no command") { CHECK(runCommand(kSymcompress).status == 2); }
    SECTION("unknown option") { CHECK(runCommand(kSymcompress + " info --frobnicate x.glb").status == 2); }
    SECTION("missing file") {
        const CommandResult result = runCommand(kSymcompress + " info " + quoted(folder / "missing.glb"));
        CHECK(result.status == 2);
        CHECK_THAT(result.output, Catch::Contains("missing.glb") && Catch::Contains("no such file"));
    }
    SECTION("a directory") {
        std::filesystem::create_directory(folder / "scene.gltf");
        const CommandResult result = runCommand(kSymcompress + " info " + quoted(folder / "scene.gltf"));
        CHECK(result.status == 2);
        CHECK_THAT(result.output, Catch::Contains("directory"));
    }
    SECTION("unknown extension") {
        writeTextFile(folder / "scene.fbx", "x");
        const CommandResult result = runCommand(kSymcompress + " info " + quoted(folder / "scene.fbx"));
        CHECK(result.status == 2);
        CHECK_THAT(result.output, Catch::Contains(".fbx"));
    }
    SECTION("converting onto the input is refused and the input is untouched") {
        const auto copy = folder / "rock.gltf";
        std::filesystem::copy_file(modelPath("vulkan_rock/rock.gltf"), copy);
        const std::string before = readTextFile(copy);
        const CommandResult result = runCommand(kSymcompress + " convert " + quoted(copy) + " -o " + quoted(copy));
        CHECK(result.status != 0);
        CHECK_THAT(result.output, Catch::Contains("input"));
        CHECK(readTextFile(copy) == before);
    }
    SECTION("a broken input leaves no output file") {
        writeTextFile(folder / "broken.glb", "glTF but not really");
        const CommandResult result =
            runCommand(kSymcompress + " convert " + quoted(folder / "broken.glb") + " -o " + quoted(folder / "out.glb"));
        CHECK(result.status == 2);
        CHECK_FALSE(std::filesystem::exists(folder / "out.glb"));
    }
}

TEST_CASE("every command has --help", "[cli]") {
    for (const std::string command : {kSymcompress + " --help", kSymcompress + " info --help",
                                      kSymcompress + " convert --help", kSymdecompress + " --help"}) {
        const CommandResult result = runCommand(command);
        INFO(command);
        CHECK(result.status == 0);
        CHECK_THAT(result.output, Catch::Contains("Usage") || Catch::Contains("usage"));
    }
}

TEST_CASE("symdecompress expands shared meshes into one flat mesh, animated parts kept as they are", "[cli]") {
    // The milk truck: its body, and two turning wheels (one mesh of 768 triangles drawn twice, each wheel node
    // animated), which stay shared and animated.
    TemporaryFolder folder;
    const auto output = folder / "flat.glb";
    const CommandResult result = runCommand(
        kSymdecompress + " " + quoted(modelPath("cesium_milk_truck/CesiumMilkTruck.gltf")) + " -o " + quoted(output));
    REQUIRE(result.status == 0);
    const auto info = nlohmann::json::parse(runCommand(kSymcompress + " info --json " + quoted(output)).output);
    CHECK(info["triangles"] == 3624);
    CHECK(info["triangles_stored"] == 3624 - 768);
    CHECK(info["meshes"] == 2);
    CHECK(info["animations"] == 1);
}

TEST_CASE("a failed write never leaves a broken output behind", "[cli][atomic]") {
    TemporaryFolder folder;
    const auto model = modelPath("kenney_racing_forest/decoration-forest.glb");
    SECTION("writing over an existing file replaces it whole") {
        const auto output = folder / "out.glb";
        writeTextFile(output, "old content");
        REQUIRE(runCommand(kSymcompress + " convert -q " + quoted(model) + " -o " + quoted(output)).status == 0);
        CHECK(readTextFile(output).substr(0, 4) == "glTF");
        CHECK(std::distance(std::filesystem::directory_iterator(folder.path()), {}) == 1);
    }
    SECTION("a read-only folder") {
        // As root permissions are not enforced, so run the tool as 'nobody' where we can.
        const std::filesystem::path readOnly = folder / "read-only";
        std::filesystem::create_directory(readOnly);
        writeTextFile(readOnly / "out.glb", "old content");
        std::filesystem::permissions(readOnly, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec |
                                                   std::filesystem::perms::others_read |
                                                   std::filesystem::perms::others_exec);
        std::filesystem::permissions(folder.path(), std::filesystem::perms::others_exec, std::filesystem::perm_options::add);
        std::string prefix;
        if (::geteuid() == 0) {
            if (runCommand("setpriv --reuid=nobody --regid=nogroup --clear-groups true").status != 0) {
                WARN("skipped: running as root without setpriv");
                return;
            }
            prefix = "setpriv --reuid=nobody --regid=nogroup --clear-groups ";
        }
        const CommandResult result =
            runCommand(prefix + kSymcompress + " convert -q " + quoted(model) + " -o " + quoted(readOnly / "out.glb"));
        INFO(result.output);
        CHECK(result.status != 0);
        CHECK_THAT(result.output, Catch::Contains("out.glb"));
        CHECK(readTextFile(readOnly / "out.glb") == "old content");
        CHECK(std::distance(std::filesystem::directory_iterator(readOnly), {}) == 1);
    }
    SECTION("a full disk") {
        const std::filesystem::path small = folder / "small";
        std::filesystem::create_directory(small);
        if (::geteuid() != 0 || runCommand("mount -t tmpfs -o size=16k tmpfs " + quoted(small)).status != 0) {
            WARN("skipped: cannot mount a small tmpfs here");
            return;
        }
        writeTextFile(small / "out.glb", "old content");
        const CommandResult result =
            runCommand(kSymcompress + " convert -q --no-draco " + quoted(model) + " -o " + quoted(small / "out.glb"));
        const std::string after = readTextFile(small / "out.glb");
        const auto files = std::distance(std::filesystem::directory_iterator(small), {});
        runCommand("umount " + quoted(small));
        INFO(result.output);
        CHECK(result.status != 0);
        CHECK_THAT(result.output, Catch::Contains("No space left"));
        CHECK(after == "old content");
        CHECK(files == 1);
    }
}

TEST_CASE("A tolerance above the default budget raises the budget, and one above a given budget is refused", "[cli]") {
    // The tolerance is a part of the budget: --tolerance 1e-4 alone once wrote an output that did not verify.
    TemporaryFolder folder;
    const std::string model = quoted(modelPath("oded_wingnut/wingnut.obj"));
    const std::string output = quoted(folder / "out.glb");
    const CommandResult raised = runCommand(kSymcompress + " " + model + " -o " + output + " --tolerance 1e-4");
    REQUIRE(raised.status == 0);
    CHECK_THAT(raised.output, Catch::Contains("the budget is 0.0002"));
    CHECK(runCommand(kSymdecompress + " " + output + " -o " + quoted(folder / "flat.glb") + " --verify " + model)
              .status == 0);
    const CommandResult refused =
        runCommand(kSymcompress + " " + model + " -o " + output + " --tolerance 1e-4 --max-error 1e-4");
    CHECK(refused.status != 0);
    CHECK_THAT(refused.output, Catch::Contains("must be below --max-error"));
}
