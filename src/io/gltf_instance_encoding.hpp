// How a GPU-instanced batch's TRANSLATION, ROTATION or SCALE values can be stored: plain accessors, or
// EXT_meshopt_compression streams (meshoptimizer's vertex codec, after its exponential or quaternion filter
// where the rounding keeps every vertex within its allowance). Each candidate is measured: the batch takes the
// one that adds the fewest bytes (gltf_gpu_instancing.cpp).
#pragma once

#include "gltf_builder.hpp"

#include <Eigen/Geometry>

#include <cstdint>

#include <string>
#include <vector>

namespace symcompress {

// One way to store one attribute of one batch.
struct InstanceEncoding {
    int componentType = kFloat;         // of the accessor: FLOAT, or normalized SHORT (rotations)
    std::size_t elementBytes = 12;      // per instance, as the accessor reads it (meshopt's byteStride)
    std::string filter;                 // EXT_meshopt_compression's (NONE, EXPONENTIAL, QUATERNION); empty: plain
    std::vector<unsigned char> values;  // the accessor's data before meshopt: filtered where there is a filter
    std::size_t storedBytes = 0;        // what the data takes in the file: meshopt's bytes, else values.size()
    bool meshopt() const { return !filter.empty(); }
};

// The candidates for vectors (translations, scales), each within `allowed`: a vertex moves by `lever` times
// the distance between a vector and the vector read back (1 for translations, the mesh's radius for scales).
// Plain FLOAT always; with `compress`, meshopt's FLOAT as it is and its exponential filter with the fewest
// mantissa bits that hold.
std::vector<InstanceEncoding> vectorEncodings(const std::vector<Eigen::Vector3d>& vectors, double lever,
                                              double allowed, bool compress);

// The candidates for unit quaternions (x, y, z, w, w >= 0), each holding where, for every instance i, the
// rotation matrix read back (the quaternion as a viewer gets it, not normalized again) differs from the
// rotation by at most allowed / lever[i] in the spectral norm (lever: the farthest vertex from the mesh's
// origin once scaled). Plain FLOAT always (float32 rounding is not counted); with `compress`, normalized SHORT
// where it holds, meshopt's FLOAT as it is, and its quaternion and exponential filters with the fewest bits
// that hold.
std::vector<InstanceEncoding> rotationEncodings(const std::vector<Eigen::Quaterniond>& rotations,
                                                const std::vector<double>& lever, double allowed, bool compress);

// The largest rotation-matrix error (spectral norm, over the instances) of normalized SHORT rotations.
double shortRotationError(const std::vector<Eigen::Quaterniond>& rotations);

// The fewest bits in [low, high] for which `holds`, more bits never holding less; 0 when even `high` fails.
template <typename Holds>
int fewestBits(int low, int high, Holds holds) {
    if (!holds(high)) return 0;
    while (low < high) {
        const int middle = (low + high) / 2;
        if (holds(middle))
            high = middle;
        else
            low = middle + 1;
    }
    return high;
}

// The most mantissa bits worth giving meshoptimizer's exponential filter: at 24 (its documented most) a mantissa
// rounded up to 2^23 overflows its 24-bit field.
constexpr int kMostExponentialBits = 23;

// meshoptimizer's exponential filter over `values`, vectors of `components` sharing one exponent, at `bits` (1 to
// 24): the filter's words. meshoptimizer 0.18 takes the exponent of a zero for 0 (frexp's), which makes a vector
// (0, 0.02, 0) step by 2^(1-bits) where 0.02 alone steps 32 times finer. With `liftZeros`, exact zeros beside a
// nonzero component are given float32's least normal magnitude first, whose mantissa rounds to 0 (it still
// decodes as 0): finer steps at the same bits, but exponents that vary from vector to vector, which meshopt
// codes in more bytes; which is smaller depends on the data.
std::vector<std::uint32_t> exponentialFiltered(const std::vector<float>& values, std::size_t components, int bits,
                                               bool liftZeros);
// The values a viewer decodes from the filter's words.
std::vector<float> exponentialDecoded(std::vector<std::uint32_t> filtered, std::size_t components);

// meshoptimizer's vertex codec (format version 0, which EXT_meshopt_compression specifies) over `values`,
// elements of `elementBytes`.
std::vector<unsigned char> meshoptEncoded(const std::vector<unsigned char>& values, std::size_t elementBytes);

}  // namespace symcompress
