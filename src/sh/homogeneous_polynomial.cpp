#include "symcompress/detail/homogeneous_polynomial.hpp"

#include <stdexcept>

namespace symcompress {

HomogeneousPolynomial::HomogeneousPolynomial(int degree) : degree_(degree), coefficients_(monomialCount(degree), 0.0) {
    if (degree < 0) throw std::invalid_argument("a polynomial degree must not be negative");
}

double HomogeneousPolynomial::operator()(const Eigen::Vector3d& point) const {
    // Powers of each coordinate, then one pass over the monomials. On the stack up to degree 64 (the
    // searches for critical points evaluate these millions of times).
    constexpr int kStackDegree = 64;
    double stack[3 * (kStackDegree + 1)];
    std::vector<double> heap;
    double* powers = stack;
    if (degree_ > kStackDegree) {
        heap.resize(3 * std::size_t(degree_ + 1));
        powers = heap.data();
    }
    double *xs = powers, *ys = powers + degree_ + 1, *zs = powers + 2 * (degree_ + 1);
    xs[0] = ys[0] = zs[0] = 1;
    for (int e = 1; e <= degree_; ++e) {
        xs[e] = xs[e - 1] * point.x();
        ys[e] = ys[e - 1] * point.y();
        zs[e] = zs[e - 1] * point.z();
    }
    double sum = 0;
    int index = 0;
    for (int k = 0; k <= degree_; ++k) {
        double row = 0;
        for (int j = 0; j <= degree_ - k; ++j) row += coefficients_[index++] * xs[degree_ - j - k] * ys[j];
        sum += row * zs[k];
    }
    return sum;
}

namespace {

constexpr int kStackDegree = 64;  // the largest degree whose powers the evaluations below keep on the stack

// Powers 0..degree of each coordinate, as operator() computes them (one product after another).
void powersOf(const Eigen::Vector3d& point, int degree, double* xs, double* ys, double* zs) {
    xs[0] = ys[0] = zs[0] = 1;
    for (int e = 1; e <= degree; ++e) {
        xs[e] = xs[e - 1] * point.x();
        ys[e] = ys[e - 1] * point.y();
        zs[e] = zs[e - 1] * point.z();
    }
}

// kLanes independent sums in the order of operator(): lane c takes its coefficients from coefficients[c]
// and its powers from xs[c], ys[c], zs[c].
template <int kLanes>
void sumLanes(int degree, const double* const* coefficients, const double (*xs)[kStackDegree + 1],
              const double (*ys)[kStackDegree + 1], const double (*zs)[kStackDegree + 1], double* values) {
    double sum[kLanes] = {};
    int index = 0;
    for (int k = 0; k <= degree; ++k) {
        double row[kLanes] = {};
        for (int j = 0; j <= degree - k; ++j, ++index)
            for (int c = 0; c < kLanes; ++c) row[c] += coefficients[c][index] * xs[c][degree - j - k] * ys[c][j];
        for (int c = 0; c < kLanes; ++c) sum[c] += row[c] * zs[c][k];
    }
    for (int c = 0; c < kLanes; ++c) values[c] = sum[c];
}

}  // namespace

void HomogeneousPolynomial::evaluate(const Eigen::Vector3d* points, std::size_t count, double* values) const {
    constexpr int kLanes = 4;
    std::size_t i = 0;
    if (degree_ <= kStackDegree) {
        double xs[kLanes][kStackDegree + 1], ys[kLanes][kStackDegree + 1], zs[kLanes][kStackDegree + 1];
        const double* coefficients[kLanes];
        for (int c = 0; c < kLanes; ++c) coefficients[c] = coefficients_.data();
        for (; i + kLanes <= count; i += kLanes) {
            for (int c = 0; c < kLanes; ++c) powersOf(points[i + std::size_t(c)], degree_, xs[c], ys[c], zs[c]);
            sumLanes<kLanes>(degree_, coefficients, xs, ys, zs, values + i);
        }
    }
    for (; i < count; ++i) values[i] = (*this)(points[i]);
}

void HomogeneousPolynomial::evaluateTogether(const HomogeneousPolynomial* const* polynomials, int count,
                                             const Eigen::Vector3d& point, double* values) {
    const int degree = count > 0 ? polynomials[0]->degree_ : 0;
    bool together = count <= kMaxTogether && degree <= kStackDegree;
    for (int c = 0; c < count; ++c) together = together && polynomials[c]->degree_ == degree;
    if (!together) {
        for (int c = 0; c < count; ++c) values[c] = (*polynomials[c])(point);
        return;
    }
    double xs[kMaxTogether][kStackDegree + 1], ys[kMaxTogether][kStackDegree + 1], zs[kMaxTogether][kStackDegree + 1];
    powersOf(point, degree, xs[0], ys[0], zs[0]);
    const double* coefficients[kMaxTogether];
    for (int c = 0; c < count; ++c) {
        coefficients[c] = polynomials[c]->coefficients_.data();
        if (c > 0)
            for (int e = 0; e <= degree; ++e) xs[c][e] = xs[0][e], ys[c][e] = ys[0][e], zs[c][e] = zs[0][e];
    }
    if (count == 3) return sumLanes<3>(degree, coefficients, xs, ys, zs, values);
    if (count == 6) return sumLanes<6>(degree, coefficients, xs, ys, zs, values);
    for (int c = 0; c < count; ++c) values[c] = (*polynomials[c])(point);
}

HomogeneousPolynomial HomogeneousPolynomial::derivative(int axis) const {
    if (degree_ == 0) return HomogeneousPolynomial(0);
    HomogeneousPolynomial result(degree_ - 1);
    for (int k = 0; k <= degree_; ++k)
        for (int j = 0; j <= degree_ - k; ++j) {
            const int i = degree_ - j - k;
            const double c = coefficient(j, k);
            if (axis == 0 && i > 0) result.coefficient(j, k) += i * c;
            if (axis == 1 && j > 0) result.coefficient(j - 1, k) += j * c;
            if (axis == 2 && k > 0) result.coefficient(j, k - 1) += k * c;
        }
    return result;
}

HomogeneousPolynomial& HomogeneousPolynomial::operator+=(const HomogeneousPolynomial& other) {
    if (other.degree_ != degree_) throw std::invalid_argument("adding homogeneous polynomials of different degrees");
    for (std::size_t i = 0; i < coefficients_.size(); ++i) coefficients_[i] += other.coefficients_[i];
    return *this;
}

HomogeneousPolynomial& HomogeneousPolynomial::operator*=(double factor) {
    for (double& c : coefficients_) c *= factor;
    return *this;
}

HomogeneousPolynomial operator*(const HomogeneousPolynomial& a, const HomogeneousPolynomial& b) {
    HomogeneousPolynomial product(a.degree_ + b.degree_);
    for (int ka = 0; ka <= a.degree_; ++ka)
        for (int ja = 0; ja <= a.degree_ - ka; ++ja) {
            const double ca = a.coefficient(ja, ka);
            if (ca == 0) continue;
            for (int kb = 0; kb <= b.degree_; ++kb)
                for (int jb = 0; jb <= b.degree_ - kb; ++jb) product.coefficient(ja + jb, ka + kb) += ca * b.coefficient(jb, kb);
        }
    return product;
}

HomogeneousPolynomial HomogeneousPolynomial::coordinate(int axis) {
    HomogeneousPolynomial p(1);
    p.coefficient(axis == 1 ? 1 : 0, axis == 2 ? 1 : 0) = 1;
    return p;
}

HomogeneousPolynomial HomogeneousPolynomial::squaredNormPower(int power) {
    HomogeneousPolynomial squaredNorm(2);
    squaredNorm.coefficient(0, 0) = squaredNorm.coefficient(2, 0) = squaredNorm.coefficient(0, 2) = 1;
    HomogeneousPolynomial result(0);
    result.coefficient(0, 0) = 1;
    for (int e = 0; e < power; ++e) result = result * squaredNorm;
    return result;
}

}  // namespace symcompress
