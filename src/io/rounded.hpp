// Numbers cut to a number of significant digits before they are printed: node transforms are written
// once per instance, so their digits count.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace symcompress {

// `value` as printed with `digits` significant digits and read back.
inline double rounded(double value, int digits) {
    char text[40];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    return std::strtod(text, nullptr);
}

// Digits kept: a translation or scale as float32 holds it; a rotation to 1e-7 rad.
constexpr int kPlacementDigits = 9;
constexpr int kRotationDigits = 7;

}  // namespace symcompress
