#include "hilbert_curve.hpp"

namespace symcompress {

std::uint64_t hilbertIndex(std::array<std::uint32_t, 3> cell, int bits) {
    std::array<std::uint32_t, 3>& x = cell;
    const std::uint32_t most = std::uint32_t(1) << (bits - 1);
    // From the top bit down, each level's reflections and exchanges of the axes undone.
    for (std::uint32_t q = most; q > 1; q >>= 1) {
        const std::uint32_t below = q - 1;
        for (int i = 0; i < 3; ++i) {
            if (x[std::size_t(i)] & q) {
                x[0] ^= below;
            } else {
                const std::uint32_t swapped = (x[0] ^ x[std::size_t(i)]) & below;
                x[0] ^= swapped;
                x[std::size_t(i)] ^= swapped;
            }
        }
    }
    // Gray code.
    x[1] ^= x[0];
    x[2] ^= x[1];
    std::uint32_t flip = 0;
    for (std::uint32_t q = most; q > 1; q >>= 1)
        if (x[2] & q) flip ^= q - 1;
    for (std::uint32_t& coordinate : x) coordinate ^= flip;
    // The transpose read out: each level's bits, x first.
    std::uint64_t index = 0;
    for (int bit = bits - 1; bit >= 0; --bit)
        for (std::uint32_t coordinate : x) index = (index << 1) | ((coordinate >> bit) & 1);
    return index;
}

}  // namespace symcompress
