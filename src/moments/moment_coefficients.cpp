#include "moment_basis.hpp"

#include "symcompress/detail/moments.hpp"
#include "symcompress/detail/spherical_harmonics.hpp"

namespace symcompress {

MomentCoefficients momentCoefficients(const SurfaceMoments& moments) {
    const MomentBasis& basis = momentBasis(moments.maxOrder);
    MomentCoefficients result;
    result.maxOrder = moments.maxOrder;
    result.area = moments.area;
    result.centroid = moments.centroid;
    for (int p = 1; p <= moments.maxOrder / 2; ++p) {
        result.bands.emplace_back();
        for (int l = 0; l <= p; ++l) {
            const auto& harmonics = basis.harmonics[p - 1][l];
            Eigen::VectorXd band(harmonics.size());
            for (std::size_t i = 0; i < harmonics.size(); ++i)
                band[i] = basis.zonalFactor[p - 1][l] * moments.integrate(harmonics[i]);
            result.bands.back().push_back(band);
        }
    }
    return result;
}

MomentCoefficients computeMomentCoefficients(const TriangleMesh& mesh, const MomentOptions& options) {
    return momentCoefficients(computeSurfaceMoments(mesh, options));
}

double evaluateMoment(const MomentCoefficients& coefficients, int order, const Eigen::Vector3d& w) {
    checkMomentOrder(order);
    if (order > coefficients.maxOrder) throw std::invalid_argument("moment order above the computed maximum");
    const std::vector<double> y = evaluateSphericalHarmonics(order, w);
    const auto& bands = coefficients.bands[order / 2 - 1];
    double sum = 0;
    for (int l = 0; l < static_cast<int>(bands.size()); ++l)
        for (int m = -2 * l; m <= 2 * l; ++m) sum += bands[l][m + 2 * l] * y[shIndex(2 * l, m)];
    return sum;
}

MomentCoefficients transformMomentCoefficients(const MomentCoefficients& coefficients, const Eigen::Matrix3d& q) {
    MomentCoefficients result = coefficients;
    result.centroid = q * coefficients.centroid;
    const int maxBand = coefficients.maxOrder / 2;
    for (int l = 0; l <= maxBand; ++l) {
        const Eigen::MatrixXd d = shRotationMatrix(2 * l, q);  // shared by every order that has band 2l
        for (int p = std::max(l, 1); p <= maxBand; ++p) result.bands[p - 1][l] = d * coefficients.bands[p - 1][l];
    }
    return result;
}

}  // namespace symcompress
