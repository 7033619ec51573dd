// The digest of the original surface stored in a compressed file (glTF asset.extras, an X3D meta).
#include "symcompress/verify.hpp"

#include "common/number_text.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace symcompress {

namespace {

void addTriangles(const std::vector<Eigen::Vector3d>& positions, const std::vector<Triangle>& triangles,
                  SurfaceDigest& digest) {
    digest.triangles += triangles.size();
    for (const Triangle& t : triangles) {
        const auto &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
        digest.area += 0.5 * (b - a).cross(c - a).norm();
        digest.bounds.extend(a).extend(b).extend(c);
    }
}

}  // namespace

SurfaceDigest digestOf(const TriangleMesh& surface, double tolerance) {
    SurfaceDigest digest;
    digest.tolerance = tolerance;
    addTriangles(surface.positions, surface.triangles, digest);
    return digest;
}

SurfaceDigest digestOf(const std::vector<WorldPrimitive>& soup, double tolerance) {
    SurfaceDigest digest;
    digest.tolerance = tolerance;
    for (const WorldPrimitive& placed : soup) {
        const Primitive& primitive = placed.primitive;
        addTriangles(primitive.positions, primitive.triangles, digest);
        // What is drawn as points and lines is kept as it is: it counts towards the bounds only.
        if (primitive.topology == Topology::Points)
            for (const Eigen::Vector3d& p : primitive.positions) digest.bounds.extend(p);
        for (const Segment& segment : primitive.lines)
            for (std::uint32_t v : segment) digest.bounds.extend(primitive.positions[v]);
    }
    return digest;
}

std::string SurfaceDigest::json() const {
    // One array, [triangles, area, budget, tolerance, min x y z, max x y z] (the budget where there is one,
    // what the decoder verifies against, else 0 and the tolerance): the digest is in every file, whose JSON is
    // most of a small one. The area to 7 digits and the bounds to a millionth of the diagonal: the decoder
    // allows at least 2^-13 of either.
    nlohmann::json digest{triangles, rounded(area, 7), rounded(maxError, 9),
                          maxError > 0 ? 0.0 : rounded(tolerance, 9)};
    if (!bounds.isEmpty()) {
        const double step = std::pow(10.0, std::floor(std::log10(std::max(bounds.diagonal().norm(), 1e-300) * 1e-6)));
        for (const Eigen::Vector3d& corner : {bounds.min(), bounds.max()})
            for (int axis = 0; axis < 3; ++axis) digest.push_back(rounded(std::round(corner[axis] / step) * step, 15));
    }
    if (poseError > 0) digest.push_back(rounded(poseError, 9));
    return nlohmann::json{{"symcompress_digest", digest}}.dump();
}

bool SurfaceDigest::fromJson(const std::string& text, SurfaceDigest& digest) {
    const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
    if (root.is_discarded() || !root.is_object() || !root.contains("symcompress_digest")) return false;
    const auto& d = root["symcompress_digest"];
    try {
        if (d.is_array()) {
            if (d.size() != 4 && d.size() != 5 && d.size() != 10 && d.size() != 11) return false;
            digest.triangles = d[0].get<std::size_t>();
            digest.area = d[1].get<double>();
            digest.maxError = d[2].get<double>();
            digest.tolerance = d[3].get<double>();
            if (d.size() == 5 || d.size() == 11) digest.poseError = d[d.size() - 1].get<double>();
            if (d.size() >= 10)
                digest.bounds =
                    Eigen::AlignedBox3d(Eigen::Vector3d(d[4].get<double>(), d[5].get<double>(), d[6].get<double>()),
                                        Eigen::Vector3d(d[7].get<double>(), d[8].get<double>(), d[9].get<double>()));
            return true;
        }
        // The object of files written before 2026-12-03: {"triangles", "area", "max_error" or "tolerance", "bbox"}.
        digest.triangles = d.at("triangles").get<std::size_t>();
        digest.area = d.at("area").get<double>();
        digest.maxError = d.value("max_error", 0.0);
        digest.tolerance = digest.maxError > 0 ? d.value("tolerance", 0.0) : d.at("tolerance").get<double>();
        if (d.contains("bbox")) {
            const auto& lo = d["bbox"].at("min");
            const auto& hi = d["bbox"].at("max");
            digest.bounds =
                Eigen::AlignedBox3d(Eigen::Vector3d(lo[0], lo[1], lo[2]), Eigen::Vector3d(hi[0], hi[1], hi[2]));
        }
    } catch (const nlohmann::json::exception&) {
        return false;
    }
    return true;
}

}  // namespace symcompress
