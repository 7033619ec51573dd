#include "find_isometry.hpp"

#include "geometry/candidate_axes.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <complex>

namespace symcompress {
namespace {

constexpr double kDistinctEigenvalues = 1e-4;  // relative gap above which principal axes are a frame
constexpr double kSameValue = 1e-3;            // relative agreement of moment values at matched directions
constexpr double kNoiseVariation = 1e-5;       // as in the detector: flatter functions have no directions
// A map is refined on this many sample points in three steps first; where that leaves it beyond kHopeless times
// the tolerance, the full refinement (5000 points, six steps) is not tried: fifty copies rounded apart by a
// quantizer (gltfpack's grid; near misses each of each, 1225 pairs) spent two minutes refining maps that no
// refinement brought within the tolerance (it left them at 1.7 to 2 times it, from 1.0 to 1.4 unrefined).
constexpr std::size_t kQuickRefinePoints = 500;
constexpr double kHopeless = 1.5;
// A Fourier mode about an axis weaker than this, relative to the function's bound, is noise (float32 data).
constexpr double kRingModeNoise = 1e-5;
constexpr double kPi = 3.14159265358979323846;

// The rotation whose columns are a, the part of b across a, and their cross product.
Eigen::Matrix3d frameOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    Eigen::Matrix3d frame;
    frame.col(0) = a.normalized();
    frame.col(1) = (b - b.dot(frame.col(0)) * frame.col(0)).normalized();
    frame.col(2) = frame.col(0).cross(frame.col(1));
    return frame;
}

// Candidate maps from the principal axes: all 8 sign choices (4 rotations, 4 reflections).
void principalCandidates(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to, std::vector<Eigen::Matrix3d>& out) {
    for (int signs = 0; signs < 8; ++signs) {
        const Eigen::Vector3d s(signs & 1 ? -1 : 1, signs & 2 ? -1 : 1, signs & 4 ? -1 : 1);
        out.push_back(to * s.asDiagonal() * from.transpose());
    }
}

// Candidate maps from critical directions of one moment function: the two directions of `from` where it is
// largest, matched to pairs of `to` with the same values and the same angle between them.
void criticalCandidates(const MomentFunction& f, const std::vector<Eigen::Vector3d>& fAxes, const MomentFunction& g,
                        const std::vector<Eigen::Vector3d>& gAxes, std::vector<Eigen::Matrix3d>& out) {
    if (fAxes.size() < 2) return;
    std::vector<Eigen::Vector3d> sorted = fAxes;
    std::sort(sorted.begin(), sorted.end(), [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y) { return f.value(x) > f.value(y); });
    const Eigen::Vector3d a = sorted[0];
    const auto second = std::find_if(sorted.begin() + 1, sorted.end(), [&](const Eigen::Vector3d& x) { return std::abs(x.dot(a)) < 0.999; });
    if (second == sorted.end()) return;
    const Eigen::Vector3d b = *second;
    const Eigen::Matrix3d fromFrame = frameOf(a, b);
    const double scale = std::abs(f.value(a));
    const Eigen::Matrix3d flip = Eigen::Vector3d(1, 1, -1).asDiagonal();
    for (const Eigen::Vector3d& a2 : gAxes) {
        if (std::abs(g.value(a2) - f.value(a)) > kSameValue * scale) continue;
        for (const Eigen::Vector3d& b2 : gAxes) {
            if (std::abs(g.value(b2) - f.value(b)) > kSameValue * scale) continue;
            if (std::abs(std::abs(a2.dot(b2)) - std::abs(a.dot(b))) > 1e-3 || std::abs(a2.dot(b2)) > 0.999) continue;
            for (double sa : {1.0, -1.0})
                for (double sb : {1.0, -1.0}) {
                    const Eigen::Matrix3d toFrame = frameOf(sa * a2, sb * b2);
                    out.push_back(toFrame * fromFrame.transpose());
                    out.push_back(toFrame * flip * fromFrame.transpose());
                }
        }
    }
}

// A moment function on a ring about an axis: the ring at polar angle theta in the frame (u, v, axis), as the
// Fourier coefficients c_m, m = 0..order, of phi -> f(sin theta (cos phi u + sin phi v) + cos theta axis). On the
// ring f is a trigonometric polynomial of degree `order`: 2 order + 2 samples give its coefficients exactly.
std::vector<std::complex<double>> ringModes(const MomentFunction& f, const Eigen::Matrix3d& frame, double theta) {
    const int order = f.order(), samples = 2 * order + 2;
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < samples; ++k) {
        const double phi = 2 * kPi * k / samples;
        points.push_back(
            frame * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
    std::vector<double> values(points.size());
    f.polynomial().evaluate(points.data(), points.size(), values.data());
    std::vector<std::complex<double>> modes(std::size_t(order) + 1);
    for (int m = 0; m <= order; ++m)
        for (int k = 0; k < samples; ++k)
            modes[std::size_t(m)] += values[std::size_t(k)] * std::polar(1.0, -2 * kPi * m * k / samples);
    return modes;
}

// A right-handed frame whose third axis is `axis`.
Eigen::Matrix3d frameAbout(const Eigen::Vector3d& axis) {
    const Eigen::Vector3d helper = std::abs(axis.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    Eigen::Matrix3d frame;
    frame.col(0) = axis.cross(helper).normalized();
    frame.col(1) = axis.cross(frame.col(0));
    frame.col(2) = axis;
    return frame;
}

// Candidate maps about a lone principal axis (two equal eigenvalues: a part with a 3-fold or finer axis, a
// cylinder) from one moment function: where f varies about the axis, the turn about it that takes f's rings onto
// g's is the phase of their strongest Fourier mode m over m, up to a multiple of 2 pi / m, for each choice of the
// axis's sign and of the map's handedness. Each candidate is weighed by how far f's rings are from g's turned by
// it, every mode counted, and the closest come first: a mirrored copy of a part that is nearly mirror-symmetric (a
// bolt's thread) matches its turned copies loosely, to be refined in vain before the reflection is tried. False
// where f is invariant about the axis to its noise (no mode tells a turn).
bool ringCandidates(const MomentFunction& f, const Eigen::Vector3d& fromAxis, const MomentFunction& g,
                    const Eigen::Vector3d& toAxis, std::vector<Eigen::Matrix3d>& out) {
    // Off the equator, whose ring is the same about the axis either way up.
    constexpr double kThetas[] = {1.2, 0.8};
    const Eigen::Matrix3d fromFrame = frameAbout(fromAxis);
    const double samples = 2 * f.order() + 2, scale = f.largestValue() * samples;
    std::vector<std::vector<std::complex<double>>> fromRings;
    for (const double theta : kThetas) fromRings.push_back(ringModes(f, fromFrame, theta));
    // The strongest mode on either ring, relative to the function's bound.
    std::size_t ring = 0;
    int mode = 0;
    double strongest = 0;
    for (std::size_t r = 0; r < fromRings.size(); ++r)
        for (int m = 1; m <= f.order(); ++m)
            if (const double amplitude = 2 * std::abs(fromRings[r][std::size_t(m)]) / scale; amplitude > strongest)
                strongest = amplitude, ring = r, mode = m;
    if (!(strongest > kRingModeNoise)) return false;
    std::vector<std::pair<double, Eigen::Matrix3d>> weighed;
    for (const double handedness : {1.0, -1.0})
        for (const double axisSign : {1.0, -1.0}) {
            const Eigen::Matrix3d toFrame =
                frameAbout(axisSign * toAxis) * Eigen::Vector3d(1, handedness, 1).asDiagonal();
            std::vector<std::vector<std::complex<double>>> toRings;
            for (const double theta : kThetas) toRings.push_back(ringModes(g, toFrame, theta));
            // f on a ring at phi is g at phi + delta: c_m(f) = c_m(g) e^(i m delta).
            const std::complex<double> toMode = toRings[ring][std::size_t(mode)];
            if (!(std::abs(toMode) > 0)) continue;
            const double delta = std::arg(fromRings[ring][std::size_t(mode)] / toMode) / mode;
            for (int j = 0; j < mode; ++j) {
                const double turn = delta + 2 * kPi * j / mode;
                double residual = 0;
                for (std::size_t r = 0; r < fromRings.size(); ++r)
                    for (int m = 0; m <= f.order(); ++m)
                        residual += std::abs(fromRings[r][std::size_t(m)] -
                                             toRings[r][std::size_t(m)] * std::polar(1.0, m * turn));
                if (residual > kSameValue * scale) continue;
                weighed.push_back(
                    {residual, toFrame * Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                   fromFrame.transpose()});
            }
        }
    std::stable_sort(weighed.begin(), weighed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [residual, map] : weighed) out.push_back(map);
    return true;
}

}  // namespace

const std::vector<Eigen::Vector3d>& TileProbe::criticalDirections(const MomentFunction& f, int order) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (const auto found = directions_.find(order); found != directions_.end()) return found->second;
    }
    // Found outside the lock: two threads that both find them find the same directions, and the first kept
    // is the one every pair sees (std::map does not move its entries).
    std::vector<Eigen::Vector3d> directions = findCandidateAxes({f}, 1e-4, threads_);
    std::lock_guard<std::mutex> lock(mutex_);
    return directions_.emplace(order, std::move(directions)).first->second;
}

