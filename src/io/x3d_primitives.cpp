#include "x3d_primitives.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress::x3d {

namespace {

std::uint32_t addVertex(Primitive& out, const Eigen::Vector3d& position, const Eigen::Vector3d& normal,
                        const Eigen::Vector2d& texcoord) {
    out.positions.push_back(position);
    out.normals.push_back(normal);
    out.texcoords.push_back(texcoord);
    return static_cast<std::uint32_t>(out.positions.size() - 1);
}

}  // namespace

Primitive tessellateBox(const Eigen::Vector3d& size) {
    Primitive out;
    const Eigen::Vector3d half = size / 2;
    for (int axis = 0; axis < 3; ++axis)
        for (int sign : {-1, 1}) {
            Eigen::Vector3d normal = Eigen::Vector3d::Zero();
            normal[axis] = sign;
            // Two tangents such that (u, v, normal) is right-handed, so that the face is counter-clockwise.
            Eigen::Vector3d u = Eigen::Vector3d::Zero();
            u[(axis + 1) % 3] = 1;
            Eigen::Vector3d v = normal.cross(u);
            const std::uint32_t base = static_cast<std::uint32_t>(out.positions.size());
            const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (const auto& c : corners)
                addVertex(out, (normal + c[0] * u + c[1] * v).cwiseProduct(half), normal,
                          Eigen::Vector2d((c[0] + 1) / 2, 1 - (c[1] + 1) / 2));
            out.triangles.push_back({base, base + 1, base + 2});
            out.triangles.push_back({base, base + 2, base + 3});
        }
    return out;
}

Primitive tessellateSphere(double radius, int slices, int stacks) {
    Primitive out;
    for (int i = 0; i <= stacks; ++i) {
        const double theta = M_PI * i / stacks;  // from the north pole (+y)
        for (int j = 0; j <= slices; ++j) {
            const double phi = 2 * M_PI * j / slices;
            const Eigen::Vector3d normal(-std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            addVertex(out, radius * normal, normal, Eigen::Vector2d(double(j) / slices, double(i) / stacks));
        }
    }
    const auto index = [&](int i, int j) { return static_cast<std::uint32_t>(i * (slices + 1) + j); };
    for (int i = 0; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            if (i > 0) out.triangles.push_back({index(i, j), index(i + 1, j), index(i, j + 1)});
            if (i + 1 < stacks) out.triangles.push_back({index(i, j + 1), index(i + 1, j), index(i + 1, j + 1)});
        }
    return out;
}

Primitive tessellateCylinder(double bottomRadius, double topRadius, double height, bool side, bool bottom, bool top,
                             int slices) {
    Primitive out;
    const double h = height / 2;
    auto ring = [&](double radius, double y, int j) {
        const double phi = 2 * M_PI * j / slices;
        return Eigen::Vector3d(-radius * std::sin(phi), y, -radius * std::cos(phi));
    };
    if (side) {
        // The side's normal tilts with the slope of a cone.
        const double slope = (bottomRadius - topRadius) / height;
        for (int j = 0; j < slices; ++j) {
            const Eigen::Vector3d b0 = ring(bottomRadius, -h, j), b1 = ring(bottomRadius, -h, j + 1);
            const Eigen::Vector3d t0 = ring(topRadius, h, j), t1 = ring(topRadius, h, j + 1);
            auto normalAt = [&](int k) {
                const Eigen::Vector3d radial = ring(1, 0, k);
                return Eigen::Vector3d(radial.x(), slope, radial.z()).normalized();
            };
            const double u0 = double(j) / slices, u1 = double(j + 1) / slices;
            const std::uint32_t a = addVertex(out, b0, normalAt(j), {u0, 1}), b = addVertex(out, b1, normalAt(j + 1), {u1, 1});
            const std::uint32_t c = addVertex(out, t1, normalAt(j + 1), {u1, 0}), d = addVertex(out, t0, normalAt(j), {u0, 0});
            out.triangles.push_back({a, b, c});
            if (topRadius > 0) out.triangles.push_back({a, c, d});
        }
    }
    auto cap = [&](double radius, double y, const Eigen::Vector3d& normal) {
        if (radius <= 0) return;
        const std::uint32_t centre = addVertex(out, Eigen::Vector3d(0, y, 0), normal, {0.5, 0.5});
        std::vector<std::uint32_t> rim;
        for (int j = 0; j <= slices; ++j) {
            const Eigen::Vector3d p = ring(radius, y, j);
            rim.push_back(addVertex(out, p, normal, {0.5 + p.x() / (2 * radius), 0.5 + p.z() / (2 * radius)}));
        }
        for (int j = 0; j < slices; ++j)
            out.triangles.push_back(normal.y() > 0 ? Triangle{centre, rim[j], rim[j + 1]} : Triangle{centre, rim[j + 1], rim[j]});
    };
    if (bottom) cap(bottomRadius, -h, {0, -1, 0});
    if (top) cap(topRadius, h, {0, 1, 0});
    return out;
}

}  // namespace symcompress::x3d
