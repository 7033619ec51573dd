#include "moment_basis.hpp"

#include "symcompress/detail/moments.hpp"

#include <cmath>

namespace symcompress {

MomentFunction::MomentFunction(const MomentCoefficients& coefficients, int order) : polynomial_(order) {
    checkMomentOrder(order);
    if (order > coefficients.maxOrder) throw std::invalid_argument("moment order above the computed maximum");
    const MomentBasis& basis = momentBasis(coefficients.maxOrder);
    const auto& bands = coefficients.bands[order / 2 - 1];
    for (std::size_t l = 0; l < bands.size(); ++l) {
        for (int i = 0; i < bands[l].size(); ++i) {
            HomogeneousPolynomial term = basis.harmonics[order / 2 - 1][l][i];
            term *= bands[l][i];
            polynomial_ += term;
        }
        (l == 0 ? bandZeroNorm_ : otherBandsNorm_) += bands[l].squaredNorm();
    }
    bandZeroNorm_ = std::sqrt(bandZeroNorm_);
    otherBandsNorm_ = std::sqrt(otherBandsNorm_);
    for (int a = 0; a < 3; ++a) {
        gradient_[a] = polynomial_.derivative(a);
        for (int b = 0; b < 3; ++b) hessian_[a][b] = gradient_[a].derivative(b);
    }
}

double MomentFunction::largestValue() const {
    constexpr double kPi = 3.14159265358979323846;
    double meanToLargest = 1;  // (2p + 1)!! / (2p)!!
    for (int k = 1; 2 * k <= order(); ++k) meanToLargest *= (2.0 * k + 1) / (2.0 * k);
    const double mean = bandZeroNorm_ / std::sqrt(4 * kPi);  // C_0 Y_0^0
    return (1 + 1e-6) * meanToLargest * mean;
}

Eigen::Vector3d MomentFunction::tangentialGradient(const Eigen::Vector3d& w, Eigen::Vector3d* euclidean) const {
    const HomogeneousPolynomial* parts[3] = {&gradient_[0], &gradient_[1], &gradient_[2]};
    Eigen::Vector3d gradient;
    HomogeneousPolynomial::evaluateTogether(parts, 3, w, gradient.data());
    if (euclidean) *euclidean = gradient;
    return gradient - gradient.dot(w) * w;
}

Eigen::Matrix3d MomentFunction::tangentialHessian(const Eigen::Vector3d& w) const {
    return tangentialHessian(w, Eigen::Vector3d(gradient_[0](w), gradient_[1](w), gradient_[2](w)));
}

Eigen::Matrix3d MomentFunction::tangentialHessian(const Eigen::Vector3d& w, const Eigen::Vector3d& gradient) const {
    // Riemannian Hessian on the unit sphere: P (D^2 G - (w . grad G) I) P, P = I - w w^T.
    // The six distinct second derivatives, evaluated side by side.
    const HomogeneousPolynomial* parts[6] = {&hessian_[0][0], &hessian_[0][1], &hessian_[0][2],
                                             &hessian_[1][1], &hessian_[1][2], &hessian_[2][2]};
    double second[6];
    HomogeneousPolynomial::evaluateTogether(parts, 6, w, second);
    Eigen::Matrix3d hessian;
    hessian << second[0], second[1], second[2], second[1], second[3], second[4], second[2], second[4], second[5];
    const Eigen::Matrix3d projector = Eigen::Matrix3d::Identity() - w * w.transpose();
    return projector * (hessian - gradient.dot(w) * Eigen::Matrix3d::Identity()) * projector;
}

}  // namespace symcompress
