// Point groups as signed permutation matrices, for the tests of fundamental regions: each lists the identity first.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace symcompress::testing {

inline std::vector<Eigen::Matrix3d> signedPermutations(const std::function<bool(const Eigen::Matrix3d&)>& keep) {
    std::vector<Eigen::Matrix3d> group;
    std::array<int, 3> order{0, 1, 2};
    do {
        for (int signs = 0; signs < 8; ++signs) {
            Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
            for (int row = 0; row < 3; ++row) m(row, order[row]) = (signs >> row) & 1 ? -1.0 : 1.0;
            if (keep(m)) group.push_back(m);
        }
    } while (std::next_permutation(order.begin(), order.end()));
    return group;
}

inline std::vector<Eigen::Matrix3d> groupOh() {
    return signedPermutations([](const Eigen::Matrix3d&) { return true; });
}
inline std::vector<Eigen::Matrix3d> groupD4h() {
    return signedPermutations([](const Eigen::Matrix3d& m) { return std::abs(m(2, 2)) == 1; });
}
inline std::vector<Eigen::Matrix3d> groupTd() {  // keeps the product of the coordinates, +1 on the tetrahedron
    return signedPermutations([](const Eigen::Matrix3d& m) { return m.rowwise().sum().prod() > 0; });
}
inline std::vector<Eigen::Matrix3d> groupC4v() {
    return signedPermutations([](const Eigen::Matrix3d& m) { return m(2, 2) == 1; });
}
inline std::vector<Eigen::Matrix3d> groupC4() {
    return signedPermutations([](const Eigen::Matrix3d& m) { return m(2, 2) == 1 && m.determinant() > 0; });
}
inline std::vector<Eigen::Matrix3d> groupMirrorX() {
    return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, 1, 1).asDiagonal().toDenseMatrix()};
}
inline std::vector<Eigen::Matrix3d> groupC2z() {
    return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()};
}

}  // namespace symcompress::testing
