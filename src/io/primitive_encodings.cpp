#include "primitive_encodings.hpp"

#include <cstring>

namespace symcompress {
namespace {

constexpr std::uint64_t rotateLeft(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

// The final avalanche of MurmurHash3's 64-bit variant: every input bit flips each output bit with probability 1/2.
constexpr std::uint64_t avalanche(std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    return x ^ (x >> 33);
}

// Two 64-bit lanes fed the same 8-byte words: xxHash64's round on one, another multiply-rotate round with other
// constants on the other.
class Fingerprinter {
public:
    void word(std::uint64_t w) {
        a_ = rotateLeft(a_ + w * 0xc2b2ae3d27d4eb4fULL, 31) * 0x9e3779b185ebca87ULL;
        b_ = rotateLeft(b_ ^ (w * 0x165667b19e3779f9ULL), 27) * 0x27d4eb2f165667c5ULL + 0x85ebca77c2b2ae63ULL;
    }
    void number(double x) {
        std::uint64_t w;
        std::memcpy(&w, &x, sizeof w);
        word(w);
    }
    // The bytes of a vector of plain values (numbers, fixed-size Eigen vectors, triangles), after its length (so
    // that where one vector ends stays part of it).
    template <typename T>
    void values(const std::vector<T>& v) {
        word(v.size());
        const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
        const std::size_t size = v.size() * sizeof(T);
        std::size_t i = 0;
        for (std::uint64_t w; i + 8 <= size; i += 8) {
            std::memcpy(&w, bytes + i, 8);
            word(w);
        }
        if (i < size) {
            std::uint64_t w = 0;
            std::memcpy(&w, bytes + i, size - i);
            word(w);
        }
    }
    void text(const std::string& s) { values(std::vector<char>(s.begin(), s.end())); }
    PrimitiveFingerprint result() const { return {avalanche(a_), avalanche(b_ ^ 0x9e3779b97f4a7c15ULL)}; }

private:
    std::uint64_t a_ = 0x27d4eb2f165667c5ULL, b_ = 0x61c8864e7a143579ULL;
};

}  // namespace

PrimitiveFingerprint fingerprintOf(const Primitive& primitive, const WriteOptions& options, bool withMaterial) {
    Fingerprinter f;
    f.values(primitive.positions);
    f.values(primitive.normals);
    f.values(primitive.texcoords);
    f.values(primitive.colors);
    f.values(primitive.triangles);
    f.word(primitive.attributes.size());
    for (const VertexAttribute& attribute : primitive.attributes) {
        f.text(attribute.name);
        f.word(std::uint64_t(attribute.components));
        f.values(attribute.values);
    }
    if (withMaterial) f.word(std::uint64_t(std::int64_t(primitive.material)));
    f.word(primitive.positionGrid.has_value());
    if (const auto& grid = primitive.positionGrid) {
        for (int k = 0; k < 3; ++k) f.number(grid->origin[k]);
        f.number(grid->range);
        f.word(std::uint64_t(grid->bits));
    }
    f.number(primitive.maxPositionError);
    f.number(primitive.closeUpDiagonal);
    f.word(std::uint64_t(std::int64_t(primitive.colorBits)));
    // The options encodePrimitive reads (positionBitsFor, dracoSpeedsWorthTrying, positionBitsWorthTrying).
    f.word(options.draco);
    f.word(options.encodingTrials);
    f.word(options.keepTriangleOrder);
    for (int bits : {options.positionBits, options.normalBits, options.texcoordBits, options.colorBits,
                     options.weightBits, options.compressionLevel})
        f.word(std::uint64_t(std::int64_t(bits)));
    f.number(options.maxPositionError);
    f.number(options.maxRelativePositionError);
    f.number(options.texcoordStep);
    return f.result();
}

std::optional<EncodedPrimitive> PrimitiveEncodings::find(const PrimitiveFingerprint& key) const {
    const std::lock_guard lock(mutex_);
    const auto found = encodings_.find(key);
    if (found == encodings_.end()) return std::nullopt;
    return found->second;
}

void PrimitiveEncodings::insert(const PrimitiveFingerprint& key, const EncodedPrimitive& encoded) {
    const std::lock_guard lock(mutex_);
    encodings_.emplace(key, encoded);
}

std::shared_ptr<PrimitiveEncodings> makePrimitiveEncodings() { return std::make_shared<PrimitiveEncodings>(); }

}  // namespace symcompress
