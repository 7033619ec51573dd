#include "candidate_axes.hpp"

#include "common/with_threads.hpp"

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace symcompress {
namespace {

constexpr int kStarts = 400;  // starting points on the hemisphere
constexpr int kIterations = 40;
constexpr double kMaxStep = 0.3;  // radians: keeps Newton near its starting point's basin

// Points spread evenly over the upper hemisphere (a Fibonacci lattice).
std::vector<Eigen::Vector3d> hemispherePoints(int count) {
    std::vector<Eigen::Vector3d> points;
    const double golden = 3.14159265358979323846 * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double z = (i + 0.5) / count, r = std::sqrt(1 - z * z), phi = golden * i;
        points.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
    return points;
}

// Two unit vectors completing w to an orthonormal frame.
void tangentFrame(const Eigen::Vector3d& w, Eigen::Vector3d& e1, Eigen::Vector3d& e2) {
    const Eigen::Vector3d helper = std::abs(w.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    e1 = w.cross(helper).normalized();
    e2 = w.cross(e1);
}

// Newton on the tangential gradient from `start`; false when it does not converge to a critical point.
bool newtonCriticalPoint(const MomentFunction& f, Eigen::Vector3d start, Eigen::Vector3d& critical) {
    Eigen::Vector3d w = start.normalized();
    for (int iteration = 0; iteration < kIterations; ++iteration) {
        Eigen::Vector3d euclidean;
        const Eigen::Vector3d g = f.tangentialGradient(w, &euclidean);
        const double scale = std::abs(f.value(w)) * f.order();
        if (g.norm() <= 1e-13 * scale) {  // converged, so within the test below: no need to evaluate it again
            critical = w;
            return true;
        }
        Eigen::Vector3d e1, e2;
        tangentFrame(w, e1, e2);
        Eigen::Matrix<double, 3, 2> e;
        e << e1, e2;
        const Eigen::Matrix2d h = e.transpose() * f.tangentialHessian(w, euclidean) * e;
        const Eigen::Vector2d g2 = e.transpose() * g;
        Eigen::Vector2d step;
        if (std::abs(h.determinant()) > 1e-14 * h.squaredNorm())
            step = -h.inverse() * g2;
        else
            step = -g2 / std::max(h.norm(), scale);  // flat: a gradient step
        Eigen::Vector3d delta = e * step;
        if (delta.norm() > kMaxStep) delta *= kMaxStep / delta.norm();
        w = (w + delta).normalized();
    }
    // Out of iterations: a critical point all the same if the gradient is small enough.
    const double scale = std::abs(f.value(w)) * f.order();
    if (!(f.tangentialGradient(w).norm() <= 1e-9 * scale)) return false;
    critical = w;
    return true;
}

}  // namespace

std::vector<Eigen::Vector3d> findCandidateAxes(const std::vector<MomentFunction>& functions, double mergeAngle,
                                               int threads) {
    const auto starts = hemispherePoints(kStarts);
    // Every start's search is independent: run them side by side, then merge in the order of one search after
    // the other (function by function, start by start), so that the axes do not depend on the threads.
    std::vector<std::optional<Eigen::Vector3d>> found(functions.size() * starts.size());
    withThreads(threads, [&] {
        tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t i) {
            Eigen::Vector3d critical;
            if (newtonCriticalPoint(functions[i / starts.size()], starts[i % starts.size()], critical)) found[i] = critical;
        });
    });
    std::vector<Eigen::Vector3d> axes;
    const double mergeCosine = std::cos(mergeAngle);
    for (const std::optional<Eigen::Vector3d>& critical : found) {
        if (!critical) continue;
        const bool known = std::any_of(axes.begin(), axes.end(), [&](const Eigen::Vector3d& a) {
            return std::abs(a.dot(*critical)) >= mergeCosine;
        });
        if (!known) axes.push_back(critical->z() < 0 ? Eigen::Vector3d(-*critical) : *critical);
    }
    return axes;
}

}  // namespace symcompress
