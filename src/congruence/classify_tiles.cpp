// Congruence classes (paper 6.2): per-tile shapes in parallel, then candidates by area through a sorted
// index, descriptor, material and group, then the geometric check.
#include "symcompress/congruence.hpp"
#include "symcompress/detail/congruence_tolerances.hpp"

#include "find_isometry.hpp"
#include "common/with_threads.hpp"
#include "geometry/bounds.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <optional>

namespace symcompress {
namespace {

Eigen::Matrix3d secondMomentsOf(const SurfaceMoments& moments) {
    const auto& m = moments.monomialIntegrals[0];
    auto at = [&](int j, int k) { return m[HomogeneousPolynomial::monomialIndex(2, j, k)]; };
    Eigen::Matrix3d s;
    s << at(0, 0), at(1, 0), at(0, 1),  //
        at(1, 0), at(2, 0), at(1, 1),   //
        at(0, 1), at(1, 1), at(0, 2);
    return s;
}

// The descriptor tolerance: a floor for the rounding of float32 tiles, and room for the geometric
// tolerance (the geometric check decides; this only has to keep congruent tiles together).
constexpr double kDescriptorFloor = 1e-3;
constexpr double kDescriptorPerTolerance = 50;
// And a ceiling: in a large scene the tolerance, relative to a small tile, opens the area window so wide
// that every tile is compared with a large share of all classes (quadratic time). Exact copies differ by
// rounding only; what the ceiling can cost is grouping copies deformed by more than about 1e-4 of their
// size, never a wrong class.
constexpr double kDescriptorCeiling = 1e-2;
// Per-tile symmetry tolerance, relative to the tile: at most this, however small the tile.
constexpr double kMaxTileTolerance = 1e-3;

// The principal second moments agree within `epsilon` of the largest: invariants like the descriptor,
// and as cheap to compare, but they also tell apart shapes whose band energies happen to agree.
bool samePrincipalMoments(const TileShape& a, const TileShape& b, double epsilon) {
    const Eigen::Vector3d& x = a.principalMoments;
    const Eigen::Vector3d& y = b.principalMoments;
    return (x - y).cwiseAbs().maxCoeff() <= epsilon * std::max(x[2], y[2]);
}

}  // namespace

double descriptorTolerance(double tileDiagonal, double absoluteTolerance) {
    return std::clamp(kDescriptorPerTolerance * absoluteTolerance / std::max(tileDiagonal, 1e-300), kDescriptorFloor, kDescriptorCeiling);
}

double tileSymmetryTolerance(double tileDiagonal, double absoluteTolerance, double relativeTolerance) {
    return std::min(kMaxTileTolerance, std::max(relativeTolerance, absoluteTolerance / tileDiagonal));
}

Eigen::Matrix4d Isometry::matrix() const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = linear;
    m.topRightCorner<3, 1>() = translation;
    return m;
}

Isometry Isometry::inverse() const {
    Isometry back;
    back.linear = linear.transpose();
    back.translation = -(back.linear * translation);
    return back;
}

Isometry Isometry::operator*(const Isometry& first) const {
    Isometry both;
    both.linear = linear * first.linear;
    both.translation = linear * first.translation + translation;
    return both;
}

