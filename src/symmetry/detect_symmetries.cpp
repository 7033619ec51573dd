// The single-shape detector (paper section 5): candidate axes, the maps each axis allows by the moments
// (docs/symmetry.md §2), verification on the shape, refinement, and the group they generate.
#include "symcompress/symmetry.hpp"

#include "geometry/candidate_axes.hpp"
#include "common/with_threads.hpp"
#include "point_group_closure.hpp"
#include "geometry/shape_verifier.hpp"
#include "geometry/bounds.hpp"

#include <tbb/parallel_for.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

namespace symcompress {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRingAngles[] = {0.35, 0.8, 1.2};  // polar angles of the sample rings about an axis
// A moment function whose variation over the sphere is below this, relative to its mean, is constant up
// to the rounding of float32 data (M_2 of a cube) and has no axes to offer; above it even a nearly round
// shape's functions point at its axes.
constexpr double kNoiseVariation = 1e-5;
// How much, relative to its mean, a moment function of a shape symmetric within the tolerance tol may
// differ from symmetric: kMomentSlack * tol, but never more than kVariationShare of the function's own
// variation (else a nearly round shape's moments would allow every map).
constexpr double kMomentSlack = 20;
// A function whose variation is below kInformative * tol could be all asymmetry: it tests nothing.
constexpr double kInformative = 0.1;
constexpr double kVariationShare = 0.3;
// The group's deviations are measured up to this many tolerances (beyond, the first distance found is reported).
constexpr double kDeviationSearch = 10;
// Maps closer than this (Frobenius norm) to an element found already are that element: far below the
// distance between distinct elements, far above the error of a candidate from the moments.
constexpr double kKnownElement = 2e-3;
// Sample points a candidate map is screened on before it is refined.
constexpr std::size_t kScreeningPoints = 2000;
// The sample points whose largest distance bounds from below the d_A of a fold the moments cannot tell.
constexpr std::size_t kFitLowerBoundPoints = 64;
// Folds whose rotation fits within this factor of the best-fitting fold's are preferred (see below), and
// folds within this share of the tolerance fit as well as any: a 96-sector lathe in float32 is 4-fold to the
// last bit but 96-fold only to 3e-8 of its diagonal.
constexpr double kGoodFitFactor = 10;
constexpr double kExactFitShare = 1e-2;
// Beyond this many folds passing the preliminary bound about one axis, none is refined (see below).
constexpr std::size_t kMaxRefinedFolds = 8;
// Beyond this many near misses that would make a finer fold, such maps are refused untested (see below).
constexpr std::size_t kMaxNearMisses = 16;
// A turn (in turns) that is no multiple of 1/n for any small n: 1 - 1/golden ratio.
constexpr double kGenericTurn = 0.3819660112501051;
// A candidate is first refined on this many sample points; beyond this many tolerances from the shape that way
// (on the screening points), it is not refined on all of them.
constexpr std::size_t kRoughRefinementPoints = 256;
constexpr double kRoughMargin = 1.5;
// How far, relative to the diagonal, a candidate from the moments may be from a symmetry before refinement.
constexpr double kPreliminaryMargin = 2e-4;

Eigen::Matrix3d mirrorWithNormal(const Eigen::Vector3d& n) { return Eigen::Matrix3d::Identity() - 2 * n * n.transpose(); }
Eigen::Matrix3d rotationAbout(const Eigen::Vector3d& axis, double angle) {
    return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

// The sines and cosines of the ring points about any axis, and the Fourier factors of the rings: the same
// for every axis of a shape, so computed once per detection rather than once per candidate axis.
class RingLayout {
public:
    explicit RingLayout(int azimuths) : azimuths_(azimuths) {
        modePoints_ = anglesAt(0);
        changePoints_ = anglesAt(0.37);  // off the azimuths of the modes
        // e^(-2 pi i m k / azimuths), row m.
        for (int m = 0; m < azimuths_ / 2; ++m)
            for (int k = 0; k < azimuths_; ++k) twiddles_.push_back(std::polar(1.0, -2 * kPi * m * k / azimuths_));
    }

    // sin(theta), cos(phi), sin(phi), cos(theta) of one ring point.
    struct Angles {
        double sinTheta, cosPhi, sinPhi, cosTheta;
    };
    int azimuths() const { return azimuths_; }
    const std::vector<Angles>& modePoints() const { return modePoints_; }
    const std::vector<Angles>& changePoints() const { return changePoints_; }
    const std::complex<double>& twiddle(int m, int k) const { return twiddles_[std::size_t(m * azimuths_ + k)]; }

private:
    // Ring after ring (each angle of kRingAngles and its mirror about the equator), `azimuths` points on
    // each, the first `offset` of a step from the frame's first axis.
    std::vector<Angles> anglesAt(double offset) const {
        std::vector<Angles> angles;
        for (double theta : kRingAngles)
            for (double ring : {theta, kPi - theta})
                for (int k = 0; k < azimuths_; ++k) {
                    const double phi = 2 * kPi * (k + offset) / azimuths_;
                    angles.push_back({std::sin(ring), std::cos(phi), std::sin(phi), std::cos(ring)});
                }
        return angles;
    }

    int azimuths_;
    std::vector<Angles> modePoints_, changePoints_;
    std::vector<std::complex<double>> twiddles_;
};

// The order in which axis views ask the moment functions: the one that decided the last question first. Any
// order gives the same answers (a map is allowed when every function allows it; the modes' gcd is that of
// every function's), but along a circle of critical points (M_2 of a box with a square section) the same
// function rejects axis after axis, and asking it first spares evaluating the others. One per run of axes that
// one thread examines in turn.
class FunctionOrder {
public:
    explicit FunctionOrder(std::size_t count) : order_(count) {
        std::iota(order_.begin(), order_.end(), std::size_t(0));
    }
    std::size_t size() const { return order_.size(); }
    std::size_t operator[](std::size_t k) const { return order_[k]; }
    // Function order_[k] decided: it is asked first from now on.
    void decided(std::size_t k) {
        std::rotate(order_.begin(), order_.begin() + std::ptrdiff_t(k), order_.begin() + std::ptrdiff_t(k) + 1);
    }

private:
    std::vector<std::size_t> order_;
};

// The moment functions seen from one axis a: values on rings of constant angle to a, which tell which
// rotations about a, mirrors with normal a and rotoreflections about a leave every function unchanged:
// a cheap filter before the shape is asked. Changes are measured relative to each function's largest
// value and compared with that function's own tolerance, so that 1 means "at the tolerance". Most axes
// of a shape with a degenerate function (a circle of critical points) allow nothing, so every answer
// stops as soon as it is known, and the values at the comparison points are computed only when asked.
class AxisView {
public:
    AxisView(const std::vector<MomentFunction>& functions, const std::vector<double>& tolerances,
             const Eigen::Vector3d& axis, const RingLayout& layout, FunctionOrder& order)
        : functions_(functions),
          tolerances_(tolerances),
          axis_(axis),
          layout_(layout),
          order_(order),
          changeValues_(functions.size()),
          changeScales_(functions.size(), 0.0) {
        const Eigen::Vector3d helper = std::abs(axis.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
        u_ = axis.cross(helper).normalized();
        v_ = axis.cross(u_);
        for (const RingLayout::Angles& a : layout_.changePoints()) changePoints_.push_back(direction(a));
    }

    Eigen::Vector3d direction(const RingLayout::Angles& a) const {
        return a.sinTheta * (a.cosPhi * u_ + a.sinPhi * v_) + a.cosTheta * axis_;
    }

    // The gcd of the Fourier modes m about the axis (1 <= m < azimuths / 2) present in some function on
    // some ring, present meaning a relative amplitude above the function's tolerance; 0 when none is.
    // The moments allow n-fold rotations for n dividing it: once it is 1, no further mode changes it.
    int presentModes() const {
        const int azimuths = layout_.azimuths();
        std::vector<Eigen::Vector3d> points;  // the same for every function
        for (const RingLayout::Angles& a : layout_.modePoints()) points.push_back(direction(a));
        std::vector<char> present(std::size_t(azimuths / 2), 0);
        int modes = 0;
        std::vector<double> values(static_cast<std::size_t>(azimuths));
        for (std::size_t k = 0; k < order_.size(); ++k) {
            const std::size_t i = order_[k];
            for (std::size_t first = 0; first < points.size(); first += std::size_t(azimuths)) {
                functions_[i].polynomial().evaluate(&points[first], std::size_t(azimuths), values.data());
                double energy = 0;
                for (int k = 0; k < azimuths; ++k) energy += values[k] * values[k];
                for (int m = 1; m < azimuths / 2; ++m) {
                    if (present[m]) continue;
                    std::complex<double> mode = 0;
                    for (int k = 0; k < azimuths; ++k) mode += values[k] * layout_.twiddle(m, k);
                    // Parseval: the pair (m, -m) carries 2 |mode|^2 / K of the ring's energy.
                    const double relative = std::sqrt(2 * std::norm(mode) / (azimuths * energy));
                    if (relative / tolerances_[i] > 1) {
                        present[m] = 1;
                        modes = std::gcd(modes, m);
                    }
                }
                if (modes == 1) {
                    order_.decided(k);
                    return 1;
                }
            }
        }
        return modes;
    }

    // Whether w -> linear w changes every function by at most its tolerance at the comparison points.
    bool allows(const Eigen::Matrix3d& linear) const {
        Eigen::Vector3d mapped[kChunk];
        double after[kChunk];
        for (std::size_t k = 0; k < order_.size(); ++k) {
            const std::size_t i = order_[k];
            if (changeValues_[i].empty() && changesBeyondBound(i, linear)) {
                order_.decided(k);
                return false;
            }
            const std::vector<double>& before = changeValuesOf(i);
            for (std::size_t first = 0; first < changePoints_.size(); first += kChunk) {
                const std::size_t count = std::min(kChunk, changePoints_.size() - first);
                for (std::size_t j = 0; j < count; ++j) mapped[j] = linear * changePoints_[first + j];
                functions_[i].polynomial().evaluate(mapped, count, after);
                for (std::size_t j = 0; j < count; ++j)
                    if (std::abs(after[j] - before[first + j]) / changeScales_[i] / tolerances_[i] > 1) {
                        order_.decided(k);
                        return false;
                    }
            }
        }
        return true;
    }

private:
    // A few points at a time (evaluated side by side), in order.
    static constexpr std::size_t kChunk = 8;

    // Whether the map changes function i, at one of the first comparison points, by more than its tolerance
    // of the function's bound on the sphere: then by more than its tolerance of its largest value at the
    // comparison points too (their scale, for which the function must be evaluated at every one of them).
    bool changesBeyondBound(std::size_t i, const Eigen::Matrix3d& linear) const {
        const std::size_t count = std::min(kChunk, changePoints_.size());
        Eigen::Vector3d mapped[kChunk];
        double before[kChunk], after[kChunk];
        for (std::size_t j = 0; j < count; ++j) mapped[j] = linear * changePoints_[j];
        functions_[i].polynomial().evaluate(changePoints_.data(), count, before);
        functions_[i].polynomial().evaluate(mapped, count, after);
        const double limit = tolerances_[i] * functions_[i].largestValue();
        for (std::size_t j = 0; j < count; ++j)
            if (std::abs(after[j] - before[j]) > limit) return true;
        return false;
    }

    // Function i at the comparison points, and its largest magnitude there: the same for every map tried.
    const std::vector<double>& changeValuesOf(std::size_t i) const {
        std::vector<double>& values = changeValues_[i];
        if (values.empty()) {
            values.resize(changePoints_.size());
            functions_[i].polynomial().evaluate(changePoints_.data(), changePoints_.size(), values.data());
            double scale = 0;
            for (const double value : values) scale = std::max(scale, std::abs(value));
            changeScales_[i] = scale;
        }
        return values;
    }

    const std::vector<MomentFunction>& functions_;
    const std::vector<double>& tolerances_;
    Eigen::Vector3d axis_, u_, v_;
    const RingLayout& layout_;
    FunctionOrder& order_;
    std::vector<Eigen::Vector3d> changePoints_;
    mutable std::vector<std::vector<double>> changeValues_;  // per function, at changePoints_, when first asked
    mutable std::vector<double> changeScales_;               // per function, its largest magnitude there
};

bool sameAxis(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::abs(a.dot(b)) > 1 - 1e-6; }

// Whether `r` is a rotation by a smaller angle than the smallest turn about its axis among `smallestTurns`.
bool turnsFiner(const Symmetry& r, const std::vector<Symmetry>& smallestTurns) {
    if (r.kind != Symmetry::Kind::Rotation) return false;
    return std::any_of(smallestTurns.begin(), smallestTurns.end(), [&](const Symmetry& smallest) {
        return sameAxis(r.axis, smallest.axis) && r.angle < smallest.angle - 1e-3;
    });
}

std::vector<int> divisorsDescending(int n) {
    std::vector<int> divisors;
    for (int d = n; d >= 2; --d)
        if (n % d == 0) divisors.push_back(d);
    return divisors;
}

// The principal axes of the second moments (order 2 function f(w) = w^T M w) when their moments are
// clearly distinct; else nothing.
std::optional<std::vector<Eigen::Vector3d>> distinctPrincipalAxes(const MomentCoefficients& coefficients, double tolerance) {
    const MomentFunction f(coefficients, 2);
    Eigen::Matrix3d m;
    const Eigen::Matrix3d unit = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i) m(i, i) = f.value(unit.col(i));
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            m(i, j) = m(j, i) = f.value((unit.col(i) + unit.col(j)).normalized()) - (m(i, i) + m(j, j)) / 2;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);
    const Eigen::Vector3d values = solver.eigenvalues();
    if (!principalAxesAreCertain(values, tolerance)) return std::nullopt;  // else a subgroup of D2h about them
    return std::vector<Eigen::Vector3d>{solver.eigenvectors().col(0), solver.eigenvectors().col(1), solver.eigenvectors().col(2)};
}

// Every element described, with its d_A into group.elements. d_A of g and of its inverse are the same number:
// one of each pair is measured. Products of accepted maps stay within a few tolerances; searching only that
// far keeps each query short.
void measureElementDeviations(const ShapeVerifier& verifier, const std::vector<Eigen::Matrix3d>& elements,
                              const std::vector<Eigen::Matrix3d>& accepted,
                              const std::vector<double>& acceptedDeviations, double tolerance, int threads,
                              SymmetryGroup& group) {
    std::vector<std::size_t> inverse(elements.size());
    for (std::size_t i = 0; i < elements.size(); ++i) {
        inverse[i] = i;
        for (std::size_t j = 0; j < elements.size(); ++j)
            if ((elements[j] - elements[i].transpose()).norm() < 1e-6) inverse[i] = j;
    }
    const double searchRadius = kDeviationSearch * tolerance;
    // A generator's d_A was measured in full when it was accepted (every point within the tolerance, so
    // every distance exact): the same number as a search up to searchRadius gives, unless sample points
    // answer for the surface at distances that search would let them.
    auto measuredOnAcceptance = [&](const Eigen::Matrix3d& element) -> std::optional<double> {
        if (!verifier.exactUpTo(tolerance)) return std::nullopt;
        for (std::size_t g = 0; g < accepted.size(); ++g)
            if (accepted[g] == element) return acceptedDeviations[g];
        return std::nullopt;
    };
    withThreads(threads, [&] {
        tbb::parallel_for(std::size_t(0), elements.size(), [&](std::size_t i) {
            group.elements[i] = describeOrthogonal(elements[i]);
            if (group.elements[i].kind == Symmetry::Kind::Identity || inverse[i] < i) return;
            const std::optional<double> known = measuredOnAcceptance(elements[i]);
            group.elements[i].deviation =
                (known ? *known : verifier.deviation(elements[i], searchRadius)) / group.diagonal;
        });
    });
    for (std::size_t i = 0; i < elements.size(); ++i)
        if (inverse[i] < i) group.elements[i].deviation = group.elements[inverse[i]].deviation;
}

}  // namespace

