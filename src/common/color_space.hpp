// Colours between glTF's linear factors and the sRGB-encoded values X3D's Phong Material holds (the decision
// and its sources: docs/scene-model.md, "Colour spaces"). The transfer function is IEC 61966-2-1's, as glTF
// specifies it for its sRGB textures and as three.js applies it.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace symcompress {

inline double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

inline double linearToSrgb(double l) { return l <= 0.0031308 ? l * 12.92 : 1.055 * std::pow(l, 1 / 2.4) - 0.055; }

inline Eigen::Vector3d srgbToLinear(const Eigen::Vector3d& c) {
    return c.unaryExpr([](double x) { return srgbToLinear(x); });
}

// A vertex colour of a format that holds display values (PLY, OBJ: three.js's loaders decode them as sRGB) as
// COLOR_0 holds it, and back: red, green and blue converted, alpha linear in both.
inline Eigen::Vector4d linearFromSrgbColor(const Eigen::Vector4d& c) {
    return {srgbToLinear(c[0]), srgbToLinear(c[1]), srgbToLinear(c[2]), c[3]};
}

// The value near `exact` with the fewest significant digits (at most 9) that `back` turns into `stored` as a
// float32 (glTF stores its factors as float32), else `exact`: glTF -> X3D -> glTF gives the factor back, and a
// value that came from X3D as a short decimal (0.8) goes back to X3D as that decimal.
template <typename Back>
double shortestReadingBack(double exact, double stored, Back back) {
    for (int digits = 1; digits <= 9; ++digits) {
        char text[40];
        std::snprintf(text, sizeof text, "%.*g", digits, exact);
        const double candidate = std::strtod(text, nullptr);
        if (static_cast<float>(back(candidate)) == static_cast<float>(stored)) return candidate;
    }
    return exact;
}

// The sRGB-encoded value of a linear factor, as shortestReadingBack gives it.
inline double linearToSrgbShortest(double linear) {
    return shortestReadingBack(linearToSrgb(linear), linear, [](double s) { return srgbToLinear(s); });
}

inline Eigen::Vector3d linearToSrgbShortest(const Eigen::Vector3d& l) {
    return l.unaryExpr([](double x) { return linearToSrgbShortest(x); });
}

}  // namespace symcompress
