// The ways to store a batch's instance values, each read back as a viewer reads it and kept only where every
// vertex stays within the allowance. Filters need no bits in the file (meshopt's exponential and quaternion
// filters store each element's scale with it), so batches of different bits share one stream.
//
// KHR_mesh_quantization's integer translations are not among them: their dequantizing scale would sit on the
// batch node and be inherited by its mesh, which would then have to be stored scaled by its inverse, and
// 16 bits over the batch's extent round by 2^-17 of it per component, more than the allowance as soon as the
// instances spread over most of the scene.
#include "gltf_instance_encoding.hpp"

#include <meshoptimizer.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace symcompress {
namespace {

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

template <typename T>
std::vector<T> valuesOf(const std::vector<unsigned char>& bytes) {
    std::vector<T> values(bytes.size() / sizeof(T));
    if (!values.empty()) std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
    return values;
}

InstanceEncoding encoding(int componentType, std::size_t elementBytes, const std::string& filter,
                          std::vector<unsigned char> values) {
    InstanceEncoding out{componentType, elementBytes, filter, std::move(values), 0};
    out.storedBytes = filter.empty() ? out.values.size() : meshoptEncoded(out.values, elementBytes).size();
    return out;
}

// The rotation a viewer builds from quaternion components as they are (three.js's compose does not normalize).
Eigen::Matrix3d matrixOf(const Eigen::Vector4d& q) {
    const double x = q[0], y = q[1], z = q[2], w = q[3];
    Eigen::Matrix3d m;
    m << 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),  //
        2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),   //
        2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y);
    return m;
}

// The spectral norm of the difference: how far the read-back matrix moves a point at distance 1.
double matrixError(const Eigen::Quaterniond& rotation, const Eigen::Vector4d& readBack) {
    const Eigen::Matrix3d difference = matrixOf(readBack) - rotation.toRotationMatrix();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(difference.transpose() * difference, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(0.0, solver.eigenvalues().maxCoeff()));
}

// Of the 16 ways to round a quaternion's components to normalized SHORTs up or down, the one whose matrix is
// nearest the rotation's: rounding each to its nearest leaves the quaternion's length up to 2^-15 off, which
// scales what a viewer draws (it does not normalize).
std::array<std::int16_t, 4> nearestShorts(const Eigen::Quaterniond& rotation) {
    const Eigen::Vector4d scaled = rotation.coeffs() * 32767.0;
    std::array<std::int16_t, 4> best{};
    double bestError = std::numeric_limits<double>::infinity();
    for (int way = 0; way < 16; ++way) {
        std::array<std::int16_t, 4> candidate{};
        Eigen::Vector4d readBack;
        for (int c = 0; c < 4; ++c) {
            const double value = (way >> c & 1) ? std::ceil(scaled[c]) : std::floor(scaled[c]);
            candidate[std::size_t(c)] = std::int16_t(std::clamp(value, -32767.0, 32767.0));
            readBack[c] = candidate[std::size_t(c)] / 32767.0;
        }
        const double error = matrixError(rotation, readBack);
        if (error < bestError) best = candidate, bestError = error;
    }
    return best;
}

std::vector<float> floatsOf(const std::vector<Eigen::Vector4d>& quaternions) {
    std::vector<float> out;
    for (const Eigen::Vector4d& q : quaternions)
        for (int c = 0; c < 4; ++c) out.push_back(float(q[c]));
    return out;
}

std::vector<Eigen::Vector4d> coefficientsOf(const std::vector<Eigen::Quaterniond>& rotations) {
    std::vector<Eigen::Vector4d> out;
    for (const Eigen::Quaterniond& q : rotations) out.push_back(q.coeffs());  // x, y, z, w
    return out;
}

}  // namespace

std::vector<std::uint32_t> exponentialFiltered(const std::vector<float>& values, std::size_t components, int bits,
                                               bool liftZeros) {
    std::vector<float> lifted = values;
    for (std::size_t v = 0; liftZeros && v + components <= lifted.size(); v += components) {
        const auto begin = lifted.begin() + std::ptrdiff_t(v), end = begin + std::ptrdiff_t(components);
        if (std::any_of(begin, end, [](float c) { return c != 0; }))
            std::replace(begin, end, 0.0f, std::numeric_limits<float>::min());
    }
    std::vector<std::uint32_t> filtered(lifted.size());
    meshopt_encodeFilterExp(filtered.data(), lifted.size() / components, components * 4, bits, lifted.data());
    return filtered;
}

std::vector<float> exponentialDecoded(std::vector<std::uint32_t> filtered, std::size_t components) {
    meshopt_decodeFilterExp(filtered.data(), filtered.size() / components, components * 4);
    std::vector<float> out(filtered.size());
    std::memcpy(out.data(), filtered.data(), out.size() * sizeof(float));
    return out;
}

std::vector<unsigned char> meshoptEncoded(const std::vector<unsigned char>& values, std::size_t elementBytes) {
    const std::size_t count = values.size() / elementBytes;
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, elementBytes));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), values.data(), count, elementBytes));
    return out;
}