SymmetryGroup detectSymmetries(const TriangleMesh& mesh, const SymmetryOptions& options) {
    SymmetryGroup group;
    group.elements.push_back(Symmetry{});
    if (mesh.triangles.empty()) {
        group.warnings.push_back("the shape has no triangles: only the identity");
        return group;
    }
    const Eigen::AlignedBox3d box = boundsOfCorners(mesh.positions, mesh.triangles);
    group.diagonal = box.diagonal().norm();

    MomentOptions momentOptions;
    momentOptions.maxOrder = options.maxOrder;
    momentOptions.threads = options.threads;
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };
    Clock::time_point start = Clock::now();
    MomentCoefficients coefficients = computeMomentCoefficients(mesh, momentOptions);
    group.centroid = coefficients.centroid;
    if (!(coefficients.area > 0) || !(group.diagonal > 0)) {
        group.warnings.push_back("the shape has no area (all its points are collinear): only the identity");
        return group;
    }
    const double tolerance = options.tolerance * group.diagonal;
    // How far the moments of a shape symmetric within the tolerance may be from symmetric, relatively.

    // The informative moment functions; orders whose function is constant say nothing about axes.
    auto informative = [&](const MomentCoefficients& c) {
        std::vector<MomentFunction> functions;
        for (int order = 2; order <= c.maxOrder; order += 2) {
            MomentFunction f(c, order);
            if (f.relativeVariation() > kNoiseVariation) functions.push_back(std::move(f));
        }
        return functions;
    };
    std::vector<MomentFunction> functions = informative(coefficients);
    if (functions.empty() && options.maxOrder < 16) {
        momentOptions.maxOrder = 16;
        coefficients = computeMomentCoefficients(mesh, momentOptions);
        functions = informative(coefficients);
    }
    const int maxOrder = coefficients.maxOrder;
    // The functions whose variation exceeds what asymmetry within the tolerance (noise, say) could make
    // test the maps about each axis, each with its own tolerance.
    std::vector<MomentFunction> tests;
    std::vector<double> momentTolerances;
    for (const MomentFunction& f : functions)
        if (f.relativeVariation() > kInformative * options.tolerance) {
            tests.push_back(f);
            momentTolerances.push_back(std::min(kMomentSlack * options.tolerance, kVariationShare * f.relativeVariation()));
        }
    if (tests.empty()) {
        group.warnings.push_back("the shape is nearly round at this tolerance: no moment function up to order " +
                                 std::to_string(maxOrder) + " varies more than the tolerance allows, so no axis can "
                                 "be told apart (try a tighter --tolerance)");
        functions.clear();
    }
    group.seconds.moments = since(start);
    start = Clock::now();
    const auto principal = distinctPrincipalAxes(coefficients, options.tolerance);
    const std::vector<Eigen::Vector3d> axes = principal ? *principal : findCandidateAxes(functions, std::max(1e-4, options.tolerance), options.threads);
    group.seconds.axes = since(start);
    start = Clock::now();
    const ShapeVerifier verifier(mesh, group.centroid);
    // Candidates come from the moments, whose critical points the data's rounding moves a little: a map is
    // first taken within a looser bound, then refined on the data, made exact again (same kind and angle
    // about the refined axis) and kept only within the tolerance.
    const double preliminary = std::max(2 * tolerance, tolerance + kPreliminaryMargin * group.diagonal);
    auto refined = [&](const Eigen::Matrix3d& map, std::size_t points = SIZE_MAX) -> Eigen::Matrix3d {
        const Symmetry before = describeOrthogonal(map);
        if (before.kind == Symmetry::Kind::Inversion) return map;
        // Only the refined axis is kept (a refined mirror may come out as a rotoreflection by a tiny angle).
        const Symmetry after = describeOrthogonal(verifier.refine(map, 2 * preliminary, 6, points));
        if (after.kind == Symmetry::Kind::Identity || after.kind == Symmetry::Kind::Inversion ||
            std::abs(after.axis.dot(before.axis)) < 0.99)
            return map;
        const Eigen::Vector3d axis = after.axis.dot(before.axis) < 0 ? Eigen::Vector3d(-after.axis) : after.axis;
        if (before.kind == Symmetry::Kind::Mirror) return mirrorWithNormal(axis);
        if (before.kind == Symmetry::Kind::Rotation) return rotationAbout(axis, before.angle);
        return rotationAbout(axis, before.angle) * mirrorWithNormal(axis);
    };
    std::vector<Eigen::Matrix3d> generators;
    std::vector<double> generatorDeviations;  // generators[i]'s d_A, as measured when it was accepted
    std::vector<Eigen::Vector3d> revolutionAxes;
    std::vector<Eigen::Matrix3d> known{Eigen::Matrix3d::Identity()};  // the group the generators so far make
    // The smallest turn of a group about each of its rotation axes, one for each axis.
    auto smallestTurnsOf = [](const std::vector<Eigen::Matrix3d>& elements) {
        std::vector<Symmetry> smallest;
        for (const Eigen::Matrix3d& g : elements) {
            const Symmetry r = describeOrthogonal(g);
            if (r.kind != Symmetry::Kind::Rotation) continue;
            const auto same = std::find_if(smallest.begin(), smallest.end(),
                                           [&](const Symmetry& t) { return sameAxis(t.axis, r.axis); });
            if (same == smallest.end())
                smallest.push_back(r);
            else if (r.angle < same->angle)
                *same = r;
        }
        return smallest;
    };
    std::vector<Symmetry> knownTurns;  // smallestTurnsOf(known), kept with it
    // Whether `closed` turns by a smaller angle than `known` does about some rotation axis of `known`.
    auto refinesAFold = [&](const std::vector<Eigen::Matrix3d>& closed) {
        return std::any_of(closed.begin(), closed.end(),
                           [&](const Eigen::Matrix3d& g) { return turnsFiner(describeOrthogonal(g), knownTurns); });
    };
    auto inKnown = [&](const Eigen::Matrix3d& map) {
        return std::any_of(known.begin(), known.end(), [&](const Eigen::Matrix3d& g) { return (g - map).norm() < kKnownElement; });
    };
    // A map already in the group found so far needs no test (several axes lead to the same elements); a
    // new one is screened on a few sample points, refined, and verified on all of them.
    const std::size_t limit = 4 * std::size_t(options.maxFold) + 8;
    // Near misses tend to fail at the same sample points: each axis's work remembers them (`hints`).
    // `refinementsLeft`, where given, counts down the refinements that may still fail about one axis: once
    // none is left, maps pass only as they are. A shape within the tolerance of a surface of revolution takes
    // a fold of hundreds, and with it hundreds of directions across the axis, each passing the screening and
    // failing only once refined (an unevenly tessellated roller: 1600 refinements, 15 s).
    // A map that would make a finer fold about an axis of the group so far must fit exactly (see below). Near a
    // surface of revolution hundreds of maps do, each a near miss screened and refined in vain (the house's round
    // parts: 270 in one), so once this many have failed, such maps are refused as they come.
    int nearMissesLeft = int(kMaxNearMisses);
    auto refinesWith = [&](const Eigen::Matrix3d& map) {
        // A finer turn about an axis of the group so far, as the map, its products with the group's elements or
        // their squares, refines its fold without closing the group anew (a pole near a surface of revolution
        // tries hundreds of turns and directions across it, each closing a group of hundreds).
        auto finer = [&](const Eigen::Matrix3d& g) {
            return turnsFiner(describeOrthogonal(g), knownTurns) || turnsFiner(describeOrthogonal(g * g), knownTurns);
        };
        if (finer(map) || std::any_of(known.begin(), known.end(),
                                      [&](const Eigen::Matrix3d& k) { return finer(map * k) || finer(k * map); }))
            return true;
        std::vector<Eigen::Matrix3d> with = generators;
        with.push_back(map);
        return refinesAFold(closeGroup(std::move(with), limit));
    };
    // Whether tryAccept refuses the map without testing it on the shape.
    auto refusedUntested = [&](const Eigen::Matrix3d& map) {
        return !inKnown(map) && nearMissesLeft == 0 && refinesWith(map);
    };
    auto tryAccept = [&](const Eigen::Matrix3d& map, RejectingPoints* hints, int* refinementsLeft = nullptr) {
        if (inKnown(map)) return true;
        if (refusedUntested(map)) return false;
        if (verifier.deviation(map, preliminary, kScreeningPoints, hints) > preliminary) return false;
        bool refine = !refinementsLeft || *refinementsLeft > 0;
        const Eigen::Matrix3d rough = refine ? refined(map, kRoughRefinementPoints) : map;
        // Refined on a few sample points onto an element found already, it is that element: refined and verified in
        // full, it would add nothing.
        if (refine && inKnown(rough)) return true;
        // A map that would make a finer fold about an axis of the group so far must fit exactly, not only within the
        // tolerance (see below): a near miss fails that at its first sample points.
        const double bound = refinesWith(rough) ? kExactFitShare * tolerance : tolerance;
        // A near miss fails as well refined on a few sample points as on all of them: one that fails that way by a
        // margin is not refined in full (a roller near a surface of revolution spent half its time on those).
        const bool failsRoughly =
            refine && verifier.deviation(rough, kRoughMargin * bound, kScreeningPoints, hints) > kRoughMargin * bound;
        if (failsRoughly) refine = false;
        Eigen::Matrix3d best = refine ? refined(map) : map;
        double deviation = verifier.deviation(best, bound, SIZE_MAX, hints);
        if (deviation > bound && refine) {
            deviation = verifier.deviation(map, bound, SIZE_MAX, hints);
            best = map;
        }
        auto rejected = [&] {
            if ((refine || failsRoughly) && refinementsLeft) --*refinementsLeft;
            if (bound < tolerance && nearMissesLeft > 0) --nearMissesLeft;
            return false;
        };
        if (deviation > bound) return rejected();
        // A map refined onto an element the group already has adds nothing to it (a nearly round shape's
        // directions across its axis: dozens of them, each closing a group of hundreds again).
        if (inKnown(best)) return true;
        generators.push_back(best);
        std::vector<Eigen::Matrix3d> closed = closeGroup(generators, limit);
        // The symmetries of a bounded shape make a finite group: a map that, with those verified before it, makes
        // none is a near miss, not a symmetry. So is one that only fits loosely and makes a finer fold about an axis
        // of the group so far: on a shape near a surface of revolution, a mirror 0.09 degrees off one of a
        // 128-sector lathe's fits within 2.5e-5 of its diagonal, and so does one halfway between two of a
        // 256-sector lathe's mirrors, which with them makes a turn by half a sector.
        if (closed.size() > limit || closed.size() % known.size() != 0 ||
            (deviation > kExactFitShare * tolerance && refinesAFold(closed))) {
            generators.pop_back();
            return rejected();
        }
        generatorDeviations.push_back(deviation);
        known = std::move(closed);
        knownTurns = smallestTurnsOf(known);
        return true;
    };

    // Every map the moments allow about each axis, tested on the shape; the largest fold per axis.
    const RingLayout layout(2 * maxOrder + 2);
    withThreads(options.threads, [&] {
        // The largest fold up to maxFold whose rotation about the axis, and its power nearest a generic turn,
        // fit within `bound`, or 1. Near a surface of revolution a turn close to the fold's fits nearly as well
        // as the fold's (a 256-sector lathe turned by 1/260 moves its points along its surface), its powers do not.
        // A fold's largest distance over the first sample points bounds its d_A from below.
        auto largestFoldWithin = [&](const Eigen::Vector3d& axis, double bound, RejectingPoints& hints) {
            auto fits = [&](double turn, std::size_t points) {
                return verifier.deviation(rotationAbout(axis, 2 * kPi * turn), bound, points, &hints) <= bound;
            };
            for (int n = options.maxFold; n >= 2; --n) {
                const int power = int(std::lround(n * kGenericTurn));
                const double powerTurn = power % n == 0 ? 1.0 / n : double(power) / n;
                if (fits(1.0 / n, kFitLowerBoundPoints) && fits(powerTurn, kFitLowerBoundPoints) &&
                    fits(1.0 / n, SIZE_MAX) && fits(powerTurn, SIZE_MAX))
                    return n;
            }
            return 1;
        };
        auto examineAxis = [&](const Eigen::Vector3d& axis, FunctionOrder& order) {
            const AxisView view(tests, momentTolerances, axis, layout, order);
            RejectingPoints hints;                  // decisions only: never for a distance that is reported
            const int modes = view.presentModes();  // the moments allow n-fold rotations for n dividing it
            std::vector<int> folds;
            bool nearRevolution = false;
            if (modes == 0) {  // invariant under every rotation about the axis: find n on the shape
                // Unless the shape itself is, within the tolerance, invariant under a rotation by an angle
                // that belongs to no small fold. Its tessellation's fold, if any, is the largest that fits far
                // better than such a turn (a 256-sector lathe in float32: 3e-8 of its diagonal against 2e-5);
                // a surface of revolution has none to report.
                if (const double generic =
                        verifier.deviation(rotationAbout(axis, 2 * kPi * kGenericTurn), tolerance, SIZE_MAX, &hints);
                    generic <= tolerance) {
                    const int n = largestFoldWithin(axis, generic / kGoodFitFactor, hints);
                    if (n == 1) {
                        revolutionAxes.push_back(axis);
                        return;
                    }
                    folds = {n};
                    nearRevolution = true;
                } else {
                    for (int n = options.maxFold; n >= 2; --n) folds.push_back(n);
                }
            } else {
                folds = divisorsDescending(modes);
            }
            // A fold's d_A measured in full at the tolerance (above it: not a symmetry), once.
            std::map<int, double> fullFit;
            auto measuredFit = [&](int n) {
                const auto known = fullFit.find(n);
                if (known != fullFit.end()) return known->second;
                return fullFit[n] = verifier.deviation(rotationAbout(axis, 2 * kPi / n), tolerance, SIZE_MAX, &hints);
            };
            bool measureWhenTried = false;  // `folds` holds folds not yet measured in full
            // The first `mayFitWell` folds are tried first where they fit within `goodFit`; the others, those among
            // them that do not fit that well included, after them, largest first.
            std::size_t mayFitWell = 0;
            double goodFit = tolerance;
            if (modes == 0 && !nearRevolution) {
                // Folds the moments cannot tell. A fold's largest distance over the first sample points is a lower
                // bound of its d_A: a fold above the bound it is measured against fails without more.
                std::vector<std::pair<double, int>> lowerBounds;  // (lower bound, n), up to the preliminary bound
                for (int n : folds)
                    if (const double d = verifier.deviation(rotationAbout(axis, 2 * kPi / n), preliminary,
                                                            kFitLowerBoundPoints, &hints);
                        d <= preliminary)
                        lowerBounds.push_back({d, n});
                // The folds within the preliminary bound, refined when tried: while at most kMaxRefinedFolds do,
                // they are the ones tried. Once more do (or for a nearly round shape: a generic turn within the
                // preliminary bound), refining each would cost too much: only the folds within the tolerance
                // count, and must pass as they are.
                std::map<int, double> preliminaryFit;
                bool strict = verifier.deviation(rotationAbout(axis, 2 * kPi * kGenericTurn), preliminary, SIZE_MAX,
                                                 &hints) <= preliminary;
                // Screened first: a fold that fails on the screening points fails in full, and too many passing make
                // the search strict without a measure in full of any (a 64-sector lathe is within the preliminary
                // bound of 360-fold to 330-fold: 80 ms each on its 51136 triangles).
                std::vector<int> screened;  // largest n first
                for (std::size_t i = 0; i < lowerBounds.size() && !strict; ++i) {
                    const int n = lowerBounds[i].second;
                    if (verifier.deviation(rotationAbout(axis, 2 * kPi / n), preliminary, kScreeningPoints, &hints) <=
                        preliminary) {
                        screened.push_back(n);
                        strict = screened.size() > kMaxRefinedFolds;
                    }
                }
                // A fold n measured to fit within d makes its divisor m fit within (n / m) d (the turn's power). Once
                // some fold fits far within the share of the tolerance below which every fold is as good as any, a
                // divisor that bound puts well within that share is not measured (a 64-fold lathe's 32, 16, ..., 2).
                const double asGoodAsAny = kExactFitShare * tolerance;
                std::map<int, double> measured;
                auto boundFromMultiple = [&](int m) -> std::optional<double> {
                    for (const auto& [n, d] : measured)
                        if (kGoodFitFactor * d <= asGoodAsAny && n % m == 0 && (n / m) * d <= asGoodAsAny / 2)
                            return (n / m) * d;
                    return std::nullopt;
                };
                for (std::size_t i = 0; i < (strict ? 0 : screened.size()); ++i) {
                    const int n = screened[i];
                    std::optional<double> d = boundFromMultiple(n);
                    if (!d)
                        d = measured[n] =
                            verifier.deviation(rotationAbout(axis, 2 * kPi / n), preliminary, SIZE_MAX, &hints);
                    if (*d <= preliminary) preliminaryFit[n] = *d;
                }
                // A 24-sided part is within a loose tolerance of 360-fold too: the folds that fit best (within a
                // factor of the best fit) come first, the largest of them first, then the others that fit.
                auto bestFirst = [&](std::vector<int>& best, std::vector<int>& others) {
                    std::sort(best.begin(), best.end(), std::greater<int>());
                    std::sort(others.begin(), others.end(), std::greater<int>());
                    folds = best;
                    folds.insert(folds.end(), others.begin(), others.end());
                };
                std::vector<int> best, others;
                if (!strict) {
                    double bestFit = std::numeric_limits<double>::infinity();
                    for (const auto& [n, d] : preliminaryFit) bestFit = std::min(bestFit, d);
                    const double good = std::max(kGoodFitFactor * bestFit, kExactFitShare * tolerance);
                    for (const auto& [n, d] : preliminaryFit) (d <= good ? best : others).push_back(n);
                    bestFirst(best, others);
                } else {
                    // Measured in full at the tolerance in the order of their lower bounds, until the best fit is
                    // known (where even the smallest lower bound is within the factor of the tolerance, every
                    // fold that fits is as good as any); the others only when the loop below reaches them (it
                    // stops at the first accepted, and refuses near misses untested once enough have failed).
                    lowerBounds.erase(std::remove_if(lowerBounds.begin(), lowerBounds.end(),
                                                     [&](const auto& bound) { return bound.first > tolerance; }),
                                      lowerBounds.end());
                    std::stable_sort(lowerBounds.begin(), lowerBounds.end(),
                                     [](const auto& a, const auto& b) { return a.first < b.first; });
                    double bestFit = lowerBounds.empty() ? 0 : lowerBounds.front().first;
                    if (kGoodFitFactor * bestFit < tolerance) {
                        bestFit = std::numeric_limits<double>::infinity();
                        for (const auto& [lower, n] : lowerBounds) {
                            if (bestFit <= lower) break;
                            if (const double d = measuredFit(n); d <= tolerance) bestFit = std::min(bestFit, d);
                        }
                    }
                    const double good =
                        std::min(std::max(kGoodFitFactor * bestFit, kExactFitShare * tolerance), tolerance);
                    for (const auto& [lower, n] : lowerBounds)
                        (good == tolerance || lower <= good ? best : others).push_back(n);
                    bestFirst(best, others);
                    measureWhenTried = true;
                    if (good < tolerance) {
                        goodFit = good;
                        mayFitWell = best.size();
                    }
                }
            }
            int fold = 1;
            // An n-fold rotation's powers are symmetries too: about an axis the moments cannot tell, the power
            // nearest a half turn must fit as well. A shape near a surface of revolution fits small turns
            // (a degree moves its points less than the tolerance) and not large ones: no fold, not C360.
            auto powersFit = [&](int n) {
                return modes != 0 || n / 2 <= 1 ||
                       verifier.deviation(rotationAbout(axis, 2 * kPi * (n / 2) / n), tolerance, SIZE_MAX, &hints) <=
                           tolerance;
            };
            auto accepted = [&](int n) {
                const Eigen::Matrix3d rotation = rotationAbout(axis, 2 * kPi / n);
                if (refusedUntested(rotation) || (measureWhenTried && measuredFit(n) > tolerance)) return false;
                return (modes == 0 || view.allows(rotation)) && powersFit(n) && tryAccept(rotation, &hints);
            };
            // A fold refused untested is not measured: near a surface of revolution, hundreds would be.
            std::vector<int> later(folds.begin() + std::ptrdiff_t(mayFitWell), folds.end());
            for (std::size_t i = 0; i < mayFitWell && fold == 1; ++i) {
                const int n = folds[i];
                if (refusedUntested(rotationAbout(axis, 2 * kPi / n))) continue;
                if (measuredFit(n) > goodFit)
                    later.push_back(n);
                else if (accepted(n))
                    fold = n;
            }
            if (mayFitWell > 0) std::sort(later.begin(), later.end(), std::greater<int>());
            for (std::size_t i = 0; i < later.size() && fold == 1; ++i)
                if (accepted(later[i])) fold = later[i];
            const Eigen::Matrix3d mirror = mirrorWithNormal(axis);
            int refinementsLeft = int(kMaxRefinedFolds);  // of the maps below that may fail
            if (view.allows(mirror)) tryAccept(mirror, &hints, &refinementsLeft);
            // A rotoreflection by pi / k squares to the rotation by 2 pi / k: k divides the fold.
            for (int k : divisorsDescending(fold)) {
                const Eigen::Matrix3d rotoreflection = rotationAbout(axis, kPi / k) * mirror;
                if (view.allows(rotoreflection) && tryAccept(rotoreflection, &hints, &refinementsLeft)) break;
            }
            // Moments invariant about the axis cannot point at the 2-fold axes and mirror normals across
            // it (all directions across are alike to them): try the directions through the farthest
            // point from the axis, and between them, at steps of pi / (2 fold).
            if (modes == 0 && fold > 1) {
                const Eigen::Vector3d across = verifier.farthestFromAxis(axis);
                // Once the refinements are spent on near misses, the directions left (hundreds for a fold of
                // hundreds) would only be near misses too.
                for (int k = 0; k < 2 * fold && refinementsLeft > 0; ++k) {
                    const Eigen::Vector3d d = rotationAbout(axis, k * kPi / (2 * fold)) * across;
                    tryAccept(rotationAbout(d, kPi), &hints, &refinementsLeft);
                    tryAccept(mirrorWithNormal(d), &hints, &refinementsLeft);
                }
            }
        };
        // The axes one after the other, each taking what the ones before it found: the group is the same on any
        // number of threads, which share each axis's measures instead (ShapeVerifier).
        FunctionOrder order(tests.size());
        for (const Eigen::Vector3d& axis : axes) examineAxis(axis, order);
    });
    tryAccept(-Eigen::Matrix3d::Identity(), nullptr);
    if (!revolutionAxes.empty())
        group.warnings.push_back("at this tolerance the shape is a surface of revolution about " +
                                 std::to_string(revolutionAxes.size()) +
                                 " axis(es): rotations by every angle fit, so no finite fold is reported for them");
    const std::vector<Eigen::Matrix3d> accepted = generators;  // in the order of generatorDeviations
    std::sort(generators.begin(), generators.end(), [](const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
        return a.determinant() > b.determinant();  // rotations first: a stable, readable order
    });

    std::vector<Eigen::Matrix3d> elements = closeGroup(generators, limit);
    if (elements.size() > limit) elements = known;  // the same group, within the rounding of its products
    elements = averagedOverGroup(elements);
    group.name = pointGroupName(elements);

    // Every element with its deviation, and the fold of each rotation axis.
    group.elements.assign(elements.size(), Symmetry{});
    if (options.elementDeviations)
        measureElementDeviations(verifier, elements, accepted, generatorDeviations, tolerance, options.threads, group);
    else
        for (std::size_t i = 0; i < elements.size(); ++i) {
            group.elements[i] = describeOrthogonal(elements[i]);
            if (group.elements[i].kind != Symmetry::Kind::Identity)
                group.elements[i].deviation = std::numeric_limits<double>::quiet_NaN();
        }
    for (Symmetry& s : group.elements) {
        if (s.kind != Symmetry::Kind::Rotation) continue;
        s.fold = 1;
        for (const Symmetry& other : group.elements)
            if (other.kind == Symmetry::Kind::Rotation && std::abs(std::abs(other.axis.dot(s.axis)) - 1) < 1e-6) ++s.fold;
    }
    group.seconds.verification = since(start);
    return group;
}

}  // namespace symcompress
