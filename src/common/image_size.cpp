#include "common/image_size.hpp"

#include "common/mime_type.hpp"

#include <string>

namespace symcompress {
namespace {

std::uint32_t bigEndian(const std::vector<std::uint8_t>& bytes, std::size_t at, int count) {
    std::uint32_t value = 0;
    for (int i = 0; i < count; ++i) value = value << 8 | bytes[at + std::size_t(i)];
    return value;
}

std::uint32_t littleEndian(const std::vector<std::uint8_t>& bytes, std::size_t at, int count) {
    std::uint32_t value = 0;
    for (int i = count - 1; i >= 0; --i) value = value << 8 | bytes[at + std::size_t(i)];
    return value;
}

// JPEG: the frame header (SOF0 to SOF15 but DHT, JPG and DAC) after the segments before it.
ImageSize jpegSize(const std::vector<std::uint8_t>& bytes) {
    std::size_t at = 2;
    while (at + 9 <= bytes.size() && bytes[at] == 0xff) {
        const std::uint8_t marker = bytes[at + 1];
        if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc)
            return {bigEndian(bytes, at + 7, 2), bigEndian(bytes, at + 5, 2)};
        at += 2 + bigEndian(bytes, at + 2, 2);
    }
    return {};
}

// WebP: the extended (VP8X), lossy (VP8) or lossless (VP8L) header of the first chunk.
ImageSize webpSize(const std::vector<std::uint8_t>& bytes) {
    if (bytes.size() < 30) return {};
    const std::string chunk(bytes.begin() + 12, bytes.begin() + 16);
    if (chunk == "VP8X") return {littleEndian(bytes, 24, 3) + 1, littleEndian(bytes, 27, 3) + 1};
    if (chunk == "VP8 ") return {littleEndian(bytes, 26, 2) & 0x3fff, littleEndian(bytes, 28, 2) & 0x3fff};
    if (chunk == "VP8L") {
        const std::uint32_t bits = littleEndian(bytes, 21, 4);
        return {(bits & 0x3fff) + 1, ((bits >> 14) & 0x3fff) + 1};
    }
    return {};
}

}  // namespace

ImageSize imageSizeOfBytes(const std::vector<std::uint8_t>& bytes) {
    const std::string type = imageMimeTypeOfBytes(bytes);
    if (type == "image/png" && bytes.size() >= 24) return {bigEndian(bytes, 16, 4), bigEndian(bytes, 20, 4)};
    if (type == "image/jpeg") return jpegSize(bytes);
    if (type == "image/webp") return webpSize(bytes);
    if (type == "image/ktx2" && bytes.size() >= 28) return {littleEndian(bytes, 20, 4), littleEndian(bytes, 24, 4)};
    return {};
}

}  // namespace symcompress