std::vector<InstanceEncoding> vectorEncodings(const std::vector<Eigen::Vector3d>& vectors, double lever,
                                              double allowed, bool compress) {
    std::vector<float> floats;
    for (const Eigen::Vector3d& v : vectors)
        for (int c = 0; c < 3; ++c) floats.push_back(float(v[c]));
    std::vector<InstanceEncoding> out{encoding(kFloat, 12, "", bytesOf(floats))};
    if (!compress) return out;
    out.push_back(encoding(kFloat, 12, "NONE", bytesOf(floats)));
    for (const bool liftZeros : {false, true}) {
        auto filtered = [&](int bits) { return exponentialFiltered(floats, 3, bits, liftZeros); };
        auto holds = [&](int bits) {
            const std::vector<float> back = exponentialDecoded(filtered(bits), 3);
            for (std::size_t i = 0; i < vectors.size(); ++i)
                if (lever * (Eigen::Vector3d(back[3 * i], back[3 * i + 1], back[3 * i + 2]) - vectors[i]).norm() >
                    allowed)
                    return false;
            return true;
        };
        if (const int bits = fewestBits(1, kMostExponentialBits, holds))
            out.push_back(encoding(kFloat, 12, "EXPONENTIAL", bytesOf(filtered(bits))));
    }
    return out;
}

double shortRotationError(const std::vector<Eigen::Quaterniond>& rotations) {
    double error = 0;
    for (const Eigen::Quaterniond& q : rotations) {
        const std::array<std::int16_t, 4> shorts = nearestShorts(q);
        error = std::max(error, matrixError(q, Eigen::Vector4d(shorts[0], shorts[1], shorts[2], shorts[3]) / 32767.0));
    }
    return error;
}

std::vector<InstanceEncoding> rotationEncodings(const std::vector<Eigen::Quaterniond>& rotations,
                                                const std::vector<double>& lever, double allowed, bool compress) {
    const std::vector<Eigen::Vector4d> coefficients = coefficientsOf(rotations);
    const std::vector<float> floats = floatsOf(coefficients);
    auto holds = [&](const std::vector<Eigen::Vector4d>& readBack) {
        for (std::size_t i = 0; i < rotations.size(); ++i)
            if (matrixError(rotations[i], readBack[i]) * lever[i] > allowed) return false;
        return true;
    };
    // Normalized SHORTs as a viewer reads them: c / 32767, no lower than -1.
    auto fromShorts = [](const std::vector<std::int16_t>& shorts) {
        std::vector<Eigen::Vector4d> out;
        for (std::size_t i = 0; i + 3 < shorts.size(); i += 4)
            out.push_back(Eigen::Vector4d(shorts[i], shorts[i + 1], shorts[i + 2], shorts[i + 3])
                              .unaryExpr([](double c) { return std::max(c / 32767.0, -1.0); }));
        return out;
    };
    std::vector<InstanceEncoding> out{encoding(kFloat, 16, "", bytesOf(floats))};
    if (!compress) return out;
    std::vector<std::int16_t> shorts;
    for (std::size_t i = 0; i < rotations.size(); ++i) {
        const std::array<std::int16_t, 4> rounded = nearestShorts(rotations[i]);
        shorts.insert(shorts.end(), rounded.begin(), rounded.end());
    }
    if (holds(fromShorts(shorts))) out.push_back(encoding(kShort, 8, "", bytesOf(shorts)));
    out.push_back(encoding(kFloat, 16, "NONE", bytesOf(floats)));

    auto quaternionFiltered = [&](int bits) {
        std::vector<std::int16_t> encoded(floats.size());
        meshopt_encodeFilterQuat(encoded.data(), rotations.size(), 8, bits, floats.data());
        return encoded;
    };
    auto quaternionHolds = [&](int bits) {
        std::vector<std::int16_t> decoded = quaternionFiltered(bits);
        meshopt_decodeFilterQuat(decoded.data(), rotations.size(), 8);
        return holds(fromShorts(decoded));
    };
    if (const int bits = fewestBits(4, 16, quaternionHolds))
        out.push_back(encoding(kShort, 8, "QUATERNION", bytesOf(quaternionFiltered(bits))));

    for (const bool liftZeros : {false, true}) {
        auto exponentialHolds = [&](int bits) {
            const std::vector<float> back = exponentialDecoded(exponentialFiltered(floats, 4, bits, liftZeros), 4);
            std::vector<Eigen::Vector4d> readBack;
            for (std::size_t i = 0; i < rotations.size(); ++i)
                readBack.push_back(Eigen::Vector4d(back[4 * i], back[4 * i + 1], back[4 * i + 2], back[4 * i + 3]));
            return holds(readBack);
        };
        if (const int bits = fewestBits(1, kMostExponentialBits, exponentialHolds))
            out.push_back(
                encoding(kFloat, 16, "EXPONENTIAL", bytesOf(exponentialFiltered(floats, 4, bits, liftZeros))));
    }
    return out;
}

}  // namespace symcompress
