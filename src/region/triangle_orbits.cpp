// A fundamental region of whole triangles: one triangle of each orbit of the group, where the group maps the
// tile's triangles onto one another (docs/fundamental-regions.md, "Whole triangles").
#include "fundamental_region_parts.hpp"

#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <unordered_map>

namespace symcompress::region_detail {

namespace {

using Corners = std::array<std::uint32_t, 3>;

struct CornersHash {
    std::size_t operator()(const Corners& c) const {
        return static_cast<std::size_t>(c[0] * 73856093ULL ^ c[1] * 19349663ULL ^ c[2] * 83492791ULL);
    }
};

Corners sorted(Corners corners) {
    std::sort(corners.begin(), corners.end());
    return corners;
}

// Whether b is a in the same cyclic order (the same winding).
bool sameWinding(const Corners& a, const Corners& b) {
    for (int shift = 0; shift < 3; ++shift)
        if (a[0] == b[shift] && a[1] == b[(shift + 1) % 3] && a[2] == b[(shift + 2) % 3]) return true;
    return false;
}

// The position that g takes each position to (positions relative to the centre): the point within the tolerance
// of its image, if any. Empty when some image is no position of the tile, or two positions go to one.
std::vector<std::uint32_t> imagesUnder(const Eigen::Matrix3d& g, const std::vector<Eigen::Vector3d>& points,
                                       double tolerance) {
    const std::size_t n = points.size();
    std::vector<Eigen::Vector3d> both(points);
    both.reserve(2 * n);
    for (const Eigen::Vector3d& p : points) both.push_back(g * p);
    // The points come first, so each image takes the index of a point within the tolerance, if any.
    const std::vector<std::uint32_t> welded = weldPositions(both, tolerance);
    std::vector<std::uint32_t> image(n);
    std::vector<char> hit(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t r = welded[n + i];
        if (r >= n || hit[r]) return {};
        hit[r] = 1;
        image[i] = r;
    }
    return image;
}

// images[e][r]: the position that element e takes position r to; empty where some element has no images, or where
// `accepted` refuses the images of an element matched against the points. Only elements that no product of earlier
// ones reaches are matched: a product's images are its factors' composed (computeFundamentalRegion checked that the
// group is closed), so a 96-sector lathe's C96v takes three matchings, not 191.
template <class Accepted>
std::vector<std::vector<std::uint32_t>> positionImages(const std::vector<Eigen::Vector3d>& points,
                                                       const std::vector<Eigen::Matrix3d>& nonIdentity,
                                                       double tolerance, const Accepted& accepted) {
    const std::size_t count = nonIdentity.size();
    auto indexOf = [&](const Eigen::Matrix3d& m) {  // count for the identity (or no element)
        for (std::size_t e = 0; e < count; ++e)
            if ((nonIdentity[e] - m).cwiseAbs().maxCoeff() < 1e-3) return e;
        return count;
    };
    std::vector<std::vector<std::uint32_t>> images(count);
    std::vector<std::size_t> generators, reached;
    for (std::size_t e = 0; e < count; ++e) {
        if (!images[e].empty()) continue;
        images[e] = imagesUnder(nonIdentity[e], points, tolerance);
        if (images[e].empty() || !accepted(e, images[e])) return {};
        generators.push_back(e);
        // Every product of a generator and an element reached from here on, until none is new (an element left
        // out is matched itself, later).
        const std::size_t first = reached.size();
        reached.push_back(e);
        for (std::size_t k = first; k < reached.size(); ++k)
            for (std::size_t s : generators) {
                const std::size_t product = indexOf(nonIdentity[s] * nonIdentity[reached[k]]);
                if (product == count || !images[product].empty()) continue;
                std::vector<std::uint32_t>& composed = images[product];
                composed.resize(points.size());
                for (std::size_t r = 0; r < points.size(); ++r) composed[r] = images[s][images[reached[k]][r]];
                reached.push_back(product);
            }
    }
    return images;
}

// Each position replaced by the mean of its orbit's positions brought back by the group, and each image by
// that mean's image: the positions are then symmetric to rounding, so that copies meet where the tile's
// vertices met, and quantization on a grid the instances map onto itself keeps them together.
std::vector<Eigen::Vector3d> symmetrized(const std::vector<Eigen::Vector3d>& points,
                                         const std::vector<Eigen::Matrix3d>& nonIdentity,
                                         const std::vector<std::vector<std::uint32_t>>& images) {
    std::vector<Eigen::Vector3d> out(points.size());
    std::vector<char> done(points.size(), 0);
    for (std::size_t r = 0; r < points.size(); ++r) {
        if (done[r]) continue;
        Eigen::Vector3d mean = points[r];
        for (std::size_t e = 0; e < nonIdentity.size(); ++e) mean += nonIdentity[e].transpose() * points[images[e][r]];
        mean /= double(nonIdentity.size() + 1);
        out[r] = mean;
        done[r] = 1;
        for (std::size_t e = 0; e < nonIdentity.size(); ++e) {
            const std::uint32_t image = images[e][r];
            if (done[image]) continue;  // r itself, or an image reached before: the mean is fixed by both
            out[image] = nonIdentity[e] * mean;
            done[image] = 1;
        }
    }
    return out;
}

}  // namespace

std::optional<TriangleOrbits> triangleOrbits(const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                                             const Eigen::Vector3d& centre, double tolerance) {
    TriangleOrbits result;
    // The tile's positions, welded within the tolerance, relative to the centre.
    const std::vector<std::uint32_t> welded = weldPositions(tile.positions, tolerance);
    result.positionOf.resize(tile.positions.size());
    std::vector<Eigen::Vector3d> points;
    for (std::size_t v = 0; v < tile.positions.size(); ++v) {
        if (welded[v] == v) {
            result.positionOf[v] = static_cast<std::uint32_t>(points.size());
            points.push_back(tile.positions[v] - centre);
        } else {
            result.positionOf[v] = result.positionOf[welded[v]];  // welded[v] < v
        }
    }
    const std::size_t count = tile.triangles.size();
    auto cornersOf = [&](std::size_t t) {
        const Triangle& triangle = tile.triangles[t];
        return Corners{result.positionOf[triangle[0]], result.positionOf[triangle[1]], result.positionOf[triangle[2]]};
    };
    std::unordered_map<Corners, std::uint32_t, CornersHash> triangleAt;
    triangleAt.reserve(count);
    for (std::size_t t = 0; t < count; ++t)
        if (!triangleAt.emplace(sorted(cornersOf(t)), static_cast<std::uint32_t>(t)).second)
            return std::nullopt;  // two triangles on the same corners: which maps to which is unclear
    // The triangle that element e (its position images `image`) takes triangle t to, wound the same way, if any.
    auto imageOf = [&](std::size_t t, std::size_t e, const std::vector<std::uint32_t>& image) {
        const Corners corners = cornersOf(t);
        // A mirror reverses the winding, which the copy's node reverses back (fundamental_region.hpp).
        const Corners moved = nonIdentity[e].determinant() > 0
                                  ? Corners{image[corners[0]], image[corners[1]], image[corners[2]]}
                                  : Corners{image[corners[0]], image[corners[2]], image[corners[1]]};
        const auto found = triangleAt.find(sorted(moved));
        return found != triangleAt.end() && sameWinding(moved, cornersOf(found->second))
                   ? std::optional<std::uint32_t>(found->second)
                   : std::nullopt;
    };
    // Where the elements matched against the points map the triangles onto one another, so do their products: one
    // that does not fails the group before the products' images are composed (C360v, whose mirrors turn a lathe's
    // quads' diagonals: 720 x 145000 images, 0.3 s and 400 MB).
    auto mapsTriangles = [&](std::size_t e, const std::vector<std::uint32_t>& image) {
        for (std::size_t t = 0; t < count; ++t)
            if (!imageOf(t, e, image)) return false;
        return true;
    };
    result.images = positionImages(points, nonIdentity, tolerance, mapsTriangles);
    if (result.images.empty()) return std::nullopt;  // the group does not map the tile's corners onto one another

    std::vector<char> done(count, 0);
    for (std::size_t t = 0; t < count; ++t) {
        if (done[t]) continue;
        done[t] = 1;
        std::vector<std::uint32_t> orbit{static_cast<std::uint32_t>(t)};
        for (std::size_t e = 0; e < nonIdentity.size(); ++e) {
            // No image, one wound the other way (the copy would face away), or one reached twice in the orbit
            // (a triangle some element maps onto itself, which would be drawn once per element that fixes it).
            const std::optional<std::uint32_t> found = imageOf(t, e, result.images[e]);
            if (!found || done[*found]) return std::nullopt;
            done[*found] = 1;
            orbit.push_back(*found);
        }
        result.orbits.push_back(std::move(orbit));
    }
    return result;
}

Primitive wholeTriangleRegion(const Primitive& tile, const TriangleOrbits& orbits,
                              const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& seed) {
    std::vector<Eigen::Vector3d> points(orbits.images.front().size());
    for (std::size_t v = 0; v < tile.positions.size(); ++v) points[orbits.positionOf[v]] = tile.positions[v] - centre;
    const std::vector<Eigen::Vector3d> symmetric = symmetrized(points, nonIdentity, orbits.images);

    // Each orbit's triangle whose centroid is nearest the seed: the one whose centroid lies in the Dirichlet
    // cone, so that the region is a patch of the tile around the seed.
    auto nearness = [&](std::uint32_t t) {
        double sum = 0;
        for (std::uint32_t corner : tile.triangles[t]) sum += seed.dot(symmetric[orbits.positionOf[corner]]);
        return sum;
    };
    std::vector<char> kept(tile.triangles.size(), 0);
    for (const std::vector<std::uint32_t>& orbit : orbits.orbits) {
        std::uint32_t best = orbit.front();
        double bestNearness = nearness(best);
        for (std::uint32_t t : orbit)
            if (const double n = nearness(t); n > bestNearness) bestNearness = n, best = t;
        kept[best] = 1;
    }

    Primitive region = tile;
    for (std::size_t v = 0; v < region.positions.size(); ++v)
        region.positions[v] = centre + symmetric[orbits.positionOf[v]];
    region.triangles.clear();
    constexpr std::uint32_t kUnused = ~std::uint32_t(0);
    std::vector<std::uint32_t> remap(tile.positions.size(), kUnused);
    for (std::size_t t = 0; t < kept.size(); ++t)
        if (kept[t])
            for (std::uint32_t corner : tile.triangles[t]) remap[corner] = 0;
    std::vector<std::uint32_t> vertices;
    for (std::uint32_t v = 0; v < remap.size(); ++v)
        if (remap[v] != kUnused) remap[v] = static_cast<std::uint32_t>(vertices.size()), vertices.push_back(v);
    keepVertices(region, vertices);
    for (std::size_t t = 0; t < kept.size(); ++t)
        if (kept[t]) {
            const Triangle& triangle = tile.triangles[t];
            region.triangles.push_back({remap[triangle[0]], remap[triangle[1]], remap[triangle[2]]});
        }
    return region;
}

}  // namespace symcompress::region_detail
