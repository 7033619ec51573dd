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

// The tiles of an assembly (some of a classification's) by class and centroid, and the assembly's
// area-weighted centroid.
class TileLocator {
public:
    TileLocator(const TileClassification& classification, const std::vector<bool>& inAssembly, double distance)
        : classification_(classification),
          distance_(distance),
          tiles_(classification.shapes.size()),
          byX_(classification.classes.size()) {
        double area = 0;
        Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < classification.classes.size(); ++k) {
            const CongruenceClass& c = classification.classes[k];
            for (std::size_t i = 0; i < c.members.size(); ++i) {
                const std::size_t t = c.members[i];
                if (!inAssembly[t]) continue;
                const auto& moments = classification.shapes[t].moments;
                tiles_[t] = {k, c.placements[i], moments.centroid};
                byX_[k].emplace_back(moments.centroid.x(), t);
                area += moments.area;
                weighted += moments.area * moments.centroid;
            }
            std::sort(byX_[k].begin(), byX_[k].end());
        }
        center_ = area > 0 ? Eigen::Vector3d(weighted / area) : Eigen::Vector3d::Zero();
    }

    const Eigen::Vector3d& center() const { return center_; }
    const PlacedTile& operator[](std::size_t t) const { return tiles_[t]; }
    std::size_t size() const { return tiles_.size(); }

    // The tile of `classIndex` whose centroid is at p, if any (else size()).
    std::size_t at(std::size_t classIndex, const Eigen::Vector3d& p) const {
        const auto& sorted = byX_[classIndex];
        for (auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{p.x() - distance_, std::size_t(0)});
             it != sorted.end() && it->first <= p.x() + distance_; ++it)
            if ((tiles_[it->second].centroid - p).norm() <= distance_) return it->second;
        return size();
    }

    // The symmetries of a class's prototype (the identity only when its group was not computed).
    const std::vector<Symmetry>& groupOf(std::size_t classIndex) const {
        const auto& elements = classification_.shapes[classification_.classes[classIndex].prototype].symmetry.elements;
        return elements.empty() ? identityOnly_ : elements;
    }

    // Whether linear (about the center) maps tile t onto tile u: J_u^-1 A J_t is in the prototype's group, as
    // one linear map, or within what the two placements' tolerance allows at the tile's size (a small tile's
    // placements, each within the distance at its corners, are loose as linear maps: a book in a room copied
    // three times, 1.3e-3 off).
    bool mapsOnto(const Eigen::Matrix3d& linear, std::size_t t, std::size_t u) const {
        const Eigen::Matrix3d relative = tiles_[u].placement.linear.transpose() * linear * tiles_[t].placement.linear;
        const auto& group = groupOf(tiles_[t].classIndex);
        const double size = classification_.shapes[t].diagonal;
        return std::any_of(group.begin(), group.end(), [&](const Symmetry& g) {
            const double off = (g.linear - relative).norm();
            return off < kSameLinear || off * size <= 2 * distance_;
        });
    }

    // The tile that linear (about the center) maps tile t onto, or size() when it maps it onto none.
    std::size_t image(const Eigen::Matrix3d& linear, std::size_t t) const {
        const std::size_t u = at(tiles_[t].classIndex, center_ + linear * (tiles_[t].centroid - center_));
        return u < size() && mapsOnto(linear, t, u) ? u : size();
    }

private:
    const TileClassification& classification_;
    double distance_;
    std::vector<PlacedTile> tiles_;
    std::vector<std::vector<std::pair<double, std::size_t>>> byX_;  // per class, members by centroid x
    Eigen::Vector3d center_;
    const std::vector<Symmetry> identityOnly_{Symmetry{}};
};

std::vector<bool> membership(std::size_t tileCount, const std::vector<std::size_t>& tiles) {
    std::vector<bool> in(tileCount, false);
    for (std::size_t t : tiles) in[t] = true;
    return in;
}

std::vector<std::size_t> allTiles(const TileClassification& classification) {
    std::vector<std::size_t> tiles(classification.shapes.size());
    for (std::size_t t = 0; t < tiles.size(); ++t) tiles[t] = t;
    return tiles;
}

}  // namespace

SymmetryGroup assemblySymmetries(const TileClassification& classification) {
    return assemblySymmetries(classification, allTiles(classification));
}

SymmetryGroup assemblySymmetries(const TileClassification& classification, const std::vector<std::size_t>& assembly) {
    SymmetryGroup result;
    result.elements.push_back(Symmetry{});
    result.diagonal = classification.sceneDiagonal;
    const std::size_t tileCount = classification.shapes.size();
    if (assembly.empty()) return result;
    const double distance = classification.absoluteTolerance;
    const std::vector<bool> inAssembly = membership(tileCount, assembly);
    const TileLocator tiles(classification, inAssembly, distance);
    const Eigen::Vector3d center = tiles.center();
    result.centroid = center;

    // The anchor: the tile with the fewest candidate maps.
    std::size_t anchor = assembly.front(), fewest = std::numeric_limits<std::size_t>::max();
    for (std::size_t t : assembly) {
        const CongruenceClass& c = classification.classes[tiles[t].classIndex];
        const std::size_t candidates = c.members.size() * std::size_t(std::max(1, classification.shapes[c.prototype].symmetry.order()));
        if (candidates < fewest) fewest = candidates, anchor = t;
    }
    const CongruenceClass& anchorClass = classification.classes[tiles[anchor].classIndex];
    const auto& anchorGroup = tiles.groupOf(tiles[anchor].classIndex);
    const double anchorRadius = (tiles[anchor].centroid - center).norm();

    std::vector<Eigen::Matrix3d> found;
    for (std::size_t image : anchorClass.members) {
        if (!inAssembly[image]) continue;
        if (std::abs((tiles[image].centroid - center).norm() - anchorRadius) > distance) continue;  // prune
        for (const Symmetry& g : anchorGroup) {
            // A = J_image g J_anchor^-1, as a linear map; it must fix the assembly's centroid.
            const Eigen::Matrix3d linear = tiles[image].placement.linear * g.linear * tiles[anchor].placement.linear.transpose();
            if ((center + linear * (tiles[anchor].centroid - center) - tiles[image].centroid).norm() > distance) continue;
            if (std::any_of(found.begin(), found.end(), [&](const Eigen::Matrix3d& f) { return (f - linear).norm() < kSameLinear; }))
                continue;
            bool all = true;
            for (std::size_t i = 0; i < assembly.size() && all; ++i) all = tiles.image(linear, assembly[i]) < tileCount;
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

std::vector<std::vector<std::size_t>> tileImages(const TileClassification& classification, const SymmetryGroup& group) {
    return tileImages(classification, group, allTiles(classification));
}

std::vector<std::vector<std::size_t>> tileImages(const TileClassification& classification, const SymmetryGroup& group,
                                                 const std::vector<std::size_t>& assembly) {
    const TileLocator tiles(classification, membership(classification.shapes.size(), assembly),
                            classification.absoluteTolerance);
    std::vector<std::vector<std::size_t>> images(group.elements.size(),
                                                 std::vector<std::size_t>(tiles.size(), tiles.size()));
    for (std::size_t e = 0; e < group.elements.size(); ++e)
        for (std::size_t t : assembly) images[e][t] = tiles.image(group.elements[e].linear, t);
    return images;
}

}  // namespace symcompress
