// Writes the bundled sample scenes (see sample_scenes.hpp) into the folder given as the first argument
// (default: the current folder), as uncompressed GLB: the input a user would start from.
#include "sample_scenes.hpp"
#include "symcompress/io.hpp"

#include <cstdio>
#include <functional>

using namespace symcompress;

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const std::vector<std::pair<const char*, std::function<Scene()>>> samples = {
        {"bolts.glb", samples::makeBoltsScene},
        {"three_spheres.glb", samples::makeThreeSpheresScene},
        {"lamp.glb", samples::makeLampScene},
        {"pliers.glb", samples::makePliersScene},
        {"chess.glb", samples::makeChessScene},
        {"icosahedral.glb", samples::makeIcosahedralScene},
        {"room.glb", samples::makeRoomScene},
    };
    WriteOptions plain;
    plain.draco = false;
    try {
        for (const auto& [name, make] : samples) {
            writeScene(make(), folder / name, plain);
            std::printf("wrote %s\n", (folder / name).string().c_str());
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "make_samples: %s\n", error.what());
        return 1;
    }
    return 0;
}
