// Repeated assemblies (issue 6): tiles that recur together, grown from the members of one class through
// tiles that touch, under the isometries between those members.
#include "symcompress/assembly.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <unordered_map>
#include <unordered_set>

namespace symcompress {
namespace {

constexpr double kTouchingPerTolerance = 10;     // bounding boxes this many tolerances apart still touch
constexpr std::size_t kMaxTrialsPerClass = 20000;  // growths tried from one anchor class (members x group)
constexpr std::size_t kLargeTileCells = 4096;       // tiles over more grid cells are checked against every tile

struct PlacedTile {
    std::size_t classIndex = 0;
    Isometry placement;  // prototype -> tile
    Eigen::Vector3d centroid;
    double radius = 0;  // largest distance of a vertex from the centroid
    Eigen::AlignedBox3d box;
};

struct CellHash {
    std::size_t operator()(const Eigen::Vector3i& c) const {
        return std::size_t(c.x()) * 73856093u ^ std::size_t(c.y()) * 19349663u ^ std::size_t(c.z()) * 83492791u;
    }
};
struct CellEqual {
    bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const { return a == b; }
};
using CellMap = std::unordered_map<Eigen::Vector3i, std::vector<std::size_t>, CellHash, CellEqual>;

Eigen::Vector3i cellOf(const Eigen::Vector3d& p, double size) { return (p / size).array().floor().cast<int>(); }

// Tiles whose bounding boxes come within `gap` of each other, on a uniform grid of boxes.
class TouchingTiles {
public:
    TouchingTiles(const std::vector<PlacedTile>& tiles, double gap) : tiles_(tiles), gap_(gap) {
        std::vector<double> sizes;
        for (const PlacedTile& t : tiles) sizes.push_back(t.box.diagonal().norm());
        std::nth_element(sizes.begin(), sizes.begin() + std::ptrdiff_t(sizes.size() / 2), sizes.end());
        cell_ = std::max(2 * sizes[sizes.size() / 2], 4 * gap);
        for (std::size_t t = 0; t < tiles.size(); ++t) {
            const Eigen::Vector3i lo = cellOf(tiles[t].box.min(), cell_), hi = cellOf(tiles[t].box.max(), cell_);
            const Eigen::Vector3d span = (hi - lo).cast<double>().array() + 1;
            if (span.prod() > double(kLargeTileCells)) {
                large_.push_back(t);
                continue;
            }
            for (int x = lo.x(); x <= hi.x(); ++x)
                for (int y = lo.y(); y <= hi.y(); ++y)
                    for (int z = lo.z(); z <= hi.z(); ++z) cells_[Eigen::Vector3i(x, y, z)].push_back(t);
        }
    }

    template <typename Visit>
    void forEachTouching(std::size_t t, Visit visit) const {
        Eigen::AlignedBox3d grown = tiles_[t].box;
        grown.min().array() -= gap_;
        grown.max().array() += gap_;
        std::unordered_set<std::size_t> seen;
        auto consider = [&](std::size_t u) {
            if (u != t && grown.intersects(tiles_[u].box) && seen.insert(u).second) visit(u);
        };
        for (std::size_t u : large_) consider(u);
        const Eigen::Vector3i lo = cellOf(grown.min(), cell_), hi = cellOf(grown.max(), cell_);
        if (((hi - lo).cast<double>().array() + 1).prod() > double(kLargeTileCells)) {
            for (std::size_t u = 0; u < tiles_.size(); ++u) consider(u);
            return;
        }
        for (int x = lo.x(); x <= hi.x(); ++x)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int z = lo.z(); z <= hi.z(); ++z)
                    if (auto it = cells_.find(Eigen::Vector3i(x, y, z)); it != cells_.end())
                        for (std::size_t u : it->second) consider(u);
    }

private:
    const std::vector<PlacedTile>& tiles_;
    double gap_;
    double cell_ = 1;
    CellMap cells_;
    std::vector<std::size_t> large_;
};

class AssemblyFinder {
public:
    AssemblyFinder(const std::vector<Tile>& tiles, const TileClassification& classification, const AssemblyOptions& options)
        : classification_(classification), options_(options), distance_(classification.absoluteTolerance),
          placed_(placeTiles(tiles, classification)), touching_(placed_, kTouchingPerTolerance * distance_),
          free_(tiles.size(), true) {
        centroidCell_ = std::max(4 * distance_, 1e-300);
        for (std::size_t t = 0; t < placed_.size(); ++t) byCentroid_[cellOf(placed_[t].centroid, centroidCell_)].push_back(t);
    }

