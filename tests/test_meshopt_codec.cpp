// meshoptimizer's vertex codec as KHR_meshopt_compression specifies it (io/meshopt_vertex_codec.hpp), against
// meshoptimizer's own encoders: the packaged library's (version 0) and its npm package's (version 1, the colour
// filter; tests/meshopt_reference.mjs).
#include "io/meshopt_vertex_codec.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <meshoptimizer.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// Element bytes of the kinds meshopt's modes are made for: 16-bit coordinates that change little, float32 on a
// random walk, random bytes (stored as they are), constants (nothing stored), 12-bit integers in the high bits.
std::vector<unsigned char> sampleElements(const std::string& kind, std::size_t count, std::size_t stride,
                                          std::uint64_t seed) {
    std::mt19937_64 random(seed);
    float position = 0;  // "walk"
    std::vector<unsigned char> bytes(count * stride);
    for (std::size_t i = 0; i < count; ++i)
        for (std::size_t c = 0; c < stride / 4; ++c) {
            std::uint32_t word = 0;
            if (kind == "smooth") {
                const auto a = std::int16_t(3000 * std::sin(0.01 * double(i) * double(c + 1)));
                const auto b = std::int16_t(i % 65536);
                word = std::uint32_t(std::uint16_t(a)) | std::uint32_t(std::uint16_t(b)) << 16;
            } else if (kind == "walk") {
                position += std::uniform_real_distribution<float>(-0.01f, 0.01f)(random);
                std::memcpy(&word, &position, 4);
            } else if (kind == "random") {
                word = std::uint32_t(random());
            } else if (kind == "constant") {
                word = 0x3f800000u + std::uint32_t(c);
            } else {  // "high bits"
                word = std::uint32_t(random() % 4096) << 20;
            }
            std::memcpy(bytes.data() + (i * stride + 4 * c), &word, 4);
        }
    return bytes;
}

std::vector<unsigned char> decoded(const std::vector<unsigned char>& stream, std::size_t count, std::size_t stride,
                                   bool* ok = nullptr) {
    std::vector<unsigned char> out(count * stride);
    const bool decodedWell = decodeMeshoptVertexStream(out.data(), count, stride, stream.data(), stream.size());
    if (ok) *ok = decodedWell;
    return out;
}

std::vector<unsigned char> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

}  // namespace

TEST_CASE("meshopt's vertex codec, version 0: what libmeshoptimizer encodes decodes to the same bytes", "[io][meshopt]") {
    for (const char* kind : {"smooth", "walk", "random", "constant", "high bits"})
        for (std::size_t stride : {4, 8, 12, 16, 64, 256})
            for (std::size_t count : {0, 1, 15, 16, 17, 255, 256, 257, 1000}) {
                INFO(kind << ", stride " << stride << ", count " << count);
                const std::vector<unsigned char> elements = sampleElements(kind, count, stride, count * 31 + stride);
                std::vector<unsigned char> stream(meshopt_encodeVertexBufferBound(count, stride));
                stream.resize(meshopt_encodeVertexBuffer(stream.data(), stream.size(), elements.data(), count, stride));
                REQUIRE(stream.at(0) == 0xa0);
                bool ok = false;
                CHECK(decoded(stream, count, stride, &ok) == elements);
                CHECK(ok);
            }
}

TEST_CASE("meshopt's vertex codec refuses a stream that is not one, reading nothing beyond it", "[io][meshopt]") {
    const std::size_t count = 300, stride = 12;
    const std::vector<unsigned char> elements = sampleElements("smooth", count, stride, 5);
    std::vector<unsigned char> stream(meshopt_encodeVertexBufferBound(count, stride));
    stream.resize(meshopt_encodeVertexBuffer(stream.data(), stream.size(), elements.data(), count, stride));
    bool ok = true;
    std::vector<unsigned char> cut(stream.begin(), stream.end() - 1);  // the tail moves: bytes left or missing
    decoded(cut, count, stride, &ok);
    CHECK_FALSE(ok);
    std::vector<unsigned char> longer = stream;
    longer.insert(longer.begin() + 1, 0);
    decoded(longer, count, stride, &ok);
    CHECK_FALSE(ok);
    std::vector<unsigned char> header = stream;
    header[0] = 0xa2;
    decoded(header, count, stride, &ok);
    CHECK_FALSE(ok);
    decoded(stream, count, 10, &ok);  // a stride that is no multiple of 4
    CHECK_FALSE(ok);
    // Every prefix, and the stream's bytes each set to 0xff in turn: false or true, never a read past the end
    // (the sanitizers' build runs this).
    for (std::size_t size = 0; size < stream.size(); size += 7) {
        std::vector<unsigned char> prefix(stream.begin(), stream.begin() + std::ptrdiff_t(size));
        std::vector<unsigned char> out(count * stride);
        CHECK_FALSE(decodeMeshoptVertexStream(out.data(), count, stride, prefix.data(), prefix.size()));
    }
    for (std::size_t at = 1; at < stream.size(); at += 3) {
        std::vector<unsigned char> changed = stream;
        changed[at] = 0xff;
        decoded(changed, count, stride);
    }
}

