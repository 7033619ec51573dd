// X3D's creased normals: made from a creaseAngle (the reader), and the creaseAngle that makes given ones (the
// writer).
#include "x3d_crease_normals.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace symcompress {

namespace {

// The browser's normal of every corner in face order, given to `visit(corner, normal)` (nullptr for a corner
// whose point is out of range) until it returns false. Returns whether every corner was visited.
template <typename Visit>
bool visitCreasedNormals(const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points,
                         double creaseAngle, bool ccw, Visit visit) {
    const std::size_t pointCount = points.size() / 3;
    auto point = [&](std::int64_t p) { return Eigen::Vector3d(points[3 * p], points[3 * p + 1], points[3 * p + 2]); };
    // The unit (Newell's) normal of each face, and those of the faces at each point, a face once at a point.
    std::vector<Eigen::Vector3d> unit(faces.size());
    std::vector<std::pair<std::uint32_t, Eigen::Vector3d>> incidences;
    incidences.reserve(3 * faces.size());
    std::vector<std::size_t> lastFaceAt(pointCount, faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        if (std::all_of(face.begin(), face.end(),
                        [&](std::int64_t p) { return p >= 0 && std::size_t(p) < pointCount; })) {
            for (std::size_t k = 0; k < face.size(); ++k)
                normal += point(face[k]).cross(point(face[(k + 1) % face.size()]));
            if (!ccw) normal = -normal;
        }
        unit[f] = normal.normalized();
        if (normal.norm() > 0)
            for (std::int64_t p : face)
                if (std::exchange(lastFaceAt[std::size_t(p)], f) != f)
                    incidences.push_back({std::uint32_t(p), unit[f]});
    }
    const NormalsAtPoints normalsAt(pointCount, incidences);
    const double cosCrease = std::cos(std::min(creaseAngle, M_PI));
    std::size_t corner = 0;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Eigen::Vector3d& own = unit[f];
        for (std::int64_t p : faces[f]) {
            if (p < 0 || std::size_t(p) >= pointCount) {
                if (!visit(corner++, nullptr)) return false;
                continue;
            }
            // A face without a normal (zero) sums every face at the point once the angle passes a right one.
            const Eigen::Vector3d sum = normalsAt.smoothed(std::size_t(p), own, cosCrease);
            const Eigen::Vector3d normal = sum.norm() > 0   ? sum.normalized()
                                           : own.norm() > 0 ? own
                                                            : Eigen::Vector3d::UnitZ();
            if (!visit(corner++, &normal)) return false;
        }
    }
    return true;
}

}  // namespace

NormalsAtPoints::NormalsAtPoints(std::size_t pointCount,
                                 const std::vector<std::pair<std::uint32_t, Eigen::Vector3d>>& incidences)
    : begin_(pointCount + 1, 0), end_(pointCount), normals_(incidences.size()), counts_(incidences.size(), 1) {
    for (const auto& [point, normal] : incidences) ++begin_[point + 1];
    for (std::size_t p = 0; p < pointCount; ++p) begin_[p + 1] += begin_[p];
    std::copy(begin_.begin(), begin_.end() - 1, end_.begin());
    for (const auto& [point, normal] : incidences) {
        // A normal the point has already is counted again; a new one appended.
        const auto first = normals_.begin() + std::ptrdiff_t(begin_[point]),
                   last = normals_.begin() + std::ptrdiff_t(end_[point]);
        const auto found = std::find(first, last, normal);
        if (found != last) {
            ++counts_[std::size_t(found - normals_.begin())];
        } else {
            normals_[end_[point]++] = normal;
        }
    }
}

Eigen::Vector3d NormalsAtPoints::smoothed(std::size_t point, const Eigen::Vector3d& own, double cosCrease) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (std::size_t k = begin_[point]; k < end_[point]; ++k)
        if (normals_[k] == own || own.dot(normals_[k]) > cosCrease) sum += counts_[k] * normals_[k];
    return sum;
}

std::pair<std::vector<double>, std::vector<std::int64_t>> creasedNormals(
    const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points, double creaseAngle,
    bool ccw) {
    std::vector<double> normals;
    std::vector<std::int64_t> cornerNormal;
    std::vector<std::vector<std::pair<Eigen::Vector3d, std::int64_t>>> madeAt(points.size() /
                                                                              3);  // distinct, per point
    std::vector<std::int64_t> pointOfCorner;
    for (const auto& face : faces) pointOfCorner.insert(pointOfCorner.end(), face.begin(), face.end());
    visitCreasedNormals(faces, points, creaseAngle, ccw, [&](std::size_t corner, const Eigen::Vector3d* normal) {
        if (!normal) {
            cornerNormal.push_back(-1);
            return true;
        }
        auto& made = madeAt[std::size_t(pointOfCorner[corner])];
        const auto found = std::find_if(made.begin(), made.end(), [&](const auto& m) { return m.first == *normal; });
        if (found != made.end()) {
            cornerNormal.push_back(found->second);
            return true;
        }
        made.push_back({*normal, std::int64_t(normals.size() / 3)});
        cornerNormal.push_back(made.back().second);
        normals.insert(normals.end(), {normal->x(), normal->y(), normal->z()});
        return true;
    });
    return {normals, cornerNormal};
}

bool creasedNormalsMatch(const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points,
                         const std::vector<Eigen::Vector3d>& cornerNormals, double creaseAngle) {
    std::size_t corners = 0;
    for (const auto& face : faces) corners += face.size();
    if (corners != cornerNormals.size()) return false;
    // Stops at the first corner that differs: most angles tried fail at once.
    return visitCreasedNormals(faces, points, creaseAngle, true,
                               [&](std::size_t corner, const Eigen::Vector3d* normal) {
                                   return normal && (*normal - cornerNormals[corner]).norm() <= kCreasedNormalMatch;
                               });
}

}  // namespace symcompress
