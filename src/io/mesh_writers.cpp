// OBJ (with .mtl) and PLY writers. Both formats have no instancing: the scene is written flattened to
// world space. Coordinates are printed with the shortest text that reads back to the same double.
#include "common/color_space.hpp"
#include "common/number_text.hpp"
#include "image_reference.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "x3d_materials.hpp"

namespace symcompress {
namespace fs = std::filesystem;

namespace {

template <typename Vector>
void appendVector(std::string& out, const char* keyword, const Vector& vector, int components) {
    out += keyword;
    for (int c = 0; c < components; ++c) {
        out += ' ';
        appendShortest(out, vector[c]);
    }
    out += '\n';
}

std::string materialName(const Scene& scene, int material) {
    if (material < 0) return "default";
    const std::string& name = scene.materials[material].name;
    return "m" + std::to_string(material) + (name.empty() ? "" : "_" + name);
}

std::string mtlFile(const Scene& scene, const fs::path& file) {
    std::string out = "# written by symcompress\nnewmtl default\nKd 0.8 0.8 0.8\n";
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        out += "\nnewmtl " + materialName(scene, static_cast<int>(m)) + "\n";
        // sRGB-encoded, as X3D's Phong Material: the fields as read, else the factors' shortest sRGB values.
        const PhongMaterial phong = x3d::phongOf(material);
        appendVector(out, "Kd", phong.diffuseColor, 3);
        if (material.phong) appendVector(out, "Ks", material.phong->specularColor, 3);
        appendVector(out, "Ke", phong.emissiveColor, 3);
        out += "d ";
        appendShortest(out, material.baseColorFactor[3]);
        out += '\n';
        if (material.baseColorTexture.texture >= 0) {
            const Texture& texture = scene.textures[material.baseColorTexture.texture];
            if (!texture.uri.empty())
                out += "map_Kd " + imageReference(texture.uri, file) + "\n";
        }
    }
    return out;
}

}  // namespace

void writeObj(const Scene& scene, const fs::path& file, const WriteOptions&) {
    const fs::path library = fs::path(file).replace_extension(".mtl");
    std::string out = "# written by symcompress\nmtllib " + library.filename().string() + "\n";
    std::size_t base = 1, textureBase = 1, normalBase = 1, part = 0;
    for (const WorldPrimitive& world : flattenScene(scene)) {
        const Primitive& primitive = world.primitive;
        out += "o part" + std::to_string(part++) + "\nusemtl " + materialName(scene, primitive.material) + "\n";
        // Vertex colours as "v x y z r g b", sRGB-encoded (OBJ holds no alpha: formatLosses says so).
        for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
            if (primitive.colors.empty()) {
                appendVector(out, "v", primitive.positions[v], 3);
                continue;
            }
            Eigen::Matrix<double, 6, 1> positionAndColor;
            positionAndColor << primitive.positions[v], primitive.colors[v].head<3>().unaryExpr([](double l) {
                return linearToSrgbShortest(std::clamp(l, 0.0, 1.0));
            });
            appendVector(out, "v", positionAndColor, 6);
        }
        for (std::size_t v = 0; v < primitive.texcoords.size(); ++v) {
            const Eigen::Vector2d t = baseColorTexcoord(scene, primitive, v);
            appendVector(out, "vt", Eigen::Vector2d(t.x(), 1 - t.y()), 2);
        }
        for (const Eigen::Vector3d& n : primitive.normals) appendVector(out, "vn", n, 3);
        const bool hasT = !primitive.texcoords.empty(), hasN = !primitive.normals.empty();
        for (const Triangle& triangle : primitive.triangles) {
            out += 'f';
            for (std::uint32_t index : triangle) {
                out += ' ' + std::to_string(base + index);
                if (hasT || hasN) out += '/';
                if (hasT) out += std::to_string(textureBase + index);
                if (hasN) out += '/' + std::to_string(normalBase + index);
            }
            out += '\n';
        }
        // Lines and points by their vertices (OBJ's l and p name no texture coordinates or normals here).
        for (const Segment& segment : primitive.lines)
            out += "l " + std::to_string(base + segment[0]) + ' ' + std::to_string(base + segment[1]) + '\n';
        if (primitive.topology == Topology::Points)
            for (std::size_t v = 0; v < primitive.positions.size(); ++v) out += "p " + std::to_string(base + v) + '\n';
        base += primitive.positions.size();
        textureBase += primitive.texcoords.size();
        normalBase += primitive.normals.size();
    }
    writeFileAtomically(library, mtlFile(scene, file));
    writeFileAtomically(file, out);
}

void writePly(const Scene& scene, const fs::path& file, const WriteOptions&) {
    // Binary little endian, double positions (exact), and the attributes every drawn primitive has.
    // Lines cannot be held, and points only as the vertices of a file without faces (formatLosses says so).
    std::vector<WorldPrimitive> world = flattenScene(scene);
    const bool pointCloud = std::all_of(
        world.begin(), world.end(), [](const WorldPrimitive& w) { return w.primitive.topology == Topology::Points; });
    world.erase(std::remove_if(world.begin(), world.end(),
                               [&](const WorldPrimitive& w) {
                                   return w.primitive.topology == Topology::Lines ||
                                          (w.primitive.topology == Topology::Points && !pointCloud);
                               }),
                world.end());
    bool normals = !world.empty(), colors = !world.empty(), texcoords = !world.empty();
    std::size_t vertexCount = 0, faceCount = 0;
    for (const WorldPrimitive& w : world) {
        normals = normals && !w.primitive.normals.empty();
        colors = colors && !w.primitive.colors.empty();
        texcoords = texcoords && !w.primitive.texcoords.empty();
        vertexCount += w.primitive.positions.size();
        faceCount += w.primitive.triangles.size();
    }
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by symcompress\n";
    out += "element vertex " + std::to_string(vertexCount) + "\nproperty double x\nproperty double y\nproperty double z\n";
    if (normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
    if (texcoords) out += "property float s\nproperty float t\n";
    if (colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
    out += "element face " + std::to_string(faceCount) + "\nproperty list uchar uint vertex_indices\nend_header\n";
    auto put = [&out](auto value) { out.append(reinterpret_cast<const char*>(&value), sizeof value); };
    for (const WorldPrimitive& w : world) {
        const Primitive& p = w.primitive;
        for (std::size_t v = 0; v < p.positions.size(); ++v) {
            for (int c = 0; c < 3; ++c) put(p.positions[v][c]);
            if (normals)
                for (int c = 0; c < 3; ++c) put(static_cast<float>(p.normals[v][c]));
            if (texcoords) {
                put(static_cast<float>(p.texcoords[v].x()));
                put(static_cast<float>(1 - p.texcoords[v].y()));
            }
            if (colors)  // sRGB-encoded, alpha linear (linearFromSrgbColor)
                for (int c = 0; c < 4; ++c) {
                    const double value = std::clamp(p.colors[v][c], 0.0, 1.0);
                    put(static_cast<std::uint8_t>(std::lround((c < 3 ? linearToSrgb(value) : value) * 255)));
                }
        }
    }
    std::uint32_t base = 0;
    for (const WorldPrimitive& w : world) {
        for (const Triangle& t : w.primitive.triangles) {
            put(static_cast<std::uint8_t>(3));
            for (std::uint32_t index : t) put(base + index);
        }
        base += static_cast<std::uint32_t>(w.primitive.positions.size());
    }
    writeFileAtomically(file, out);
}

}  // namespace symcompress
