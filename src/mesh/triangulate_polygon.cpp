#include "symcompress/detail/triangulate_polygon.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Whether the turn a -> b -> c is straight up to rounding (relative to the edge lengths): such a corner is
// neither an ear nor reflex, and clipping it would leave a sliver of zero area.
bool nearlyCollinear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return std::abs(cross2(b - a, c - b)) <= 1e-12 * (b - a).norm() * (c - b).norm();
}

// Whether p lies inside or on triangle (a, b, c), which is counter-clockwise. "On" is up to rounding, so that
// a corner lying on the diagonal of a candidate ear blocks it (clipping it would leave a T-junction).
bool insideTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                    const Eigen::Vector2d& c) {
    const auto leftOf = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
        return cross2(to - from, p - from) >= -1e-12 * (to - from).norm() * (p - from).norm();
    };
    return leftOf(a, b) && leftOf(b, c) && leftOf(c, a);
}

}  // namespace

std::vector<Triangle> triangulatePolygon(const std::vector<Eigen::Vector3d>& corners) {
    // Distinct consecutive corners only (a repeated corner would make a zero-length edge).
    std::vector<std::uint32_t> ring;
    for (std::uint32_t i = 0; i < corners.size(); ++i)
        if (ring.empty() || corners[i] != corners[ring.back()]) ring.push_back(i);
    while (ring.size() > 1 && corners[ring.front()] == corners[ring.back()]) ring.pop_back();
    std::vector<Triangle> triangles;
    if (ring.size() < 3) return triangles;
    if (ring.size() == 3) return {{ring[0], ring[1], ring[2]}};

    // Newell's normal: robust for non-planar and concave polygons; its direction is the winding.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < ring.size(); ++i) normal += corners[ring[i]].cross(corners[ring[(i + 1) % ring.size()]]);
    if (normal.norm() == 0) return triangles;
    normal.normalize();
    const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
    std::vector<Eigen::Vector2d> flat;
    for (std::uint32_t index : ring) flat.emplace_back(corners[index].dot(u), corners[index].dot(v));

    // Ear clipping: in the (u, v) plane the polygon is counter-clockwise, so an ear is a convex corner whose
    // triangle contains no other remaining corner. A convex polygon has an ear at every corner and is fanned.
    std::vector<std::size_t> remaining(ring.size());
    for (std::size_t i = 0; i < ring.size(); ++i) remaining[i] = i;
    std::size_t guard = 0;
    while (remaining.size() > 3 && guard < remaining.size()) {
        bool clipped = false;
        for (std::size_t k = 0; k < remaining.size(); ++k) {
            const std::size_t previous = remaining[(k + remaining.size() - 1) % remaining.size()], current = remaining[k],
                              next = remaining[(k + 1) % remaining.size()];
            const Eigen::Vector2d &a = flat[previous], &b = flat[current], &c = flat[next];
            if (cross2(b - a, c - b) <= 0 || nearlyCollinear(a, b, c)) continue;  // reflex or straight corner
            bool containsOther = false;
            for (std::size_t other : remaining) {
                if (other == previous || other == current || other == next) continue;
                if (flat[other] == a || flat[other] == b || flat[other] == c) continue;
                if (insideTriangle(flat[other], a, b, c)) {
                    containsOther = true;
                    break;
                }
            }
            if (containsOther) continue;
            triangles.push_back({ring[previous], ring[current], ring[next]});
            remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(k));
            clipped = true;
            break;
        }
        if (!clipped) {
            // Only collinear or self-intersecting corners are left: drop one collinear corner, or give up
            // on the rest by fanning it (a self-intersecting polygon has no correct triangulation).
            bool droppedCollinear = false;
            for (std::size_t k = 0; k < remaining.size(); ++k) {
                const Eigen::Vector2d &a = flat[remaining[(k + remaining.size() - 1) % remaining.size()]],
                                      &b = flat[remaining[k]], &c = flat[remaining[(k + 1) % remaining.size()]];
                if (nearlyCollinear(a, b, c)) {
                    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(k));
                    droppedCollinear = true;
                    break;
                }
            }
            if (!droppedCollinear) {
                for (std::size_t k = 1; k + 1 < remaining.size(); ++k)
                    triangles.push_back({ring[remaining[0]], ring[remaining[k]], ring[remaining[k + 1]]});
                return triangles;
            }
            ++guard;
        }
    }
    if (remaining.size() == 3) {
        const Eigen::Vector2d &a = flat[remaining[0]], &b = flat[remaining[1]], &c = flat[remaining[2]];
        if (!nearlyCollinear(a, b, c)) triangles.push_back({ring[remaining[0]], ring[remaining[1]], ring[remaining[2]]});
    }
    return triangles;
}

std::vector<Triangle> triangulateFace(const std::vector<Eigen::Vector3d>& corners) {
    Eigen::Vector3d newell = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < corners.size(); ++k) newell += corners[k].cross(corners[(k + 1) % corners.size()]);
    std::vector<Triangle> fan;
    for (std::uint32_t k = 1; k + 1 < corners.size(); ++k) {
        const Eigen::Vector3d normal = (corners[k] - corners[0]).cross(corners[k + 1] - corners[0]);
        if (normal.dot(newell) < -1e-12 * normal.norm() * newell.norm()) return triangulatePolygon(corners);
        fan.push_back({0, k, k + 1});
    }
    return fan;
}

}  // namespace symcompress
