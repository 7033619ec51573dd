#include "x3d_primitives.hpp"

#include "x3d_crease_normals.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace symcompress::x3d {

namespace {

// A primitive built face by face, as X_ITE builds its geometric primitives from IndexedFaceSets: each face a
// fan from its first corner, a vertex for each distinct position, normal and texture coordinate.
class FaceBuilder {
public:
    struct Corner {
        Eigen::Vector3d position, normal;
        Eigen::Vector2d texcoord;  // X3D's, t up
    };
    void addFace(const std::vector<Corner>& corners) {
        std::vector<std::uint32_t> vertices;
        for (const Corner& c : corners) {
            const std::array<double, 8> key{c.position.x(), c.position.y(), c.position.z(), c.normal.x(),
                                            c.normal.y(),   c.normal.z(),   c.texcoord.x(), c.texcoord.y()};
            auto [entry, added] = vertexOf_.try_emplace(key, std::uint32_t(out_.positions.size()));
            if (added) {
                out_.positions.push_back(c.position);
                out_.normals.push_back(c.normal);
                out_.texcoords.emplace_back(c.texcoord.x(), 1 - c.texcoord.y());  // glTF's v points down
            }
            vertices.push_back(entry->second);
        }
        for (std::size_t k = 1; k + 1 < vertices.size(); ++k)
            out_.triangles.push_back({vertices[0], vertices[k], vertices[k + 1]});
    }
    Primitive take() { return std::move(out_); }

private:
    Primitive out_;
    std::map<std::array<double, 8>, std::uint32_t> vertexOf_;
};

// X_ITE's circle of `dimension` points: the i-th at angle 2 pi i / dimension, from -z turning towards -x.
Eigen::Vector3d aroundY(int i, int dimension, double radius, double y) {
    const double theta = 2 * M_PI * i / dimension;
    return {-radius * std::sin(theta), y, -radius * std::cos(theta)};
}

// A cap's texture coordinate at the i-th point of the circle (X_ITE's: the bottom's mirrored from the top's).
Eigen::Vector2d capTexcoord(int i, int dimension, bool top) {
    const double theta = 2 * M_PI * i / dimension;
    return {(1 - std::sin(theta)) / 2, top ? (1 + std::cos(theta)) / 2 : (1 - std::cos(theta)) / 2};
}

// A disc at height y facing down (the bottom: its points turned back) or up, one face of `dimension` corners.
void addCap(FaceBuilder& faces, int dimension, double radius, double y, bool top) {
    std::vector<FaceBuilder::Corner> corners;
    for (int k = 0; k < dimension; ++k) {
        const int i = top ? k : dimension - 1 - k;
        corners.push_back(
            {aroundY(i, dimension, radius, y), Eigen::Vector3d(0, top ? 1 : -1, 0), capTexcoord(i, dimension, top)});
    }
    faces.addFace(corners);
}

}  // namespace

Primitive tessellateBox(const Eigen::Vector3d& size) {
    // X_ITE's box: its corners, and each face's by them (front, back, left, right, top, bottom), every face's
    // texture from (1, 1) at its first corner round to (1, 0).
    const double corners[8][3] = {{1, 1, 1},  {-1, 1, 1},  {-1, -1, 1},  {1, -1, 1},
                                  {1, 1, -1}, {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}};
    const int faces[6][4] = {{0, 1, 2, 3}, {5, 4, 7, 6}, {1, 5, 6, 2}, {4, 0, 3, 7}, {4, 5, 1, 0}, {3, 2, 6, 7}};
    const Eigen::Vector2d texcoords[4] = {{1, 1}, {0, 1}, {0, 0}, {1, 0}};
    FaceBuilder out;
    for (const auto& face : faces) {
        auto corner = [&](int k) -> Eigen::Vector3d {
            const double* c = corners[face[k]];
            return Eigen::Vector3d(c[0], c[1], c[2]).cwiseProduct(size / 2);
        };
        const Eigen::Vector3d normal = (corner(1) - corner(0)).cross(corner(2) - corner(0)).normalized();
        std::vector<FaceBuilder::Corner> built;
        for (int k = 0; k < 4; ++k) built.push_back({corner(k), normal, texcoords[k]});
        out.addFace(built);
    }
    return out.take();
}

