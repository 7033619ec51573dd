// An image's size from its header (common/image_size.hpp), for the glTF writer's texture coordinate bits.
#include "common/image_size.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

std::vector<std::uint8_t> fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

}  // namespace

TEST_CASE("imageSizeOfBytes reads the size of PNG, JPEG, WebP and KTX2 headers", "[io]") {
    // Real files (sizes as `file` reports them): a JPEG with an Exif segment before its frame, and PNGs.
    const ImageSize jpeg = imageSizeOfBytes(fileBytes(modelPath("pbr/cesium_man/CesiumMan.jpg")));
    CHECK((jpeg.width == 1024 && jpeg.height == 1024));
    const ImageSize png = imageSizeOfBytes(fileBytes(modelPath("pbr/box_specgloss/CesiumLogoFlat.png")));
    CHECK((png.width == 211 && png.height == 211));
    const ImageSize notSquare = imageSizeOfBytes(fileBytes(modelPath("pbr/texture_transform/Arrow.png")));
    CHECK((notSquare.width == 128 && notSquare.height == 128));
    // Hand-made headers: WebP's extended, lossy and lossless forms, KTX2.
    const std::string riff = std::string("RIFF\0\0\0\0WEBP", 12);
    const ImageSize extended = imageSizeOfBytes(bytesOf(riff + std::string("VP8X\x0a\0\0\0\0\0\0\0\x2b\x01\0\xc7\0\0", 18)));
    CHECK((extended.width == 300 && extended.height == 200));
    const ImageSize lossy = imageSizeOfBytes(
        bytesOf(riff + std::string("VP8 \0\0\0\0\0\0\0\x9d\x01\x2a\x2c\x01\xc8\x00", 18)));
    CHECK((lossy.width == 300 && lossy.height == 200));
    // VP8L: 14 bits of width - 1 (299), then 14 of height - 1 (199), after the signature byte 0x2f.
    const std::uint32_t packed = 299u | 199u << 14;
    std::string lossless = riff + std::string("VP8L\0\0\0\0\x2f", 9);
    for (int i = 0; i < 4; ++i) lossless += char((packed >> (8 * i)) & 0xff);
    lossless += std::string(5, '\0');
    const ImageSize losslessSize = imageSizeOfBytes(bytesOf(lossless));
    CHECK((losslessSize.width == 300 && losslessSize.height == 200));
    std::string ktx2 = "\xabKTX 20\xbb\r\n\x1a\n";
    ktx2 += std::string(8, '\0');                                 // vkFormat, typeSize
    ktx2 += std::string("\x00\x04\0\0\x00\x02\0\0", 8);           // 1024 x 512
    const ImageSize texture = imageSizeOfBytes(bytesOf(ktx2));
    CHECK((texture.width == 1024 && texture.height == 512));
    // Cut short, or no image: nothing.
    CHECK(imageSizeOfBytes(bytesOf("\x89PNG\r\n\x1a\n")).width == 0);
    CHECK(imageSizeOfBytes(bytesOf("\xff\xd8\xff\xe0\x00\x10")).width == 0);
    CHECK(imageSizeOfBytes(bytesOf("not an image")).width == 0);
}
