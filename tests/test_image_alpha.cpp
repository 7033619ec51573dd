// Whether an image has translucent pixels (common/image_alpha.hpp): what X3D's alpha mode AUTO blends by.
#include "common/image_alpha.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <png.h>

#include <fstream>
#include <iterator>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// A 4 x 3 PNG of `format` (libpng's simplified API) with every channel 200 and, where it has alpha, every pixel's
// alpha 255 but one pixel's, `oddAlpha`.
std::vector<std::uint8_t> pngOf(png_uint_32 format, png_byte oddAlpha) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = 4;
    image.height = 3;
    image.format = format;
    const std::size_t channels = PNG_IMAGE_SAMPLE_CHANNELS(format);
    std::vector<png_byte> pixels(PNG_IMAGE_SIZE(image), 200);
    if (format & PNG_FORMAT_FLAG_ALPHA) {
        for (std::size_t alpha = channels - 1; alpha < pixels.size(); alpha += channels) pixels[alpha] = 255;
        pixels[5 * channels + channels - 1] = oddAlpha;
    }
    png_alloc_size_t size = 0;
    REQUIRE(png_image_write_to_memory(&image, nullptr, &size, 0, pixels.data(), 0, nullptr));
    std::vector<std::uint8_t> bytes(size);
    REQUIRE(png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels.data(), 0, nullptr));
    bytes.resize(size);
    return bytes;
}

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

}  // namespace

TEST_CASE("imageHasTranslucentPixels: a PNG's decoded alpha, WebP's flag, no alpha in JPEG or in broken bytes",
          "[io]") {
    CHECK(!imageHasTranslucentPixels(pngOf(PNG_FORMAT_RGB, 0)));
    CHECK(!imageHasTranslucentPixels(pngOf(PNG_FORMAT_RGBA, 255)));  // an alpha channel, every pixel opaque
    CHECK(imageHasTranslucentPixels(pngOf(PNG_FORMAT_RGBA, 254)));
    CHECK(imageHasTranslucentPixels(pngOf(PNG_FORMAT_GA, 0)));
    CHECK(!imageHasTranslucentPixels(pngOf(PNG_FORMAT_GA, 255)));
    // Real files: the grass's flowers (RGBA, cut out), Cesium's logo (a palette without transparency), a JPEG.
    CHECK(imageHasTranslucentPixels(fileBytes(modelPath("cge_grass_flowers/textures/flower111.png"))));
    CHECK(!imageHasTranslucentPixels(fileBytes(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"))));
    CHECK(!imageHasTranslucentPixels(fileBytes(modelPath("pbr/cesium_man/CesiumMan.jpg"))));
    // A PNG cut short after its header, and bytes that are no image.
    std::vector<std::uint8_t> cut = pngOf(PNG_FORMAT_RGBA, 0);
    cut.resize(40);
    CHECK(!imageHasTranslucentPixels(cut));
    CHECK(!imageHasTranslucentPixels(bytesOf("not an image")));
    CHECK(!imageHasTranslucentPixels({}));
    // WebP headers: the extended form's alpha flag, the lossless form's alpha_is_used bit, lossy without alpha.
    const std::string riff = std::string("RIFF\0\0\0\0WEBP", 12);
    CHECK(imageHasTranslucentPixels(bytesOf(riff + std::string("VP8X\x0a\0\0\0\x10\0\0\0\x2b\x01\0\xc7\0\0", 18))));
    CHECK(!imageHasTranslucentPixels(bytesOf(riff + std::string("VP8X\x0a\0\0\0\0\0\0\0\x2b\x01\0\xc7\0\0", 18))));
    CHECK(imageHasTranslucentPixels(bytesOf(riff + std::string("VP8L\0\0\0\0\x2f\0\0\0\x10", 13))));
    CHECK(!imageHasTranslucentPixels(bytesOf(riff + std::string("VP8L\0\0\0\0\x2f\0\0\0\0", 13))));
    CHECK(
        !imageHasTranslucentPixels(bytesOf(riff + std::string("VP8 \0\0\0\0\0\0\0\x9d\x01\x2a\x2c\x01\xc8\x00", 18))));
}
