#include "symcompress/tiles.hpp"
#include "symcompress/detail/weld_positions.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>
#include <unordered_map>

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

struct EdgeOfMaterial {
    std::uint64_t edge;  // the two welded vertex indices, smaller first
    int material;
    bool operator==(const EdgeOfMaterial& other) const { return edge == other.edge && material == other.material; }
};
struct EdgeOfMaterialHash {
    std::size_t operator()(const EdgeOfMaterial& key) const {
        return std::hash<std::uint64_t>()(key.edge * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(key.material));
    }
};

}  // namespace

std::vector<Tile> splitIntoTiles(const std::vector<WorldPrimitive>& soup, const TileOptions& options) {
    // All positions in one array, so that welding works across primitives of one material.
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::uint32_t> firstVertex;
    Eigen::AlignedBox3d bounds;
    for (const WorldPrimitive& world : soup) {
        firstVertex.push_back(static_cast<std::uint32_t>(positions.size()));
        for (const Triangle& triangle : world.primitive.triangles)
            for (std::uint32_t index : triangle) bounds.extend(world.primitive.positions[index]);
        positions.insert(positions.end(), world.primitive.positions.begin(), world.primitive.positions.end());
    }
    const double diagonal = bounds.isEmpty() ? 0.0 : bounds.diagonal().norm();
    const std::vector<std::uint32_t> welded = weldPositions(positions, options.weldTolerance * diagonal);

    std::vector<TriangleSource> sources;
    std::vector<Triangle> weldedTriangles;
    std::vector<int> materials;
    for (std::uint32_t p = 0; p < soup.size(); ++p) {
        const Primitive& primitive = soup[p].primitive;
        for (std::uint32_t t = 0; t < primitive.triangles.size(); ++t) {
            const Triangle& triangle = primitive.triangles[t];
            sources.push_back({p, t});
            weldedTriangles.push_back({welded[firstVertex[p] + triangle[0]], welded[firstVertex[p] + triangle[1]],
                                       welded[firstVertex[p] + triangle[2]]});
            materials.push_back(primitive.material);
        }
    }

    // Triangles that share an undirected edge (and a material) are in one tile.
    DisjointSets sets(weldedTriangles.size());
    std::unordered_map<EdgeOfMaterial, std::uint32_t, EdgeOfMaterialHash> firstTriangleOfEdge;
    firstTriangleOfEdge.reserve(weldedTriangles.size() * 3 / 2);
    for (std::uint32_t t = 0; t < weldedTriangles.size(); ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            std::uint32_t a = weldedTriangles[t][corner], b = weldedTriangles[t][(corner + 1) % 3];
            if (a == b) continue;  // a collapsed edge connects nothing
            if (a > b) std::swap(a, b);
            // The material is part of the key: tiles never cross materials.
            const EdgeOfMaterial key{static_cast<std::uint64_t>(a) << 32 | b, materials[t]};
            auto [entry, inserted] = firstTriangleOfEdge.try_emplace(key, t);
            if (!inserted) sets.unite(entry->second, t);
        }
    }

    std::vector<Tile> tiles;
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> tileOfRoot(weldedTriangles.size(), kNone);
    for (std::uint32_t t = 0; t < weldedTriangles.size(); ++t) {
        const std::uint32_t root = sets.find(t);
        if (tileOfRoot[root] == kNone) {
            tileOfRoot[root] = static_cast<std::uint32_t>(tiles.size());
            tiles.emplace_back();
            tiles.back().material = materials[t];
        }
        Tile& tile = tiles[tileOfRoot[root]];
        tile.sources.push_back(sources[t]);
        tile.mesh.triangles.push_back(weldedTriangles[t]);  // global indices for now, compacted below
    }
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
                    tile.mesh.positions.push_back(positions[index]);
                }
                index = local[index];
            }
    }
    return tiles;
}

}  // namespace symcompress
