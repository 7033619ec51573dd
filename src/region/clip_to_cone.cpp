// S ∩ F for a polyhedral cone F: Sutherland-Hodgman clipping of every triangle against the cone's
// half-spaces, with attributes interpolated at the cut points.
#include "fundamental_region_parts.hpp"

#include <Eigen/Geometry>

#include <array>
#include <map>

namespace symcompress::region_detail {

namespace {

// Moves a point onto every plane it lies within `tolerance` of (and onto plane `forced`, if any): the
// projection onto the intersection of those planes, all through the apex. A coordinate plane sets its
// coordinate exactly, so that quantization keeps such seams closed.
Eigen::Vector3d snapToPlanes(const Eigen::Vector3d& point, const DirichletCone& cone, double tolerance, int forced) {
    Eigen::Vector3d offset = point - cone.apex;
    std::vector<Eigen::Vector3d> basis;  // orthonormal span of the planes' normals
    std::vector<int> coordinatePlanes;
    for (std::size_t k = 0; k < cone.normals.size(); ++k) {
        const Eigen::Vector3d& n = cone.normals[k];
        if (static_cast<int>(k) != forced && std::abs(n.dot(offset)) > tolerance) continue;
        Eigen::Vector3d residual = n;
        for (const Eigen::Vector3d& q : basis) residual -= q.dot(residual) * q;
        if (residual.norm() > 1e-6) basis.push_back(residual.normalized());
        for (int axis = 0; axis < 3; ++axis)
            if (std::abs(n[axis]) == 1.0) coordinatePlanes.push_back(axis);
    }
    if (basis.empty()) return point;
    for (const Eigen::Vector3d& q : basis) offset -= q.dot(offset) * q;
    Eigen::Vector3d snapped = cone.apex + offset;
    for (int axis : coordinatePlanes) snapped[axis] = cone.apex[axis];
    return snapped;
}

class ConeClipper {
public:
    ConeClipper(const Primitive& tile, const DirichletCone& cone, double tolerance)
        : tile_(tile), cone_(cone), tolerance_(tolerance), work_(tile) {
        work_.triangles.clear();
        for (Eigen::Vector3d& position : work_.positions) position = snapToPlanes(position, cone_, tolerance_, -1);
    }

    ClippedRegion run() {
        std::size_t cut = 0;
        for (const Triangle& triangle : tile_.triangles) cut += clipTriangle(triangle);
        return {compacted(), cut};
    }

private:
    // -1 outside, 0 on, +1 inside the half-space of plane k.
    int side(std::size_t k, std::uint32_t vertex) const {
        const double d = cone_.normals[k].dot(work_.positions[vertex] - cone_.apex);
        return d > tolerance_ ? 1 : (d < -tolerance_ ? -1 : 0);
    }

    // A triangle lying in a plane of F is also on the boundary of the neighbouring copy g F. Exactly one
    // of it and its partner under g faces into F, so keeping only triangles that face into F counts every
    // such triangle once (for a mirror, the copy supplies the reversed layer).
    bool liesOutwardInPlane(const Triangle& triangle) const {
        const Eigen::Vector3d& a = work_.positions[triangle[0]];
        const Eigen::Vector3d normal = (work_.positions[triangle[1]] - a).cross(work_.positions[triangle[2]] - a);
        for (std::size_t k = 0; k < cone_.normals.size(); ++k) {
            if (side(k, triangle[0]) == 0 && side(k, triangle[1]) == 0 && side(k, triangle[2]) == 0)
                return !(cone_.normals[k].dot(normal) > 0);
        }
        return false;
    }

    // Clips one triangle; returns 1 when it was cut (and something of it kept), else 0.
    std::size_t clipTriangle(const Triangle& triangle) {
        if (liesOutwardInPlane(triangle)) return 0;
        std::vector<std::uint32_t> polygon(triangle.begin(), triangle.end());
        bool clipped = false;
        for (std::size_t k = 0; k < cone_.normals.size() && !polygon.empty(); ++k) {
            std::vector<int> sides(polygon.size());
            bool anyIn = false, anyOut = false;
            for (std::size_t i = 0; i < polygon.size(); ++i) {
                sides[i] = side(k, polygon[i]);
                anyIn = anyIn || sides[i] > 0;
                anyOut = anyOut || sides[i] < 0;
            }
            if (!anyOut) continue;
            if (!anyIn) {  // on or outside: at most an edge touches F
                polygon.clear();
                break;
            }
            clipped = true;
            std::vector<std::uint32_t> next;
            for (std::size_t i = 0; i < polygon.size(); ++i) {
                const std::size_t j = (i + 1) % polygon.size();
                if (sides[i] >= 0) next.push_back(polygon[i]);
                if (sides[i] * sides[j] < 0) next.push_back(cutPoint(k, polygon[i], polygon[j]));
            }
            polygon.swap(next);
            if (polygon.size() < 3) polygon.clear();
        }
        if (polygon.empty()) return 0;
        if (!clipped) {
            work_.triangles.push_back(triangle);
            return 0;
        }
        return fan(polygon) ? 1 : 0;
    }

