// Triangles joined into the polygons they fan over (x3d_polygons.hpp).
#include "x3d_polygons.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress::x3d {
namespace {

// The triangle's unit normal; zero for a triangle of zero area, which joins nothing and nothing joins.
Eigen::Vector3d unitNormal(const Triangle& t, const std::vector<Eigen::Vector3d>& positions) {
    const Eigen::Vector3d normal = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    const double length = normal.norm();
    return length > 0 && std::isfinite(length) ? Eigen::Vector3d(normal / length) : Eigen::Vector3d::Zero();
}

// Whether (a, last, next), the fan's next triangle, keeps the polygon convex in the plane of `normal`: it turns
// the same way at `last`, and at the corner it closes on, `a`.
bool staysConvex(const std::vector<std::uint32_t>& polygon, std::uint32_t next, const Eigen::Vector3d& normal,
                 const std::vector<Eigen::Vector3d>& positions) {
    const Eigen::Vector3d& a = positions[polygon[0]];
    const Eigen::Vector3d& b = positions[polygon[1]];
    const Eigen::Vector3d& previous = positions[polygon[polygon.size() - 2]];
    const Eigen::Vector3d& last = positions[polygon.back()];
    const Eigen::Vector3d& x = positions[next];
    auto turns = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
        return (q - p).cross(r - q).dot(normal) > 0;
    };
    return turns(previous, last, x) && turns(last, x, a) && turns(x, a, b);
}

}  // namespace

std::vector<std::vector<std::uint32_t>> fanPolygons(const std::vector<Triangle>& triangles,
                                                    const std::vector<Eigen::Vector3d>& positions, double maxTurn) {
    const double leastCosine = std::cos(maxTurn);
    std::vector<std::vector<std::uint32_t>> polygons;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the last polygon's
    for (const Triangle& t : triangles) {
        const Eigen::Vector3d n = unitNormal(t, positions);
        if (!polygons.empty()) {
            std::vector<std::uint32_t>& polygon = polygons.back();
            if (t[0] == polygon[0] && t[1] == polygon.back() && n != Eigen::Vector3d::Zero() &&
                normal != Eigen::Vector3d::Zero() && n.dot(normal) >= leastCosine &&
                staysConvex(polygon, t[2], normal, positions)) {
                polygon.push_back(t[2]);
                continue;
            }
        }
        polygons.push_back({t[0], t[1], t[2]});
        normal = n;
    }
    return polygons;
}

}  // namespace symcompress::x3d