Primitive tessellateSphere(double radius) {
    // X_ITE's quad sphere: 32 points around, 15 from pole to pole; faces from each pole, quads between.
    constexpr int around = 32, rings = 13;  // rings of points between the poles
    std::vector<double> points{0, radius, 0};
    for (int v = 1; v <= rings; ++v) {
        const double polar = M_PI * v / (rings + 1);
        for (int u = 0; u < around; ++u) {
            const Eigen::Vector3d p = aroundY(u, around, radius * std::sin(polar), radius * std::cos(polar));
            points.insert(points.end(), {p.x(), p.y(), p.z()});
        }
    }
    points.insert(points.end(), {0, -radius, 0});
    const std::int64_t south = std::int64_t(points.size() / 3 - 1);
    auto point = [&](int v, int u) { return std::int64_t(1 + (v - 1) * around + (u % around)); };  // v in 1..rings
    // Faces by point, and each corner's texture coordinate (u / 32 across, 1 at the north pole to 0 at the south;
    // a pole's at the middle of its face).
    std::vector<std::vector<std::int64_t>> faces;
    std::vector<std::vector<Eigen::Vector2d>> texcoords;
    auto ringTexcoord = [&](int v, int u) { return Eigen::Vector2d(double(u) / around, 1 - double(v) / (rings + 1)); };
    for (int u = 0; u < around; ++u) {
        faces.push_back({0, point(1, u), point(1, u + 1)});
        texcoords.push_back({{(u + 0.5) / around, 1}, ringTexcoord(1, u), ringTexcoord(1, u + 1)});
    }
    for (int v = 1; v < rings; ++v)
        for (int u = 0; u < around; ++u) {
            faces.push_back({point(v, u), point(v + 1, u), point(v + 1, u + 1), point(v, u + 1)});
            texcoords.push_back(
                {ringTexcoord(v, u), ringTexcoord(v + 1, u), ringTexcoord(v + 1, u + 1), ringTexcoord(v, u + 1)});
        }
    for (int u = 0; u < around; ++u) {
        faces.push_back({south, point(rings, u + 1), point(rings, u)});
        texcoords.push_back({{(u + 0.5) / around, 0}, ringTexcoord(rings, u + 1), ringTexcoord(rings, u)});
    }
    // Smoothed at every point, as X_ITE's face set with a creaseAngle of pi.
    const auto [normals, normalOfCorner] = creasedNormals(faces, points, M_PI, true);
    FaceBuilder out;
    std::size_t corner = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        std::vector<FaceBuilder::Corner> corners;
        for (std::size_t k = 0; k < faces[f].size(); ++k, ++corner) {
            const std::int64_t p = faces[f][k], n = normalOfCorner[corner];
            corners.push_back({Eigen::Vector3d(points[3 * p], points[3 * p + 1], points[3 * p + 2]),
                               Eigen::Vector3d(normals[3 * n], normals[3 * n + 1], normals[3 * n + 2]),
                               texcoords[f][k]});
        }
        out.addFace(corners);
    }
    return out.take();
}

