// STL reader, ASCII and binary. STL is a triangle soup: corners are shared here only where their
// positions are bit-for-bit equal; welding within a tolerance is the tiles stage's job.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "text_scanner.hpp"

#include <algorithm>
#include <cctype>
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

// `word` is `keyword` in capitals or not: STL's keywords are lower case, and some writers spell them in capitals
// ("SOLID", "FACET NORMAL"), which readers take as well.
bool isKeyword(std::string_view word, std::string_view keyword) {
    return word.size() == keyword.size() && std::equal(word.begin(), word.end(), keyword.begin(), [](char a, char b) {
               return std::tolower(static_cast<unsigned char>(a)) == b;
           });
}

void checkFinite(const fs::path& file, const Eigen::Vector3d& p, std::size_t facet) {
    if (!p.allFinite()) throw FileError(file, "facet " + std::to_string(facet) + " has a NaN or infinite coordinate");
}

std::uint32_t announcedTriangles(const std::vector<unsigned char>& bytes) {
    std::uint32_t count;
    std::memcpy(&count, bytes.data() + 80, 4);
    return count;
}

std::uint64_t binarySize(std::uint32_t triangles) { return 84 + 50 * static_cast<std::uint64_t>(triangles); }

// Reads the triangles the header announces (the caller checked the file holds them).
void readBinaryStl(const fs::path& file, const std::vector<unsigned char>& bytes, Primitive& out) {
    const std::uint32_t count = announcedTriangles(bytes);
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
        if (isKeyword(keyword, "solid")) {
            sawSolid = true;
        } else if (isKeyword(keyword, "vertex")) {
            if (corner == 3) scanner.fail("a facet with more than 3 vertices");
            Eigen::Vector3d p;
            for (int c = 0; c < 3; ++c) p[c] = nextFiniteNumber<double>(line, scanner, "vertex coordinate");
            corners[corner++] = p;
        } else if (isKeyword(keyword, "endloop")) {
            if (corner != 3) scanner.fail("a facet with " + std::to_string(corner) + " vertices instead of 3");
            indexer.addTriangle(corners);
            corner = 0;
        } else if (isKeyword(keyword, "endsolid")) {
            sawEnd = true;
        } else if (!keyword.empty() && !isKeyword(keyword, "facet") && !isKeyword(keyword, "outer") &&
                   !isKeyword(keyword, "endfacet")) {
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
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    // Binary when the size matches the header's triangle count, though many binary headers start with "solid"
    // too; else ASCII when it starts with "solid" (in capitals or not, after any byte order mark) and is text
    // (a binary file's "solid" comes with NUL bytes: its count's high bytes, its zeros); else binary when the
    // file holds the triangles its header announces and more (some writers pad it), the rest ignored.
    const std::uint64_t announced = bytes.size() >= 84 ? binarySize(announcedTriangles(bytes)) : 0;
    const bool looksAscii =
        isKeyword(withoutByteOrderMark(text).substr(0, 5), "solid") && text.find('\0') == std::string_view::npos;
    std::uint64_t trailingBytes = 0;
    if (announced == bytes.size()) {
        readBinaryStl(file, bytes, primitive);
    } else if (looksAscii) {
        readAsciiStl(file, bytes, primitive);
    } else if (bytes.size() < 84) {
        throw FileError(file, "too short for a binary STL and not ASCII STL");
    } else if (announced > bytes.size()) {
        throw FileError(file, "binary STL header announces " + std::to_string(announcedTriangles(bytes)) +
                                  " triangles (" + std::to_string(announced) + " bytes) but the file has " +
                                  std::to_string(bytes.size()) + " bytes (truncated?)");
    } else {
        readBinaryStl(file, bytes, primitive);
        trailingBytes = bytes.size() - announced;
    }
    Scene scene = sceneOfOneMesh(file.stem().string(), std::move(primitive));
    if (trailingBytes)
        scene.warnings.push_back(file.filename().string() + ": " + std::to_string(trailingBytes) + " bytes after the " +
                                 std::to_string(announcedTriangles(bytes)) +
                                 " triangles its binary header announces ignored");
    return scene;
}

}  // namespace symcompress