TEST_CASE("meshopt's vertex codec, version 1: meshoptimizer's streams decode as its own decoder decodes them",
          "[io][meshopt][interop]") {
    if (!interopAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    std::set<unsigned> channelModes, controlModes;
    struct Sample {
        const char* kind;
        std::size_t stride, count;
    };
    for (const Sample& sample : {Sample{"smooth", 8, 500}, Sample{"walk", 12, 700}, Sample{"random", 4, 1024},
                                 Sample{"constant", 16, 33}, Sample{"high bits", 4, 1024}, Sample{"walk", 4, 1000},
                                 Sample{"random", 20, 301}})
        for (const char* level : {"2", "3"}) {
            INFO(sample.kind << ", stride " << sample.stride << ", count " << sample.count << ", level " << level);
            const std::vector<unsigned char> elements =
                sampleElements(sample.kind, sample.count, sample.stride, sample.count);
            writeTextFile(folder / "raw.bin", std::string(elements.begin(), elements.end()));
            const std::string command =
                "node " + quoted(std::filesystem::path(SYMCOMPRESS_SOURCE_DIR) / "tests/meshopt_reference.mjs") + " --modules " +
                quoted(sharedDir() / "bench/node/node_modules") + " --in " + quoted(folder / "raw.bin") +
                " --count " + std::to_string(sample.count) + " --stride " + std::to_string(sample.stride) +
                " --level " + level + " --stream " + quoted(folder / "stream.bin") + " --decoded " +
                quoted(folder / "decoded.bin");
            REQUIRE(runCommand(command).status == 0);
            const std::vector<unsigned char> stream = bytesOf(readTextFile(folder / "stream.bin"));
            REQUIRE(stream.at(0) == 0xa1);
            CHECK(bytesOf(readTextFile(folder / "decoded.bin")) == elements);
            bool ok = false;
            CHECK(decoded(stream, sample.count, sample.stride, &ok) == elements);
            CHECK(ok);
            for (std::size_t c = 0; c < sample.stride / 4; ++c) channelModes.insert(stream[stream.size() - 1 - c] & 15);
            for (std::size_t k = 0; k < sample.stride; ++k) controlModes.insert(stream[1 + k / 4] >> (k % 4 * 2) & 3);
        }
    // The samples reach every mode the specification has.
    CHECK(channelModes == std::set<unsigned>{0, 1, 2});
    CHECK(controlModes == std::set<unsigned>{0, 1, 2, 3});
}

TEST_CASE("meshopt's colour filter decodes as meshoptimizer's own decoder does", "[io][meshopt][interop]") {
    if (!interopAvailable()) {
        WARN("skipped: the peers in ../shared/bench are not installed");
        return;
    }
    TemporaryFolder folder;
    std::mt19937_64 random(11);
    std::uniform_real_distribution<float> unit(0, 1);
    const std::size_t count = 400;
    std::vector<float> colors(4 * count);
    for (float& c : colors) c = unit(random);
    for (std::size_t i = 0; i < 8; ++i) colors[4 * i + 3] = i % 2 ? 1.0f : 0.0f;  // opaque and clear too
    writeTextFile(folder / "colors.bin",
                  std::string(reinterpret_cast<const char*>(colors.data()), colors.size() * sizeof(float)));
    for (const auto& [stride, bits] : {std::pair<std::size_t, int>{4, 8}, {4, 6}, {8, 12}, {8, 16}}) {
        INFO("stride " << stride << ", " << bits << " bits");
        REQUIRE(runCommand("node " + quoted(std::filesystem::path(SYMCOMPRESS_SOURCE_DIR) / "tests/meshopt_reference.mjs") +
                           " --modules " + quoted(sharedDir() / "bench/node/node_modules") + " --in " +
                           quoted(folder / "colors.bin") + " --count " + std::to_string(count) + " --stride " +
                           std::to_string(stride) + " --filter COLOR --bits " + std::to_string(bits) + " --stream " +
                           quoted(folder / "stream.bin") + " --decoded " + quoted(folder / "decoded.bin"))
                    .status == 0);
        const std::vector<unsigned char> stream = bytesOf(readTextFile(folder / "stream.bin"));
        const std::vector<unsigned char> reference = bytesOf(readTextFile(folder / "decoded.bin"));
        std::vector<unsigned char> ours = decoded(stream, count, stride);
        decodeMeshoptColorFilter(ours.data(), count, stride);
        REQUIRE(ours.size() == reference.size());
        // The specification allows a unit in the last place; each component also near the colour encoded.
        const double largest = stride == 4 ? 255 : 65535;
        double worst = 0, worstFromColor = 0;
        for (std::size_t i = 0; i < 4 * count; ++i) {
            auto component = [&, wide = stride == 8](const std::vector<unsigned char>& bytes) {
                if (!wide) return double(bytes[i]);
                std::uint16_t value;
                std::memcpy(&value, bytes.data() + 2 * i, 2);
                return double(value);
            };
            worst = std::max(worst, std::abs(component(ours) - component(reference)));
            worstFromColor = std::max(worstFromColor, std::abs(component(ours) / largest - double(colors[i])));
        }
        CHECK(worst <= 1);
        CHECK(worstFromColor <= 2.0 / double((1 << (bits - 1)) - 1));
    }
}
