// Numbers as text, the one formatter of the writers: numbers cut before they are printed (node transforms
// are written once per instance and accessor bounds once per primitive, so their digits count in small
// files), and the shortest text that reads back to a value.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

namespace symcompress {

// `value` as printed with `digits` significant digits and read back.
inline double rounded(double value, int digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    return std::strtod(text, nullptr);
}

// The value of fewest significant digits within `precision` of `value` (0 where `value` is that small): a
// placement's coordinate printed no finer than its share of the error budget.
inline double shortestWithin(double value, double precision) {
    if (std::abs(value) <= precision) return 0;
    for (int digits = 1; digits < 17; ++digits)
        if (const double near = rounded(value, digits); std::abs(near - value) <= precision) return near;
    return value;
}

// `value` in the fewest digits at float32's precision about `largest` (the largest of the numbers printed with it,
// a vector's): a component far smaller than the others (1.9e-18 beside 1.2, a placement's rounding) prints as 0.
inline double atFloat32PrecisionOf(double value, double largest) {
    return shortestWithin(value, std::ldexp(std::abs(largest), -23));
}

// `value` to `decimals` places after the point: for numbers of magnitude at most 1 (quaternions, axes),
// where tiny components are noise that must print as 0, not as 1e-16.
inline double roundedDecimals(double value, int decimals) {
    const double scale = std::pow(10.0, decimals);
    return std::round(value * scale) / scale + 0.0;  // + 0.0: no "-0"
}

// The double that prints as the shortest text reading back as float(value): a reader that takes the
// number as float32 (as glTF does) gets exactly float(value), in at most 9 digits instead of 17.
// A value beyond float32's range is returned as it is: as a float it would be infinite.
inline double asFloat32(double value) {
    if (!(std::abs(value) <= double(std::numeric_limits<float>::max()))) return value;
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text - 1, static_cast<float>(value));
    *result.ptr = '\0';
    return std::strtod(text, nullptr);
}

// `value` itself where it is no float32, else asFloat32(value): a number that came as float32 (an X3D SFFloat)
// prints in at most 9 digits, one that came as a double keeps every digit.
inline double asFloat32WhereExact(double value) {
    return static_cast<double>(static_cast<float>(value)) == value ? asFloat32(value) : value;
}

// Appends the shortest text that reads back to exactly `value` as a double.
inline void appendShortest(std::string& out, double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

// Appends the shortest text that reads back to `value`, as a float where `value` is one (most data comes
// from float32 files: 0.1f prints as 0.1, not 0.10000000149011612), else as a double.
inline void appendShortestFloat(std::string& out, double value) {
    char buffer[32];
    const float single = static_cast<float>(value);
    const auto result = static_cast<double>(single) == value ? std::to_chars(buffer, buffer + sizeof buffer, single)
                                                             : std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

// Places kept in a rotation (quaternion or axis and angle): 1e-7, about float32's resolution at 1.
constexpr int kRotationDecimals = 7;
constexpr int kNormalDecimals = 4;  // X3D output's unit normals
// A scale within this of 1 on every axis is written as none: float32's noise at 1 (an exporter's 0.9999998 for 1,
// Cesium Man's joints), which moves what the node draws by at most that share of its size.
constexpr double kScaleNoise = 1.0 / (1 << 22);
// Significant digits of a translation or scale written as text (X3D): what float32 holds.
constexpr int kPlacementDigits = 9;

}  // namespace symcompress