TileClassification classifyTiles(const std::vector<Tile>& tiles, const CongruenceOptions& options) {
    TileClassification result;
    Eigen::AlignedBox3d sceneBox;
    for (const Tile& tile : tiles)
        for (const auto& p : tile.mesh.positions) sceneBox.extend(p);
    result.sceneDiagonal = sceneBox.isEmpty() ? 0 : sceneBox.diagonal().norm();
    const double tolerance = options.absoluteTolerance > 0 ? options.absoluteTolerance : options.tolerance * result.sceneDiagonal;
    const double relativeTolerance = result.sceneDiagonal > 0 ? tolerance / result.sceneDiagonal : options.tolerance;
    result.absoluteTolerance = tolerance;
    result.tolerance = relativeTolerance;

    // Per tile, in parallel: moments, descriptor, second moments.
    result.shapes.resize(tiles.size());
    withThreads(options.threads, [&] {
        tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t i) {
            const Tile& tile = tiles[i];
            TileShape& shape = result.shapes[i];
            shape.material = tile.material;
            shape.triangles = tile.mesh.triangles.size();
            const Eigen::AlignedBox3d box = boundsOf(tile.mesh.positions);
            shape.diagonal = box.isEmpty() ? 0 : box.diagonal().norm();
            MomentOptions momentOptions;
            momentOptions.maxOrder = options.maxOrder;
            momentOptions.threads = 1;
            const SurfaceMoments surface = computeSurfaceMoments(tile.mesh, momentOptions);
            shape.moments = momentCoefficients(surface);
            shape.descriptor = computeCongruenceDescriptor(shape.moments);
            shape.secondMoments = secondMomentsOf(surface);
            // Once per tile: the pairs compare them for every candidate class.
            shape.principalMoments =
                Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(shape.secondMoments, Eigen::EigenvaluesOnly).eigenvalues();
        });
    });

    // Largest tiles first, so that prototypes are found early; classes indexed by prototype area.
    std::vector<std::size_t> order(tiles.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return result.shapes[a].descriptor.area > result.shapes[b].descriptor.area;
    });
    std::multimap<double, std::size_t> classByArea;
    std::vector<std::unique_ptr<TileProbe>> prototypeProbes;
    auto sameInvariants = [&](const TileShape& shape, std::size_t k, double epsilon, bool anyMaterial = false) {
        const TileShape& prototype = result.shapes[result.classes[k].prototype];
        // The RMS radii's relative difference is one of the terms whose largest descriptorDifference is: beyond
        // epsilon, so is the whole (most classes in the area window of a large scene are rejected here).
        const double x = prototype.descriptor.rmsRadius, y = shape.descriptor.rmsRadius;
        const double larger = std::max(std::abs(x), std::abs(y));
        if ((larger > 0 ? std::abs(x - y) / larger : 0.0) > epsilon) return false;
        return (anyMaterial || prototype.material == shape.material) &&
               descriptorDifference(prototype.descriptor, shape.descriptor) <= epsilon &&
               samePrincipalMoments(prototype, shape, epsilon);
    };
    auto newProbe = [&](std::size_t tile) {
        return std::make_unique<TileProbe>(tiles[tile].mesh, result.shapes[tile].moments.centroid, options.threads);
    };
    // Tiles a batch at a time: each tries the classes that existed before its batch in parallel, in the
    // index's order up to the first that fits (the geometric checks are most of this stage); then, in order,
    // the classes the batch's earlier tiles created are tried where they come first in the index. The
    // classes, placements and counts are those of trying every tile in turn.
    struct Trial {
        std::size_t classIndex;
        std::optional<FoundIsometry> found;
    };
    struct Attempt {
        std::unique_ptr<TileProbe> probe;
        std::vector<Trial> trials;
    };
    constexpr std::size_t kBatch = 32;
    for (std::size_t begin = 0; begin < order.size(); begin += kBatch) {
        const std::size_t end = std::min(order.size(), begin + kBatch), known = result.classes.size();
        std::vector<Attempt> attempts(end - begin);
        withThreads(options.threads, [&] {
            tbb::parallel_for(begin, end, [&](std::size_t i) {
                const std::size_t tile = order[i];
                const TileShape& shape = result.shapes[tile];
                const double area = shape.descriptor.area, epsilon = descriptorTolerance(shape.diagonal, tolerance);
                Attempt& attempt = attempts[i - begin];
                for (auto it = classByArea.lower_bound(area * (1 - epsilon));
                     it != classByArea.end() && it->first <= area * (1 + epsilon); ++it) {
                    if (!sameInvariants(shape, it->second, epsilon)) continue;
                    if (!attempt.probe) attempt.probe = newProbe(tile);
                    const TileShape& prototype = result.shapes[result.classes[it->second].prototype];
                    attempt.trials.push_back(
                        {it->second, findIsometry(prototype, *prototypeProbes[it->second], shape, *attempt.probe, tolerance)});
                    if (attempt.trials.back().found) break;
                }
            });
        });
        for (std::size_t i = begin; i < end; ++i) {
            const std::size_t tile = order[i];
            const TileShape& shape = result.shapes[tile];
            const double area = shape.descriptor.area, epsilon = descriptorTolerance(shape.diagonal, tolerance);
            Attempt& attempt = attempts[i - begin];
            std::size_t tried = 0;
            bool placed = false;
            for (auto it = classByArea.lower_bound(area * (1 - epsilon)); it != classByArea.end() && it->first <= area * (1 + epsilon);
                 ++it) {
                const std::size_t k = it->second;
                std::optional<FoundIsometry> found;
                if (k < known) {
                    // Tried in parallel: every class of the same invariants, in this order, up to the first that fits.
                    if (tried == attempt.trials.size() || attempt.trials[tried].classIndex != k) continue;
                    found = attempt.trials[tried++].found;
                } else {
                    if (!sameInvariants(shape, k, epsilon)) continue;
                    if (!attempt.probe) attempt.probe = newProbe(tile);
                    found = findIsometry(result.shapes[result.classes[k].prototype], *prototypeProbes[k], shape, *attempt.probe,
                                         tolerance);
                }
                ++result.descriptorMatches;
                if (!found) continue;
                ++result.verifiedMatches;
                CongruenceClass& candidate = result.classes[k];
                const TileShape& prototype = result.shapes[candidate.prototype];
                Isometry placement;
                placement.linear = found->linear;
                placement.translation = shape.moments.centroid - found->linear * prototype.moments.centroid;
                candidate.members.push_back(tile);
                candidate.placements.push_back(placement);
                candidate.deviations.push_back(found->deviation / result.sceneDiagonal);
                placed = true;
                break;
            }
            if (placed) continue;
            CongruenceClass created;
            created.prototype = tile;
            created.members.push_back(tile);
            created.placements.emplace_back();
            created.deviations.push_back(0);
            classByArea.emplace(area, result.classes.size());
            result.classes.push_back(std::move(created));
            prototypeProbes.push_back(attempt.probe ? std::move(attempt.probe) : newProbe(tile));
        }
    }

    // Families: each class joins the first earlier class of another material whose prototype is congruent to its
    // own, if any (only prototypes are compared: the classes are few beside the tiles).
    std::vector<std::optional<std::pair<std::size_t, FoundIsometry>>> joins(result.classes.size());
    withThreads(options.threads, [&] {
        tbb::parallel_for(std::size_t(0), result.classes.size(), [&](std::size_t k) {
            const TileShape& shape = result.shapes[result.classes[k].prototype];
            const double area = shape.descriptor.area, epsilon = descriptorTolerance(shape.diagonal, tolerance);
            std::vector<std::size_t> candidates;  // in the classes' order: the first that fits leads
            for (auto it = classByArea.lower_bound(area * (1 - epsilon));
                 it != classByArea.end() && it->first <= area * (1 + epsilon); ++it)
                if (it->second < k && sameInvariants(shape, it->second, epsilon, true))
                    candidates.push_back(it->second);
            std::sort(candidates.begin(), candidates.end());
            for (std::size_t j : candidates)
                if (auto found = findIsometry(result.shapes[result.classes[j].prototype], *prototypeProbes[j], shape,
                                              *prototypeProbes[k], tolerance)) {
                    joins[k] = std::pair{j, *found};
                    return;
                }
        });
    });
    for (std::size_t k = 0; k < result.classes.size(); ++k) {
        CongruenceClass& c = result.classes[k];
        c.family = k;
        if (!joins[k]) continue;
        const auto& [j, found] = *joins[k];
        const CongruenceClass& lead = result.classes[j];  // j < k: its own family settled, through its lead
        const TileShape& prototype = result.shapes[lead.prototype];
        Isometry fromLead;
        fromLead.linear = found.linear;
        fromLead.translation = result.shapes[c.prototype].moments.centroid - found.linear * prototype.moments.centroid;
        c.family = lead.family;
        c.fromFamily = fromLead * lead.fromFamily;
        c.familyDeviation = found.deviation / result.sceneDiagonal + lead.familyDeviation;
    }

    // The group of each prototype, in parallel; a member's is its prototype's carried over by its
    // placement J (J g J^-1), congruent tiles having conjugate groups. Only prototypes need the detector:
    // the geometric check already keeps tiles of different groups apart.
    if (options.symmetries) {
        auto detect = [&](const std::vector<std::size_t>& classes) {
            withThreads(options.threads, [&] {
                tbb::parallel_for(std::size_t(0), classes.size(), [&](std::size_t i) {
                    const std::size_t prototype = result.classes[classes[i]].prototype;
                    TileShape& shape = result.shapes[prototype];
                    SymmetryOptions symmetryOptions;
                    symmetryOptions.tolerance = tileSymmetryTolerance(shape.diagonal, tolerance, relativeTolerance);
                    symmetryOptions.threads = 0;  // the classification's threads, shared (the same group on any number)
                    symmetryOptions.elementDeviations = options.elementDeviations;
                    shape.symmetry = detectSymmetries(tiles[prototype].mesh, symmetryOptions);
                });
            });
        };
        // Classes of one tile whose group no use could be made of: detected last, and only while the
        // assembly's symmetry might need them.
        // A class of one tile in a family of others is placed by its group's elements (the plan's member check).
        std::vector<std::size_t> familyMembers(result.classes.size(), 0);
        for (const CongruenceClass& c : result.classes) familyMembers[c.family] += c.members.size();
        std::vector<std::size_t> needed, optional;
        for (std::size_t k = 0; k < result.classes.size(); ++k) {
            const CongruenceClass& c = result.classes[k];
            if (!(result.shapes[c.prototype].diagonal > 0)) continue;
            const bool usable = !options.groupUsable || familyMembers[c.family] > 1 || options.groupUsable(c.prototype);
            (usable ? needed : optional).push_back(k);
        }
        detect(needed);
        // The assembly's symmetry (assemblySymmetries) maps the one tile of such a class onto itself by one
        // of its symmetries: one of them with none leaves it the identity alone, whatever the groups of the
        // others. Until one is known, the others are detected a batch at a time.
        auto asymmetricAlone = [&](std::size_t k) {
            const CongruenceClass& c = result.classes[k];
            return c.members.size() == 1 && result.shapes[c.prototype].symmetry.order() == 1;
        };
        bool identityAlone = std::any_of(needed.begin(), needed.end(), asymmetricAlone);
        const std::size_t batch = 16;
        std::size_t next = 0;
        while (!identityAlone && next < optional.size()) {
            const std::vector<std::size_t> some(optional.begin() + std::ptrdiff_t(next),
                                                optional.begin() + std::ptrdiff_t(std::min(next + batch, optional.size())));
            detect(some);
            next += some.size();
            identityAlone = std::any_of(some.begin(), some.end(), asymmetricAlone);
        }
        for (; next < optional.size(); ++next) {
            result.shapes[result.classes[optional[next]].prototype].symmetrySkipped = true;
            ++result.groupsSkipped;
        }
        for (const CongruenceClass& c : result.classes)
            for (std::size_t i = 1; i < c.members.size(); ++i) {
                const Isometry& j = c.placements[i];
                SymmetryGroup& group = result.shapes[c.members[i]].symmetry;
                group = result.shapes[c.prototype].symmetry;
                group.centroid = result.shapes[c.members[i]].moments.centroid;
                for (Symmetry& g : group.elements) g = describeOrthogonal(j.linear * g.linear * j.linear.transpose());
                for (std::size_t e = 0; e < group.elements.size(); ++e) {
                    group.elements[e].fold = result.shapes[c.prototype].symmetry.elements[e].fold;
                    group.elements[e].deviation = result.shapes[c.prototype].symmetry.elements[e].deviation;
                }
            }
    }
    return result;
}

}  // namespace symcompress
