// The size in pixels an image's header gives, for stages that need a texture's resolution without decoding it
// (the glTF writer's texture coordinate quantization).
#pragma once

#include <cstdint>
#include <vector>

namespace symcompress {

struct ImageSize {
    std::uint32_t width = 0, height = 0;
};

// The width and height of a PNG, JPEG, WebP or KTX2 image from its header; 0 x 0 for bytes that are none of
// these or are cut short before their size.
ImageSize imageSizeOfBytes(const std::vector<std::uint8_t>& bytes);

}  // namespace symcompress
