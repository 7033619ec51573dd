// The Hilbert curve's order (geometry/hilbert_curve.hpp) checked against its definition: over a cube of 2^bits cells a
// side, every cell once, and each cell next to the one before it.
#include "geometry/hilbert_curve.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <vector>

using namespace symcompress;

TEST_CASE("Hilbert curve: a path through every cell, each next to the one before", "[geometry]") {
    for (int bits = 1; bits <= 4; ++bits) {
        INFO("bits " << bits);
        const std::uint32_t side = 1u << bits;
        std::vector<std::array<std::uint32_t, 3>> atIndex(std::size_t(side) * side * side);
        std::vector<char> seen(atIndex.size(), 0);
        for (std::uint32_t x = 0; x < side; ++x)
            for (std::uint32_t y = 0; y < side; ++y)
                for (std::uint32_t z = 0; z < side; ++z) {
                    const std::uint64_t index = hilbertIndex({x, y, z}, bits);
                    REQUIRE(index < atIndex.size());
                    REQUIRE_FALSE(seen[index]);
                    seen[index] = 1;
                    atIndex[index] = {x, y, z};
                }
        for (std::size_t i = 1; i < atIndex.size(); ++i) {
            int steps = 0;
            for (int c = 0; c < 3; ++c) steps += std::abs(int(atIndex[i][c]) - int(atIndex[i - 1][c]));
            CHECK(steps == 1);
        }
        CHECK(hilbertIndex({0, 0, 0}, bits) == 0);  // the curve starts at a corner
    }
}

TEST_CASE("Hilbert curve: at 16 bits, the octants in the order of the curve at 1 bit", "[geometry]") {
    // The curve visits each octant's 2^45 cells in one run, the octants in the order of the curve through 8 cells:
    // an index's top three bits are its octant's index at 1 bit.
    const std::uint32_t half = 1u << 15;
    for (std::uint32_t x : {0u, half})
        for (std::uint32_t y : {0u, half})
            for (std::uint32_t z : {0u, half})
                CHECK(hilbertIndex({x, y, z}, 16) >> 45 == hilbertIndex({x / half, y / half, z / half}, 1));
}
