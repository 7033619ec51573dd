// The digest of the original surface stored in a compressed file (glTF asset.extras, an X3D meta).
#include "symcompress/verify.hpp"

#include "common/number_text.hpp"

#include <nlohmann/json.hpp>

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
    for (const WorldPrimitive& placed : soup) addTriangles(placed.primitive.positions, placed.primitive.triangles, digest);
    return digest;
}

std::string SurfaceDigest::json() const {
    // Nine digits: far below any tolerance the digest is checked with, and half the text of seventeen.
    auto number = [](double x) { return rounded(x, 9); };
    auto vector = [&](const Eigen::Vector3d& v) { return nlohmann::json{number(v.x()), number(v.y()), number(v.z())}; };
    // The budget where there is one (what the decoder verifies against), else the tolerance.
    nlohmann::json digest{{"triangles", triangles}, {"area", number(area)}};
    if (maxError > 0)
        digest["max_error"] = number(maxError);
    else
        digest["tolerance"] = number(tolerance);
    if (!bounds.isEmpty()) digest["bbox"] = {{"min", vector(bounds.min())}, {"max", vector(bounds.max())}};
    return nlohmann::json{{"symcompress_digest", digest}}.dump();
}

bool SurfaceDigest::fromJson(const std::string& text, SurfaceDigest& digest) {
    const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
    if (root.is_discarded() || !root.is_object() || !root.contains("symcompress_digest")) return false;
    const auto& d = root["symcompress_digest"];
    try {
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
