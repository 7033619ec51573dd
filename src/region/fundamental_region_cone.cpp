// The Dirichlet cone of a seed (docs/fundamental-regions.md, "The cone construction") and the choice of the seed that
// cuts fewest triangles.
#include "fundamental_region_parts.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

namespace symcompress::region_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Seeds closer than this (relative) to a fixed set of some element give ill-conditioned planes.
constexpr double kMinimumSeparation = 1e-2;

// Whether the plane of normals[k] carries a 2D face of the cone: some direction in the plane satisfies
// every other half-space strictly. The directions allowed by one half-space form a half-circle of the
// plane; intersecting half-circles one by one keeps a single arc (an arc of at most half a turn meets a
// half-circle in one piece), so the test is linear in the number of planes.
bool boundsCone(const std::vector<Eigen::Vector3d>& normals, std::size_t k) {
    const Eigen::Vector3d& n = normals[k];
    const Eigen::Vector3d u = n.unitOrthogonal();
    const Eigen::Vector3d v = n.cross(u);
    double start = 0, length = 2 * kPi;  // the arc of allowed directions, by angle in the (u, v) plane
    for (std::size_t l = 0; l < normals.size(); ++l) {
        if (l == k) continue;
        const Eigen::Vector2d w(normals[l].dot(u), normals[l].dot(v));
        if (w.norm() < 1e-12) {
            if (normals[l].dot(n) < 0) return false;  // the cone is flat; cannot happen for a valid seed
            if (l < k) return false;                  // the same plane twice: the first one bounds
            continue;
        }
        const double halfStart = std::atan2(w.y(), w.x()) - kPi / 2;  // the half-circle [halfStart, + pi]
        if (length > kPi) {                                           // the first constraint
            start = halfStart;
            length = kPi;
            continue;
        }
        const double offset = std::fmod(std::fmod(halfStart - start, 2 * kPi) + 2 * kPi, 2 * kPi);
        double from, to;
        if (offset < length) {
            from = offset;
            to = std::min(length, offset + kPi);
        } else if (offset > kPi) {
            from = 0;
            to = std::min(length, offset - kPi);
        } else {
            return false;
        }
        start += from;
        length = to - from;
        if (length <= 1e-9) return false;
    }
    return true;
}

// A uniform double in [0, 1) from the generator's raw bits (portable, unlike std distributions).
double unitInterval(std::mt19937_64& generator) { return static_cast<double>(generator() >> 11) * 0x1.0p-53; }

