#include "moment_basis.hpp"

#include "symcompress/detail/moments.hpp"
#include "symcompress/detail/spherical_harmonics.hpp"

#include <array>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace symcompress {
namespace {

constexpr double kPi = 3.14159265358979323846;

double legendre(int degree, double x) {
    double previous = 1, current = x;
    if (degree == 0) return 1;
    for (int n = 2; n <= degree; ++n) {
        const double next = ((2 * n - 1) * x * current - (n - 1) * previous) / n;
        previous = current;
        current = next;
    }
    return current;
}

MomentBasis buildBasis(int maxOrder) {
    MomentBasis basis;
    basis.maxOrder = maxOrder;
    const int maxP = maxOrder / 2;
    std::vector<std::vector<HomogeneousPolynomial>> solid(maxP + 1);
    for (int l = 0; l <= maxP; ++l)
        for (int m = -2 * l; m <= 2 * l; ++m) solid[l].push_back(solidHarmonic(2 * l, m));
    for (int p = 1; p <= maxP; ++p) {
        // (1 - x^2)^p P_2l(x) has degree 2p + 2l <= 4p: 2p + 1 Gauss-Legendre nodes integrate it exactly.
        std::vector<double> nodes, weights;
        gaussLegendre(2 * p + 1, nodes, weights);
        basis.harmonics.emplace_back();
        basis.zonalFactor.emplace_back();
        for (int l = 0; l <= p; ++l) {
            double integral = 0;
            for (std::size_t i = 0; i < nodes.size(); ++i)
                integral += weights[i] * std::pow(1 - nodes[i] * nodes[i], p) * legendre(2 * l, nodes[i]);
            basis.zonalFactor.back().push_back(2 * kPi * integral);
            const HomogeneousPolynomial radial = HomogeneousPolynomial::squaredNormPower(p - l);
            basis.harmonics.back().emplace_back();
            for (const HomogeneousPolynomial& harmonic : solid[l]) basis.harmonics.back().back().push_back(radial * harmonic);
        }
    }
    return basis;
}

}  // namespace

void checkMomentOrder(int maxOrder) {
    if (maxOrder < 2 || maxOrder > kMaxMomentOrder || maxOrder % 2 != 0)
        throw std::invalid_argument("moment order " + std::to_string(maxOrder) + " is not an even number in 2.." +
                                    std::to_string(kMaxMomentOrder));
}

const MomentBasis& momentBasis(int maxOrder) {
    checkMomentOrder(maxOrder);
    // One immutable table per order, built on first use: a cache of constants, not shared mutable state.
    static std::array<std::once_flag, kMaxMomentOrder / 2 + 1> once;
    static std::array<std::unique_ptr<MomentBasis>, kMaxMomentOrder / 2 + 1> tables;
    const int slot = maxOrder / 2;
    std::call_once(once[slot], [&] { tables[slot] = std::make_unique<MomentBasis>(buildBasis(maxOrder)); });
    return *tables[slot];
}

}  // namespace symcompress
