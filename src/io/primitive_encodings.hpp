// The glTF writer's Draco encodings kept by a fingerprint of what they encode, so that a compression job, which
// writes the same primitives in each plan it measures and prices many of them before, encodes each once.
#pragma once

#include "gltf_builder.hpp"

#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <utility>

namespace symcompress {

// 128 bits of a primitive's content (every vertex value, triangle, attribute, its material, grid and error bound;
// not its morph targets, which are never Draco-encoded)
// and of the write options its encoding depends on. Two lanes with their own constants, so that two different
// inputs agree in both by chance with a probability of about 2^-128.
// withMaterial false: of the geometry alone, the same for the primitive in any material.
using PrimitiveFingerprint = std::pair<std::uint64_t, std::uint64_t>;
PrimitiveFingerprint fingerprintOf(const Primitive& primitive, const WriteOptions& options, bool withMaterial = true);

// Its first lane: already a hash.
struct PrimitiveFingerprintHash {
    std::size_t operator()(const PrimitiveFingerprint& key) const { return std::size_t(key.first); }
};

// Thread-safe: the writer encodes a scene's primitives in parallel.
class PrimitiveEncodings {
public:
    std::optional<EncodedPrimitive> find(const PrimitiveFingerprint& key) const;
    void insert(const PrimitiveFingerprint& key, const EncodedPrimitive& encoded);

private:
    mutable std::mutex mutex_;
    std::unordered_map<PrimitiveFingerprint, EncodedPrimitive, PrimitiveFingerprintHash> encodings_;
};

}  // namespace symcompress
