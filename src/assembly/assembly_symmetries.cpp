#include "symcompress/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace symcompress {
namespace {

constexpr double kSameLinear = 1e-3;  // Frobenius distance under which two linear maps are one

struct PlacedTile {
    std::size_t classIndex = 0;
    Isometry placement;  // prototype -> this tile
    Eigen::Vector3d centroid;
};

}  // namespace

SymmetryGroup assemblySymmetries(const TileClassification& classification, double tolerance) {
    SymmetryGroup result;
    result.elements.push_back(Symmetry{});
    result.diagonal = classification.sceneDiagonal;
    const std::size_t tileCount = classification.shapes.size();
    if (tileCount == 0) return result;
    const double distance = tolerance * classification.sceneDiagonal;

    // Each tile with its class and placement; the assembly's area-weighted centroid.
    std::vector<PlacedTile> tiles(tileCount);
    double area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < classification.classes.size(); ++k) {
        const CongruenceClass& c = classification.classes[k];
        for (std::size_t i = 0; i < c.members.size(); ++i) {
            const std::size_t t = c.members[i];
            tiles[t] = {k, c.placements[i], classification.shapes[t].moments.centroid};
            area += classification.shapes[t].moments.area;
            weighted += classification.shapes[t].moments.area * classification.shapes[t].moments.centroid;
        }
    }
    const Eigen::Vector3d center = area > 0 ? Eigen::Vector3d(weighted / area) : Eigen::Vector3d::Zero();
    result.centroid = center;

    // The tile of `classIndex` whose centroid is at p, if any.
    auto tileAt = [&](std::size_t classIndex, const Eigen::Vector3d& p) -> std::size_t {
        for (std::size_t t : classification.classes[classIndex].members)
            if ((tiles[t].centroid - p).norm() <= distance) return t;
        return tileCount;
    };
    // Whether linear (about the centroid) maps tile t onto tile u: J_u^-1 A J_t is in the prototype's group.
    // A tile whose group was not computed has the identity only.
    const std::vector<Symmetry> identityOnly{Symmetry{}};
    auto groupOf = [&](std::size_t classIndex) -> const std::vector<Symmetry>& {
        const auto& elements = classification.shapes[classification.classes[classIndex].prototype].symmetry.elements;
        return elements.empty() ? identityOnly : elements;
    };
    auto mapsOnto = [&](const Eigen::Matrix3d& linear, std::size_t t, std::size_t u) {
        const Eigen::Matrix3d relative = tiles[u].placement.linear.transpose() * linear * tiles[t].placement.linear;
        const auto& group = groupOf(tiles[t].classIndex);
        return std::any_of(group.begin(), group.end(), [&](const Symmetry& g) { return (g.linear - relative).norm() < kSameLinear; });
    };

    // The anchor: the tile with the fewest candidate maps.
    std::size_t anchor = 0, fewest = std::numeric_limits<std::size_t>::max();
    for (std::size_t t = 0; t < tileCount; ++t) {
        const CongruenceClass& c = classification.classes[tiles[t].classIndex];
        const std::size_t candidates = c.members.size() * std::size_t(std::max(1, classification.shapes[c.prototype].symmetry.order()));
        if (candidates < fewest) fewest = candidates, anchor = t;
    }
    const CongruenceClass& anchorClass = classification.classes[tiles[anchor].classIndex];
    const auto& anchorGroup = groupOf(tiles[anchor].classIndex);
    const double anchorRadius = (tiles[anchor].centroid - center).norm();

    std::vector<Eigen::Matrix3d> found;
    for (std::size_t image : anchorClass.members) {
        if (std::abs((tiles[image].centroid - center).norm() - anchorRadius) > distance) continue;  // prune
        for (const Symmetry& g : anchorGroup) {
            // A = J_image g J_anchor^-1, as a linear map; it must fix the assembly's centroid.
            const Eigen::Matrix3d linear = tiles[image].placement.linear * g.linear * tiles[anchor].placement.linear.transpose();
            if ((center + linear * (tiles[anchor].centroid - center) - tiles[image].centroid).norm() > distance) continue;
            if (std::any_of(found.begin(), found.end(), [&](const Eigen::Matrix3d& f) { return (f - linear).norm() < kSameLinear; }))
                continue;
            bool all = true;
            for (std::size_t t = 0; t < tileCount && all; ++t) {
                const std::size_t u = tileAt(tiles[t].classIndex, center + linear * (tiles[t].centroid - center));
                all = u < tileCount && mapsOnto(linear, t, u);
            }
            if (all) found.push_back(linear);
        }
    }
    result.elements.clear();
    for (const Eigen::Matrix3d& linear : found) result.elements.push_back(describeOrthogonal(linear));
    std::stable_sort(result.elements.begin(), result.elements.end(),
                     [](const Symmetry& a, const Symmetry& b) { return a.kind == Symmetry::Kind::Identity && b.kind != Symmetry::Kind::Identity; });
    result.name = pointGroupName(found);
    for (Symmetry& s : result.elements) {
        if (s.kind != Symmetry::Kind::Rotation) continue;
        s.fold = 1;
        for (const Symmetry& other : result.elements)
            if (other.kind == Symmetry::Kind::Rotation && std::abs(std::abs(other.axis.dot(s.axis)) - 1) < 1e-6) ++s.fold;
    }
    return result;
}

}  // namespace symcompress
