// Vertex clustering for the report's preview, and the base64 the page embeds it in.
#include "report/preview_geometry.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace symcompress {
namespace {

// Calls emit(a, b, c) for each triangle that keeps three distinct cells, with the cells' indices; fills
// `means` (sums, then divided) with each cell's mean position when it is given.
template <class Emit>
void clusterPiece(const PreviewPiece& piece, double cell, std::vector<Eigen::Vector3d>* means, Emit&& emit) {
    const std::vector<Eigen::Vector3d>& positions = *piece.positions;
    std::vector<std::uint32_t> cellOf(positions.size());
    std::vector<std::uint32_t> members;
    if (cell <= 0) {
        for (std::uint32_t v = 0; v < positions.size(); ++v) cellOf[v] = v;
        if (means) *means = positions;
    } else {
        // Cells relative to the piece's own size: a small part keeps its shape while a big one is simplified.
        Eigen::AlignedBox3d box;
        for (const Eigen::Vector3d& p : positions) box.extend(p);
        const double step = cell * std::max(box.isEmpty() ? 0.0 : box.diagonal().norm(), 1e-300);
        std::unordered_map<std::uint64_t, std::uint32_t> cells;
        cells.reserve(positions.size());
        for (std::size_t v = 0; v < positions.size(); ++v) {
            // 21 bits a coordinate: the cells are never finer than a millionth of the diagonal.
            std::uint64_t key = 0;
            for (int axis = 0; axis < 3; ++axis)
                key |= (std::uint64_t(std::int64_t(std::floor(positions[v][axis] / step))) & 0x1fffff) << (21 * axis);
            const auto found = cells.emplace(key, std::uint32_t(cells.size()));
            cellOf[v] = found.first->second;
        }
        if (means) {
            means->assign(cells.size(), Eigen::Vector3d::Zero());
            members.assign(cells.size(), 0);
            for (std::size_t v = 0; v < positions.size(); ++v) {
                (*means)[cellOf[v]] += positions[v];
                ++members[cellOf[v]];
            }
            for (std::size_t c = 0; c < means->size(); ++c) (*means)[c] /= double(members[c]);
        }
    }
    for (const Triangle& t : *piece.triangles) {
        const std::uint32_t a = cellOf[t[0]], b = cellOf[t[1]], c = cellOf[t[2]];
        if (a != b && b != c && a != c) emit(a, b, c);
    }
}

}  // namespace

PreviewGeometry previewGeometry(const PreviewSource& source, double cell) {
    PreviewGeometry geometry;
    std::vector<Eigen::Vector3d> means;
    for (const PreviewPiece& piece : source.pieces) {
        const std::uint32_t offset = std::uint32_t(geometry.positions.size() / 3);
        // Only the cells some kept triangle uses are written.
        std::vector<std::uint32_t> written;
        clusterPiece(piece, cell, &means, [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
            if (written.empty()) written.assign(means.size(), kNoClass);
            for (std::uint32_t corner : {a, b, c}) {
                if (written[corner] == kNoClass) {
                    written[corner] = std::uint32_t(geometry.positions.size() / 3) - offset;
                    for (int axis = 0; axis < 3; ++axis) geometry.positions.push_back(float(means[corner][axis]));
                    if (source.vertexClasses) geometry.vertexClasses.push_back(piece.vertexClass);
                }
                geometry.indices.push_back(offset + written[corner]);
            }
        });
    }
    return geometry;
}

std::size_t previewTriangles(const PreviewSource& source, double cell) {
    std::size_t kept = 0;
    for (const PreviewPiece& piece : source.pieces)
        clusterPiece(piece, cell, nullptr, [&](std::uint32_t, std::uint32_t, std::uint32_t) { ++kept; });
    return kept;
}

double previewCell(const std::vector<PreviewSource>& sources, std::size_t budget) {
    auto triangles = [&](double cell) {
        std::size_t total = 0;
        for (const PreviewSource& source : sources) total += previewTriangles(source, cell);
        return total;
    };
    if (triangles(0) <= budget) return 0;
    // Bisection on the cell's logarithm: more triangles go as the cells grow (not strictly, but closely).
    double fine = 1e-6, coarse = 0.25;
    for (int step = 0; step < 14 && coarse / fine > 1.05; ++step) {
        const double middle = std::sqrt(fine * coarse);
        (triangles(middle) <= budget ? coarse : fine) = middle;
    }
    return coarse;
}

std::string base64(const void* bytes, std::size_t count) {
    static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto* in = static_cast<const unsigned char*>(bytes);
    std::string out;
    out.reserve((count + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < count; i += 3) {
        const std::uint32_t word = (std::uint32_t(in[i]) << 16) | (std::uint32_t(in[i + 1]) << 8) | in[i + 2];
        for (int shift : {18, 12, 6, 0}) out.push_back(kDigits[(word >> shift) & 63]);
    }
    if (i < count) {
        const std::uint32_t word = (std::uint32_t(in[i]) << 16) | (i + 1 < count ? std::uint32_t(in[i + 1]) << 8 : 0);
        out.push_back(kDigits[(word >> 18) & 63]);
        out.push_back(kDigits[(word >> 12) & 63]);
        out.push_back(i + 1 < count ? kDigits[(word >> 6) & 63] : '=');
        out.push_back('=');
    }
    return out;
}

}  // namespace symcompress
