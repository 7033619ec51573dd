#include "symcompress/detail/congruence_descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace symcompress {

CongruenceDescriptor computeCongruenceDescriptor(const MomentCoefficients& coefficients) {
    CongruenceDescriptor descriptor;
    descriptor.maxOrder = coefficients.maxOrder;
    descriptor.area = coefficients.area;
    // C(2; 0, 0) = 2 pi (4/3) * Y_0^0 * integral |s|^2 ds, Y_0^0 = 1 / sqrt(4 pi).
    constexpr double kPi = 3.14159265358979323846;
    const double secondMoment = coefficients.maxOrder >= 2 && !coefficients.bands.empty()
                                    ? coefficients(2, 0, 0) / (2 * kPi * 4.0 / 3.0 / std::sqrt(4 * kPi))
                                    : 0.0;
    descriptor.rmsRadius = coefficients.area > 0 ? std::sqrt(std::max(0.0, secondMoment / coefficients.area)) : 0.0;
    for (int k = 1; k <= coefficients.maxOrder / 2; ++k) {
        const double scale = coefficients.area * std::pow(descriptor.rmsRadius, 2 * k);
        for (int l = 0; l <= k; ++l) {
            const double energy = coefficients.bands[k - 1][l].norm();
            descriptor.shape.push_back(scale > 0 ? energy / scale : 0.0);
        }
    }
    return descriptor;
}

double descriptorDifference(const CongruenceDescriptor& a, const CongruenceDescriptor& b) {
    if (a.maxOrder != b.maxOrder || a.shape.size() != b.shape.size())
        throw std::invalid_argument("comparing congruence descriptors of different orders");
    auto relative = [](double x, double y) {
        const double larger = std::max(std::abs(x), std::abs(y));
        return larger > 0 ? std::abs(x - y) / larger : 0.0;
    };
    double difference = std::max(relative(a.area, b.area), relative(a.rmsRadius, b.rmsRadius));
    std::size_t index = 0;
    for (int k = 1; k <= a.maxOrder / 2; ++k) {
        double largest = 0, largestDifference = 0;
        for (int l = 0; l <= k; ++l, ++index) {
            largest = std::max({largest, std::abs(a.shape[index]), std::abs(b.shape[index])});
            largestDifference = std::max(largestDifference, std::abs(a.shape[index] - b.shape[index]));
        }
        if (largest > 0) difference = std::max(difference, largestDifference / largest);
    }
    return difference;
}

}  // namespace symcompress
