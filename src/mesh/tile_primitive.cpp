#include "symcompress/tiles.hpp"

#include <unordered_map>

namespace symcompress {

Primitive tilePrimitive(const Tile& tile, const std::vector<WorldPrimitive>& soup) {
    Primitive out;
    out.material = tile.material;
    if (tile.sources.empty()) return out;
    const Primitive& first = soup[tile.sources.front().primitive].primitive;
    // A tile may gather triangles from several primitives of one material: an attribute is kept only
    // when every one of them has it.
    bool normals = !first.normals.empty(), texcoords = !first.texcoords.empty(), colors = !first.colors.empty();
    for (const TriangleSource& source : tile.sources) {
        const Primitive& primitive = soup[source.primitive].primitive;
        normals = normals && !primitive.normals.empty();
        texcoords = texcoords && !primitive.texcoords.empty();
        colors = colors && !primitive.colors.empty();
    }
    // Its other attributes every source has (splitIntoTiles never mixes them).
    for (const VertexAttribute& attribute : first.attributes) out.attributes.push_back(attribute.withoutValues());
    std::unordered_map<std::uint64_t, std::uint32_t> localIndex;  // (primitive, vertex) -> index in out
    for (const TriangleSource& source : tile.sources) {
        const Primitive& primitive = soup[source.primitive].primitive;
        Triangle triangle;
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t vertex = primitive.triangles[source.triangle][corner];
            const std::uint64_t key = static_cast<std::uint64_t>(source.primitive) << 32 | vertex;
            auto [entry, inserted] = localIndex.try_emplace(key, static_cast<std::uint32_t>(out.positions.size()));
            if (inserted) {
                out.positions.push_back(primitive.positions[vertex]);
                if (normals) out.normals.push_back(primitive.normals[vertex]);
                if (texcoords) out.texcoords.push_back(primitive.texcoords[vertex]);
                if (colors) out.colors.push_back(primitive.colors[vertex]);
                for (std::size_t a = 0; a < out.attributes.size(); ++a)
                    out.attributes[a].appendVertex(primitive.attributes[a], vertex);
            }
            triangle[corner] = entry->second;
        }
        out.triangles.push_back(triangle);
    }
    return out;
}

}  // namespace symcompress
