// X3D writer: XML encoding with X3D 3.3 Interchange nodes only, so that X3D 3 and 4 readers (X_ITE,
// assimp, meshlab) load it. Each mesh becomes one DEF'd Group of Shapes the first time a node draws it
// and a USE afterwards; node transforms become Transforms (any affine matrix, mirrors included, through
// rotation, scale and scaleOrientation). `.x3dz` is the same, gzip-compressed.
#include "symcompress/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "rounded.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <zlib.h>

#include <charconv>
#include <set>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// The shortest text that reads back to the same value: as float when the value is a float (most data
// comes from float32 files), else as double.
void appendNumber(std::string& out, double value) {
    char buffer[32];
    const float single = static_cast<float>(value);
    const auto result = static_cast<double>(single) == value ? std::to_chars(buffer, buffer + sizeof buffer, single)
                                                             : std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

// Each component cut by `round` (rounded.hpp) before it is printed.
template <typename Vector, typename Round = double (*)(double)>
void appendVector(std::string& out, const Vector& v, int components, Round round = [](double x) { return x; }) {
    for (int c = 0; c < components; ++c) {
        if (c) out += ' ';
        appendNumber(out, round(v[c]));
    }
}

std::string escapeXml(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::uint32_t chunk = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                                    (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += alphabet[chunk >> 18 & 63];
        out += alphabet[chunk >> 12 & 63];
        out += i + 1 < bytes.size() ? alphabet[chunk >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[chunk & 63] : '=';
    }
    return out;
}

// X3D's Transform is T * R * SR * S * SR^-1. With the SVD L = U S V^T of the linear part, R = U V^T and
// SR = V reproduce any affine matrix; a mirror shows up as a negative scale.
void appendTransformFields(std::string& out, const Eigen::Matrix4d& matrix) {
    const Eigen::Matrix3d linear = matrix.topLeftCorner<3, 3>();
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d u = svd.matrixU(), v = svd.matrixV();
    Eigen::Vector3d scale = svd.singularValues();
    if (v.determinant() < 0) v.col(2) = -v.col(2), u.col(2) = -u.col(2);
    if (u.determinant() < 0) u.col(2) = -u.col(2), scale[2] = -scale[2];
    const Eigen::AngleAxisd rotation(u * v.transpose()), orientation(v);
    const Eigen::Vector3d translation = matrix.topRightCorner<3, 1>();
    auto placement = [](double x) { return rounded(x, kPlacementDigits); };
    auto turn = [](double x) { return roundedDecimals(x, kRotationDecimals); };
    if (!translation.isZero(0)) {
        out += " translation='";
        appendVector(out, translation, 3, placement);
        out += "'";
    }
    auto appendRotation = [&](const char* field, const Eigen::AngleAxisd& value) {
        if (turn(value.angle()) == 0) return;
        out += std::string(" ") + field + "='";
        appendVector(out, value.axis(), 3, turn);
        out += ' ';
        appendNumber(out, turn(value.angle()));
        out += "'";
    };
    appendRotation("rotation", rotation);
    if (!scale.isApprox(Eigen::Vector3d::Ones(), 1e-15)) {
        out += " scale='";
        appendVector(out, scale, 3, placement);
        out += "'";
        appendRotation("scaleOrientation", orientation);
    }
}

class X3dWriter {
public:
    X3dWriter(const Scene& scene, const WriteOptions& options) : scene_(scene), options_(options) {}

    std::string write() {
        out_ += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                "<!DOCTYPE X3D PUBLIC \"ISO//Web3D//DTD X3D 3.3//EN\" \"http://www.web3d.org/specifications/x3d-3.3.dtd\">\n"
                "<X3D profile='Interchange' version='3.3'>\n<head>\n<meta name='generator' content='symcompress'/>\n";
        if (!options_.extrasJson.empty())
            out_ += "<meta name='symcompress' content='" + escapeXml(options_.extrasJson) + "'/>\n";
        out_ += "</head>\n<Scene>\n";
        if (!options_.extrasJson.empty())
            out_ += "<MetadataString name='symcompress' value='\"" + escapeXml(escapeQuotes(options_.extrasJson)) + "\"'/>\n";
        written_.assign(scene_.meshes.size(), false);
        for (int root : scene_.roots) writeNode(root, 1);
        out_ += "</Scene>\n</X3D>\n";
        return std::move(out_);
    }

private:
    static std::string escapeQuotes(const std::string& text) {
        std::string out;
        for (char c : text) {
            if (c == '"' || c == '\\') out += '\\';
            out += c;
        }
        return out;
    }

    void indent(int depth) { out_.append(static_cast<std::size_t>(depth), ' '); }

    void writeNode(int index, int depth) {
        const Node& node = scene_.nodes[index];
        indent(depth);
        out_ += "<Transform";
        if (!node.name.empty()) out_ += " DEF='" + uniqueName(node.name) + "'";
        appendTransformFields(out_, node.transform);
        out_ += ">\n";
        if (node.mesh >= 0) writeMesh(node.mesh, depth + 1);
        for (int child : node.children) writeNode(child, depth + 1);
        indent(depth);
        out_ += "</Transform>\n";
    }

    // DEF names must be unique in the file.
    std::string uniqueName(const std::string& name) {
        std::string clean;
        for (char c : name) clean += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') ? c : '_';
        if (clean.empty() || std::isdigit(static_cast<unsigned char>(clean[0]))) clean = "n" + clean;
        std::string unique = clean;
        for (int k = 2; !names_.insert(unique).second; ++k) unique = clean + "_" + std::to_string(k);
        return unique;
    }

    void writeMesh(int mesh, int depth) {
        indent(depth);
        const std::string def = "mesh" + std::to_string(mesh);
        if (written_[mesh]) {
            out_ += "<Group USE='" + def + "'/>\n";
            return;
        }
        written_[mesh] = true;
        names_.insert(def);
        out_ += "<Group DEF='" + def + "'>\n";
        for (const Primitive& primitive : scene_.meshes[mesh].primitives)
            if (!primitive.triangles.empty()) writeShape(primitive, depth + 1);
        indent(depth);
        out_ += "</Group>\n";
    }

    void writeAppearance(int material, int depth) {
        indent(depth);
        if (material < 0) {
            out_ += "<Appearance><Material/></Appearance>\n";
            return;
        }
        const std::string def = "material" + std::to_string(material);
        if (!materialWritten_.insert(material).second) {
            out_ += "<Appearance USE='" + def + "'/>\n";
            return;
        }
        const Material& m = scene_.materials[material];
        PhongMaterial phong;
        if (m.phong) {
            phong = *m.phong;
        } else {
            phong.diffuseColor = m.baseColorFactor.head<3>();
            phong.emissiveColor = m.emissiveFactor;
            phong.transparency = 1 - m.baseColorFactor[3];
            phong.shininess = 1 - m.roughnessFactor;
        }
        out_ += "<Appearance DEF='" + def + "'>";
        out_ += "<Material diffuseColor='";
        appendVector(out_, phong.diffuseColor, 3);
        out_ += "' specularColor='";
        appendVector(out_, phong.specularColor, 3);
        out_ += "' emissiveColor='";
        appendVector(out_, phong.emissiveColor, 3);
        out_ += "' ambientIntensity='";
        appendNumber(out_, phong.ambientIntensity);
        out_ += "' shininess='";
        appendNumber(out_, phong.shininess);
        out_ += "' transparency='";
        appendNumber(out_, phong.transparency);
        out_ += "'/>";
        if (m.baseColorTexture >= 0) {
            const Texture& texture = scene_.textures[m.baseColorTexture];
            std::string url = texture.uri;
            if (!texture.bytes.empty())
                url = "data:" + (texture.mimeType.empty() ? std::string("image/png") : texture.mimeType) + ";base64," +
                      base64(texture.bytes);
            if (!url.empty()) out_ += "<ImageTexture url='\"" + escapeXml(url) + "\"'/>";
        }
        out_ += "</Appearance>\n";
    }

    void writeShape(const Primitive& primitive, int depth) {
        indent(depth);
        out_ += "<Shape>\n";
        writeAppearance(primitive.material, depth + 1);
        const bool doubleSided = primitive.material >= 0 && scene_.materials[primitive.material].doubleSided;
        indent(depth + 1);
        out_ += "<IndexedTriangleSet solid='" + std::string(doubleSided ? "false" : "true") + "' index='";
        bool first = true;
        for (const Triangle& t : primitive.triangles)
            for (std::uint32_t i : t) {
                if (!first) out_ += ' ';
                first = false;
                out_ += std::to_string(i);
            }
        out_ += "'>\n";
        auto writeValues = [&](const char* node, const char* field, const auto& values, int components, auto transform) {
            indent(depth + 2);
            out_ += std::string("<") + node + " " + field + "='";
            for (std::size_t i = 0; i < values.size(); ++i) {
                if (i) out_ += ' ';
                appendVector(out_, transform(values[i]), components);
            }
            out_ += "'/>\n";
        };
        auto same = [](const auto& v) { return v; };
        writeValues("Coordinate", "point", primitive.positions, 3, same);
        if (!primitive.normals.empty()) writeValues("Normal", "vector", primitive.normals, 3, same);
        if (!primitive.texcoords.empty())
            writeValues("TextureCoordinate", "point", primitive.texcoords, 2,
                        [](const Eigen::Vector2d& t) { return Eigen::Vector2d(t.x(), 1 - t.y()); });
        if (!primitive.colors.empty()) writeValues("ColorRGBA", "color", primitive.colors, 4, same);
        indent(depth + 1);
        out_ += "</IndexedTriangleSet>\n";
        indent(depth);
        out_ += "</Shape>\n";
    }

    const Scene& scene_;
    const WriteOptions& options_;
    std::string out_;
    std::vector<bool> written_;
    std::set<int> materialWritten_;
    std::set<std::string> names_;
};

std::string gzip(const std::string& text, const fs::path& file) {
    z_stream stream{};
    if (deflateInit2(&stream, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw FileError(file, "cannot start gzip compression");
    std::string out(deflateBound(&stream, static_cast<uLong>(text.size())), '\0');
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
    stream.avail_in = static_cast<uInt>(text.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = deflate(&stream, Z_FINISH);
    deflateEnd(&stream);
    if (status != Z_STREAM_END) throw FileError(file, "gzip compression failed");
    out.resize(stream.total_out);
    return out;
}

}  // namespace

std::size_t x3dMeshBytes(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.triangles.empty()) return 0;
    // The file with a node drawing the mesh, less the file with the node alone.
    Scene scene;
    scene.meshes.push_back({"", {primitive}});
    scene.meshes[0].primitives[0].material = -1;
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    WriteOptions plain = options;
    plain.extrasJson.clear();
    const std::size_t withMesh = X3dWriter(scene, plain).write().size();
    scene.nodes[0].mesh = -1;
    return withMesh - X3dWriter(scene, plain).write().size();
}

std::size_t x3dNodeBytes(const Node& node) {
    // A file whose one mesh a first node draws, with and without `node` drawing it again (a USE).
    Scene scene;
    Primitive triangle;
    triangle.positions = {Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    triangle.triangles = {{0, 1, 2}};
    scene.meshes.push_back({"", {triangle}});
    scene.nodes.resize(2);
    scene.nodes[0].mesh = 0;
    scene.nodes[1] = node;
    scene.nodes[1].mesh = 0;
    scene.nodes[1].children.clear();
    scene.roots = {0, 1};
    const std::size_t withNode = X3dWriter(scene, {}).write().size();
    scene.roots = {0};
    return withNode - X3dWriter(scene, {}).write().size();
}

void writeX3d(const Scene& scene, const fs::path& file, const WriteOptions& options) {
    std::string text = X3dWriter(scene, options).write();
    std::string extension = file.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    writeFileAtomically(file, extension == ".x3dz" ? gzip(text, file) : text);
}

}  // namespace symcompress
