// The monomial integrals of a triangle mesh, exactly (docs/moments.md, "Integration").
//
// For a triangle T with vertices a, b, c and area A, and any direction t:
//   integral over T of (t.s)^d ds = 2A d! / (d + 2)! * h_d(t.a, t.b, t.c),
// where h_d is the complete homogeneous symmetric polynomial (the sum of all monomials of degree d). Read as
// a polynomial in t, h_d's coefficient of t^beta gives integral of s^beta = 2A beta! / (d + 2)! [t^beta] h_d.
// h_d follows from three recurrences that each multiply by one linear form:
//   E_d = (t.a) E_{d-1},  F_d = E_d + (t.b) F_{d-1},  H_d = F_d + (t.c) H_{d-1} = h_d(t.a, t.b, t.c).
// So each triangle costs a few multiply-adds per monomial, and the factors beta! / (d + 2)! are applied once
// to the sums.
#include "moment_basis.hpp"
#include "common/with_threads.hpp"

#include "symcompress/detail/moments.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace symcompress {
namespace {

using Poly = HomogeneousPolynomial;

// Triangles are processed in batches of kLanes with every coefficient stored as kLanes consecutive values,
// one per triangle, so that each step below is the same arithmetic on every lane: the compiler turns the
// innermost loops into SIMD instructions and the index bookkeeping is paid once per batch.
constexpr int kLanes = 8;
using Lanes = std::array<double, kLanes>;

// out (degree d) = base + (cx x + cy y + cz z) * in (degree d - 1), lane by lane; base may be null (zero).
// Row k of a degree-d polynomial holds the monomials x^(d-j-k) y^j z^k, j = 0..d-k. Each output is written
// once: out(j, k) = base(j, k) + cx in(j, k) + cy in(j - 1, k) + cz in(j, k - 1), terms outside in dropped.
template <bool WithBase>
inline void multiplyByLinearForm(const Lanes* in, int d, const Lanes& cx, const Lanes& cy, const Lanes& cz,
                                 const Lanes* base, Lanes* out) {
    int inRow = 0, previousInRow = 0, outRow = 0;
    for (int k = 0; k <= d; ++k) {
        const int length = d - k + 1;  // out row k: j = 0..d-k; in row k: j = 0..d-k-1; in row k-1: j = 0..d-k
        const Lanes* row = in + inRow;
        const Lanes* below = in + previousInRow;
        for (int j = 0; j < length; ++j) {
            Lanes value;
            for (int lane = 0; lane < kLanes; ++lane) value[lane] = WithBase ? base[outRow + j][lane] : 0.0;
            if (j < length - 1)
                for (int lane = 0; lane < kLanes; ++lane) value[lane] += cx[lane] * row[j][lane];
            if (j > 0)
                for (int lane = 0; lane < kLanes; ++lane) value[lane] += cy[lane] * row[j - 1][lane];
            if (k > 0)
                for (int lane = 0; lane < kLanes; ++lane) value[lane] += cz[lane] * below[j][lane];
            out[outRow + j] = value;
        }
        previousInRow = inRow;
        if (k < d) inRow += d - k;
        outRow += length;
    }
}

// Sums over triangles of 2A [t^beta] h_d for the even degrees d = 2..maxOrder, concatenated.
struct MonomialSums {
    std::vector<double> values;
    explicit MonomialSums(std::size_t size = 0) : values(size, 0.0) {}
};

class TriangleKernel {
public:
    explicit TriangleKernel(int maxOrder) : maxOrder_(maxOrder) {
        const std::size_t size = Poly::monomialCount(maxOrder);
        for (auto* buffer : {&e_, &f_, &h_, &e2_, &f2_, &h2_}) buffer->resize(size);
        for (int d = 2; d <= maxOrder; d += 2) {
            offsets_.push_back(total_);
            total_ += Poly::monomialCount(d);
        }
    }
    std::size_t total() const { return total_; }

    // Queues a triangle (coordinates about the centroid); every kLanes triangles are added to sums.
    void add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double* sums) {
        const double twiceArea = (b - a).cross(c - a).norm();
        if (twiceArea == 0) return;
        for (int axis = 0; axis < 3; ++axis) {
            a_[axis][queued_] = a[axis];
            b_[axis][queued_] = b[axis];
            c_[axis][queued_] = c[axis];
        }
        twiceArea_[queued_] = twiceArea;
        if (++queued_ == kLanes) flush(sums);
    }

