// Homogeneous polynomials in (x, y, z): the Cartesian form of solid harmonics and of the moment functions.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace symcompress {

// p(x, y, z) = sum over i + j + k = degree of c(j, k) x^i y^j z^k.
// Invariant: coefficients().size() == monomialCount(degree()); the coefficient of x^i y^j z^k is stored at
// monomialIndex(degree, j, k) (rows of equal k, j increasing), the layout the moment kernel also uses.
class HomogeneousPolynomial {
public:
    explicit HomogeneousPolynomial(int degree = 0);

    static int monomialCount(int degree) { return (degree + 1) * (degree + 2) / 2; }
    static int monomialIndex(int degree, int j, int k) { return k * (degree + 1) - k * (k - 1) / 2 + j; }

    int degree() const { return degree_; }
    const std::vector<double>& coefficients() const { return coefficients_; }
    double& coefficient(int j, int k) { return coefficients_[monomialIndex(degree_, j, k)]; }
    double coefficient(int j, int k) const { return coefficients_[monomialIndex(degree_, j, k)]; }

    double operator()(const Eigen::Vector3d& point) const;
    // The same at `count` points, each value the very number operator() gives: the points' sums are
    // independent, so they run side by side instead of one waiting for the other's additions.
    void evaluate(const Eigen::Vector3d* points, std::size_t count, double* values) const;
    // `count` polynomials (at most kMaxTogether) of one degree at one point, each value the very number
    // operator() gives (a gradient's three, a Hessian's six).
    static constexpr int kMaxTogether = 6;
    static void evaluateTogether(const HomogeneousPolynomial* const* polynomials, int count,
                                 const Eigen::Vector3d& point, double* values);
    HomogeneousPolynomial derivative(int axis) const;  // d/dx, d/dy or d/dz (axis 0, 1, 2)

    HomogeneousPolynomial& operator+=(const HomogeneousPolynomial& other);  // degrees must be equal
    HomogeneousPolynomial& operator*=(double factor);
    friend HomogeneousPolynomial operator*(const HomogeneousPolynomial& a, const HomogeneousPolynomial& b);

    // x, y or z (axis 0, 1, 2), and (x^2 + y^2 + z^2)^power.
    static HomogeneousPolynomial coordinate(int axis);
    static HomogeneousPolynomial squaredNormPower(int power);

private:
    int degree_;
    std::vector<double> coefficients_;
};

}  // namespace symcompress
