// Meshes of any size for the benchmarks.
#pragma once

#include "symcompress/scene.hpp"

#include <cmath>
#include <functional>
#include <vector>

namespace symcompress::bench {

// A torus with a row of `columns` vertices at each angle of `rowAngles` (around the axis), vertices shared,
// and the tube radius r(u, v) (u around the axis, v around the tube).
inline TriangleMesh torusOnRows(const std::vector<double>& rowAngles, std::size_t columns,
                                const std::function<double(double, double)>& radius) {
    const double pi = 3.14159265358979323846;
    const std::size_t rows = rowAngles.size();
    TriangleMesh mesh;
    mesh.positions.reserve(rows * columns);
    for (std::size_t i = 0; i < rows; ++i)
        for (std::size_t j = 0; j < columns; ++j) {
            const double u = rowAngles[i], v = 2 * pi * j / columns, r = radius(u, v);
            mesh.positions.emplace_back((1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u),
                                        r * std::sin(v));
        }
    mesh.triangles.reserve(2 * rows * columns);
    auto index = [&](std::size_t i, std::size_t j) { return std::uint32_t((i % rows) * columns + j % columns); };
    for (std::size_t i = 0; i < rows; ++i)
        for (std::size_t j = 0; j < columns; ++j) {
            mesh.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
            mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
        }
    return mesh;
}

// A torus as a regular grid of about `triangles` triangles, with `rows` a multiple of `rowMultiple`.
inline TriangleMesh torusGrid(std::size_t triangles, std::size_t rowMultiple,
                              const std::function<double(double, double)>& radius) {
    const double pi = 3.14159265358979323846;
    std::size_t rows = std::size_t(std::sqrt(triangles / 2.0));
    rows -= rows % rowMultiple;
    std::vector<double> rowAngles(rows);
    for (std::size_t i = 0; i < rows; ++i) rowAngles[i] = 2 * pi * i / rows;
    return torusOnRows(rowAngles, triangles / (2 * rows), radius);
}

}  // namespace symcompress::bench
