// Meshes of any size for the benchmarks.
#pragma once

#include "symcompress/scene.hpp"

#include <cmath>
#include <functional>

namespace symcompress::bench {

// A torus as a grid of about `triangles` triangles (vertices shared), with `rows` a multiple of
// `rowMultiple` and the tube radius r(u, v) (u around the axis, v around the tube).
inline TriangleMesh torusGrid(std::size_t triangles, std::size_t rowMultiple, const std::function<double(double, double)>& radius) {
    const double pi = 3.14159265358979323846;
    std::size_t rows = std::size_t(std::sqrt(triangles / 2.0));
    rows -= rows % rowMultiple;
    const std::size_t columns = triangles / (2 * rows);
    TriangleMesh mesh;
    mesh.positions.reserve(rows * columns);
    for (std::size_t i = 0; i < rows; ++i)
        for (std::size_t j = 0; j < columns; ++j) {
            const double u = 2 * pi * i / rows, v = 2 * pi * j / columns, r = radius(u, v);
            mesh.positions.emplace_back((1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u), r * std::sin(v));
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

}  // namespace symcompress::bench
