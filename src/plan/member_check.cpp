#include "plan/member_check.hpp"

#include "geometry/bounds.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/tiles.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace symcompress {
namespace {

constexpr double kNormalCosine = 0.999;  // normals within 2.6 degrees are the same
constexpr double kTexcoordTolerance = 1e-4;
constexpr double kColorTolerance = 1e-3;

// The surface's orientation, independent of how it is cut into triangles: its vector area S = ∫ n dA and
// M = ∫ n (x - c)^T dA about its area centroid c (for a closed part, its volume times the identity).
struct OrientedMoments {
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    Eigen::Matrix3d first = Eigen::Matrix3d::Zero();
};

OrientedMoments orientedMoments(const Primitive& part) {
    double total = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (const Triangle& t : part.triangles) {
        const Eigen::Vector3d &a = part.positions[t[0]], &b = part.positions[t[1]], &c = part.positions[t[2]];
        const double area = 0.5 * (b - a).cross(c - a).norm();
        total += area;
        weighted += area * (a + b + c) / 3;
    }
    const Eigen::Vector3d centre = total > 0 ? Eigen::Vector3d(weighted / total) : Eigen::Vector3d::Zero();
    OrientedMoments moments;
    for (const Triangle& t : part.triangles) {
        const Eigen::Vector3d &a = part.positions[t[0]], &b = part.positions[t[1]], &c = part.positions[t[2]];
        const Eigen::Vector3d vectorArea = 0.5 * (b - a).cross(c - a);
        moments.area += vectorArea;
        moments.first += vectorArea * ((a + b + c) / 3 - centre).transpose();
    }
    return moments;
}

// Whether the member faces the way the prototype placed by j does (a mirrored placement is drawn with its
// winding reversed, as glTF and X3D viewers do for a negative determinant, so both map as j): a flat part
// turned over matches its copy as a point set, not in orientation. Parts that look the same both ways
// (two-faced sheets) pass.
bool sameOrientation(const Primitive& prototype, const Primitive& member, const Isometry& j, double radius) {
    const OrientedMoments p = orientedMoments(prototype), m = orientedMoments(member);
    const Eigen::Vector3d expectedArea = j.linear * p.area;
    const Eigen::Matrix3d expectedFirst = j.linear * p.first * j.linear.transpose();
    const double difference = (m.area - expectedArea).norm() + (m.first - expectedFirst).norm() / radius;
    const double size = p.area.norm() + p.first.norm() / radius;
    return difference <= 0.5 * size;
}

bool reproducesWithAttributes(const Primitive& prototype, const Primitive& member, const Isometry& j,
                              double tolerance, double* deviation) {
    if (prototype.triangles.size() != member.triangles.size() ||
        prototype.positions.size() != member.positions.size() || prototype.normals.empty() != member.normals.empty() ||
        prototype.texcoords.empty() != member.texcoords.empty() || prototype.colors.empty() != member.colors.empty())
        return false;
    std::vector<Eigen::Vector3d> both;
    both.reserve(prototype.positions.size() + member.positions.size());
    for (const auto& p : prototype.positions) both.push_back(j.linear * p + j.translation);
    both.insert(both.end(), member.positions.begin(), member.positions.end());
    const std::vector<std::uint32_t> representative = weldPositions(both, tolerance);
    // Prototype vertices by position (seams put several vertices, with different attributes, at one place).
    std::multimap<std::uint32_t, std::uint32_t> atPosition;
    for (std::uint32_t u = 0; u < prototype.positions.size(); ++u) atPosition.emplace(representative[u], u);
    auto same = [&](std::uint32_t u, std::uint32_t v) {
        if (!prototype.normals.empty() && (j.linear * prototype.normals[u]).dot(member.normals[v]) < kNormalCosine)
            return false;
        if (!prototype.texcoords.empty() &&
            (prototype.texcoords[u] - member.texcoords[v]).cwiseAbs().maxCoeff() > kTexcoordTolerance)
            return false;
        if (!prototype.colors.empty() &&
            (prototype.colors[u] - member.colors[v]).cwiseAbs().maxCoeff() > kColorTolerance)
            return false;
        return true;
    };
    double largest = 0;
    for (std::uint32_t v = 0; v < member.positions.size(); ++v) {
        const auto [first, last] = atPosition.equal_range(representative[prototype.positions.size() + v]);
        bool found = false;
        for (auto it = first; it != last && !found; ++it) {
            found = same(it->second, v);
            if (found) largest = std::max(largest, (both[it->second] - member.positions[v]).norm());
        }
        if (!found) return false;
    }
    if (deviation) *deviation = largest;
    const Eigen::AlignedBox3d box = boundsOf(member.positions);
    return sameOrientation(prototype, member, j, std::max(box.diagonal().norm(), tolerance));
}

// The barycentric coordinates of p (on or near the triangle abc) in it.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
    const Eigen::Vector3d u = b - a, v = c - a, w = p - a;
    const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), wu = w.dot(u), wv = w.dot(v);
    const double denominator = uu * vv - uv * uv;
    if (!(std::abs(denominator) > 0)) return {1, 0, 0};
    const double beta = (vv * wu - uv * wv) / denominator, gamma = (uu * wv - uv * wu) / denominator;
    return {1 - beta - gamma, beta, gamma};
}