std::optional<FoundIsometry> findIsometry(const TileShape& from, TileProbe& fromProbe, const TileShape& to, TileProbe& toProbe,
                                          double tolerance) {
    const ShapeVerifier& fromVerifier = fromProbe.verifier();
    const ShapeVerifier& toVerifier = toProbe.verifier();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> fromAxes(from.secondMoments), toAxes(to.secondMoments);
    const Eigen::Vector3d& values = fromAxes.eigenvalues();
    const double screening = std::max(2 * tolerance, tolerance + 2e-4 * from.diagonal);
    // The first candidate that passes closely, refined: candidates come in stages, cheapest first. One that
    // passes only loosely (a bolt turned by a sixth of its thread's pitch: its head matches, its thread is off)
    // is kept while the stage's others are tried, and the closest of them returned: a placement the budget
    // accepts at a looser tolerance still spends it.
    auto firstPassing = [&](const std::vector<Eigen::Matrix3d>& candidates) -> std::optional<FoundIsometry> {
        const double close = tolerance / 16;
        // One candidate's measures: screened out, or its deviation as it is and, where that is not close, refined.
        struct Trial {
            bool screened = false;
            double direct = 0, refinedDeviation = 0;
            Eigen::Matrix3d refined = Eigen::Matrix3d::Identity();
        };
        auto measure = [&](const Eigen::Matrix3d& candidate) {
            Trial trial;
            if (fromVerifier.farthestOnto(toVerifier, candidate, screening, 2000) > screening) return trial;
            trial.screened = true;
            // Exact copies pass as they are; refine what does not.
            trial.direct = deviationBetween(fromVerifier, toVerifier, candidate, tolerance);
            if (trial.direct <= close) return trial;
            // The quick map measured on the screening's points: beyond the bound there, it is beyond it on all.
            const Eigen::Matrix3d quick =
                fromVerifier.refineOnto(toVerifier, candidate, 2 * screening, 3, kQuickRefinePoints);
            if (fromVerifier.farthestOnto(toVerifier, quick, kHopeless * tolerance, 2000) > kHopeless * tolerance) {
                trial.refined = candidate;
                trial.refinedDeviation = HUGE_VAL;
                return trial;
            }
            trial.refined = fromVerifier.refineOnto(toVerifier, candidate, 2 * screening);
            trial.refinedDeviation = deviationBetween(fromVerifier, toVerifier, trial.refined, tolerance);
            return trial;
        };
        std::optional<FoundIsometry> best;
        auto keep = [&](const Eigen::Matrix3d& map, double d) {
            if (d <= tolerance && (!best || d < best->deviation)) best = FoundIsometry{map, d};
        };
        // As many candidates at once as there are threads (a nearly round part tries dozens, each refined),
        // then taken in their order, as one at a time would take them.
        const auto batch = std::size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
        for (std::size_t first = 0; first < candidates.size(); first += batch) {
            const std::size_t last = std::min(candidates.size(), first + batch);
            std::vector<Trial> trials(last - first);
            tbb::parallel_for(first, last, [&](std::size_t c) { trials[c - first] = measure(candidates[c]); });
            for (std::size_t c = first; c < last; ++c) {
                const Trial& trial = trials[c - first];
                if (!trial.screened) continue;
                if (trial.direct <= close) return FoundIsometry{candidates[c], trial.direct};
                if (trial.refinedDeviation <= close) return FoundIsometry{trial.refined, trial.refinedDeviation};
                keep(candidates[c], trial.direct);
                keep(trial.refined, trial.refinedDeviation);
            }
        }
        return best;
    };
    std::vector<Eigen::Matrix3d> candidates;
    const double gap = std::min(values[1] - values[0], values[2] - values[1]);
    if (gap > kDistinctEigenvalues * values[2]) {
        principalCandidates(fromAxes.eigenvectors(), toAxes.eigenvectors(), candidates);
        if (auto found = firstPassing(candidates)) return found;
        // A congruent tile's principal frame is then one of the 8 sign choices: when none passes, no frame will.
        if (principalAxesAreCertain(values, tolerance / from.diagonal)) return std::nullopt;
    }
    const int lone = values[1] - values[0] > values[2] - values[1] ? 0 : 2;
    const Eigen::Vector3d axisFrom = fromAxes.eigenvectors().col(lone), axisTo = toAxes.eigenvectors().col(lone);
    // One eigenvalue apart from a pair: the turn about its axis from the moments' Fourier modes about it, order by
    // order (without the critical directions, 400 Newton searches a tile and order). A part whose moments vary about
    // no axis but by its polar angle (a lathe of many sectors) goes to the farthest point across the axis below.
    bool variesAbout = true;
    if (std::max(values[1] - values[0], values[2] - values[1]) > kDistinctEigenvalues * values[2]) {
        variesAbout = false;
        for (int order = 4; order <= from.moments.maxOrder; order += 2) {
            const MomentFunction f(from.moments, order), g(to.moments, order);
            candidates.clear();
            if (!ringCandidates(f, axisFrom, g, axisTo, candidates)) continue;
            variesAbout = true;
            if (auto found = firstPassing(candidates)) return found;
        }
    }
    // Degenerate principal axes: the critical directions of each order in turn (a low order may be
    // invariant about an axis, M_4 of a 6-fold part, and its critical points then lie anywhere on circles).
    for (int order = 4; order <= from.moments.maxOrder && variesAbout; order += 2) {
        const MomentFunction f(from.moments, order), g(to.moments, order);
        if (!(f.relativeVariation() > kNoiseVariation)) continue;
        candidates.clear();
        criticalCandidates(f, fromProbe.criticalDirections(f, order), g, toProbe.criticalDirections(g, order), candidates);
        if (auto found = firstPassing(candidates)) return found;
    }
    // Moments invariant about an axis (a part turned on a lathe, a high-order gear): the axis with the
    // distinct eigenvalue, and the direction across it to the farthest point.
    candidates.clear();
    const Eigen::Matrix3d fromFrame = frameOf(axisFrom, fromVerifier.farthestFromAxis(axisFrom));
    const Eigen::Matrix3d flip = Eigen::Vector3d(1, 1, -1).asDiagonal();
    for (double sa : {1.0, -1.0}) {
        const Eigen::Matrix3d toFrame = frameOf(sa * axisTo, toVerifier.farthestFromAxis(axisTo));
        candidates.push_back(toFrame * fromFrame.transpose());
        candidates.push_back(toFrame * flip * fromFrame.transpose());
    }
    return firstPassing(candidates);
}

}  // namespace symcompress
