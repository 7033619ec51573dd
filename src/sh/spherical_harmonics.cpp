#include "symcompress/detail/spherical_harmonics.hpp"

#include <cmath>
#include <stdexcept>

namespace symcompress {
namespace {

constexpr double kPi = 3.14159265358979323846;

// N_l^m, times sqrt(2) when m > 0 (the real harmonics' factor).
double normalization(int l, int m) {
    double ratio = 1;  // (l - m)! / (l + m)!
    for (int k = l - m + 1; k <= l + m; ++k) ratio /= k;
    return std::sqrt((2 * l + 1) / (4 * kPi) * ratio) * (m > 0 ? std::sqrt(2.0) : 1.0);
}

}  // namespace

std::vector<double> evaluateSphericalHarmonics(int maxDegree, const Eigen::Vector3d& w) {
    const double length = w.norm();
    if (!(length > 0)) throw std::invalid_argument("spherical harmonics need a non-zero direction");
    const Eigen::Vector3d u = w / length;
    std::vector<double> values(shCount(maxDegree), 0.0);
    // A_m + i B_m = (x + i y)^m, and Pi_l^m = P_l^m(z) / (1 - z^2)^(m/2) by the Legendre recurrence in l.
    double a = 1, b = 0, doubleFactorial = 1;  // (2m - 1)!!
    for (int m = 0; m <= maxDegree; ++m) {
        if (m > 0) {
            const double nextA = u.x() * a - u.y() * b;
            b = u.x() * b + u.y() * a;
            a = nextA;
            doubleFactorial *= 2 * m - 1;
        }
        double previous = 0, current = doubleFactorial;  // Pi_{m-1}^m = 0, Pi_m^m = (2m-1)!!
        for (int l = m; l <= maxDegree; ++l) {
            if (l > m) {
                const double next = ((2 * l - 1) * u.z() * current - (l + m - 1) * previous) / (l - m);
                previous = current;
                current = next;
            }
            const double n = normalization(l, m);
            values[shIndex(l, m)] = n * current * a;
            if (m > 0) values[shIndex(l, -m)] = n * current * b;
        }
    }
    return values;
}

HomogeneousPolynomial solidHarmonic(int l, int m) {
    const int order = std::abs(m);
    if (order > l) throw std::invalid_argument("solid harmonic with |m| > l");
    using P = HomogeneousPolynomial;
    // (x + i y)^|m| split into real and imaginary parts.
    P real(0), imaginary(0);
    real.coefficient(0, 0) = 1;
    for (int e = 0; e < order; ++e) {
        P nextReal = P::coordinate(0) * real;
        P minusYImaginary = P::coordinate(1) * imaginary;
        minusYImaginary *= -1;
        nextReal += minusYImaginary;
        P nextImaginary = P::coordinate(0) * imaginary;
        nextImaginary += P::coordinate(1) * real;
        real = nextReal;
        imaginary = nextImaginary;
    }
    // |s|^(l-m) Pi_l^m(z / |s|) through (l - m) Pi_l = (2l - 1) z Pi_{l-1} - (l + m - 1) r^2 Pi_{l-2}.
    double doubleFactorial = 1;
    for (int k = 1; k <= order; ++k) doubleFactorial *= 2 * k - 1;
    P previous(0), current(0);
    current.coefficient(0, 0) = doubleFactorial;
    bool hasPrevious = false;
    for (int degree = order + 1; degree <= l; ++degree) {
        P next = P::coordinate(2) * current;
        next *= double(2 * degree - 1);
        if (hasPrevious) {
            P older = P::squaredNormPower(1) * previous;
            older *= -double(degree + order - 1);
            next += older;
        }
        next *= 1.0 / (degree - order);
        previous = current;
        current = next;
        hasPrevious = true;
    }
    P result = current * (m >= 0 ? real : imaginary);
    result *= normalization(l, order);
    return result;
}

Eigen::MatrixXd shRotationMatrix(int l, const Eigen::Matrix3d& orthogonal) {
    std::vector<double> nodes, weights;
    gaussLegendre(l + 1, nodes, weights);
    const int azimuths = 2 * l + 1;
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(2 * l + 1, 2 * l + 1);
    Eigen::VectorXd here(2 * l + 1), there(2 * l + 1);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const double z = nodes[i], radius = std::sqrt(std::max(0.0, 1 - z * z));
        for (int j = 0; j < azimuths; ++j) {
            const double f = 2 * kPi * (j + 0.5) / azimuths;
            const Eigen::Vector3d w(radius * std::cos(f), radius * std::sin(f), z);
            const auto atW = evaluateSphericalHarmonics(l, w);
            const auto atRotated = evaluateSphericalHarmonics(l, orthogonal.transpose() * w);
            for (int m = -l; m <= l; ++m) {
                here[m + l] = atW[shIndex(l, m)];
                there[m + l] = atRotated[shIndex(l, m)];
            }
            d.noalias() += (weights[i] * 2 * kPi / azimuths) * here * there.transpose();
        }
    }
    return d;
}

void gaussLegendre(int count, std::vector<double>& nodes, std::vector<double>& weights) {
    if (count < 1) throw std::invalid_argument("Gauss-Legendre needs at least one node");
    nodes.assign(count, 0.0);
    weights.assign(count, 0.0);
    for (int i = 0; i < (count + 1) / 2; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (count + 0.5)), derivative = 1;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1, p1 = x;  // P_n(x) and P_n'(x) by the three-term recurrence
            for (int n = 2; n <= count; ++n) {
                const double p2 = ((2 * n - 1) * x * p1 - (n - 1) * p0) / n;
                p0 = p1;
                p1 = p2;
            }
            derivative = count * (x * p1 - p0) / (x * x - 1);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-16) break;
        }
        nodes[i] = -x;
        nodes[count - 1 - i] = x;
        weights[i] = weights[count - 1 - i] = 2 / ((1 - x * x) * derivative * derivative);
    }
}

}  // namespace symcompress