Primitive tessellateCylinder(double radius, double height, bool side, bool bottom, bool top) {
    constexpr int dimension = 20;  // X_ITE's
    const double h = height / 2;
    FaceBuilder out;
    if (side)
        for (int i = 0; i < dimension; ++i) {
            const Eigen::Vector3d n0 = aroundY(i, dimension, 1, 0), n1 = aroundY(i + 1, dimension, 1, 0);
            const double u0 = double(i) / dimension, u1 = double(i + 1) / dimension;
            out.addFace({{aroundY(i, dimension, radius, -h), n0, {u0, 0}},
                         {aroundY(i + 1, dimension, radius, -h), n1, {u1, 0}},
                         {aroundY(i + 1, dimension, radius, h), n1, {u1, 1}},
                         {aroundY(i, dimension, radius, h), n0, {u0, 1}}});
        }
    if (bottom) addCap(out, dimension, radius, -h, false);
    if (top) addCap(out, dimension, radius, h, true);
    return out.take();
}

Primitive tessellateCone(double bottomRadius, double height, bool side, bool bottom) {
    constexpr int dimension = 20;  // X_ITE's
    const double h = height / 2;
    FaceBuilder out;
    if (side) {
        // The side's normal tilts up by the slope's angle; at the apex, each triangle's at its middle.
        const double tilt = std::atan2(bottomRadius, height);
        auto normalAt = [&](double i) {
            const double theta = 2 * M_PI * i / dimension;
            return Eigen::Vector3d(-std::sin(theta) * std::cos(tilt), std::sin(tilt),
                                   -std::cos(theta) * std::cos(tilt));
        };
        for (int i = 0; i < dimension; ++i)
            out.addFace({{aroundY(i, dimension, bottomRadius, -h), normalAt(i), {double(i) / dimension, 0}},
                         {aroundY(i + 1, dimension, bottomRadius, -h), normalAt(i + 1), {double(i + 1) / dimension, 0}},
                         {Eigen::Vector3d(0, h, 0), normalAt(i + 0.5), {(i + 0.5) / dimension, 1}}});
    }
    if (bottom) addCap(out, dimension, bottomRadius, -h, false);
    return out.take();
}

Primitive tessellateRectangle2D(const Eigen::Vector2d& size) {
    const Eigen::Vector2d half = size.cwiseAbs() / 2;
    FaceBuilder out;
    const Eigen::Vector3d up(0, 0, 1);
    out.addFace({{Eigen::Vector3d(half.x(), half.y(), 0), up, {1, 1}},
                 {Eigen::Vector3d(-half.x(), half.y(), 0), up, {0, 1}},
                 {Eigen::Vector3d(-half.x(), -half.y(), 0), up, {0, 0}},
                 {Eigen::Vector3d(half.x(), -half.y(), 0), up, {1, 0}}});
    return out.take();
}

namespace {

constexpr int kCircleDimension = 40;  // X_ITE's segments of a whole turn (Geometry2D)

Eigen::Vector2d onCircle(double radius, double theta) {
    return radius * Eigen::Vector2d(std::cos(theta), std::sin(theta));
}

// The angle an arc sweeps from start to end, each taken within [0, 2 pi): a whole turn where they are equal.
double sweepOf(double startAngle, double endAngle) {
    auto wrapped = [](double angle) { return angle - 2 * M_PI * std::floor(angle / (2 * M_PI)); };
    const double start = wrapped(startAngle), end = wrapped(endAngle);
    return start == end ? 2 * M_PI : start > end ? 2 * M_PI - (start - end) : end - start;
}

// The steps an arc of `sweep` takes: its share of a whole turn's, at least `fewest`.
int stepsOf(double sweep, int fewest) {
    return std::max(fewest, int(std::floor(sweep * kCircleDimension / (2 * M_PI))));
}

}  // namespace

