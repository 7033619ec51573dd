#include "plan/member_check.hpp"

#include "geometry/bounds.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/tiles.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace symcompress {
namespace {

constexpr double kNormalCosine = 0.999;  // normals within 2.6 degrees are the same
constexpr double kTexcoordTolerance = 1e-4;
constexpr double kColorTolerance = 1e-3;
constexpr double kOtherTolerance = 1e-5;  // relative to the value's size, at least 1: an application's data
constexpr int kMostComponents = 16;       // a MAT4

// Whether the two primitives have the same other attributes (Primitive::attributes), by name and size.
bool sameAttributeNames(const Primitive& a, const Primitive& b) {
    return std::equal(a.attributes.begin(), a.attributes.end(), b.attributes.begin(), b.attributes.end(),
                      [](const VertexAttribute& x, const VertexAttribute& y) {
                          return x.name == y.name && x.components == y.components;
                      });
}

// Whether the prototype has what the member's drawing needs: the same normals, colours and other attributes, and
// texture coordinates where the member has them. A member without them may be drawn with the prototype's: its
// material reads none (they were pruned as unread, or it never had them), so they change nothing it shows.
bool carriesAttributes(const Primitive& prototype, const Primitive& member) {
    return prototype.normals.empty() == member.normals.empty() &&
           (member.texcoords.empty() || !prototype.texcoords.empty()) &&
           prototype.colors.empty() == member.colors.empty() && sameAttributeNames(prototype, member);
}

// Whether the values `x` of an attribute (turned by `linear` where they are a direction) and `y` agree: a
// TANGENT's direction within the normals' angle and its handedness the same (a viewer builds the bitangent
// from the placed normal and tangent, so a mirrored placement keeps w), texture coordinates and colours
// within their tolerances, an application's data nearly exactly.
bool sameValues(const VertexAttribute& attribute, const double* x, const double* y, const Eigen::Matrix3d& linear) {
    if (attribute.name == "TANGENT" && attribute.components == 4) {
        const Eigen::Vector3d turned = linear * Eigen::Vector3d(x[0], x[1], x[2]);
        const Eigen::Vector3d other(y[0], y[1], y[2]);
        return turned.normalized().dot(other.normalized()) >= kNormalCosine && x[3] * y[3] > 0;
    }
    const bool texcoord = attribute.name.rfind("TEXCOORD_", 0) == 0, color = attribute.name.rfind("COLOR_", 0) == 0;
    for (int k = 0; k < attribute.components; ++k) {
        const double difference = std::abs(x[k] - y[k]);
        if (texcoord ? difference > kTexcoordTolerance
            : color  ? difference > kColorTolerance
                     : !(difference <= kOtherTolerance * std::max({1.0, std::abs(x[k]), std::abs(y[k])})))
            return false;
    }
    return true;
}

// Attribute `attribute`'s value at `weights` in triangle t, into `out`.
void interpolate(const VertexAttribute& attribute, const Triangle& t, const Eigen::Vector3d& weights, double* out) {
    for (int k = 0; k < attribute.components; ++k)
        out[k] = weights[0] * attribute.vertex(t[0])[k] + weights[1] * attribute.vertex(t[1])[k] +
                 weights[2] * attribute.vertex(t[2])[k];
}

// Whether `a`'s other attributes at `weights` in its triangle `s` agree with `b`'s at `onto` in its triangle `t`
// (a's directions turned by `linear`); a and b have the same attribute names.
bool sameOtherAttributes(const Primitive& a, const Triangle& s, const Eigen::Vector3d& weights,
                         const Eigen::Matrix3d& linear, const Primitive& b, const Triangle& t,
                         const Eigen::Vector3d& onto) {
    std::array<double, kMostComponents> x, y;
    for (std::size_t k = 0; k < a.attributes.size(); ++k) {
        const VertexAttribute& attribute = a.attributes[k];
        if (attribute.components > kMostComponents) return false;
        interpolate(attribute, s, weights, x.data());
        interpolate(b.attributes[k], t, onto, y.data());
        if (!sameValues(attribute, x.data(), y.data(), linear)) return false;
    }
    return true;
}

}  // namespace

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

