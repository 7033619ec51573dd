// symcompress: command-line front end. Thin: parses arguments, calls the library, prints.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace fs = std::filesystem;
using namespace symcompress;

namespace {

constexpr int kExitBadInput = 2;

nlohmann::json vectorJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

int runInfo(const fs::path& file, bool json) {
    const Scene scene = readScene(file);
    const SceneStatistics statistics = sceneStatistics(scene);
    if (json) {
        nlohmann::json out;
        out["file"] = file.string();
        out["triangles"] = statistics.trianglesDrawn;
        out["triangles_stored"] = statistics.trianglesStored;
        out["nodes"] = statistics.nodes;
        out["meshes"] = statistics.meshes;
        out["materials"] = statistics.materials;
        out["textures"] = scene.textures.size();
        if (statistics.bounds.isEmpty())
            out["bbox"] = nullptr;
        else
            out["bbox"] = {{"min", vectorJson(statistics.bounds.min())}, {"max", vectorJson(statistics.bounds.max())}};
        out["warnings"] = scene.warnings;
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::printf("%s\n", file.string().c_str());
    std::printf("  triangles drawn   %zu\n", statistics.trianglesDrawn);
    std::printf("  triangles stored  %zu\n", statistics.trianglesStored);
    std::printf("  nodes             %zu\n", statistics.nodes);
    std::printf("  meshes            %zu\n", statistics.meshes);
    std::printf("  materials         %zu\n", statistics.materials);
    std::printf("  textures          %zu\n", scene.textures.size());
    if (statistics.bounds.isEmpty()) {
        std::printf("  bounding box      (empty)\n");
    } else {
        const Eigen::Vector3d lo = statistics.bounds.min(), hi = statistics.bounds.max();
        std::printf("  bounding box      [%g %g %g] .. [%g %g %g], diagonal %g\n", lo.x(), lo.y(), lo.z(), hi.x(),
                    hi.y(), hi.z(), statistics.bounds.diagonal().norm());
    }
    for (const std::string& warning : scene.warnings) std::printf("  warning: %s\n", warning.c_str());
    return 0;
}

int runConvert(const fs::path& input, const fs::path& output, const WriteOptions& options, bool quiet) {
    const Scene scene = readScene(input);
    if (!quiet)
        for (const std::string& warning : scene.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    writeScene(scene, output, options, {input});
    if (!quiet) {
        const SceneStatistics statistics = sceneStatistics(scene);
        std::error_code error;
        std::printf("%s -> %s: %zu triangles drawn, %zu stored, %ju bytes -> %ju bytes\n", input.string().c_str(),
                    output.string().c_str(), statistics.trianglesDrawn, statistics.trianglesStored,
                    static_cast<std::uintmax_t>(fs::file_size(input, error)),
                    static_cast<std::uintmax_t>(fs::file_size(output, error)));
    }
    return 0;
}

void addWriteOptions(CLI::App& command, WriteOptions& options) {
    command.add_flag("--no-draco", [&options](std::int64_t) { options.draco = false; },
                     "glTF: write plain accessors instead of KHR_draco_mesh_compression");
    command.add_option("--position-bits", options.positionBits, "Draco position quantization bits")
        ->check(CLI::Range(8, 30))
        ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"symcompress: makes 3D scenes smaller by finding what repeats in them"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "symcompress 0.1.0");

    bool json = false, quiet = false;
    fs::path infoFile, input, output;
    WriteOptions writeOptions;

    CLI::App* info = app.add_subcommand("info", "Describe a scene: nodes, meshes, materials, triangles, bounds");
    info->add_option("FILE", infoFile, "scene file (.gltf .glb .x3d .x3dz .obj .ply .stl)")->required();
    info->add_flag("--json", json, "print one JSON object");

    CLI::App* convert = app.add_subcommand("convert", "Convert between formats through the scene model");
    convert->add_option("IN", input, "input scene file")->required();
    convert->add_option("-o,--output", output, "output file; its extension picks the format")->required();
    convert->add_flag("-q,--quiet", quiet, "print nothing but errors");
    addWriteOptions(*convert, writeOptions);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        const int status = app.exit(error);
        return status == 0 ? 0 : kExitBadInput;
    }

    try {
        if (*info) return runInfo(infoFile, json);
        if (*convert) return runConvert(input, output, writeOptions, quiet);
    } catch (const FileError& error) {
        std::fprintf(stderr, "symcompress: %s\n", error.what());
        return kExitBadInput;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "symcompress: error: %s\n", error.what());
        return 1;
    }
    return 0;
}
