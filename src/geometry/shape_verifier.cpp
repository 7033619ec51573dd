#include "shape_verifier.hpp"
#include "geometry/bounds.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>
#include <Eigen/Cholesky>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace symcompress {
namespace {
// Cells of the sample-point hash, relative to the diagonal: well above the rounding of float32 data (a
// small part far from the origin rounds at 1e-5 of its size), well below the spacing of vertices.
constexpr double kSnapCell = 1e-4;
// A sample point found in the cell stands for the surface only this close (relative to the diagonal, a
// tenth of the default tolerance): the distance to it is an upper bound of the distance to the surface,
// tight only at rounding level.
constexpr double kSnapDistance = 1e-6;
// From this many sample points on, a measure is shared among the threads of the arena it runs in, in blocks of
// kParallelBlock points (a search is a microsecond or two: fewer points would not pay for the tasks).
constexpr std::size_t kParallelSamples = 256;
constexpr std::size_t kParallelBlock = 64;

bool worthThreads(std::size_t points) {
    return points >= kParallelSamples && tbb::this_task_arena::max_concurrency() > 1;
}
}  // namespace

void RejectingPoints::remember(std::uint32_t index) {
    const auto known = std::find(indices_.begin(), indices_.end(), index);
    if (known != indices_.end()) indices_.erase(known);
    if (indices_.size() == kCapacity) indices_.pop_back();
    indices_.insert(indices_.begin(), index);
}

ShapeVerifier::ShapeVerifier(const TriangleMesh& mesh, const Eigen::Vector3d& center)
    : mesh_(mesh), bvh_(mesh), center_(center) {
    std::vector<Eigen::Vector3d> points;
    std::vector<char> used(mesh.positions.size(), 0);
    for (const Triangle& t : mesh.triangles) {
        for (auto v : t)
            if (!used[v]) {
                used[v] = 1;
                points.push_back(mesh.positions[v] - center);
            }
        if (mesh.triangles.size() <= kCentroidSamplesUpTo)
            points.push_back((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3 - center);
    }
    // A fixed stride through the points (coprime with their count) visits the whole shape early, so that
    // a wrong map is rejected after a few queries.
    const std::size_t n = points.size();
    std::size_t stride = std::max<std::size_t>(1, std::size_t(double(n) * 0.618));
    while (n > 1 && std::gcd(stride, n) != 1) ++stride;
    samples_.reserve(n);
    for (std::size_t i = 0, at = 0; i < n; ++i, at = (at + stride) % n) samples_.push_back(points[at]);

    const Eigen::AlignedBox3d box = boundsOf(samples_);
    cellSize_ = std::max(kSnapCell * box.diagonal().norm(), 1e-300);
    snapSquared_ = std::pow(kSnapDistance * box.diagonal().norm(), 2);
    sampleInCell_.reserve(samples_.size());
    for (std::size_t i = 0; i < samples_.size(); ++i) sampleInCell_.emplace(cellKey(samples_[i]), std::uint32_t(i));
}

std::uint64_t ShapeVerifier::cellKey(const Eigen::Vector3d& p) const {
    std::uint64_t key = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const auto cell = static_cast<std::int64_t>(std::floor(p[axis] / cellSize_));
        key = key * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(cell);
    }
    return key;
}

double ShapeVerifier::squaredDistanceToSurface(const Eigen::Vector3d& p, double accept, double bound,
                                               double enough) const {
    const auto found = sampleInCell_.find(cellKey(p));
    if (found != sampleInCell_.end()) {
        const double d = (samples_[found->second] - p).squaredNorm();  // the sample point is on the surface
        if (d <= std::min(accept, snapSquared_)) return d;
    }
    if (enough >= 0) return bvh_.squaredDistanceAbove(center_ + p, enough, bound);
    return bvh_.squaredDistance(center_ + p, bound);
}

double ShapeVerifier::farthestOnto(const ShapeVerifier& target, const Eigen::Matrix3d& linear, double reject,
                                   std::size_t points, RejectingPoints* hints) const {
    double worst = 0;
    const double rejectSquared = reject * reject;
    const std::size_t count = std::min(points, samples_.size());
    // No need to search beyond the rejection distance: anything farther rejects the map.
    const double bound = 2 * rejectSquared + 1e-300;
    if (hints)
        for (const std::uint32_t i : hints->indices()) {
            if (i >= count) continue;
            const double d = target.squaredDistanceToSurface(linear * samples_[i], rejectSquared, bound);
            if (d > rejectSquared) {
                hints->remember(i);
                return std::sqrt(d);
            }
        }
    // Only the largest distance counts: a point's search stops at the first triangle no farther than the
    // largest so far, which leaves that largest (and the first point beyond the rejection distance) as
    // they are.
    if (!worthThreads(count)) {
        for (std::size_t i = 0; i < count; ++i) {
            const double d = target.squaredDistanceToSurface(linear * samples_[i], rejectSquared, bound, worst);
            worst = std::max(worst, d);
            if (d > rejectSquared) {
                if (hints) hints->remember(std::uint32_t(i));
                break;
            }
        }
        return std::sqrt(worst);
    }
    // On several threads each block keeps its own largest, and stops past the first point beyond the rejection
    // distance found so far: every point before the first such point in the samples' order is measured, so
    // that point, the largest and the hints come out as on one thread.
    std::atomic<std::size_t> firstRejecting{SIZE_MAX};
    worst = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, count, kParallelBlock), 0.0,
        [&](const tbb::blocked_range<std::size_t>& range, double largest) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                if (i > firstRejecting.load(std::memory_order_relaxed)) break;
                const double d = target.squaredDistanceToSurface(linear * samples_[i], rejectSquared, bound, largest);
                if (d > rejectSquared) {
                    std::size_t first = firstRejecting.load();
                    while (i < first && !firstRejecting.compare_exchange_weak(first, i)) {}
                    break;
                }
                largest = std::max(largest, d);
            }
            return largest;
        },
        [](double a, double b) { return std::max(a, b); });
    const std::size_t first = firstRejecting.load();
    if (first == SIZE_MAX) return std::sqrt(worst);
    if (hints) hints->remember(std::uint32_t(first));
    // Beyond the rejection distance, hence beyond any `enough`: the exact distance, as one thread finds it.
    return std::sqrt(target.squaredDistanceToSurface(linear * samples_[first], rejectSquared, bound, 0.0));
}

