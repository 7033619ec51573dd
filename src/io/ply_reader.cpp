// PLY reader: ASCII, binary little and big endian; any scalar property types; faces as lists of any
// length (polygons triangulated); properties we do not use are skipped.
#include "common/color_space.hpp"
#include "image_file.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/triangulate_polygon.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "text_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
    std::string name;
    ScalarType type = ScalarType::Float32;
    bool isList = false;
    ScalarType countType = ScalarType::UInt8;
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
};

int scalarSize(ScalarType type) {
    switch (type) {
        case ScalarType::Int8:
        case ScalarType::UInt8: return 1;
        case ScalarType::Int16:
        case ScalarType::UInt16: return 2;
        case ScalarType::Int32:
        case ScalarType::UInt32:
        case ScalarType::Float32: return 4;
        case ScalarType::Float64: return 8;
    }
    return 0;
}

bool parseScalarType(std::string_view name, ScalarType& type) {
    static const std::pair<const char*, ScalarType> names[] = {
        {"char", ScalarType::Int8},     {"int8", ScalarType::Int8},       {"uchar", ScalarType::UInt8},
        {"uint8", ScalarType::UInt8},   {"short", ScalarType::Int16},     {"int16", ScalarType::Int16},
        {"ushort", ScalarType::UInt16}, {"uint16", ScalarType::UInt16},   {"int", ScalarType::Int32},
        {"int32", ScalarType::Int32},   {"uint", ScalarType::UInt32},     {"uint32", ScalarType::UInt32},
        {"float", ScalarType::Float32}, {"float32", ScalarType::Float32}, {"double", ScalarType::Float64},
        {"float64", ScalarType::Float64}};
    for (const auto& [known, value] : names)
        if (name == known) {
            type = value;
            return true;
        }
    return false;
}

// Reads values one by one from the body, in whichever encoding the header named.
class PlyBody {
public:
    enum class Encoding { Ascii, LittleEndian, BigEndian };
    PlyBody(const fs::path& file, const std::vector<unsigned char>& bytes, std::size_t offset, Encoding encoding)
        : file_(file), bytes_(bytes), position_(offset), encoding_(encoding) {}

    double read(ScalarType type) {
        if (encoding_ == Encoding::Ascii) return readAscii();
        const int size = scalarSize(type);
        if (position_ + size > bytes_.size()) throw FileError(file_, "truncated: the body ends before the header's counts");
        unsigned char raw[8];
        std::memcpy(raw, bytes_.data() + position_, size);
        position_ += size;
        if (encoding_ == Encoding::BigEndian) std::reverse(raw, raw + size);
        auto as = [&raw](auto value) {
            std::memcpy(&value, raw, sizeof value);
            return static_cast<double>(value);
        };
        switch (type) {
            case ScalarType::Int8: return as(std::int8_t());
            case ScalarType::UInt8: return as(std::uint8_t());
            case ScalarType::Int16: return as(std::int16_t());
            case ScalarType::UInt16: return as(std::uint16_t());
            case ScalarType::Int32: return as(std::int32_t());
            case ScalarType::UInt32: return as(std::uint32_t());
            case ScalarType::Float32: return as(float());
            case ScalarType::Float64: return as(double());
        }
        return 0;
    }

    std::size_t bytesLeft() const { return position_ < bytes_.size() ? bytes_.size() - position_ : 0; }

private:
    double readAscii() {
        while (position_ < bytes_.size() && std::isspace(bytes_[position_])) ++position_;
        std::size_t end = position_;
        while (end < bytes_.size() && !std::isspace(bytes_[end])) ++end;
        if (end == position_) throw FileError(file_, "truncated: the body ends before the header's counts");
        double value;
        const std::string_view word(reinterpret_cast<const char*>(bytes_.data() + position_), end - position_);
        if (!parseNumber(word, value)) throw FileError(file_, "cannot read the number '" + std::string(word) + "'");
        position_ = end;
        return value;
    }

    const fs::path& file_;
    const std::vector<unsigned char>& bytes_;
    std::size_t position_;
    Encoding encoding_;
};

