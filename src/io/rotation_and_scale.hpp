// A node's linear map as rotation times scale, the form glTF nodes take and animation channels replace
// (shared by the glTF and X3D writers, so that both write an animated node's parts the same way).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <utility>

namespace symcompress {

// A linear map as R * S: a rotation, then a scale along the rotated axes (a mirror as one negative scale,
// on x). Nothing when the map shears (L^T L is not diagonal), which TRS cannot hold.
inline std::optional<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> asRotationAndScale(const Eigen::Matrix3d& linear) {
    const Eigen::Matrix3d gram = linear.transpose() * linear;
    const double size = gram.diagonal().maxCoeff();
    if (!(size > 0) || (gram - Eigen::Matrix3d(gram.diagonal().asDiagonal())).norm() > 1e-9 * size) return std::nullopt;
    Eigen::Vector3d scale = gram.diagonal().cwiseSqrt();
    if ((scale.array() <= 0).any()) return std::nullopt;
    if (linear.determinant() < 0) scale.x() = -scale.x();
    return std::pair{Eigen::Matrix3d(linear * scale.cwiseInverse().asDiagonal()), scale};
}

}  // namespace symcompress
