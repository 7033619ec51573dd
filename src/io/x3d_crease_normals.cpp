// X3D's creased normals: made from a creaseAngle (the reader), and the creaseAngle that makes given ones (the
// writer).
#include "x3d_crease_normals.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace symcompress {

std::pair<std::vector<double>, std::vector<std::int64_t>> creasedNormals(const std::vector<std::vector<std::int64_t>>& faces,
                                                                          const std::vector<double>& points,
                                                                          double creaseAngle, bool ccw) {
    const std::size_t pointCount = points.size() / 3;
    auto point = [&](std::int64_t p) { return Eigen::Vector3d(points[3 * p], points[3 * p + 1], points[3 * p + 2]); };
    // Newell's normal of each face.
    std::vector<Eigen::Vector3d> faceNormal(faces.size(), Eigen::Vector3d::Zero());
    std::vector<std::vector<std::size_t>> facesAt(pointCount);
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        if (!std::all_of(face.begin(), face.end(), [&](std::int64_t p) { return p >= 0 && std::size_t(p) < pointCount; }))
            continue;
        for (std::size_t k = 0; k < face.size(); ++k) faceNormal[f] += point(face[k]).cross(point(face[(k + 1) % face.size()]));
        if (!ccw) faceNormal[f] = -faceNormal[f];
        for (std::int64_t p : face)
            if (facesAt[std::size_t(p)].empty() || facesAt[std::size_t(p)].back() != f) facesAt[std::size_t(p)].push_back(f);
    }
    const double cosCrease = std::cos(std::min(creaseAngle, M_PI));
    std::vector<double> normals;
    std::vector<std::int64_t> cornerNormal;
    std::vector<std::vector<std::pair<Eigen::Vector3d, std::int64_t>>> madeAt(pointCount);  // distinct, per point
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Eigen::Vector3d own = faceNormal[f].normalized();
        for (std::int64_t p : faces[f]) {
            if (p < 0 || std::size_t(p) >= pointCount) {
                cornerNormal.push_back(-1);
                continue;
            }
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for (std::size_t g : facesAt[std::size_t(p)])
                if (g == f || own.dot(faceNormal[g].normalized()) > cosCrease) sum += faceNormal[g].normalized();
            Eigen::Vector3d normal = sum.norm() > 0 ? sum.normalized() : own.norm() > 0 ? own : Eigen::Vector3d::UnitZ();
            auto& made = madeAt[std::size_t(p)];
            const auto found = std::find_if(made.begin(), made.end(), [&](const auto& m) { return m.first == normal; });
            if (found != made.end()) {
                cornerNormal.push_back(found->second);
                continue;
            }
            made.push_back({normal, std::int64_t(normals.size() / 3)});
            cornerNormal.push_back(made.back().second);
            normals.insert(normals.end(), {normal.x(), normal.y(), normal.z()});
        }
    }
    return {normals, cornerNormal};
}


bool creasedNormalsMatch(const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points,
                         const std::vector<Eigen::Vector3d>& cornerNormals, double creaseAngle) {
    constexpr double kMatch = 3.5e-3;
    const auto [normals, normalOfCorner] = creasedNormals(faces, points, creaseAngle, true);
    if (normalOfCorner.size() != cornerNormals.size()) return false;
    for (std::size_t c = 0; c < cornerNormals.size(); ++c) {
        const std::int64_t n = normalOfCorner[c];
        if (n < 0 || (Eigen::Vector3d(normals[3 * n], normals[3 * n + 1], normals[3 * n + 2]) - cornerNormals[c]).norm() > kMatch)
            return false;
    }
    return true;
}

}  // namespace symcompress
