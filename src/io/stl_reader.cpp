// STL reader, ASCII and binary. STL is a triangle soup: corners are shared here only where their
// positions are bit-for-bit equal; welding within a tolerance is the tiles stage's job.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "text_scanner.hpp"

#include <cmath>
#include <cstring>
#include <map>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// Shares corners with equal coordinates and appends the triangle.
class SoupIndexer {
public:
    explicit SoupIndexer(Primitive& out) : out_(out) {}
    void addTriangle(const std::array<Eigen::Vector3d, 3>& corners) {
        Triangle triangle;
        for (int k = 0; k < 3; ++k) {
            const std::array<double, 3> key = {corners[k].x(), corners[k].y(), corners[k].z()};
            auto [entry, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(out_.positions.size()));
            if (inserted) out_.positions.push_back(corners[k]);
            triangle[k] = entry->second;
        }
        out_.triangles.push_back(triangle);
    }

private:
    Primitive& out_;
    std::map<std::array<double, 3>, std::uint32_t> index_;
};

void checkFinite(const fs::path& file, const Eigen::Vector3d& p, std::size_t facet) {
    if (!p.allFinite()) throw FileError(file, "facet " + std::to_string(facet) + " has a NaN or infinite coordinate");
}

void readBinaryStl(const fs::path& file, const std::vector<unsigned char>& bytes, Primitive& out) {
    std::uint32_t count;
    std::memcpy(&count, bytes.data() + 80, 4);
    SoupIndexer indexer(out);
    for (std::uint32_t f = 0; f < count; ++f) {
        const unsigned char* record = bytes.data() + 84 + 50 * static_cast<std::size_t>(f);
        std::array<Eigen::Vector3d, 3> corners;
        for (int k = 0; k < 3; ++k) {
            float xyz[3];
            std::memcpy(xyz, record + 12 + 12 * k, 12);
            corners[k] = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
            checkFinite(file, corners[k], f);
        }
        indexer.addTriangle(corners);
    }
}

void readAsciiStl(const fs::path& file, const std::vector<unsigned char>& bytes, Primitive& out) {
    TextScanner scanner(file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    SoupIndexer indexer(out);
    std::array<Eigen::Vector3d, 3> corners;
    int corner = 0;
    bool sawSolid = false, sawEnd = false;
    while (!scanner.atEnd()) {
        std::string_view line = scanner.nextLine();
        const std::string_view keyword = nextWord(line);
        if (keyword == "solid") {
            sawSolid = true;
        } else if (keyword == "vertex") {
            if (corner == 3) scanner.fail("a facet with more than 3 vertices");
            Eigen::Vector3d p;
            for (int c = 0; c < 3; ++c) p[c] = nextFiniteNumber<double>(line, scanner, "vertex coordinate");
            corners[corner++] = p;
        } else if (keyword == "endloop") {
            if (corner != 3) scanner.fail("a facet with " + std::to_string(corner) + " vertices instead of 3");
            indexer.addTriangle(corners);
            corner = 0;
        } else if (keyword == "endsolid") {
            sawEnd = true;
        } else if (!keyword.empty() && keyword != "facet" && keyword != "outer" && keyword != "endfacet") {
            scanner.fail("unexpected '" + std::string(keyword) + "'");
        }
    }
    if (!sawSolid) throw FileError(file, "not an STL file (no 'solid' header and not binary)");
    if (corner != 0 || !sawEnd) throw FileError(file, "truncated ASCII STL (no 'endsolid')");
}

}  // namespace

Scene readStl(const fs::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    if (bytes.empty()) throw FileError(file, "the file is empty");
    Primitive primitive;
    // Binary when the size matches the facet count; many binary files also start with "solid".
    bool binary = false;
    if (bytes.size() >= 84) {
        std::uint32_t count;
        std::memcpy(&count, bytes.data() + 80, 4);
        binary = bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
    }
    const bool looksAscii = bytes.size() >= 5 && std::memcmp(bytes.data(), "solid", 5) == 0;
    if (binary) {
        readBinaryStl(file, bytes, primitive);
    } else if (looksAscii) {
        readAsciiStl(file, bytes, primitive);
    } else if (bytes.size() >= 84) {
        std::uint32_t count;
        std::memcpy(&count, bytes.data() + 80, 4);
        throw FileError(file, "binary STL header announces " + std::to_string(count) + " triangles (" +
                                  std::to_string(84 + 50 * static_cast<std::uint64_t>(count)) + " bytes) but the file has " +
                                  std::to_string(bytes.size()) + " bytes (truncated?)");
    } else {
        throw FileError(file, "too short for a binary STL and not ASCII STL");
    }
    return sceneOfOneMesh(file.stem().string(), std::move(primitive));
}

}  // namespace symcompress
