// glTF 2.0 writer: .glb (one binary chunk) or .gltf (JSON plus a sibling .bin). Meshes shared by several
// nodes stay shared (instancing, mirrors included: a negative-determinant node matrix is valid glTF and
// renderers flip the winding for it). Geometry is compressed with KHR_draco_mesh_compression unless
// WriteOptions::draco is false.
#include "common/number_text.hpp"
#include "gltf_builder.hpp"
#include "rotation_and_scale.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// A node's fields: translation (float32, what a glTF reader keeps of it), rotation quaternion to 1e-7 and
// scale, each left out when it does nothing. Instance nodes are the common case, where their size counts:
// a rigid or uniformly scaled transform takes about half the bytes of a matrix.
Json transformFields(const Eigen::Vector3d& translation, const Eigen::Matrix3d& rotation,
                     const Eigen::Vector3d& scale) {
    Json out = Json::object();
    Eigen::Quaterniond q(rotation);
    if (q.w() < 0) q.coeffs() *= -1;
    const Eigen::Vector3d t = translation.unaryExpr(&asFloat32), s = scale.unaryExpr(&asFloat32);
    const Eigen::Vector4d r = q.coeffs().unaryExpr([](double x) { return roundedDecimals(x, kRotationDecimals); });
    if (!t.isZero(0)) out["translation"] = {t.x(), t.y(), t.z()};
    if (r != Eigen::Vector4d(0, 0, 0, 1)) out["rotation"] = {r.x(), r.y(), r.z(), r.w()};
    if (s == Eigen::Vector3d(-1, 1, 1))
        out["scale"] = {-1, 1, 1};  // a mirror: the common case, short
    else if (s != Eigen::Vector3d::Ones())
        out["scale"] = {s.x(), s.y(), s.z()};
    return out;
}

// Writes a node. glTF requires node matrices to decompose into TRS, so a transform that shears (X3D's
// scaleOrientation, a turned child of a non-uniformly scaled parent) is split by the SVD L = U Σ V^T:
// this node takes translation, U and Σ, and a new child, appended to `extra` (its index is firstExtra +
// its position there), takes V^T with the mesh and the children.
Json writeNode(const Node& node, const std::vector<int>& meshIndex, std::size_t firstExtra, std::vector<Json>& extra) {
    const Eigen::Matrix3d linear = node.transform.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = node.transform.topRightCorner<3, 1>();
    Json out;
    Json* drawing = &out;  // the node that carries the mesh and the children
    if (const auto trs = asRotationAndScale(linear)) {
        out = transformFields(translation, trs->first, trs->second);
    } else {
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
        Eigen::Matrix3d u = svd.matrixU(), v = svd.matrixV();
        Eigen::Vector3d sigma = svd.singularValues();
        if (v.determinant() < 0) v.col(2) = -v.col(2), u.col(2) = -u.col(2);
        if (u.determinant() < 0) u.col(2) = -u.col(2), sigma[2] = -sigma[2];
        out = transformFields(translation, u, sigma);
        out["children"] = {firstExtra + extra.size()};
        extra.push_back(transformFields(Eigen::Vector3d::Zero(), v.transpose(), Eigen::Vector3d::Ones()));
        drawing = &extra.back();
    }
    if (!node.name.empty()) out["name"] = node.name;
    if (node.mesh >= 0 && meshIndex[node.mesh] >= 0) (*drawing)["mesh"] = meshIndex[node.mesh];
    if (node.camera >= 0) (*drawing)["camera"] = node.camera;
    if (node.light >= 0) (*drawing)["extensions"]["KHR_lights_punctual"]["light"] = node.light;
    if (!node.children.empty()) (*drawing)["children"] = node.children;
    return out;
}

Json writeCamera(const Camera& camera) {
    Json out = Json::object();
    if (!camera.name.empty()) out["name"] = camera.name;
    if (camera.projection == Camera::Projection::Orthographic) {
        out["type"] = "orthographic";
        out["orthographic"] = {
            {"xmag", camera.xmag}, {"ymag", camera.ymag}, {"znear", camera.znear}, {"zfar", camera.zfar}};
        return out;
    }
    out["type"] = "perspective";
    Json perspective = {{"yfov", camera.yfov}, {"znear", camera.znear}};
    if (camera.aspectRatio > 0) perspective["aspectRatio"] = camera.aspectRatio;
    if (camera.zfar > 0) perspective["zfar"] = camera.zfar;
    out["perspective"] = perspective;
    return out;
}

