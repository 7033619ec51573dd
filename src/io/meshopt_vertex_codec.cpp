// meshoptimizer's vertex codec, versions 0 and 1, and the colour filter (meshopt_vertex_codec.hpp), written from
// KHR_meshopt_compression's Appendices A and B. Plain scalar code: files read once, not a renderer's loop.
#include "meshopt_vertex_codec.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace symcompress {
namespace {

constexpr std::size_t kGroupSize = 16;  // elements whose deltas of one byte share a header entry

// Elements per attribute block: as many as 8 KiB holds, a whole number of groups, at most 256.
std::size_t blockElements(std::size_t stride) { return std::min<std::size_t>((8192 / stride) & ~(kGroupSize - 1), 256); }

// A group's 16 deltas of `bits` bits each (0: all zero, nothing stored; 8: the bytes as they are). A delta of
// all ones is a sentinel: its value is the next of the full bytes stored after the packed ones. 1-bit deltas are
// packed from the least significant bit, 2- and 4-bit ones from the most. Null where the data ends too early.
const unsigned char* decodeGroup(const unsigned char* data, const unsigned char* end, unsigned char* deltas,
                                 int bits) {
    if (bits == 0) {
        std::memset(deltas, 0, kGroupSize);
        return data;
    }
    const std::size_t packed = kGroupSize * std::size_t(bits) / 8;
    if (std::size_t(end - data) < packed) return nullptr;
    if (bits == 8) {
        std::memcpy(deltas, data, kGroupSize);
        return data + kGroupSize;
    }
    const unsigned sentinel = (1u << bits) - 1;
    const int perByte = 8 / bits;
    const unsigned char* extra = data + packed;
    for (std::size_t i = 0; i < kGroupSize; ++i) {
        const unsigned byte = data[i / std::size_t(perByte)];
        const int slot = int(i % std::size_t(perByte));
        unsigned value = bits == 1 ? (byte >> slot) & 1u : (byte >> (8 - bits * (slot + 1))) & sentinel;
        if (value == sentinel) {
            if (extra == end) return nullptr;
            value = *extra++;
        }
        deltas[i] = static_cast<unsigned char>(value);
    }
    return extra;
}

// One byte position's deltas in a block of `groups` groups: a header of 2 bits a group (4 to a byte, from the
// least significant bits), each choosing the group's bits from `bitsOfMode`, then the groups.
const unsigned char* decodeByteDeltas(const unsigned char* data, const unsigned char* end, unsigned char* deltas,
                                      std::size_t groups, const std::array<int, 4>& bitsOfMode) {
    const std::size_t headerBytes = (groups + 3) / 4;
    if (std::size_t(end - data) < headerBytes) return nullptr;
    const unsigned char* header = data;
    data += headerBytes;
    for (std::size_t g = 0; g < groups && data; ++g)
        data = decodeGroup(data, end, deltas + g * kGroupSize, bitsOfMode[(header[g / 4] >> (g % 4 * 2)) & 3]);
    return data;
}

// Version 1's byte positions by their block's control mode (2 bits each, 4 to a byte): 0 and 1 choose the
// groups' bits from two sets, 2 stores nothing (all deltas 0), 3 stores the block's deltas as they are, one byte
// an element (not a whole number of groups).
const unsigned char* decodeControlledDeltas(const unsigned char* data, const unsigned char* end,
                                            unsigned char* deltas, std::size_t elements, unsigned control) {
    const std::size_t groups = (elements + kGroupSize - 1) / kGroupSize;
    switch (control) {
        case 0: return decodeByteDeltas(data, end, deltas, groups, {0, 1, 2, 4});
        case 1: return decodeByteDeltas(data, end, deltas, groups, {1, 2, 4, 8});
        case 2: std::memset(deltas, 0, elements); return data;
        default:
            if (std::size_t(end - data) < elements) return nullptr;
            std::memcpy(deltas, data, elements);
            return data + elements;
    }
}

template <typename T>
T unzigzag(T v) {
    return (v & 1) ? T(~(v >> 1)) : T(v >> 1);
}

// The encoder rotates an XOR delta left by r (the specification's rotate); the decoder undoes it.
std::uint32_t rotateRight(std::uint32_t v, unsigned r) { return (v >> r) | (v << ((32 - r) & 31)); }

// Element i's 4 bytes of channel c from their deltas and the element before (`previous`), by the channel's mode:
// 0 byte deltas, 1 16-bit deltas, 2 32-bit XOR deltas rotated by the mode's high 4 bits (all zigzag coded but
// the XOR). Little-endian throughout.
void applyChannel(unsigned char* element, const unsigned char* previous, const unsigned char delta[4],
                  unsigned mode) {
    switch (mode & 15) {
        case 0:
            for (int j = 0; j < 4; ++j)
                element[j] = static_cast<unsigned char>(previous[j] + unzigzag<unsigned char>(delta[j]));
            break;
        case 1:
            for (int h = 0; h < 4; h += 2) {
                const auto d = std::uint16_t(delta[h] | delta[h + 1] << 8);
                const auto v = std::uint16_t((previous[h] | previous[h + 1] << 8) + unzigzag<std::uint16_t>(d));
                element[h] = static_cast<unsigned char>(v);
                element[h + 1] = static_cast<unsigned char>(v >> 8);
            }
            break;
        default: {
            std::uint32_t d = 0, p = 0;
            for (int j = 0; j < 4; ++j) {
                d |= std::uint32_t(delta[j]) << (8 * j);
                p |= std::uint32_t(previous[j]) << (8 * j);
            }
            const std::uint32_t v = rotateRight(d, mode >> 4) ^ p;
            for (int j = 0; j < 4; ++j) element[j] = static_cast<unsigned char>(v >> (8 * j));
        }
    }
}

}  // namespace

