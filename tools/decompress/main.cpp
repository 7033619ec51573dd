// symdecompress: reads a symcompress output (or any scene) and writes it with every instance expanded.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>

namespace fs = std::filesystem;
using namespace symcompress;

int main(int argc, char** argv) {
    CLI::App app{"symdecompress: rebuilds the full geometry of a scene, every instance expanded"};
    app.set_version_flag("--version", "symdecompress 0.1.0");
    fs::path input, output;
    WriteOptions options;
    options.draco = false;  // the expanded scene is the reference geometry: keep it exact
    app.add_option("IN", input, "scene file (.gltf .glb .x3d .x3dz .obj .ply .stl)")->required();
    app.add_option("-o,--output", output, "output file; its extension picks the format")->required();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        const int status = app.exit(error);
        return status == 0 ? 0 : 2;
    }
    Scene scene;
    try {
        scene = readScene(input);
    } catch (const FileError& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return 2;
    }
    try {
        const Scene flat = expandInstances(scene);
        writeScene(flat, output, options, {input});
        std::printf("%s -> %s: %zu triangles\n", input.string().c_str(), output.string().c_str(),
                    sceneStatistics(flat).trianglesDrawn);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return 1;
    }
    return 0;
}
