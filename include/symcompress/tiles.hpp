// Tiles (paper 6.5.2): the maximal edge-connected sets of triangles of a polygon soup, per material.
#pragma once

#include "symcompress/scene_ops.hpp"

#include <cstdint>
#include <vector>

namespace symcompress {

// Where a tile's triangle came from: the primitive (index into the flattened scene) and its triangle.
struct TriangleSource {
    std::uint32_t primitive;
    std::uint32_t triangle;
};

// Invariant: mesh.triangles[i] is the welded copy of sources[i]; every position of mesh is used by a
// triangle; all triangles share one material.
struct Tile {
    int material = -1;
    TriangleMesh mesh;
    std::vector<TriangleSource> sources;
};

struct TileOptions {
    // Positions closer than this, relative to the soup's bounding-box diagonal, are one vertex.
    double weldTolerance = 1e-6;
    // Materials (by index) whose every primitive, as one node draws it, is one tile however its triangles connect,
    // and shares no tile with another: those viewers draw blended (drawnBlended), which they sort as wholes.
    std::vector<bool> wholePrimitiveMaterials;
};

// Welds positions within the tolerance, then groups triangles that share an edge (two welded vertices),
// never across materials or sets of attributes (attributeSignature). Tiles come in order of their first triangle.
// A triangle with two corners at one point (zero area: it draws nothing) belongs to no tile; the compression
// keeps those apart (SceneAnalysis::zeroArea).
std::vector<Tile> splitIntoTiles(const std::vector<WorldPrimitive>& soup, const TileOptions& options = {});

// The tile's triangles with their original (unwelded) vertices and attributes, taken from the soup:
// what a writer stores for the tile. Vertices shared by several of its triangles in the source stay shared.
Primitive tilePrimitive(const Tile& tile, const std::vector<WorldPrimitive>& soup);

}  // namespace symcompress