template <typename Vector>
Vector interpolated(const std::vector<Vector>& values, const Triangle& t, const Eigen::Vector3d& weights) {
    return weights[0] * values[t[0]] + weights[1] * values[t[1]] + weights[2] * values[t[2]];
}

// One way of the surface check: `from`'s vertices and centroids, mapped by `map` into `onto`'s frame, against
// `onto`'s surface, and at the vertices `from`'s attributes against `onto`'s interpolated (normals turned by
// map's linear part). The largest distance, or nothing.
std::optional<double> oneWay(const TileSurface& from, const TileSurface& onto, const Isometry& map, double tolerance,
                             bool geometryOnly) {
    const Primitive &a = from.primitive(), &b = onto.primitive();
    const double bound = tolerance * tolerance;
    double largest = 0;
    std::uint32_t triangle = 0;
    Eigen::Vector3d weights;
    for (std::uint32_t v = 0; v < a.positions.size(); ++v) {
        // Where the vertex has a normal, on the triangles facing its way: at a crease (a cap's rim), the side
        // its normal belongs to.
        const Eigen::Vector3d normal =
            a.normals.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(map.linear * a.normals[v]);
        const double squared = onto.closest(map.linear * a.positions[v] + map.translation, bound, triangle, weights,
                                            a.normals.empty() || geometryOnly ? nullptr : &normal);
        if (squared > bound) return std::nullopt;
        largest = std::max(largest, squared);
        if (geometryOnly) continue;
        const Triangle& t = b.triangles[triangle];
        if (!a.normals.empty() && normal.dot(interpolated(b.normals, t, weights).normalized()) < kNormalCosine)
            return std::nullopt;
        if (!a.texcoords.empty() &&
            (a.texcoords[v] - interpolated(b.texcoords, t, weights)).cwiseAbs().maxCoeff() > kTexcoordTolerance)
            return std::nullopt;
        if (!a.colors.empty() &&
            (a.colors[v] - interpolated(b.colors, t, weights)).cwiseAbs().maxCoeff() > kColorTolerance)
            return std::nullopt;
    }
    for (const Triangle& t : a.triangles) {
        const Eigen::Vector3d centroid = (a.positions[t[0]] + a.positions[t[1]] + a.positions[t[2]]) / 3;
        const double squared = onto.closest(map.linear * centroid + map.translation, bound, triangle, weights);
        if (squared > bound) return std::nullopt;
        largest = std::max(largest, squared);
    }
    return std::sqrt(largest);
}

// The primitive with its positions only: what the check compares when attributes are ignored.
Primitive geometryOf(Primitive primitive) {
    primitive.normals.clear();
    primitive.texcoords.clear();
    primitive.colors.clear();
    return primitive;
}

}  // namespace

TileSurface::TileSurface(const Primitive& primitive)
    : primitive_(primitive), mesh_{primitive.positions, primitive.triangles}, bvh_(mesh_) {}

double TileSurface::closest(const Eigen::Vector3d& p, double bound, std::uint32_t& triangle, Eigen::Vector3d& weights,
                            const Eigen::Vector3d* facing) const {
    Eigen::Vector3d point;
    const double squared = bvh_.squaredDistance(p, bound, &point, &triangle, facing);
    if (squared < bound) {
        const Triangle& t = mesh_.triangles[triangle];
        weights = barycentric(point, mesh_.positions[t[0]], mesh_.positions[t[1]], mesh_.positions[t[2]]);
    }
    return squared;
}

std::optional<double> surfaceDeviation(const TileSurface& prototype, const TileSurface& member, const Isometry& j,
                                       double tolerance, bool geometryOnly) {
    const Primitive &p = prototype.primitive(), &m = member.primitive();
    if (!geometryOnly && (p.normals.empty() != m.normals.empty() || p.texcoords.empty() != m.texcoords.empty() ||
                          p.colors.empty() != m.colors.empty()))
        return std::nullopt;
    Isometry inverse;
    inverse.linear = j.linear.transpose();
    inverse.translation = -(inverse.linear * j.translation);
    const std::optional<double> there = oneWay(prototype, member, j, tolerance, geometryOnly);
    if (!there) return std::nullopt;
    const std::optional<double> back = oneWay(member, prototype, inverse, tolerance, geometryOnly);
    if (!back) return std::nullopt;
    const Eigen::AlignedBox3d box = boundsOf(m.positions);
    if (!sameOrientation(p, m, j, std::max(box.diagonal().norm(), tolerance))) return std::nullopt;
    return std::max(*there, *back);
}

bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly, double* deviation) {
    return geometryOnly ? reproducesWithAttributes(geometryOf(prototype), geometryOf(member), j, tolerance, deviation)
                        : reproducesWithAttributes(prototype, member, j, tolerance, deviation);
}

}  // namespace symcompress