bool decodeMeshoptVertexStream(unsigned char* out, std::size_t count, std::size_t stride, const unsigned char* data,
                               std::size_t size) {
    if (stride == 0 || stride % 4 != 0 || stride > 256 || size == 0) return false;
    const int version = data[0] == 0xa0 ? 0 : data[0] == 0xa1 ? 1 : -1;
    if (version < 0) return false;
    // The tail: the baseline element, then (version 1) a mode byte for each 4-byte channel; zeros before it bring
    // it to at least 32 bytes (version 0) or 24 (version 1).
    const std::size_t channels = stride / 4;
    const std::size_t tail = stride + (version == 1 ? channels : 0);
    const std::size_t paddedTail = std::max<std::size_t>(tail, version == 1 ? 24 : 32);
    if (size < 1 + paddedTail) return false;
    const unsigned char* end = data + size - paddedTail;
    const unsigned char* baseline = data + size - tail;
    std::array<unsigned, 64> channelMode{};
    for (std::size_t c = 0; c < channels && version == 1; ++c) {
        channelMode[c] = baseline[stride + c];
        const unsigned mode = channelMode[c] & 15, rotation = channelMode[c] >> 4;
        if (mode > 2 || (mode < 2 && rotation != 0)) return false;
    }

    const std::size_t perBlock = blockElements(stride);
    std::vector<unsigned char> deltas(stride * perBlock);  // a block's, by byte position
    const unsigned char* at = data + 1;
    for (std::size_t start = 0; start < count; start += perBlock) {
        const std::size_t elements = std::min(perBlock, count - start), groups = (elements + kGroupSize - 1) / kGroupSize;
        const unsigned char* control = at;
        if (version == 1) {
            if (std::size_t(end - at) < channels) return false;
            at += channels;
        }
        for (std::size_t k = 0; k < stride && at; ++k) {
            unsigned char* byteDeltas = deltas.data() + k * perBlock;
            at = version == 0
                     ? decodeByteDeltas(at, end, byteDeltas, groups, {0, 2, 4, 8})
                     : decodeControlledDeltas(at, end, byteDeltas, elements, (control[k / 4] >> (k % 4 * 2)) & 3);
        }
        if (!at) return false;
        for (std::size_t i = 0; i < elements; ++i) {
            unsigned char* element = out + (start + i) * stride;
            const unsigned char* previous = start + i == 0 ? baseline : element - stride;
            for (std::size_t c = 0; c < channels; ++c) {
                const unsigned char delta[4] = {deltas[(4 * c) * perBlock + i], deltas[(4 * c + 1) * perBlock + i],
                                                deltas[(4 * c + 2) * perBlock + i], deltas[(4 * c + 3) * perBlock + i]};
                applyChannel(element + 4 * c, previous + 4 * c, delta, channelMode[c]);
            }
        }
    }
    return at == end;
}

void decodeMeshoptColorFilter(unsigned char* data, std::size_t count, std::size_t stride) {
    const bool wide = stride == 8;
    const double largest = wide ? 65535.0 : 255.0;
    for (std::size_t e = 0; e < count; ++e) {
        unsigned char* element = data + e * stride;
        std::array<std::int32_t, 4> in{};
        for (int j = 0; j < 4; ++j) {
            if (wide) {
                std::uint16_t u;
                std::memcpy(&u, element + 2 * j, 2);
                in[j] = (j == 1 || j == 2) ? std::int32_t(std::int16_t(u)) : std::int32_t(u);  // Co, Cg signed
            } else {
                in[j] = (j == 1 || j == 2) ? std::int32_t(std::int8_t(element[j])) : std::int32_t(element[j]);
            }
        }
        // The alpha's highest set bit is bit K-1 of K-bit components: its scale.
        int highest = -1;
        for (int bit = 0; bit < 16; ++bit)
            if (in[3] >> bit & 1) highest = bit;
        std::array<double, 4> rgba{};
        if (highest >= 0) {
            const std::int32_t scale = (1 << (highest + 1)) - 1;
            const std::int32_t y = in[0], co = in[1], cg = in[2];
            std::int32_t alpha = in[3] & (scale >> 1);
            alpha = (alpha << 1) | (alpha & 1);
            const std::array<std::int32_t, 4> fixed = {y + co - cg, y + cg, y - co - cg, alpha};
            for (int j = 0; j < 4; ++j)
                rgba[std::size_t(j)] = std::clamp(std::round(double(fixed[std::size_t(j)]) * largest / scale), 0.0, largest);
        }
        for (int j = 0; j < 4; ++j) {
            const auto value = static_cast<std::uint16_t>(rgba[std::size_t(j)]);
            if (wide)
                std::memcpy(element + 2 * j, &value, 2);
            else
                element[j] = static_cast<unsigned char>(value);
        }
    }
}

}  // namespace symcompress