    // Adds the queued triangles (the unused lanes have zero area).
    void flush(double* sums) {
        if (queued_ == 0) return;
        for (int lane = queued_; lane < kLanes; ++lane) {
            for (int axis = 0; axis < 3; ++axis) a_[axis][lane] = b_[axis][lane] = c_[axis][lane] = 0;
            twiceArea_[lane] = 0;
        }
        queued_ = 0;
        Lanes *e = e_.data(), *f = f_.data(), *h = h_.data(), *e2 = e2_.data(), *f2 = f2_.data(), *h2 = h2_.data();
        for (int lane = 0; lane < kLanes; ++lane) e[0][lane] = f[0][lane] = h[0][lane] = 1;
        for (int d = 1; d <= maxOrder_; ++d) {
            multiplyByLinearForm<false>(e, d, a_[0], a_[1], a_[2], nullptr, e2);
            multiplyByLinearForm<true>(f, d, b_[0], b_[1], b_[2], e2, f2);
            multiplyByLinearForm<true>(h, d, c_[0], c_[1], c_[2], f2, h2);
            std::swap(e, e2);
            std::swap(f, f2);
            std::swap(h, h2);
            if (d % 2 == 0) {
                double* target = sums + offsets_[d / 2 - 1];
                const int count = Poly::monomialCount(d);
                for (int i = 0; i < count; ++i) {
                    double sum = 0;
                    for (int lane = 0; lane < kLanes; ++lane) sum += twiceArea_[lane] * h[i][lane];
                    target[i] += sum;
                }
            }
        }
    }

private:
    int maxOrder_;
    std::size_t total_ = 0;
    std::vector<std::size_t> offsets_;
    std::vector<Lanes> e_, f_, h_, e2_, f2_, h2_;
    Lanes a_[3] = {}, b_[3] = {}, c_[3] = {};
    Lanes twiceArea_ = {};
    int queued_ = 0;
};

constexpr std::size_t kGrain = 4096;  // triangles per task: large enough to amortize, small enough to balance

}  // namespace

double SurfaceMoments::integrate(const HomogeneousPolynomial& polynomial) const {
    const int d = polynomial.degree();
    if (d < 2 || d > maxOrder || d % 2 != 0) throw std::invalid_argument("no monomial integrals of that degree");
    const auto& integrals = monomialIntegrals[d / 2 - 1];
    double sum = 0;
    for (std::size_t i = 0; i < integrals.size(); ++i) sum += polynomial.coefficients()[i] * integrals[i];
    return sum;
}

SurfaceMoments computeSurfaceMoments(const TriangleMesh& mesh, const MomentOptions& options) {
    checkMomentOrder(options.maxOrder);
    SurfaceMoments result;
    result.maxOrder = options.maxOrder;
    const std::size_t triangleCount = mesh.triangles.size();
    const int threads = triangleCount < 4 * kGrain ? 1 : options.threads;
    const auto& positions = mesh.positions;

    // Pass 1: area and centroid (sum of area * triangle centroid).
    using AreaSums = Eigen::Vector4d;  // (2A * (a + b + c), 2A) summed
    const AreaSums areaSums = withThreads(threads, [&] {
        return tbb::parallel_deterministic_reduce(
            tbb::blocked_range<std::size_t>(0, triangleCount, kGrain), AreaSums(AreaSums::Zero()),
            [&](const tbb::blocked_range<std::size_t>& range, AreaSums sums) {
                for (std::size_t t = range.begin(); t != range.end(); ++t) {
                    const Triangle& tri = mesh.triangles[t];
                    const Eigen::Vector3d &a = positions[tri[0]], &b = positions[tri[1]], &c = positions[tri[2]];
                    const double twiceArea = (b - a).cross(c - a).norm();
                    sums.head<3>() += twiceArea * (a + b + c);
                    sums[3] += twiceArea;
                }
                return sums;
            },
            [](const AreaSums& x, const AreaSums& y) -> AreaSums { return x + y; });
    });
    result.area = areaSums[3] / 2;
    if (areaSums[3] > 0) {
        result.centroid = areaSums.head<3>() / (3 * areaSums[3]);
    } else if (!positions.empty()) {
        for (const Eigen::Vector3d& p : positions) result.centroid += p;
        result.centroid /= double(positions.size());
    }

    // Pass 2: every monomial integral about the centroid.
    const Eigen::Vector3d centroid = result.centroid;
    const std::size_t total = TriangleKernel(options.maxOrder).total();
    const MonomialSums sums = withThreads(threads, [&] {
        return tbb::parallel_deterministic_reduce(
            tbb::blocked_range<std::size_t>(0, triangleCount, kGrain), MonomialSums(total),
            [&](const tbb::blocked_range<std::size_t>& range, MonomialSums partial) {
                TriangleKernel kernel(options.maxOrder);
                for (std::size_t t = range.begin(); t != range.end(); ++t) {
                    const Triangle& tri = mesh.triangles[t];
                    kernel.add(positions[tri[0]] - centroid, positions[tri[1]] - centroid, positions[tri[2]] - centroid,
                               partial.values.data());
                }
                kernel.flush(partial.values.data());
                return partial;
            },
            [](MonomialSums x, const MonomialSums& y) {
                for (std::size_t i = 0; i < x.values.size(); ++i) x.values[i] += y.values[i];
                return x;
            });
    });

    // Apply beta! / (d + 2)!.
    std::vector<double> factorial(options.maxOrder + 3, 1.0);
    for (std::size_t n = 1; n < factorial.size(); ++n) factorial[n] = factorial[n - 1] * double(n);
    std::size_t offset = 0;
    for (int d = 2; d <= options.maxOrder; d += 2) {
        std::vector<double> integrals(Poly::monomialCount(d));
        for (int k = 0; k <= d; ++k)
            for (int j = 0; j <= d - k; ++j) {
                const int index = Poly::monomialIndex(d, j, k);
                integrals[index] = sums.values[offset + index] * factorial[d - j - k] * factorial[j] * factorial[k] /
                                   factorial[d + 2];
            }
        offset += integrals.size();
        result.monomialIntegrals.push_back(std::move(integrals));
    }
    return result;
}

}  // namespace symcompress
