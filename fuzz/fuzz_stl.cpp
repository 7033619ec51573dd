// libFuzzer target: each input is a .stl file read through readScene, then written as .glb and .x3d.
#include "fuzz_scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return symcompress::fuzz::readAndWrite({{"scene.stl", symcompress::fuzz::asText(data, size)}});
}