Eigen::Vector3d randomDirection(std::mt19937_64& generator) {
    const double z = 2 * unitInterval(generator) - 1;
    const double phi = 2 * kPi * unitInterval(generator);
    const double r = std::sqrt(std::max(0.0, 1 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Indices 0, stride, 2 stride, ... : at most `limit` of `count`, spread evenly.
std::vector<std::size_t> evenSample(std::size_t count, std::size_t limit) {
    std::vector<std::size_t> picked;
    if (count == 0 || limit == 0) return picked;
    const std::size_t taken = std::min(count, limit);
    picked.reserve(taken);
    for (std::size_t i = 0; i < taken; ++i) picked.push_back(i * count / taken);
    return picked;
}

// The proper rotations of the group with their axis and angle in (0, pi].
struct Rotation {
    Eigen::Vector3d axis;
    double angle;
};

std::vector<Rotation> properRotations(const std::vector<Eigen::Matrix3d>& nonIdentity) {
    std::vector<Rotation> rotations;
    for (const Eigen::Matrix3d& g : nonIdentity) {
        if (g.determinant() <= 0) continue;
        const double cosine = std::clamp((g.trace() - 1) / 2, -1.0, 1.0);
        const double angle = std::acos(cosine);
        const std::optional<Eigen::Vector3d> axis = elementAxis(g);
        if (axis && angle > 1e-6) rotations.push_back({*axis, angle});
    }
    return rotations;
}

// Seeds in a fixed order: random directions, centroid directions, then for every rotation by angle t
// about a, vertices turned by -t/2 and +t/2 so that the bisector plane of the seed and its image (the
// plane through a at half the angle) passes through the vertex and possibly along the mesh's edges.
std::vector<Eigen::Vector3d> seedCandidates(const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                                            const Eigen::Vector3d& centre, const RegionOptions& options) {
    std::vector<Eigen::Vector3d> candidates;
    std::mt19937_64 generator(options.randomSeed);
    for (std::size_t i = 0; i < options.randomCandidates; ++i) candidates.push_back(randomDirection(generator));
    for (std::size_t t : evenSample(tile.triangles.size(), 64)) {
        const Triangle& triangle = tile.triangles[t];
        const Eigen::Vector3d centroid =
            (tile.positions[triangle[0]] + tile.positions[triangle[1]] + tile.positions[triangle[2]]) / 3;
        candidates.push_back(centroid - centre);
    }
    const std::vector<Rotation> rotations = properRotations(nonIdentity);
    if (!rotations.empty()) {
        const std::size_t perRotation = std::clamp<std::size_t>(256 / (2 * rotations.size()), 1, 16);
        const std::vector<std::size_t> vertices = evenSample(tile.positions.size(), perRotation);
        for (const Rotation& rotation : rotations) {
            for (std::size_t v : vertices) {
                const Eigen::Vector3d offset = tile.positions[v] - centre;
                candidates.push_back(Eigen::AngleAxisd(-rotation.angle / 2, rotation.axis) * offset);
                candidates.push_back(Eigen::AngleAxisd(rotation.angle / 2, rotation.axis) * offset);
            }
        }
    }
    return candidates;
}

// Triangles crossing some plane of the cone (vertices strictly on both sides) and not outside one plane.
std::size_t countCuts(const Primitive& tile, const std::vector<std::size_t>& sample, const DirichletCone& cone,
                      double tolerance) {
    std::size_t cuts = 0;
    for (std::size_t t : sample) {
        const Triangle& triangle = tile.triangles[t];
        bool crossing = false;
        bool outside = false;
        for (const Eigen::Vector3d& n : cone.normals) {
            int in = 0, out = 0;
            for (std::uint32_t corner : triangle) {
                const double d = n.dot(tile.positions[corner] - cone.apex);
                in += d > tolerance;
                out += d < -tolerance;
            }
            if (out > 0 && in == 0) outside = true;
            if (out > 0 && in > 0) crossing = true;
        }
        cuts += crossing && !outside;
    }
    return cuts;
}

}  // namespace

std::optional<Eigen::Vector3d> elementAxis(const Eigen::Matrix3d& element) {
    // The axis spans the null space of g - s I, s = det(g) = +-1: the smallest eigenvalue of its Gram
    // matrix is 0 and, for an axis to be defined, the only one.
    const double sign = element.determinant() >= 0 ? 1.0 : -1.0;
    const Eigen::Matrix3d shifted = element - sign * Eigen::Matrix3d::Identity();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(shifted.transpose() * shifted);
    const Eigen::Vector3d values = solver.eigenvalues();  // increasing
    if (values(0) > 1e-8 || values(1) < 1e-6) return std::nullopt;
    return solver.eigenvectors().col(0).normalized();
}

double seedSeparation(const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& seed) {
    const double length = seed.norm();
    if (!(length > 0)) return 0;
    double separation = 2;
    for (const Eigen::Matrix3d& g : nonIdentity) separation = std::min(separation, (seed - g * seed).norm() / length);
    return separation;
}

DirichletCone dirichletCone(const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& seed,
                            const Eigen::Vector3d& apex) {
    std::vector<Eigen::Vector3d> all;
    all.reserve(nonIdentity.size());
    for (const Eigen::Matrix3d& g : nonIdentity) all.push_back((seed - g * seed).normalized());
    DirichletCone cone;
    cone.apex = apex;
    for (std::size_t k = 0; k < all.size(); ++k)
        if (boundsCone(all, k)) cone.normals.push_back(all[k]);
    return cone;
}

SeedChoice chooseSeed(const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                      const Eigen::Vector3d& centre, double tolerance, const RegionOptions& options) {
    const std::vector<std::size_t> sample =
        evenSample(tile.triangles.size(), std::max<std::size_t>(1, options.maxScoredTriangles));
    SeedChoice best;
    double bestSeparation = -1;
    bool found = false;
    for (const Eigen::Vector3d& candidate : seedCandidates(tile, nonIdentity, centre, options)) {
        const double length = candidate.norm();
        if (!(length > 0)) continue;
        const Eigen::Vector3d seed = candidate / length;
        const double separation = seedSeparation(nonIdentity, seed);
        if (separation < kMinimumSeparation) continue;
        DirichletCone cone = dirichletCone(nonIdentity, seed, centre);
        const std::size_t cuts = countCuts(tile, sample, cone, tolerance);
        if (!found || cuts < best.estimatedCuts || (cuts == best.estimatedCuts && separation > bestSeparation)) {
            best = {seed, std::move(cone), cuts};
            bestSeparation = separation;
            found = true;
        }
    }
    if (!found) {
        // Random directions avoid every fixed set (a finite union of planes and lines) unless the
        // caller asked for none; this fallback keeps the choice total and deterministic.
        std::mt19937_64 generator(options.randomSeed ^ 0x9e3779b97f4a7c15ULL);
        for (int attempt = 0; attempt < 1000 && !found; ++attempt) {
            const Eigen::Vector3d seed = randomDirection(generator);
            if (seedSeparation(nonIdentity, seed) < kMinimumSeparation) continue;
            DirichletCone cone = dirichletCone(nonIdentity, seed, centre);
            best = {seed, cone, countCuts(tile, sample, cone, tolerance)};
            found = true;
        }
    }
    return best;
}

}  // namespace symcompress::region_detail