double ShapeVerifier::deviation(const Eigen::Matrix3d& linear, double reject, std::size_t points,
                                RejectingPoints* hints) const {
    const double forward = farthestOnto(*this, linear, reject, points, hints);
    // An involution (mirror, half turn, inversion) is its own inverse: one direction measures both.
    if (forward > reject || (linear - linear.transpose()).norm() < 1e-12) return forward;
    return std::max(forward, farthestOnto(*this, linear.transpose(), reject, points, hints));
}

Eigen::Vector3d ShapeVerifier::farthestFromAxis(const Eigen::Vector3d& axis) const {
    Eigen::Vector3d best = axis.unitOrthogonal();
    double bestDistance = 0;
    for (const Eigen::Vector3d& p : samples_) {
        const Eigen::Vector3d across = p - p.dot(axis) * axis;
        if (across.squaredNorm() > bestDistance) {
            bestDistance = across.squaredNorm();
            best = across;
        }
    }
    return best.normalized();
}

double deviationBetween(const ShapeVerifier& from, const ShapeVerifier& to, const Eigen::Matrix3d& linear,
                        double reject) {
    const double forward = from.farthestOnto(to, linear, reject);
    if (forward > reject) return forward;
    return std::max(forward, to.farthestOnto(from, linear.transpose(), reject));
}

Eigen::Matrix3d ShapeVerifier::refine(const Eigen::Matrix3d& linear, double searchRadius, int steps,
                                      std::size_t points) const {
    return refineOnto(*this, linear, searchRadius, steps, points);
}

Eigen::Matrix3d ShapeVerifier::refineOnto(const ShapeVerifier& target, const Eigen::Matrix3d& linear,
                                          double searchRadius, int steps, std::size_t points) const {
    const double searchSquared = searchRadius * searchRadius;
    Eigen::Matrix3d current = linear;
    // At most this many sample points, spread over the shape (the samples' order does that).
    constexpr std::size_t kMaxPoints = 5000;
    const std::size_t used = std::min({samples_.size(), kMaxPoints, points});
    // Each point's row of the least squares (a jacobian and a residual), found on the arena's threads and
    // summed in the points' order: the sums are the same on any number of threads.
    struct Row {
        Eigen::Vector3d jacobian;
        double residual = 0;
        bool used = false;
    };
    std::vector<Row> rows(used);
    for (int step = 0; step < steps; ++step) {
        // Residual n.(x - q) of x = current p against the plane of its closest triangle; a small rotation w
        // applied after current changes it by w.(x cross n).
        auto rowsOf = [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                Row& row = rows[i];
                row.used = false;
                const Eigen::Vector3d x = current * samples_[i];
                Eigen::Vector3d closest;
                std::uint32_t triangle = 0;
                // Points with nothing near (a hole, or a wrong map) say nothing about the fit.
                if (!(target.bvh_.squaredDistance(target.center_ + x, searchSquared, &closest, &triangle) <
                      searchSquared))
                    continue;
                const auto& positions = target.mesh_.positions;
                const Triangle& t = target.mesh_.triangles[triangle];
                const Eigen::Vector3d normal =
                    (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]).normalized();
                if (!normal.allFinite()) continue;
                row = {x.cross(normal), normal.dot(target.center_ + x - closest), true};
            }
        };
        if (worthThreads(used))
            tbb::parallel_for(
                tbb::blocked_range<std::size_t>(0, used, kParallelBlock),
                [&](const tbb::blocked_range<std::size_t>& range) { rowsOf(range.begin(), range.end()); });
        else
            rowsOf(0, used);
        Eigen::Matrix3d normalMatrix = Eigen::Matrix3d::Zero();
        Eigen::Vector3d rightSide = Eigen::Vector3d::Zero();
        for (const Row& row : rows)
            if (row.used) {
                normalMatrix += row.jacobian * row.jacobian.transpose();
                rightSide -= row.jacobian * row.residual;
            }
        const Eigen::Vector3d w = normalMatrix.ldlt().solve(rightSide);
        if (!w.allFinite()) return current;
        const double angle = w.norm();
        if (angle > 0) current = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() * current;
        if (angle < 1e-14) break;
    }
    return current;
}

}  // namespace symcompress