// A KHR_lights_punctual light, its fields left out where they are the extension's defaults.
Json writeLight(const Light& light) {
    Json out = Json::object();
    if (!light.name.empty()) out["name"] = light.name;
    out["type"] = light.type == Light::Type::Directional ? "directional"
                  : light.type == Light::Type::Spot      ? "spot"
                                                         : "point";
    if (light.color != Eigen::Vector3d::Ones()) out["color"] = {light.color.x(), light.color.y(), light.color.z()};
    if (light.intensity != 1) out["intensity"] = light.intensity;
    if (light.range > 0 && light.type != Light::Type::Directional) out["range"] = light.range;
    if (light.type == Light::Type::Spot)
        out["spot"] = {{"innerConeAngle", light.innerConeAngle}, {"outerConeAngle", light.outerConeAngle}};
    return out;
}

// textureIndex: the glTF texture of each of the scene's textures once written (-1 before), shared by
// textures of the same image.
Json writeMaterial(const Material& material, GltfBuilder& builder, Json& root, const Scene& scene,
                   const std::vector<int>& sameImage, std::vector<int>& textureIndex) {
    // Factors as float32 text, and left out where they are glTF's defaults.
    Json pbr = Json::object();
    if (material.baseColorFactor != Eigen::Vector4d::Ones())
        pbr["baseColorFactor"] = {asFloat32(material.baseColorFactor[0]), asFloat32(material.baseColorFactor[1]),
                                  asFloat32(material.baseColorFactor[2]), asFloat32(material.baseColorFactor[3])};
    if (material.metallicFactor != 1) pbr["metallicFactor"] = asFloat32(material.metallicFactor);
    if (material.roughnessFactor != 1) pbr["roughnessFactor"] = asFloat32(material.roughnessFactor);
    const int texture = material.baseColorTexture >= 0 ? sameImage[material.baseColorTexture] : -1;
    if (texture >= 0 && !scene.textures[texture].bytes.empty()) {
        if (textureIndex[texture] < 0) {
            const Texture& source = scene.textures[texture];
            Json image = {{"bufferView", builder.addBufferView(source.bytes.data(), source.bytes.size())},
                          {"mimeType", source.mimeType.empty() ? "image/png" : source.mimeType}};
            if (!source.name.empty()) image["name"] = source.name;
            root["images"].push_back(image);
            if (!root.contains("samplers")) root["samplers"].push_back(Json::object());
            root["textures"].push_back({{"source", root["images"].size() - 1}, {"sampler", 0}});
            textureIndex[texture] = static_cast<int>(root["textures"].size()) - 1;
        }
        pbr["baseColorTexture"] = {{"index", textureIndex[texture]}};
    }
    Json out = Json::object();
    if (!pbr.empty()) out["pbrMetallicRoughness"] = pbr;
    if (!material.name.empty()) out["name"] = material.name;
    if (!material.emissiveFactor.isZero())
        out["emissiveFactor"] = {asFloat32(material.emissiveFactor[0]), asFloat32(material.emissiveFactor[1]),
                                 asFloat32(material.emissiveFactor[2])};
    if (material.alphaMode == Material::AlphaMode::Mask) {
        out["alphaMode"] = "MASK";
        out["alphaCutoff"] = asFloat32(material.alphaCutoff);
    } else if (material.alphaMode == Material::AlphaMode::Blend) {
        out["alphaMode"] = "BLEND";
    }
    if (material.doubleSided) out["doubleSided"] = true;
    return out;
}

std::string glbFile(const Json& root, std::vector<unsigned char> binary) {
    std::string json = jsonText(root);
    while (json.size() % 4) json.push_back(' ');
    while (binary.size() % 4) binary.push_back(0);
    const bool hasBinary = !binary.empty();
    const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + json.size() + (hasBinary ? 8 + binary.size() : 0));
    std::string out;
    auto put32 = [&out](std::uint32_t value) { out.append(reinterpret_cast<const char*>(&value), 4); };
    out.append("glTF");
    put32(2);
    put32(total);
    put32(static_cast<std::uint32_t>(json.size()));
    out.append("JSON");
    out.append(json);
    if (hasBinary) {
        put32(static_cast<std::uint32_t>(binary.size()));
        out.append("BIN", 3);
        out.push_back('\0');
        out.append(reinterpret_cast<const char*>(binary.data()), binary.size());
    }
    return out;
}

}  // namespace

std::size_t gltfMeshBytes(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.triangles.empty()) return 0;
    Json root = Json::object(), primitives = Json::array();
    GltfBuilder builder(root);
    writePrimitive(builder, primitive, options, "(a mesh measured for the plan)", primitives);
    const Json mesh = {{"primitives", primitives}};
    return jsonText(root).size() + jsonText(mesh).size() + builder.binary().size();
}