    std::vector<RepeatedAssembly> find() {
        // Anchors on the largest parts first: a vehicle is found from its body rather than from a wheel.
        std::vector<std::size_t> order;
        for (std::size_t k = 0; k < classification_.classes.size(); ++k)
            if (classification_.classes[k].members.size() > 1) order.push_back(k);
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return classification_.shapes[classification_.classes[a].prototype].triangles >
                   classification_.shapes[classification_.classes[b].prototype].triangles;
        });
        std::vector<RepeatedAssembly> found;
        for (std::size_t k : order) {
            std::size_t trials = 0;
            while (auto assembly = growFromClass(k, trials)) {
                for (const auto& copy : assembly->copies)
                    for (std::size_t t : copy) free_[t] = false;
                found.push_back(std::move(*assembly));
            }
        }
        return found;
    }

private:
    static std::vector<PlacedTile> placeTiles(const std::vector<Tile>& tiles, const TileClassification& classification) {
        std::vector<PlacedTile> placed(tiles.size());
        for (std::size_t k = 0; k < classification.classes.size(); ++k) {
            const CongruenceClass& c = classification.classes[k];
            for (std::size_t i = 0; i < c.members.size(); ++i) {
                PlacedTile& p = placed[c.members[i]];
                p.classIndex = k;
                p.placement = c.placements[i];
                p.centroid = classification.shapes[c.members[i]].moments.centroid;
                for (const auto& v : tiles[c.members[i]].mesh.positions) {
                    p.box.extend(v);
                    p.radius = std::max(p.radius, (v - p.centroid).norm());
                }
            }
        }
        return placed;
    }

    const std::vector<Symmetry>& groupOf(std::size_t classIndex) const {
        static const std::vector<Symmetry> identityOnly{Symmetry{}};
        const auto& elements = classification_.shapes[classification_.classes[classIndex].prototype].symmetry.elements;
        return elements.empty() ? identityOnly : elements;
    }

    // The tile that `map` takes tile t onto, if it is of t's class, placed consistently within the
    // tolerance, and acceptable (when `checked`); else none (placed_.size()).
    std::size_t imageOf(std::size_t t, const Isometry& map, bool checked) const {
        const PlacedTile& from = placed_[t];
        const Eigen::Vector3d at = map.linear * from.centroid + map.translation;
        const Eigen::Vector3i cell = cellOf(at, centroidCell_);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = byCentroid_.find(cell + Eigen::Vector3i(dx, dy, dz));
                    if (it == byCentroid_.end()) continue;
                    for (std::size_t u : it->second) {
                        const PlacedTile& to = placed_[u];
                        if (to.classIndex != from.classIndex || (to.centroid - at).norm() > distance_) continue;
                        // map J_t = J_u g for some g of the class's group; the rest, times the tile's size,
                        // bounds how far the rebuilt tile's vertices are from J_u g's.
                        const Eigen::Matrix3d relative = to.placement.linear.transpose() * map.linear * from.placement.linear;
                        for (const Symmetry& g : groupOf(from.classIndex)) {
                            const double bound = (g.linear - relative).norm() * from.radius + (to.centroid - at).norm();
                            if (bound <= distance_ && (!checked || !options_.accept || options_.accept(t, u, map)))
                                return u;
                        }
                    }
                }
        return placed_.size();
    }

    // Copy 0 grown from `seed` through touching tiles, with copy j its image under maps[j] (maps[0] the
    // identity), every tile of every copy free and in one copy only; and acceptable, when `checked` (else the
    // copies are at least as large as the checked ones).
    RepeatedAssembly grow(std::size_t seed, const std::vector<std::size_t>& seedImages,
                          const std::vector<Isometry>& maps, bool checked = true) const {
        RepeatedAssembly assembly;
        assembly.placements = maps;
        assembly.copies.assign(maps.size(), {});
        std::unordered_set<std::size_t> used{seed};
        for (std::size_t j = 0; j < maps.size(); ++j) {
            assembly.copies[j].push_back(seedImages[j]);
            used.insert(seedImages[j]);
        }
        std::deque<std::size_t> queue{seed};
        std::vector<std::size_t> images(maps.size());
        while (!queue.empty()) {
            const std::size_t t = queue.front();
            queue.pop_front();
            touching_.forEachTouching(t, [&](std::size_t u) {
                if (!free_[u] || used.count(u)) return;
                images[0] = u;
                for (std::size_t j = 1; j < maps.size(); ++j) {
                    images[j] = imageOf(u, maps[j], checked);
                    if (images[j] == placed_.size() || !free_[images[j]] || used.count(images[j]) ||
                        std::find(images.begin(), images.begin() + std::ptrdiff_t(j), images[j]) != images.begin() + std::ptrdiff_t(j))
                        return;
                }
                for (std::size_t j = 0; j < maps.size(); ++j) {
                    assembly.copies[j].push_back(images[j]);
                    used.insert(images[j]);
                }
                queue.push_back(u);
            });
        }
        return assembly;
    }

    // The next assembly anchored on free members of class k: the first free member is copy 0; each other
    // free member b is a copy under the map (of J_b g J_a^-1) that grows the most tiles; the copies that
    // reach the most are kept.
    std::optional<RepeatedAssembly> growFromClass(std::size_t k, std::size_t& trials) const {
        std::vector<std::size_t> anchors;
        for (std::size_t t : classification_.classes[k].members)
            if (free_[t]) anchors.push_back(t);
        if (anchors.size() < 2) return std::nullopt;
        const std::size_t a = anchors[0];
        const PlacedTile& from = placed_[a];
        struct Copy {
            std::size_t anchor;
            Isometry map;
            std::size_t tiles;
        };
        // Every other anchor under every element of the group: too many trials, and the class anchors no more.
        const std::vector<Symmetry>& group = groupOf(k);
        trials += (anchors.size() - 1) * group.size();
        if (trials > kMaxTrialsPerClass) return std::nullopt;
        // Each other anchor's best map is its own (in parallel), the copies then taken in the anchors' order.
        std::vector<Copy> bestOf(anchors.size(), Copy{0, {}, 0});
        tbb::parallel_for(std::size_t(1), std::max<std::size_t>(1, anchors.size()), [&](std::size_t i) {
            const PlacedTile& to = placed_[anchors[i]];
            // Each map's growth unchecked first (cheap): it bounds the checked growth (but where tiles are
            // claimed in another order). Then the maps are checked (each tile's copy accepted, a costly surface
            // comparison) from the largest bound down, until no bound can beat the best: the map that checking
            // every map in the group's order would pick, at a few checks where the group has hundreds.
            struct Trial {
                std::size_t element, bound;
                Isometry map;
            };
            std::vector<Trial> trialsOf;
            for (std::size_t e = 0; e < group.size(); ++e) {
                Isometry map;
                map.linear = to.placement.linear * group[e].linear * from.placement.linear.transpose();
                map.translation = to.centroid - map.linear * from.centroid;
                // A map that grows no tile beyond the anchor makes no assembly.
                const std::size_t bound = grow(a, {a, anchors[i]}, {Isometry{}, map}, false).copies[0].size();
                if (bound >= 2) trialsOf.push_back({e, bound, map});
            }
            std::stable_sort(trialsOf.begin(), trialsOf.end(),
                             [](const Trial& x, const Trial& y) { return x.bound > y.bound; });
            Copy& best = bestOf[i];
            best.anchor = anchors[i];
            std::size_t bestElement = group.size();
            for (const Trial& trial : trialsOf) {
                if (trial.bound < best.tiles) break;
                if (trial.bound == best.tiles && trial.element > bestElement) continue;
                const std::size_t grown = grow(a, {a, anchors[i]}, {Isometry{}, trial.map}).copies[0].size();
                if (grown < 2 || grown < best.tiles || (grown == best.tiles && trial.element > bestElement)) continue;
                if (options_.accept && !options_.accept(a, anchors[i], trial.map)) continue;
                best = {anchors[i], trial.map, grown};
                bestElement = trial.element;
            }
        });
        std::vector<Copy> copies;
        for (std::size_t i = 1; i < anchors.size(); ++i)
            if (bestOf[i].tiles > 0) copies.push_back(bestOf[i]);
        // The copies that reach at least `least` tiles, for the `least` that makes their number times it (the
        // tiles the copies spare) largest: four rooms of 26 tiles that reach all but one tile beat one of 27.
        std::vector<std::size_t> counts;
        for (const Copy& c : copies) counts.push_back(c.tiles);
        std::sort(counts.begin(), counts.end(), std::greater<>());
        std::size_t least = 0, spared = 0;
        for (std::size_t k = 0; k < counts.size(); ++k)
            if ((k + 1) * counts[k] > spared) spared = (k + 1) * counts[k], least = counts[k];
        if (least < 2) return std::nullopt;
        std::vector<std::size_t> seedImages{a};
        std::vector<Isometry> maps{Isometry{}};
        for (const Copy& c : copies)
            if (c.tiles >= least) seedImages.push_back(c.anchor), maps.push_back(c.map);
        RepeatedAssembly assembly = grow(a, seedImages, maps);
        if (assembly.copies[0].size() < 2) return std::nullopt;
        // The deviation bound: the placements' own, plus the classes' for the tiles rebuilt.
        double worst = 0;
        for (std::size_t j = 1; j < assembly.copies.size(); ++j)
            for (std::size_t i = 0; i < assembly.copies[j].size(); ++i) {
                const PlacedTile& t = placed_[assembly.copies[0][i]];
                const PlacedTile& u = placed_[assembly.copies[j][i]];
                const Eigen::Matrix3d relative = u.placement.linear.transpose() * maps[j].linear * t.placement.linear;
                double bound = std::numeric_limits<double>::infinity();
                for (const Symmetry& g : groupOf(t.classIndex))
                    bound = std::min(bound, (g.linear - relative).norm() * t.radius +
                                                (maps[j].linear * t.centroid + maps[j].translation - u.centroid).norm());
                worst = std::max(worst, bound);
            }
        assembly.deviation = classification_.sceneDiagonal > 0 ? worst / classification_.sceneDiagonal : 0;
        return assembly;
    }

    const TileClassification& classification_;
    const AssemblyOptions& options_;
    double distance_;
    std::vector<PlacedTile> placed_;
    TouchingTiles touching_;
    std::vector<bool> free_;
    double centroidCell_ = 1;
    CellMap byCentroid_;
};

}  // namespace

std::vector<RepeatedAssembly> findRepeatedAssemblies(const std::vector<Tile>& tiles, const TileClassification& classification,
                                                     const AssemblyOptions& options) {
    if (tiles.empty() || classification.shapes.size() != tiles.size()) return {};
    return AssemblyFinder(tiles, classification, options).find();
}

}  // namespace symcompress
