// Shared helpers for the tests: temporary folders, the shared models, running the tools.
#pragma once

#include "symcompress/io.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace symcompress::testing {

inline std::filesystem::path sharedDir() { return SYMCOMPRESS_SHARED_DIR; }
inline std::filesystem::path modelPath(const std::string& relative) { return sharedDir() / "models" / relative; }

// Every model of ../shared/models (MANIFEST.md), by its path there.
inline const std::vector<std::string>& sharedModels() {
    static const std::vector<std::string> models{
        "assimp_spider/spider.obj", "cesium_milk_truck/CesiumMilkTruck.gltf", "cge_cat_x3d/scene.x3d",
        "cge_grass_flowers/grass_flowers.x3d", "cge_sterile_room/sterile_room.gltf", "kenney_racing_forest/decoration-forest.glb",
        "khronos_lantern/Lantern.gltf", "menger_sponge/Menger_sponge-Binary.stl", "oded_demosthenes/demosthenes-low-res.obj",
        "oded_hammer/hammer.obj", "oded_koala/koala.obj", "oded_wingnut/wingnut.obj", "savage_chevy_tahoe/ChevyTahoe.x3d",
        "stanford_bunny/bun_zipper.ply", "vianney_house_2/scene.gltf", "vulkan_geosphere/geosphere.gltf", "vulkan_rock/rock.gltf",
        "vulkan_subpass_scene/subpass_scene_opaque.gltf", "vulkan_torusknot/torusknot.gltf", "xj3d_cad_teapot/teapot.x3d",
        "xj3d_coffee_cup/coffeeCup.x3d"};
    return models;
}

// A fresh folder under the system's temporary folder, removed when the object goes out of scope.
class TemporaryFolder {
public:
    TemporaryFolder() {
        std::random_device entropy;
        path_ = std::filesystem::temp_directory_path() / ("symcompress-test-" + std::to_string(entropy()));
        std::filesystem::create_directories(path_);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ignored);
        std::filesystem::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

inline void writeTextFile(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
}

// How many times `what` occurs in `text` (overlapping occurrences counted).
inline std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

inline std::string readTextFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct CommandResult {
    int status = -1;
    std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing what it prints.
inline CommandResult runCommand(const std::string& commandLine) {
    CommandResult result;
    std::FILE* pipe = ::popen((commandLine + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t got;
    while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, got);
    const int status = ::pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// The JSON chunk of a GLB file.
inline nlohmann::json glbJson(const std::filesystem::path& file) {
    const std::string bytes = readTextFile(file);
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, length));
}

inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

// The peers in ../shared/bench (Node.js tools) are used when installed and not switched off.
inline bool interopAvailable() {
    if (std::getenv("SYMCOMPRESS_SKIP_INTEROP")) return false;
    return std::filesystem::exists(sharedDir() / "bench/node/node_modules/gltf-validator") &&
           runCommand("node --version").status == 0;
}
inline bool x3dInteropAvailable() {
    if (std::getenv("SYMCOMPRESS_SKIP_INTEROP")) return false;
    return std::filesystem::exists(sharedDir() / "bench/x3d/node_modules/x_ite-node") &&
           runCommand("node --version").status == 0;
}

// The render check of ../shared/bench/render (three.js and X_ITE in headless Chromium) is installed.
inline bool renderAvailable() {
    return interopAvailable() && std::filesystem::exists(sharedDir() / "bench/render/node_modules") &&
           runCommand("command -v chromium").status == 0;
}

// Renders `reference` and `output` with ../shared/bench/render (three.js for glTF, X_ITE for X3D) in `mode` from
// `views`, and compares them (render_compare.sh: status 0 where they draw the same).
inline CommandResult renderCompare(const std::filesystem::path& reference, const std::filesystem::path& output,
                                   const std::string& mode, const std::string& views) {
    return runCommand("PATH=/usr/bin:$PATH " + quoted(sharedDir() / "bench/render/render_compare.sh") + " --mode " +
                      mode + " --views " + views + " " + quoted(reference) + " " + quoted(output));
}

// `compressed` renders as `reference` does (render_compare.sh, lit and normals modes, its default limits).
inline void checkRendersSame(const std::filesystem::path& reference, const std::filesystem::path& compressed,
                             const std::string& views = "abc") {
    for (const char* mode : {"lit", "normals"}) {
        const CommandResult result = renderCompare(reference, compressed, mode, views);
        INFO(mode << ": " << result.output);
        CHECK(result.status == 0);
    }
}

// Runs a command that prints a JSON object (after any warnings) and returns the object.
inline nlohmann::json runJson(const std::string& commandLine) {
    const CommandResult result = runCommand(commandLine);
    INFO(commandLine << "\n" << result.output);
    REQUIRE(result.status == 0);
    // The tools may print warnings first; the JSON object is the last line.
    const auto start = result.output.rfind("\n{");
    return nlohmann::json::parse(start == std::string::npos ? result.output : result.output.substr(start + 1));
}

// The validator's errors, except the missing image files that the input itself refers to without having
// them (several models in ../shared come without their textures; the output keeps the references).
inline std::vector<std::string> validatorErrors(const std::filesystem::path& file) {
    const CommandResult result = runCommand("node " + quoted(sharedDir() / "bench/validate.js") + " --json " + quoted(file));
    INFO(result.output);
    const auto report = nlohmann::json::parse(result.output.substr(result.output.find('{')));
    std::vector<std::string> errors;
    for (const auto& message : report["issues"]["messages"]) {
        if (message["severity"] != 0) continue;
        const std::string pointer = message["pointer"], code = message["code"], text = message["message"];
        if (code == "IO_ERROR" && pointer.rfind("/images/", 0) == 0 && text.find("ENOENT") != std::string::npos) continue;
        errors.push_back(code + " " + pointer + " " + text);
    }
    return errors;
}

// `content` written as `name` in `folder` must be refused by readScene with an error naming the file and holding
// `problem`.
inline void expectReadError(const TemporaryFolder& folder, const std::string& name, const std::string& content,
                            const std::string& problem) {
    const auto file = folder / name;
    writeTextFile(file, content);
    INFO(name);
    try {
        readScene(file);
        FAIL("no error for " << name);
    } catch (const FileError& error) {
        const std::string message = error.what();
        INFO(message);
        CHECK(message.find(name) != std::string::npos);
        CHECK(message.find(problem) != std::string::npos);
    }
}

}  // namespace symcompress::testing
