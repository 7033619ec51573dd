// libFuzzer target: each input is an OBJ file and, after a line "#@mtl", the material library it names
// (the seeds say "mtllib scene.mtl"), read through readScene, then written as .glb and .x3d.
#include "fuzz_scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input = symcompress::fuzz::asText(data, size);
    // The marker is a comment to the OBJ reader, so an input without one is a plain OBJ file.
    constexpr std::string_view marker = "#@mtl\n";
    const std::size_t split = input.find(marker);
    if (split == std::string_view::npos) return symcompress::fuzz::readAndWrite({{"scene.obj", input}});
    return symcompress::fuzz::readAndWrite(
        {{"scene.obj", input.substr(0, split)}, {"scene.mtl", input.substr(split + marker.size())}});
}