int propertyIndex(const Element& element, std::initializer_list<const char*> names) {
    for (const char* name : names)
        for (std::size_t i = 0; i < element.properties.size(); ++i)
            if (element.properties[i].name == name) return static_cast<int>(i);
    return -1;
}

// `primitive` with a vertex for each point and corner texture coordinates (s, t per corner of each face, PLY's
// t up) that faces name, the faces renumbered; the point's other attributes copied to each of its vertices.
Primitive withCornerTexcoords(Primitive primitive, std::vector<std::vector<std::uint32_t>>& faces,
                              const std::vector<std::vector<double>>& faceTexcoords) {
    Primitive out;
    out.topology = primitive.topology;
    std::map<std::tuple<std::uint32_t, double, double>, std::uint32_t> vertexOf;
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (std::size_t k = 0; k < faces[f].size(); ++k) {
            const std::uint32_t point = faces[f][k];
            const double s = faceTexcoords[f][2 * k], t = faceTexcoords[f][2 * k + 1];
            const auto [entry, added] =
                vertexOf.try_emplace({point, s, t}, static_cast<std::uint32_t>(out.positions.size()));
            if (added) {
                out.positions.push_back(primitive.positions[point]);
                if (!primitive.normals.empty()) out.normals.push_back(primitive.normals[point]);
                if (!primitive.colors.empty()) out.colors.push_back(primitive.colors[point]);
                out.texcoords.emplace_back(s, 1 - t);
            }
            faces[f][k] = entry->second;
        }
    return out;
}

}  // namespace

