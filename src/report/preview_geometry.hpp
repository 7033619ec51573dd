// The geometry a report embeds: meshes as float positions and triangle indices, each optionally with a
// class per vertex, simplified by vertex clustering when the page's triangle budget asks for it.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace symcompress {

constexpr std::uint32_t kNoClass = std::numeric_limits<std::uint32_t>::max();

// One surface of a geometry: positions and triangles held elsewhere (they outlive the geometry).
struct PreviewPiece {
    const std::vector<Eigen::Vector3d>* positions = nullptr;
    const std::vector<Triangle>* triangles = nullptr;
    std::uint32_t vertexClass = kNoClass;  // given to each of its vertices when the geometry keeps classes
};

struct PreviewSource {
    std::vector<PreviewPiece> pieces;
    bool vertexClasses = false;
};

struct PreviewGeometry {
    std::vector<float> positions;  // x y z per vertex
    std::vector<std::uint32_t> indices;
    std::vector<std::uint32_t> vertexClasses;  // one per vertex, or empty
    std::size_t triangles() const { return indices.size() / 3; }
};

// Each piece's vertices snapped to cells of `cell` times the piece's diagonal (0 keeps them all): the
// vertices of a cell become their mean and triangles left with fewer than three corners are dropped. Pieces
// are clustered apart, each relative to its own size (a small part keeps its shape while a big one is
// simplified), and a vertex keeps its piece's class.
PreviewGeometry previewGeometry(const PreviewSource& source, double cell);

// The triangles previewGeometry(source, cell) keeps, without building it.
std::size_t previewTriangles(const PreviewSource& source, double cell);

// The smallest cell (to within a few percent) whose previews keep at most `budget` triangles in all; 0 when
// every triangle fits.
double previewCell(const std::vector<PreviewSource>& sources, std::size_t budget);

std::string base64(const void* bytes, std::size_t count);

}  // namespace symcompress
