#include "common/image_alpha.hpp"

#include "common/mime_type.hpp"

#include <png.h>

#include <algorithm>
#include <string>

namespace symcompress {
namespace {

constexpr std::uint64_t kMostDecodedPixels = std::uint64_t(1) << 25;  // 128 MiB of RGBA

bool pngHasTranslucentPixels(const std::vector<std::uint8_t>& bytes) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return false;
    // The simplified API sets the alpha flag for an alpha channel and for a tRNS chunk alike.
    if (!(image.format & PNG_FORMAT_FLAG_ALPHA)) {
        png_image_free(&image);
        return false;
    }
    if (std::uint64_t(image.width) * image.height > kMostDecodedPixels) {
        png_image_free(&image);
        return true;
    }
    image.format = PNG_FORMAT_RGBA;
    std::vector<png_byte> pixels(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return false;  // frees the image
    for (std::size_t alpha = 3; alpha < pixels.size(); alpha += 4)
        if (pixels[alpha] != 255) return true;
    return false;
}

// WebP: the extended header's alpha flag, or the lossless header's alpha_is_used bit; a lossy image alone has none.
bool webpHasAlpha(const std::vector<std::uint8_t>& bytes) {
    if (bytes.size() < 25) return false;
    const std::string chunk(bytes.begin() + 12, bytes.begin() + 16);
    if (chunk == "VP8X") return (bytes[20] & 0x10) != 0;
    if (chunk == "VP8L") return (bytes[24] & 0x10) != 0;
    return false;
}

}  // namespace

bool imageHasTranslucentPixels(const std::vector<std::uint8_t>& bytes) {
    const std::string type = imageMimeTypeOfBytes(bytes);
    if (type == "image/png") return pngHasTranslucentPixels(bytes);
    if (type == "image/webp") return webpHasAlpha(bytes);
    return false;
}

bool TranslucentTextures::operator()(int texture) {
    if (texture < 0) return false;
    const auto [entry, added] = known_.try_emplace(texture, false);
    if (added) entry->second = imageHasTranslucentPixels(textures_[std::size_t(texture)].bytes);
    return entry->second;
}

}  // namespace symcompress