Scene readPly(const fs::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    if (bytes.empty()) throw FileError(file, "the file is empty");
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    TextScanner header(file, text);
    std::string_view magic = header.nextLine();
    if (nextWord(magic) != "ply")
        throw FileError(file, "not a PLY file (no 'ply' magic line)");
    PlyBody::Encoding encoding = PlyBody::Encoding::Ascii;
    std::vector<Element> elements;
    std::string textureFile;  // MeshLab's "comment TextureFile NAME" (photogrammetry tools write it too)
    bool sawFormat = false, sawEnd = false;
    while (!header.atEnd() && !sawEnd) {
        std::string_view line = header.nextLine();
        const std::string_view keyword = nextWord(line);
        if (keyword == "format") {
            const std::string_view name = nextWord(line);
            if (name == "ascii") encoding = PlyBody::Encoding::Ascii;
            else if (name == "binary_little_endian") encoding = PlyBody::Encoding::LittleEndian;
            else if (name == "binary_big_endian") encoding = PlyBody::Encoding::BigEndian;
            else header.fail("unknown format '" + std::string(name) + "'");
            sawFormat = true;
        } else if (keyword == "element") {
            Element element;
            element.name = std::string(nextWord(line));
            element.count = nextNumber<std::size_t>(line, header, "an element count");
            elements.push_back(element);
        } else if (keyword == "property") {
            if (elements.empty()) header.fail("a property before any element");
            Property property;
            std::string_view type = nextWord(line);
            if (type == "list") {
                property.isList = true;
                if (!parseScalarType(nextWord(line), property.countType)) header.fail("unknown list count type");
                type = nextWord(line);
            }
            if (!parseScalarType(type, property.type)) header.fail("unknown property type '" + std::string(type) + "'");
            property.name = std::string(nextWord(line));
            elements.back().properties.push_back(property);
        } else if (keyword == "end_header") {
            sawEnd = true;
        } else if (keyword == "comment" && nextWord(line) == "TextureFile" && textureFile.empty()) {
            textureFile = std::string(line);
            textureFile.erase(0, textureFile.find_first_not_of(" \t"));
            textureFile.erase(textureFile.find_last_not_of(" \t\r") + 1);
        } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
            header.fail("unexpected '" + std::string(keyword) + "' in the header");
        }
    }
    if (!sawFormat || !sawEnd) throw FileError(file, "incomplete PLY header (no format or no end_header)");

    Primitive primitive;
    std::vector<std::vector<std::uint32_t>> faces;
    std::vector<std::vector<double>> faceTexcoords;  // MeshLab's per-corner "texcoord" list: s, t for each corner
    std::size_t skippedPolygons = 0, otherElements = 0;
    PlyBody body(file, bytes, header.offset(), encoding);
    for (const Element& element : elements) {
        const bool isVertex = element.name == "vertex", isFace = element.name == "face";
        if (!isVertex && !isFace) ++otherElements;
        const int x = propertyIndex(element, {"x"}), y = propertyIndex(element, {"y"}), z = propertyIndex(element, {"z"});
        const int nx = propertyIndex(element, {"nx"}), ny = propertyIndex(element, {"ny"}), nz = propertyIndex(element, {"nz"});
        const int red = propertyIndex(element, {"red", "r"}), green = propertyIndex(element, {"green", "g"}),
                  blue = propertyIndex(element, {"blue", "b"}), alpha = propertyIndex(element, {"alpha", "a"});
        const int s = propertyIndex(element, {"s", "u", "texture_u", "texture_s"}),
                  t = propertyIndex(element, {"t", "v", "texture_v", "texture_t"});
        const int indices = propertyIndex(element, {"vertex_indices", "vertex_index"});
        const int cornerTexcoords = isFace ? propertyIndex(element, {"texcoord"}) : -1;
        if (isVertex && (x < 0 || y < 0 || z < 0)) throw FileError(file, "vertex element without x, y and z");
        if (isFace && (indices < 0 || !element.properties[indices].isList))
            throw FileError(file, "face element without a vertex_indices list");
        // Every item takes at least a byte per property (a digit, or a binary value or list count of at least
        // a byte), so a count the body cannot hold is refused before the loop: an element of no properties
        // holds nothing at all, however many items it claims.
        std::size_t leastItemBytes = 0;
        for (const Property& property : element.properties)
            leastItemBytes += encoding == PlyBody::Encoding::Ascii ? 1 : scalarSize(property.isList ? property.countType : property.type);
        if (leastItemBytes == 0) continue;
        if (element.count > body.bytesLeft() / leastItemBytes)
            throw FileError(file, "element '" + element.name + "' has a count of " + std::to_string(element.count) +
                                      ", more than the " + std::to_string(body.bytesLeft()) + " bytes left could hold");
        std::vector<double> values(element.properties.size());
        for (std::size_t item = 0; item < element.count; ++item) {
            std::vector<std::uint32_t> face;
            std::vector<double> texcoords;
            for (std::size_t p = 0; p < element.properties.size(); ++p) {
                const Property& property = element.properties[p];
                if (!property.isList) {
                    values[p] = body.read(property.type);
                    continue;
                }
                const double count = body.read(property.countType);
                if (!(count >= 0 && count < 1e6)) throw FileError(file, "implausible list length " + std::to_string(count));
                for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k) {
                    const double value = body.read(property.type);
                    if (isFace && static_cast<int>(p) == indices) {
                        if (!(value >= 0 && value < 4294967295.0))
                            throw FileError(file, "face " + std::to_string(item) + ": negative or invalid vertex index");
                        face.push_back(static_cast<std::uint32_t>(value));
                    }
                    if (static_cast<int>(p) == cornerTexcoords) texcoords.push_back(value);
                }
            }
            if (isVertex) {
                const Eigen::Vector3d position(values[x], values[y], values[z]);
                if (!position.allFinite())
                    throw FileError(file, "vertex " + std::to_string(item) + " has a NaN or infinite coordinate");
                primitive.positions.push_back(position);
                if (nx >= 0 && ny >= 0 && nz >= 0) primitive.normals.emplace_back(values[nx], values[ny], values[nz]);
                if (s >= 0 && t >= 0) primitive.texcoords.emplace_back(values[s], 1 - values[t]);  // PLY's v points up
                if (red >= 0 && green >= 0 && blue >= 0) {
                    // Integer colours are 0..255; float colours are already 0..1. Both are display values
                    // (sRGB-encoded), as three.js's PLYLoader reads them: COLOR_0 is linear.
                    const double scale = element.properties[red].type == ScalarType::Float32 ||
                                                 element.properties[red].type == ScalarType::Float64
                                             ? 1.0
                                             : 255.0;
                    primitive.colors.push_back(
                        linearFromSrgbColor({values[red] / scale, values[green] / scale, values[blue] / scale,
                                             alpha >= 0 ? values[alpha] / scale : 1.0}));
                }
            } else if (isFace) {
                faces.push_back(std::move(face));
                if (cornerTexcoords >= 0) faceTexcoords.push_back(std::move(texcoords));
            }
        }
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        for (std::uint32_t index : face)
            if (index >= primitive.positions.size())
                throw FileError(file, "face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                                          " out of range (" + std::to_string(primitive.positions.size()) + " vertices)");
    }
    std::vector<std::string> warnings;
    // Texture coordinates per corner: a vertex for each point and pair of coordinates, as OBJ's.
    if (!faceTexcoords.empty()) {
        bool whole = true;
        for (std::size_t f = 0; f < faces.size(); ++f)
            whole = whole && faceTexcoords[f].size() == 2 * faces[f].size() &&
                    std::all_of(faceTexcoords[f].begin(), faceTexcoords[f].end(),
                                [](double value) { return std::isfinite(value); });
        if (whole)
            primitive = withCornerTexcoords(primitive, faces, faceTexcoords);
        else
            warnings.push_back(file.filename().string() + ": a face's texcoord list is not two finite numbers a " +
                               "corner; the texture coordinates left out");
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& face = faces[f];
        if (face.size() == 3) {
            primitive.triangles.push_back({face[0], face[1], face[2]});
            continue;
        }
        std::vector<Eigen::Vector3d> corners;
        for (std::uint32_t index : face) corners.push_back(primitive.positions[index]);
        const auto triangles = triangulateFace(corners);
        if (triangles.empty()) ++skippedPolygons;
        for (const Triangle& local : triangles) primitive.triangles.push_back({face[local[0]], face[local[1]], face[local[2]]});
    }
    auto dropIfNotFinite = [&](auto& attribute, const char* name) {
        for (const auto& value : attribute)
            if (!value.allFinite()) {
                warnings.push_back(file.filename().string() + ": " + name + " with NaN or infinite values dropped");
                attribute.clear();
                return;
            }
    };
    dropIfNotFinite(primitive.normals, "normals");
    dropIfNotFinite(primitive.texcoords, "texture coordinates");
    dropIfNotFinite(primitive.colors, "colours");
    if (skippedPolygons)
        warnings.push_back(file.filename().string() + ": " + std::to_string(skippedPolygons) +
                           " faces with fewer than 3 corners or no area skipped");
    if (otherElements)
        warnings.push_back(file.filename().string() + ": " + std::to_string(otherElements) +
                           " elements other than vertex and face ignored");
    // Vertices without faces: a point cloud (a scan), drawn as points, as three.js's PLYLoader gives it.
    if (faces.empty()) primitive.topology = Topology::Points;
    // The texture the header names, drawn through the texture coordinates (MeshLab draws it so; three.js's
    // PLYLoader reads no texture).
    std::vector<Texture> textures;
    if (!textureFile.empty() && !primitive.texcoords.empty()) {
        bool found = false;
        textures.push_back(textureOfImageFile(file.parent_path(), textureFile, found));
        if (!found)
            warnings.push_back(file.filename().string() + ": texture '" + textureFile +
                               "' not found; its reference is kept");
        primitive.material = 0;
    }
    Scene scene = sceneOfOneMesh(file.stem().string(), std::move(primitive));
    if (!textures.empty()) {
        Material material;
        material.name = fs::path(textureFile).stem().string();
        material.metallicFactor = 0;
        material.baseColorTexture.texture = 0;
        scene.materials.push_back(material);
        scene.textures = std::move(textures);
    }
    scene.warnings = std::move(warnings);
    return scene;
}

}  // namespace symcompress
