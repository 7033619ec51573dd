#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/tiles.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <numeric>
#include <string>

namespace symcompress {

namespace {

// Union-find over triangles, with path halving.
class DisjointSets {
public:
    explicit DisjointSets(std::size_t count) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the smaller index leads: tiles keep input order
    }

private:
    std::vector<std::uint32_t> parent_;
};

}  // namespace

std::vector<Tile> splitIntoTiles(const std::vector<WorldPrimitive>& soup, const TileOptions& options) {
    // All positions as one list (pointers into the soup, not a copy), so that welding works across primitives
    // of one material.
    std::vector<const Eigen::Vector3d*> positions;
    Eigen::AlignedBox3d bounds;
    std::size_t triangleCount = 0;
    for (const WorldPrimitive& world : soup) {
        for (const Triangle& triangle : world.primitive.triangles)
            for (std::uint32_t index : triangle) bounds.extend(world.primitive.positions[index]);
        for (const Eigen::Vector3d& p : world.primitive.positions) positions.push_back(&p);
        triangleCount += world.primitive.triangles.size();
    }
    const double diagonal = bounds.isEmpty() ? 0.0 : bounds.diagonal().norm();
    const std::vector<std::uint32_t> welded = weldPositions(positions, options.weldTolerance * diagonal);

    // Every triangle's welded corners, in the soup's order, and whether it has two corners at one point (zero
    // area: it belongs to no tile).
    std::vector<Triangle> weldedTriangles;
    weldedTriangles.reserve(triangleCount);
    std::vector<char> zeroArea;
    zeroArea.reserve(triangleCount);
    {
        std::uint32_t first = 0;
        for (const WorldPrimitive& world : soup) {
            const std::vector<Eigen::Vector3d>& p = world.primitive.positions;
            for (const Triangle& t : world.primitive.triangles) {
                weldedTriangles.push_back({welded[first + t[0]], welded[first + t[1]], welded[first + t[2]]});
                zeroArea.push_back(hasTwoCornersAtOnePoint(p, t));
            }
            first += static_cast<std::uint32_t>(p.size());
        }
    }
    // Each triangle's kind: its material and the names of its other attributes (attributeSignature), which a tile
    // never mixes, so that its primitive carries every attribute of each of its triangles.
    // A primitive whose material is drawn whole is a kind of its own.
    std::vector<int> kinds;
    kinds.reserve(triangleCount);
    std::vector<char> whole(soup.size(), 0);
    {
        std::map<std::pair<int, std::string>, int> kindOf;
        int kindsAlone = 0;
        for (std::size_t p = 0; p < soup.size(); ++p) {
            const Primitive& primitive = soup[p].primitive;
            const int m = primitive.material;
            whole[p] = m >= 0 && std::size_t(m) < options.wholePrimitiveMaterials.size() &&
                       options.wholePrimitiveMaterials[std::size_t(m)];
            const int kind =
                whole[p] ? -++kindsAlone
                         : kindOf.try_emplace({m, attributeSignature(primitive)}, int(kindOf.size())).first->second;
            kinds.insert(kinds.end(), primitive.triangles.size(), kind);
        }
    }

    // Triangles that share an undirected edge (and a kind) are in one tile: for each edge a-b (a != b), the
    // triangles at a that also have b as a corner (every two distinct corners of a triangle are an edge). The
    // sets' roots are their first triangles whatever order they are united in.
    DisjointSets sets(weldedTriangles.size());
    {
        std::vector<std::uint32_t> start(positions.size() + 1, 0), incident(weldedTriangles.size() * 3);
        for (const Triangle& triangle : weldedTriangles)
            for (std::uint32_t v : triangle) ++start[v + 1];
        for (std::size_t v = 0; v < positions.size(); ++v) start[v + 1] += start[v];
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::uint32_t t = 0; t < weldedTriangles.size(); ++t)
            for (std::uint32_t v : weldedTriangles[t]) incident[fill[v]++] = t;
        for (std::uint32_t t = 0; t < weldedTriangles.size(); ++t) {
            if (zeroArea[t]) continue;
            const Triangle& triangle = weldedTriangles[t];
            for (int corner = 0; corner < 3; ++corner) {
                const std::uint32_t a = triangle[corner], b = triangle[(corner + 1) % 3];
                if (a == b) continue;  // a collapsed edge connects nothing
                for (std::uint32_t i = start[a]; i < start[a + 1]; ++i) {
                    const std::uint32_t u = incident[i];
                    if (u >= t) continue;  // each pair once; a triangle listed twice at a (a collapsed corner) is harmless
                    const Triangle& other = weldedTriangles[u];
                    if ((other[0] == b || other[1] == b || other[2] == b) && kinds[u] == kinds[t] && !zeroArea[u])
                        sets.unite(u, t);
                }
            }
        }
    }

    // A primitive drawn whole: all its triangles one tile, connected or not.
    {
        std::uint32_t first = 0;
        for (std::size_t p = 0; p < soup.size(); ++p) {
            const auto count = static_cast<std::uint32_t>(soup[p].primitive.triangles.size());
            if (whole[p]) {
                std::uint32_t lead = first;
                while (lead < first + count && zeroArea[lead]) ++lead;
                for (std::uint32_t t = lead + 1; t < first + count; ++t)
                    if (!zeroArea[t]) sets.unite(lead, t);
            }
            first += count;
        }
    }

    std::vector<Tile> tiles;
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> tileOfRoot(weldedTriangles.size(), kNone);
    {
        std::uint32_t p = 0, local = 0;  // the triangle's source: primitive p, its triangle `local`
        for (std::uint32_t t = 0; t < weldedTriangles.size(); ++t, ++local) {
            while (local == soup[p].primitive.triangles.size()) ++p, local = 0;
            if (zeroArea[t]) continue;
            const std::uint32_t root = sets.find(t);
            if (tileOfRoot[root] == kNone) {
                tileOfRoot[root] = static_cast<std::uint32_t>(tiles.size());
                tiles.emplace_back();
                tiles.back().material = soup[p].primitive.material;
            }
            Tile& tile = tiles[tileOfRoot[root]];
            tile.sources.push_back({p, local});
            tile.mesh.triangles.push_back(weldedTriangles[t]);  // global indices for now, compacted below
        }
    }
    std::vector<std::uint32_t>().swap(tileOfRoot);
    std::vector<Triangle>().swap(weldedTriangles);
    std::vector<int>().swap(kinds);
    // Local indices in the order of first use; `local` is shared by the tiles (a tile's entries are those
    // stamped with its number).
    std::vector<std::uint32_t> local(positions.size()), stamp(positions.size(), kNone);
    for (std::uint32_t k = 0; k < tiles.size(); ++k) {
        Tile& tile = tiles[k];
        for (Triangle& triangle : tile.mesh.triangles)
            for (std::uint32_t& index : triangle) {
                if (stamp[index] != k) {
                    stamp[index] = k;
                    local[index] = static_cast<std::uint32_t>(tile.mesh.positions.size());
                    tile.mesh.positions.push_back(*positions[index]);
                }
                index = local[index];
            }
    }
    return tiles;
}

}  // namespace symcompress
