// libFuzzer target: each input is an X3D file (XML, or gzipped XML as in .x3dz: the reader goes by the
// bytes) read through readScene, then written as .glb and .x3d.
#include "fuzz_scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return symcompress::fuzz::readAndWrite({{"scene.x3d", symcompress::fuzz::asText(data, size)}});
}