Primitive tessellateDisk2D(double innerRadius, double outerRadius) {
    const double inner = std::min(std::abs(innerRadius), std::abs(outerRadius));
    const double outer = std::max(std::abs(innerRadius), std::abs(outerRadius));
    if (inner == outer) return arc2D(outer, 0, 0);  // a circle (X_ITE draws a point where both are 0)
    FaceBuilder out;
    const Eigen::Vector3d up(0, 0, 1);
    // The texture across the outer circle's box.
    auto corner = [&](double radius, double theta) -> FaceBuilder::Corner {
        const Eigen::Vector2d p = onCircle(radius, theta);
        return {Eigen::Vector3d(p.x(), p.y(), 0), up, Eigen::Vector2d::Constant(0.5) + p / (2 * outer)};
    };
    for (int n = 0; n < kCircleDimension; ++n) {
        const double theta1 = 2 * M_PI * n / kCircleDimension, theta2 = 2 * M_PI * (n + 1) / kCircleDimension;
        if (inner == 0) {
            out.addFace({corner(0, 0), corner(outer, theta1), corner(outer, theta2)});
        } else {
            out.addFace({corner(inner, theta1), corner(outer, theta1), corner(outer, theta2)});
            out.addFace({corner(inner, theta1), corner(outer, theta2), corner(inner, theta2)});
        }
    }
    return out.take();
}

Primitive triangleSet2D(const std::vector<Eigen::Vector2d>& vertices) {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& v : vertices) box.extend(v);
    const double side = box.isEmpty() ? 0 : box.sizes().maxCoeff();
    FaceBuilder out;
    for (std::size_t i = 0; i + 2 < vertices.size(); i += 3) {
        std::vector<FaceBuilder::Corner> corners;
        for (std::size_t k = i; k < i + 3; ++k)
            corners.push_back({Eigen::Vector3d(vertices[k].x(), vertices[k].y(), 0), Eigen::Vector3d::UnitZ(),
                               side > 0 ? Eigen::Vector2d((vertices[k] - box.min()) / side) : Eigen::Vector2d::Zero()});
        out.addFace(corners);
    }
    return out.take();
}

Primitive arc2D(double radius, double startAngle, double endAngle) {
    const double sweep = sweepOf(startAngle, endAngle);
    const int steps = stepsOf(sweep, 3);
    Primitive out;
    out.topology = Topology::Lines;
    for (int n = 0; n <= steps; ++n) {
        const Eigen::Vector2d p = onCircle(std::abs(radius), startAngle + sweep * n / steps);
        out.positions.emplace_back(p.x(), p.y(), 0);
        if (n) out.lines.push_back({std::uint32_t(n - 1), std::uint32_t(n)});
    }
    return out;
}

Primitive tessellateArcClose2D(double radius, double startAngle, double endAngle, bool chord) {
    const double sweep = sweepOf(startAngle, endAngle);
    const int points = stepsOf(sweep, 4);  // X_ITE's: from start to end, both ends included
    const Eigen::Vector3d up(0, 0, 1);
    auto corner = [&](int n) -> FaceBuilder::Corner {
        const double theta = startAngle + sweep * n / (points - 1);
        const Eigen::Vector2d p = onCircle(std::abs(radius), theta);
        return {Eigen::Vector3d(p.x(), p.y(), 0), up, Eigen::Vector2d::Constant(0.5) + onCircle(0.5, theta)};
    };
    // A chord: a fan from the arc's first point; a pie: from the centre.
    const FaceBuilder::Corner centre{Eigen::Vector3d::Zero(), up, Eigen::Vector2d::Constant(0.5)};
    FaceBuilder out;
    for (int n = chord ? 1 : 0; n + 1 < points; ++n)
        out.addFace({chord ? corner(0) : centre, corner(n), corner(n + 1)});
    return out.take();
}

Primitive polyline2D(const std::vector<Eigen::Vector2d>& points) {
    Primitive out = polypoint2D(points);
    out.topology = Topology::Lines;
    for (std::size_t i = 1; i < points.size(); ++i) out.lines.push_back({std::uint32_t(i - 1), std::uint32_t(i)});
    return out;
}

Primitive polypoint2D(const std::vector<Eigen::Vector2d>& points) {
    Primitive out;
    out.topology = Topology::Points;
    for (const Eigen::Vector2d& p : points) out.positions.emplace_back(p.x(), p.y(), 0);
    return out;
}

}  // namespace symcompress::x3d