    // The convex clipped polygon as a fan from its first corner, skipping slivers of no area.
    bool fan(const std::vector<std::uint32_t>& polygon) {
        bool emitted = false;
        const Eigen::Vector3d& a = work_.positions[polygon[0]];
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
            const Eigen::Vector3d ab = work_.positions[polygon[i]] - a;
            const Eigen::Vector3d ac = work_.positions[polygon[i + 1]] - a;
            const double longest = std::max({ab.squaredNorm(), ac.squaredNorm(), (ac - ab).squaredNorm()});
            if (!(ab.cross(ac).norm() > 1e-12 * longest)) continue;
            work_.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
            emitted = true;
        }
        return emitted;
    }

    // The point where edge (a, b) crosses plane k, made once per edge and plane (from the lower index to
    // the higher, so that both triangles of a shared edge get the same bits).
    std::uint32_t cutPoint(std::size_t k, std::uint32_t a, std::uint32_t b) {
        const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
        const std::array<std::uint32_t, 3> key{static_cast<std::uint32_t>(k), lo, hi};
        const auto found = cuts_.find(key);
        if (found != cuts_.end()) return found->second;
        const Eigen::Vector3d& n = cone_.normals[k];
        const Eigen::Vector3d from = work_.positions[lo], to = work_.positions[hi];
        const double dFrom = n.dot(from - cone_.apex), dTo = n.dot(to - cone_.apex);
        const double t = dFrom / (dFrom - dTo);
        const std::uint32_t index = static_cast<std::uint32_t>(work_.positions.size());
        work_.positions.push_back(snapToPlanes(from + t * (to - from), cone_, tolerance_, static_cast<int>(k)));
        if (!work_.normals.empty()) {
            const Eigen::Vector3d blended = (1 - t) * work_.normals[lo] + t * work_.normals[hi];
            const double length = blended.norm();
            work_.normals.push_back(length > 0 ? Eigen::Vector3d(blended / length)
                                               : Eigen::Vector3d(work_.normals[lo]));
        }
        if (!work_.texcoords.empty())
            work_.texcoords.push_back(Eigen::Vector2d((1 - t) * work_.texcoords[lo] + t * work_.texcoords[hi]));
        if (!work_.colors.empty())
            work_.colors.push_back(Eigen::Vector4d((1 - t) * work_.colors[lo] + t * work_.colors[hi]));
        for (VertexAttribute& attribute : work_.attributes) cutAttribute(attribute, lo, hi, t);
        cuts_.emplace(key, index);
        return index;
    }

    // The attribute at the point t of the way from vertex lo to hi, appended: blended, a TANGENT's direction
    // brought back to unit length and its handedness (w, which is +1 or -1) the nearer end's.
    static void cutAttribute(VertexAttribute& attribute, std::uint32_t lo, std::uint32_t hi, double t) {
        const std::size_t at = attribute.values.size();
        for (int k = 0; k < attribute.components; ++k)
            attribute.values.push_back((1 - t) * attribute.vertex(lo)[k] + t * attribute.vertex(hi)[k]);
        if (attribute.name != "TANGENT" || attribute.components != 4) return;
        Eigen::Map<Eigen::Vector3d> direction(&attribute.values[at]);
        const double length = direction.norm();
        if (length > 0)
            direction /= length;
        else
            direction = Eigen::Map<const Eigen::Vector3d>(attribute.vertex(lo));
        attribute.values[at + 3] = attribute.vertex(t < 0.5 ? lo : hi)[3];
    }

    // Only the vertices the kept triangles use, in their original order.
    Primitive compacted() const {
        const std::uint32_t unused = ~std::uint32_t(0);
        std::vector<std::uint32_t> remap(work_.positions.size(), unused);
        for (const Triangle& triangle : work_.triangles)
            for (std::uint32_t corner : triangle) remap[corner] = 0;
        Primitive region;
        region.material = work_.material;
        for (const VertexAttribute& attribute : work_.attributes)
            region.attributes.push_back(attribute.withoutValues());
        for (std::size_t v = 0; v < remap.size(); ++v) {
            if (remap[v] == unused) continue;
            remap[v] = static_cast<std::uint32_t>(region.positions.size());
            region.positions.push_back(work_.positions[v]);
            if (!work_.normals.empty()) region.normals.push_back(work_.normals[v]);
            if (!work_.texcoords.empty()) region.texcoords.push_back(work_.texcoords[v]);
            if (!work_.colors.empty()) region.colors.push_back(work_.colors[v]);
            for (std::size_t a = 0; a < work_.attributes.size(); ++a)
                region.attributes[a].appendVertex(work_.attributes[a], v);
        }
        region.triangles.reserve(work_.triangles.size());
        for (const Triangle& triangle : work_.triangles)
            region.triangles.push_back({remap[triangle[0]], remap[triangle[1]], remap[triangle[2]]});
        return region;
    }

    const Primitive& tile_;
    const DirichletCone& cone_;
    double tolerance_;
    Primitive work_;  // the tile's vertices (snapped), then the cut points; the kept triangles
    std::map<std::array<std::uint32_t, 3>, std::uint32_t> cuts_;
};

}  // namespace

ClippedRegion clipToCone(const Primitive& tile, const DirichletCone& cone, double tolerance) {
    return ConeClipper(tile, cone, tolerance).run();
}

}  // namespace symcompress::region_detail
