#include "plan/member_check.hpp"

#include "geometry/bounds.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/tiles.hpp"

#include <algorithm>
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
                              double tolerance) {
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
    for (std::uint32_t v = 0; v < member.positions.size(); ++v) {
        const auto [first, last] = atPosition.equal_range(representative[prototype.positions.size() + v]);
        bool found = false;
        for (auto it = first; it != last && !found; ++it) found = same(it->second, v);
        if (!found) return false;
    }
    const Eigen::AlignedBox3d box = boundsOf(member.positions);
    return sameOrientation(prototype, member, j, std::max(box.diagonal().norm(), tolerance));
}

// The primitive with its positions only: what the check compares when attributes are ignored.
Primitive geometryOf(Primitive primitive) {
    primitive.normals.clear();
    primitive.texcoords.clear();
    primitive.colors.clear();
    return primitive;
}

}  // namespace

bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly) {
    return geometryOnly ? reproducesWithAttributes(geometryOf(prototype), geometryOf(member), j, tolerance)
                        : reproducesWithAttributes(prototype, member, j, tolerance);
}

}  // namespace symcompress