namespace {

// Whether the member faces the way the prototype placed by j does (a mirrored placement is drawn with its
// winding reversed, as glTF and X3D viewers do for a negative determinant, so both map as j): a flat part
// turned over matches its copy as a point set, not in orientation. Parts that look the same both ways
// (two-faced sheets) pass.
bool sameOrientation(const OrientedMoments& p, const OrientedMoments& m, const Isometry& j, double radius) {
    const Eigen::Vector3d expectedArea = j.linear * p.area;
    const Eigen::Matrix3d expectedFirst = j.linear * p.first * j.linear.transpose();
    const double difference = (m.area - expectedArea).norm() + (m.first - expectedFirst).norm() / radius;
    const double size = p.area.norm() + p.first.norm() / radius;
    return difference <= 0.5 * size;
}

Reproduction reproducesWithAttributes(const Primitive& prototype, const Primitive& member, const Isometry& j,
                                      double tolerance, double* deviation) {
    if (prototype.triangles.size() != member.triangles.size() ||
        prototype.positions.size() != member.positions.size() || !carriesAttributes(prototype, member))
        return Reproduction::Differs;
    std::vector<Eigen::Vector3d> both;
    both.reserve(prototype.positions.size() + member.positions.size());
    for (const auto& p : prototype.positions) both.push_back(j.linear * p + j.translation);
    both.insert(both.end(), member.positions.begin(), member.positions.end());
    const std::vector<std::uint32_t> representative = weldPositions(both, tolerance);
    // Triangles by their corners' places, in their cyclic order from the first place: corner by corner, since
    // seams put several vertices with different attributes at one place (a cone's tip, a normal for each side),
    // and a vertex that matches one of them may belong to another triangle. The prototype placed by a mirror is
    // drawn with its winding reversed, so its triangles are keyed backwards.
    using Corners = std::array<std::uint32_t, 3>;
    auto keyed = [&](const Triangle& t, std::size_t offset, bool backwards) {
        Corners corners{t[0], t[1], t[2]};
        if (backwards) std::swap(corners[1], corners[2]);
        std::rotate(corners.begin(),
                    std::min_element(corners.begin(), corners.end(),
                                     [&](std::uint32_t a, std::uint32_t b) {
                                         return representative[a + offset] < representative[b + offset];
                                     }),
                    corners.end());
        return corners;
    };
    auto places = [&](const Corners& corners, std::size_t offset) {
        return Corners{representative[corners[0] + offset], representative[corners[1] + offset],
                       representative[corners[2] + offset]};
    };
    const bool mirrored = j.linear.determinant() < 0;
    // (place, corners) sorted by place, triangles of one place in the prototype's order: one allocation where a
    // multimap took one per triangle (the assemblies ask this of thousands of tile pairs).
    std::vector<std::pair<Corners, Corners>> prototypeAt;
    prototypeAt.reserve(prototype.triangles.size());
    for (const Triangle& t : prototype.triangles) {
        const Corners corners = keyed(t, 0, mirrored);
        prototypeAt.emplace_back(places(corners, 0), corners);
    }
    auto byPlace = [](const std::pair<Corners, Corners>& a, const std::pair<Corners, Corners>& b) {
        return a.first < b.first;
    };
    std::stable_sort(prototypeAt.begin(), prototypeAt.end(), byPlace);
    auto same = [&](std::uint32_t u, std::uint32_t v) {
        if (!prototype.normals.empty() && (j.linear * prototype.normals[u]).dot(member.normals[v]) < kNormalCosine)
            return false;
        if (!member.texcoords.empty() &&
            (prototype.texcoords[u] - member.texcoords[v]).cwiseAbs().maxCoeff() > kTexcoordTolerance)
            return false;
        if (!prototype.colors.empty() &&
            (prototype.colors[u] - member.colors[v]).cwiseAbs().maxCoeff() > kColorTolerance)
            return false;
        return sameOtherAttributes(prototype, {u, u, u}, Eigen::Vector3d(1, 0, 0), j.linear, member, {v, v, v},
                                   Eigen::Vector3d(1, 0, 0));
    };
    const std::size_t offset = prototype.positions.size();
    double largest = 0;
    bool attributesDiffer = false;  // at some triangle's corners: the others are only asked for their places
    for (const Triangle& t : member.triangles) {
        const Corners corners = keyed(t, offset, false);
        const auto [first, last] = std::equal_range(prototypeAt.begin(), prototypeAt.end(),
                                                    std::pair{places(corners, offset), Corners{}}, byPlace);
        if (first == last)  // the same corners, other triangles (a quad's other diagonal)
            return attributesDiffer ? Reproduction::Differs : Reproduction::CutOtherwise;
        if (attributesDiffer) continue;
        const auto match = std::find_if(first, last, [&](const auto& entry) {
            for (int k = 0; k < 3; ++k)
                if (!same(entry.second[k], corners[k])) return false;
            return true;
        });
        if (match == last) {
            attributesDiffer = true;
            continue;
        }
        for (int k = 0; k < 3; ++k)
            largest = std::max(largest, (both[match->second[k]] - member.positions[corners[k]]).norm());
    }
    if (attributesDiffer) return Reproduction::AttributesDiffer;
    if (deviation) *deviation = largest;
    const Eigen::AlignedBox3d box = boundsOf(member.positions);
    return sameOrientation(orientedMoments(prototype), orientedMoments(member), j,
                           std::max(box.diagonal().norm(), tolerance))
               ? Reproduction::Reproduced
               : Reproduction::Differs;
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

// Whether `a`'s attributes at `weights` in its triangle `s` agree with `b`'s at `onto` in its triangle `t`
// (a's normals turned by `linear`).
bool sameAttributes(const Primitive& a, const Triangle& s, const Eigen::Vector3d& weights,
                    const Eigen::Matrix3d& linear, const Primitive& b, const Triangle& t, const Eigen::Vector3d& onto) {
    if (!a.normals.empty() &&
        (linear * interpolated(a.normals, s, weights)).normalized().dot(interpolated(b.normals, t, onto).normalized()) <
            kNormalCosine)
        return false;
    if (!a.texcoords.empty() && !b.texcoords.empty() &&
        (interpolated(a.texcoords, s, weights) - interpolated(b.texcoords, t, onto)).cwiseAbs().maxCoeff() >
            kTexcoordTolerance)
        return false;
    if (!a.colors.empty() &&
        (interpolated(a.colors, s, weights) - interpolated(b.colors, t, onto)).cwiseAbs().maxCoeff() > kColorTolerance)
        return false;
    return sameOtherAttributes(a, s, weights, linear, b, t, onto);
}

// One way of the surface check: `from`'s vertices and centroids, mapped by `map` into `onto`'s frame, against
// `onto`'s surface, and there `from`'s attributes against `onto`'s interpolated (normals turned by map's linear
// part): at the centroids too, since a vertex where a seam puts several (a cone's tip, a normal for each side)
// may match the attributes of another triangle than its own. The largest distance, or nothing.
std::optional<double> oneWay(const TileSurface& from, const TileSurface& onto, const Isometry& map, double tolerance,
                             bool geometryOnly) {
    const Primitive &a = from.primitive(), &b = onto.primitive();
    const double bound = tolerance * tolerance;
    double largest = 0;
    std::uint32_t triangle = 0;
    Eigen::Vector3d weights;
    const bool attributes =
        !geometryOnly && !(a.normals.empty() && a.texcoords.empty() && a.colors.empty() && a.attributes.empty());
    // The squared distance of p from onto's surface (bound when nothing is closer). Without attributes (and then
    // without `facing`) only the largest matters: a point no farther than the largest so far stops at the first
    // triangle that close, not at the closest.
    auto squaredTo = [&](const Eigen::Vector3d& p, const Eigen::Vector3d* facing) {
        return attributes ? onto.closest(p, bound, triangle, weights, facing)
                          : onto.squaredDistanceAbove(p, largest, bound);
    };
    for (std::uint32_t v = 0; v < a.positions.size(); ++v) {
        // Where the vertex has a normal, on the triangles facing its way: at a crease (a cap's rim), the side
        // its normal belongs to.
        const Eigen::Vector3d normal =
            a.normals.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(map.linear * a.normals[v]);
        const double squared = squaredTo(map.linear * a.positions[v] + map.translation,
                                         a.normals.empty() || geometryOnly ? nullptr : &normal);
        if (squared >= bound) return std::nullopt;
        largest = std::max(largest, squared);
        if (attributes &&
            !sameAttributes(a, {v, v, v}, Eigen::Vector3d(1, 0, 0), map.linear, b, b.triangles[triangle], weights))
            return std::nullopt;
    }
    const Eigen::Vector3d third = Eigen::Vector3d::Constant(1.0 / 3);
    for (const Triangle& t : a.triangles) {
        const Eigen::Vector3d &p = a.positions[t[0]], &q = a.positions[t[1]], &r = a.positions[t[2]];
        // On the triangles facing the way this one does (a thin part's other side lies within the tolerance).
        const Eigen::Vector3d facing = map.linear * (q - p).cross(r - p);
        const double squared = squaredTo(map.linear * (p + q + r) / 3 + map.translation,
                                         attributes && facing.squaredNorm() > 0 ? &facing : nullptr);
        if (squared >= bound) return std::nullopt;
        largest = std::max(largest, squared);
        if (attributes && !sameAttributes(a, t, third, map.linear, b, b.triangles[triangle], weights))
            return std::nullopt;
    }
    return std::sqrt(largest);
}

// The primitive with its positions only: what the check compares when attributes are ignored.
Primitive geometryOf(Primitive primitive) {
    primitive.normals.clear();
    primitive.texcoords.clear();
    primitive.colors.clear();
    primitive.attributes.clear();
    return primitive;
}

}  // namespace

TileSurface::TileSurface(const Primitive& primitive)
    : primitive_(primitive),
      mesh_{primitive.positions, primitive.triangles},
      bvh_(mesh_),
      moments_(orientedMoments(primitive)),
      diagonal_(boundsOf(primitive.positions).diagonal().norm()) {}

double TileSurface::squaredDistanceAbove(const Eigen::Vector3d& p, double enough, double bound) const {
    return bvh_.squaredDistanceAbove(p, enough, bound);
}

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
    if (!geometryOnly && !carriesAttributes(p, m)) return std::nullopt;
    // The orientation first: it costs a product of 3x3 matrices, the rest two searches per sample point.
    if (!sameOrientation(prototype.moments(), member.moments(), j, std::max(member.diagonal(), tolerance)))
        return std::nullopt;
    const std::optional<double> there = oneWay(prototype, member, j, tolerance, geometryOnly);
    if (!there) return std::nullopt;
    // A surface mapped onto itself by an involution (a mirror, a half turn) is the same comparison both ways.
    if (&prototype == &member && (j.linear * j.linear - Eigen::Matrix3d::Identity()).norm() < 1e-12 &&
        (j.linear * j.translation + j.translation).norm() <= 1e-12 * (1 + j.translation.norm()))
        return there;
    const std::optional<double> back = oneWay(member, prototype, j.inverse(), tolerance, geometryOnly);
    if (!back) return std::nullopt;
    return std::max(*there, *back);
}

Reproduction reproduction(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                          bool geometryOnly, double* deviation) {
    return geometryOnly ? reproducesWithAttributes(geometryOf(prototype), geometryOf(member), j, tolerance, deviation)
                        : reproducesWithAttributes(prototype, member, j, tolerance, deviation);
}

bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly, double* deviation) {
    const Reproduction corners = reproduction(prototype, member, j, tolerance, geometryOnly, deviation);
    if (corners != Reproduction::CutOtherwise) return corners == Reproduction::Reproduced;
    // The same corners cut into other triangles: the same surface where it is within the tolerance of the
    // other's and its attributes agree as fields.
    const TileSurface prototypeSurface(prototype), memberSurface(member);
    const std::optional<double> surface = surfaceDeviation(prototypeSurface, memberSurface, j, tolerance, geometryOnly);
    if (surface && deviation) *deviation = *surface;
    return bool(surface);
}

}  // namespace symcompress