// Animation channels as glTF samplers (float keys and values in buffer views of their own) and channels.
Json writeAnimation(const Animation& animation, GltfBuilder& builder) {
    Json channels = Json::array(), samplers = Json::array();
    for (const AnimationChannel& channel : animation.channels) {
        const bool rotation = channel.path == AnimationChannel::Path::Rotation;
        const std::vector<float> times(channel.times.begin(), channel.times.end()),
            values(channel.values.begin(), channel.values.end());
        Json sampler = {{"input", builder.addFloatAccessor(times, 1, "SCALAR", true, 0)},
                        {"output", builder.addFloatAccessor(values, int(channel.components()),
                                                            rotation ? "VEC4" : "VEC3", false, 0)}};
        if (channel.interpolation == AnimationChannel::Interpolation::Step) sampler["interpolation"] = "STEP";
        if (channel.interpolation == AnimationChannel::Interpolation::CubicSpline)
            sampler["interpolation"] = "CUBICSPLINE";
        const char* path = rotation                                        ? "rotation"
                           : channel.path == AnimationChannel::Path::Scale ? "scale"
                                                                           : "translation";
        channels.push_back({{"sampler", samplers.size()}, {"target", {{"node", channel.node}, {"path", path}}}});
        samplers.push_back(std::move(sampler));
    }
    Json out = {{"channels", channels}, {"samplers", samplers}};
    if (!animation.name.empty()) out["name"] = animation.name;
    return out;
}

std::size_t gltfNodeBytes(const Node& node) {
    Node drawing = node;
    drawing.mesh = 0;
    drawing.children.clear();
    std::vector<Json> extra;
    std::size_t bytes = jsonText(writeNode(drawing, {0}, 1, extra)).size() + 1;  // and its comma
    for (const Json& child : extra) bytes += jsonText(child).size() + 1;
    return bytes + 3;  // its index in the scene's list of nodes, typically
}

void writeGltf(const Scene& scene, const fs::path& file, const WriteOptions& options) {
    Json root = {{"asset", {{"version", "2.0"}, {"generator", "symcompress"}}}};
    if (!options.extrasJson.empty()) {
        try {
            root["asset"]["extras"] = Json::parse(options.extrasJson);
        } catch (const Json::exception& error) {
            throw std::invalid_argument(std::string("extras are not valid JSON: ") + error.what());
        }
    }
    GltfBuilder builder(root);
    std::vector<int> textureIndex(scene.textures.size(), -1);
    const std::vector<int> sameImage = firstTextureOfSameImage(scene.textures);
    for (const Material& material : scene.materials)
        root["materials"].push_back(writeMaterial(material, builder, root, scene, sameImage, textureIndex));

    // Meshes with no triangles are left out (glTF requires at least one primitive), and so is the
    // reference to them from nodes.
    std::vector<int> meshIndex(scene.meshes.size(), -1);
    bool usedDraco = false;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        Json primitives = Json::array();
        for (const Primitive& primitive : scene.meshes[m].primitives) {
            if (primitive.triangles.empty()) continue;
            writePrimitive(builder, primitive, options, file, primitives);
            usedDraco = options.draco;
        }
        if (primitives.empty()) continue;
        Json mesh = {{"primitives", primitives}};
        if (!scene.meshes[m].name.empty()) mesh["name"] = scene.meshes[m].name;
        root["meshes"].push_back(mesh);
        meshIndex[m] = static_cast<int>(root["meshes"].size()) - 1;
    }
    std::vector<Json> extraNodes;
    for (const Node& node : scene.nodes)
        root["nodes"].push_back(writeNode(node, meshIndex, scene.nodes.size(), extraNodes));
    for (Json& node : extraNodes) root["nodes"].push_back(std::move(node));
    root["scenes"] = {{{"nodes", scene.roots}}};
    root["scene"] = 0;
    for (const Animation& animation : scene.animations)
        root["animations"].push_back(writeAnimation(animation, builder));
    for (const Camera& camera : scene.cameras) root["cameras"].push_back(writeCamera(camera));
    for (const Light& light : scene.lights)
        root["extensions"]["KHR_lights_punctual"]["lights"].push_back(writeLight(light));
    if (usedDraco) {
        root["extensionsUsed"].push_back("KHR_draco_mesh_compression");
        root["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    }
    if (!scene.lights.empty()) root["extensionsUsed"].push_back("KHR_lights_punctual");

    std::vector<unsigned char>& binary = builder.binary();
    if (formatFromExtension(file) == FileFormat::Glb) {
        if (!binary.empty()) root["buffers"] = {{{"byteLength", binary.size()}}};
        writeFileAtomically(file, glbFile(root, binary));
        return;
    }
    // .gltf: the binary data in a .bin beside it, written first so that the JSON never points at nothing.
    if (!binary.empty()) {
        const fs::path bin = fs::path(file).replace_extension(".bin");
        root["buffers"] = {{{"byteLength", binary.size()}, {"uri", bin.filename().string()}}};
        writeFileAtomically(bin, std::string_view(reinterpret_cast<const char*>(binary.data()), binary.size()));
    }
    writeFileAtomically(file, jsonText(root, 1));
}

}  // namespace symcompress
