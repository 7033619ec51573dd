// glTF 2.0 writer: .glb (one binary chunk) or .gltf (JSON plus a sibling .bin). Meshes shared by several
// nodes stay shared (instancing, mirrors included: a negative-determinant node matrix is valid glTF and
// renderers flip the winding for it). Geometry is compressed with KHR_draco_mesh_compression unless
// WriteOptions::draco is false.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "rotation_and_scale.hpp"
#include "common/number_text.hpp"
#include "geometry/bounds.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

namespace symcompress {
namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

// The JSON's text. Names come from files that need not be UTF-8 (X3D's DEFs, OBJ's groups): bytes that are
// not UTF-8 are written as U+FFFD instead of making dump() throw.
std::string jsonText(const Json& json, int indent = -1) {
    return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

constexpr int kFloat = 5126, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The growing binary buffer and the JSON arrays that describe it.
class GltfBuilder {
public:
    explicit GltfBuilder(Json& root) : root_(root) {}

    // Appends bytes (4-byte aligned) as a new buffer view; returns its index.
    int addBufferView(const void* data, std::size_t size, int target = 0) {
        while (binary_.size() % 4) binary_.push_back(0);
        Json view = {{"buffer", 0}, {"byteLength", size}};
        if (!binary_.empty()) view["byteOffset"] = binary_.size();
        if (target) view["target"] = target;
        const auto* bytes = static_cast<const unsigned char*>(data);
        binary_.insert(binary_.end(), bytes, bytes + size);
        root_["bufferViews"].push_back(view);
        return static_cast<int>(root_["bufferViews"].size()) - 1;
    }

    int addAccessor(Json accessor) {
        root_["accessors"].push_back(std::move(accessor));
        return static_cast<int>(root_["accessors"].size()) - 1;
    }

    // A float accessor over `components`-vectors, stored in its own buffer view.
    template <typename Vector>
    int addFloatAccessor(const std::vector<Vector>& values, int components, const char* type, bool withBounds) {
        std::vector<float> flat;
        flat.reserve(values.size() * components);
        for (const Vector& value : values)
            for (int c = 0; c < components; ++c) flat.push_back(static_cast<float>(value[c]));
        return addFloatAccessor(flat, components, type, withBounds, kArrayBuffer);
    }
    // The same over values already flat; `target` 0 for data that is not a vertex attribute (animations).
    int addFloatAccessor(const std::vector<float>& flat, int components, const char* type, bool withBounds, int target) {
        Json accessor = {{"bufferView", addBufferView(flat.data(), flat.size() * sizeof(float), target)},
                         {"componentType", kFloat},
                         {"count", flat.size() / std::size_t(components)},
                         {"type", type}};
        if (withBounds) addBounds(accessor, flat, components);
        return addAccessor(std::move(accessor));
    }

    static void addBounds(Json& accessor, const std::vector<float>& flat, int components) {
        std::vector<float> lo(components, std::numeric_limits<float>::max()),
            hi(components, std::numeric_limits<float>::lowest());
        for (std::size_t i = 0; i < flat.size(); ++i) {
            lo[i % components] = std::min(lo[i % components], flat[i]);
            hi[i % components] = std::max(hi[i % components], flat[i]);
        }
        auto shortest = [](const std::vector<float>& values) {
            Json out = Json::array();
            for (float value : values) out.push_back(asFloat32(value));
            return out;
        };
        accessor["min"] = shortest(lo);
        accessor["max"] = shortest(hi);
    }

    std::vector<unsigned char>& binary() { return binary_; }

private:
    Json& root_;
    std::vector<unsigned char> binary_;
};

// A float32 attribute in a Draco soup builder, one value per triangle corner.
template <typename Vector>
void addDracoAttribute(draco::TriangleSoupMeshBuilder& builder, const Primitive& primitive,
                       const std::vector<Vector>& values, draco::GeometryAttribute::Type type, int components,
                       int& attributeId) {
    if (values.empty()) return;
    attributeId = builder.AddAttribute(type, static_cast<std::int8_t>(components), draco::DT_FLOAT32);
    std::vector<float> corner(3 * components);
    for (std::size_t f = 0; f < primitive.triangles.size(); ++f) {
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < components; ++c)
                corner[k * components + c] = static_cast<float>(values[primitive.triangles[f][k]][c]);
        builder.SetAttributeValuesForFace(attributeId, draco::FaceIndex(static_cast<std::uint32_t>(f)), corner.data(),
                                          corner.data() + components, corner.data() + 2 * components);
    }
}

struct DracoAttributeIds {
    int position = -1, normal = -1, texcoord = -1, color = -1;
};

// The primitive's triangles split in two: those Draco's edgebreaker keeps, and those whose corners its
// quantization of positions (`bits` over the box's largest side, or the primitive's own grid) puts on one
// point, which it would drop. The second part goes to the sequential method, so that a few slivers do not
// cost a whole mesh its edgebreaker compression (vertex arrays are shared; Draco takes only the corners
// its triangles use).
std::pair<Primitive, Primitive> splitCollapsingTriangles(const Primitive& primitive, int bits) {
    QuantizationGrid grid;
    if (primitive.positionGrid) {
        grid = *primitive.positionGrid;
    } else {
        const Eigen::AlignedBox3d box = boundsOfCorners(primitive.positions, primitive.triangles);
        grid = {box.min(), box.sizes().maxCoeff(), bits};
    }
    const double scale = grid.range > 0 ? double((1u << grid.bits) - 1) / grid.range : 0;
    std::pair<Primitive, Primitive> parts{primitive, primitive};
    parts.first.triangles.clear();
    parts.second.triangles.clear();
    for (const Triangle& t : primitive.triangles) {
        auto onGrid = [&](std::uint32_t v) -> Eigen::Array3d { return (((primitive.positions[v] - grid.origin) * scale).array() + 0.5).floor(); };
        const Eigen::Array3d qa = onGrid(t[0]), qb = onGrid(t[1]), qc = onGrid(t[2]);
        const bool collapses = (qa == qb).all() || (qb == qc).all() || (qa == qc).all();
        (collapses ? parts.second : parts.first).triangles.push_back(t);
    }
    return parts;
}

// How to encode: edgebreaker compresses best but drops triangles whose corners its quantization merges;
// the sequential method keeps every triangle.
enum class DracoMethod {
    EdgebreakerOrNothing,       // nothing (no primitive written) when a triangle would be lost
    EdgebreakerElseSequential,  // the sequential method when a triangle would be lost
    Sequential,
};

// Encodes one primitive with Draco and describes it in glTF: the accessors carry counts and bounds
// (decoded from our own output, since Draco merges equal corners) but no buffer view.
std::optional<Json> writeDracoPrimitive(GltfBuilder& builder, const Primitive& primitive, const WriteOptions& options,
                                        const fs::path& file, DracoMethod method) {
    draco::TriangleSoupMeshBuilder soup;
    soup.Start(static_cast<int>(primitive.triangles.size()));
    DracoAttributeIds ids;
    addDracoAttribute(soup, primitive, primitive.positions, draco::GeometryAttribute::POSITION, 3, ids.position);
    addDracoAttribute(soup, primitive, primitive.normals, draco::GeometryAttribute::NORMAL, 3, ids.normal);
    addDracoAttribute(soup, primitive, primitive.texcoords, draco::GeometryAttribute::TEX_COORD, 2, ids.texcoord);
    addDracoAttribute(soup, primitive, primitive.colors, draco::GeometryAttribute::COLOR, 4, ids.color);
    std::unique_ptr<draco::Mesh> mesh = soup.Finalize();
    if (!mesh) throw FileError(file, "Draco could not build a mesh from a primitive");

    // The decoded mesh, or nothing when the encoder refuses (edgebreaker: "all triangles are degenerate").
    auto encode = [&](int encoding, draco::EncoderBuffer& encoded) -> std::unique_ptr<draco::Mesh> {
        draco::Encoder encoder;
        const int speed = std::clamp(10 - options.compressionLevel, 0, 10);
        encoder.SetSpeedOptions(speed, speed);
        encoder.SetEncodingMethod(encoding);
        if (const auto& grid = primitive.positionGrid) {
            const float origin[3] = {float(grid->origin.x()), float(grid->origin.y()), float(grid->origin.z())};
            encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, grid->bits, 3, origin, float(grid->range));
        } else {
            encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.positionBits);
        }
        encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, options.normalBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, options.texcoordBits);
        encoder.SetAttributeQuantization(draco::GeometryAttribute::COLOR, options.colorBits);
        const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &encoded);
        if (!status.ok()) {
            if (encoding == draco::MESH_EDGEBREAKER_ENCODING) return nullptr;
            throw FileError(file, "Draco encoding failed: " + status.error_msg_string());
        }
        draco::DecoderBuffer decoderBuffer;
        decoderBuffer.Init(encoded.data(), encoded.size());
        auto decoded = draco::Decoder().DecodeMeshFromBuffer(&decoderBuffer);
        if (!decoded.ok())
            throw FileError(file, "Draco cannot decode what it encoded: " + decoded.status().error_msg_string());
        return std::move(decoded).value();
    };
    auto complete = [&](const std::unique_ptr<draco::Mesh>& decoded) { return decoded && decoded->num_faces() == primitive.triangles.size(); };
    draco::EncoderBuffer encoded;
    std::unique_ptr<draco::Mesh> result;
    if (method != DracoMethod::Sequential) {
        result = encode(draco::MESH_EDGEBREAKER_ENCODING, encoded);
        if (!complete(result) && method == DracoMethod::EdgebreakerOrNothing) return std::nullopt;
    }
    if (!complete(result)) {
        encoded.Clear();
        result = encode(draco::MESH_SEQUENTIAL_ENCODING, encoded);
    }
    if (result->num_faces() != primitive.triangles.size())
        throw FileError(file, "Draco lost " + std::to_string(primitive.triangles.size() - result->num_faces()) +
                                  " triangles of a primitive; write with --no-draco");

    const int view = builder.addBufferView(encoded.data(), encoded.size());
    Json attributes = Json::object(), dracoAttributes = Json::object();
    auto describe = [&](const char* name, int sourceId, draco::GeometryAttribute::Type type, int components,
                        const char* accessorType) {
        if (sourceId < 0) return;
        const draco::PointAttribute* attribute = result->GetNamedAttribute(type);
        Json accessor = {{"componentType", kFloat}, {"count", result->num_points()}, {"type", accessorType}};
        if (type == draco::GeometryAttribute::POSITION) {
            std::vector<float> flat(result->num_points() * 3);
            for (draco::PointIndex p(0); p < result->num_points(); ++p)
                attribute->ConvertValue<float>(attribute->mapped_index(p), 3, &flat[p.value() * 3]);
            GltfBuilder::addBounds(accessor, flat, 3);
        }
        (void)components;
        attributes[name] = builder.addAccessor(std::move(accessor));
        dracoAttributes[name] = attribute->unique_id();
    };
    describe("POSITION", ids.position, draco::GeometryAttribute::POSITION, 3, "VEC3");
    describe("NORMAL", ids.normal, draco::GeometryAttribute::NORMAL, 3, "VEC3");
    describe("TEXCOORD_0", ids.texcoord, draco::GeometryAttribute::TEX_COORD, 2, "VEC2");
    describe("COLOR_0", ids.color, draco::GeometryAttribute::COLOR, 4, "VEC4");
    const int indexType = result->num_points() <= 65535 ? kUnsignedShort : kUnsignedInt;
    Json out = {{"attributes", attributes},
                {"indices", builder.addAccessor({{"componentType", indexType},
                                                 {"count", result->num_faces() * 3},
                                                 {"type", "SCALAR"}})},
                {"extensions",
                 {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", dracoAttributes}}}}}};
    return out;
}

Json writePlainPrimitive(GltfBuilder& builder, const Primitive& primitive) {
    Json attributes = Json::object();
    attributes["POSITION"] = builder.addFloatAccessor(primitive.positions, 3, "VEC3", true);
    if (!primitive.normals.empty()) attributes["NORMAL"] = builder.addFloatAccessor(primitive.normals, 3, "VEC3", false);
    if (!primitive.texcoords.empty())
        attributes["TEXCOORD_0"] = builder.addFloatAccessor(primitive.texcoords, 2, "VEC2", false);
    if (!primitive.colors.empty()) attributes["COLOR_0"] = builder.addFloatAccessor(primitive.colors, 4, "VEC4", false);
    Json indices;
    if (primitive.positions.size() <= 65535) {
        std::vector<std::uint16_t> flat;
        for (const Triangle& t : primitive.triangles)
            for (std::uint32_t i : t) flat.push_back(static_cast<std::uint16_t>(i));
        indices = {{"bufferView", builder.addBufferView(flat.data(), flat.size() * 2, kElementArrayBuffer)},
                   {"componentType", kUnsignedShort}};
    } else {
        std::vector<std::uint32_t> flat;
        for (const Triangle& t : primitive.triangles) flat.insert(flat.end(), t.begin(), t.end());
        indices = {{"bufferView", builder.addBufferView(flat.data(), flat.size() * 4, kElementArrayBuffer)},
                   {"componentType", kUnsignedInt}};
    }
    indices["count"] = primitive.triangles.size() * 3;
    indices["type"] = "SCALAR";
    return {{"attributes", attributes}, {"indices", builder.addAccessor(indices)}};  // mode: TRIANGLES by default
}

// A node's fields: translation (float32, what a glTF reader keeps of it), rotation quaternion to 1e-7 and
// scale, each left out when it does nothing. Instance nodes are the common case, where their size counts:
// a rigid or uniformly scaled transform takes about half the bytes of a matrix.
Json transformFields(const Eigen::Vector3d& translation, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& scale) {
    Json out = Json::object();
    Eigen::Quaterniond q(rotation);
    if (q.w() < 0) q.coeffs() *= -1;
    const Eigen::Vector3d t = translation.unaryExpr(&asFloat32), s = scale.unaryExpr(&asFloat32);
    const Eigen::Vector4d r = q.coeffs().unaryExpr([](double x) { return roundedDecimals(x, kRotationDecimals); });
    if (!t.isZero(0)) out["translation"] = {t.x(), t.y(), t.z()};
    if (r != Eigen::Vector4d(0, 0, 0, 1)) out["rotation"] = {r.x(), r.y(), r.z(), r.w()};
    if (s == Eigen::Vector3d(-1, 1, 1)) out["scale"] = {-1, 1, 1};  // a mirror: the common case, short
    else if (s != Eigen::Vector3d::Ones()) out["scale"] = {s.x(), s.y(), s.z()};
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
        out["orthographic"] = {{"xmag", camera.xmag}, {"ymag", camera.ymag}, {"znear", camera.znear}, {"zfar", camera.zfar}};
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
    out["type"] = light.type == Light::Type::Directional ? "directional" : light.type == Light::Type::Spot ? "spot" : "point";
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
        out["emissiveFactor"] = {asFloat32(material.emissiveFactor[0]), asFloat32(material.emissiveFactor[1]), asFloat32(material.emissiveFactor[2])};
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
    const std::uint32_t total =
        static_cast<std::uint32_t>(12 + 8 + json.size() + (hasBinary ? 8 + binary.size() : 0));
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

// Appends the glTF primitives that store `primitive` (one, or with Draco two when edgebreaker would drop
// some triangles) to `primitives`.
void writePrimitive(GltfBuilder& builder, const Primitive& primitive, const WriteOptions& options, const fs::path& file,
                    Json& primitives) {
    auto add = [&](Json out, int material) {
        if (material >= 0) out["material"] = material;
        primitives.push_back(std::move(out));
    };
    if (!options.draco) {
        add(writePlainPrimitive(builder, primitive), primitive.material);
        return;
    }
    if (auto whole = writeDracoPrimitive(builder, primitive, options, file, DracoMethod::EdgebreakerOrNothing)) {
        add(std::move(*whole), primitive.material);
        return;
    }
    // Edgebreaker would drop some triangles: they go to a sequential primitive of their own.
    const auto [kept, collapsing] = splitCollapsingTriangles(primitive, options.positionBits);
    for (const auto& [part, method] : {std::pair{&kept, DracoMethod::EdgebreakerElseSequential},
                                       std::pair{&collapsing, DracoMethod::Sequential}})
        if (!part->triangles.empty()) add(*writeDracoPrimitive(builder, *part, options, file, method), part->material);
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
                        {"output", builder.addFloatAccessor(values, int(channel.components()), rotation ? "VEC4" : "VEC3", false, 0)}};
        if (channel.interpolation == AnimationChannel::Interpolation::Step) sampler["interpolation"] = "STEP";
        if (channel.interpolation == AnimationChannel::Interpolation::CubicSpline) sampler["interpolation"] = "CUBICSPLINE";
        const char* path = rotation ? "rotation" : channel.path == AnimationChannel::Path::Scale ? "scale" : "translation";
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
    for (const Node& node : scene.nodes) root["nodes"].push_back(writeNode(node, meshIndex, scene.nodes.size(), extraNodes));
    for (Json& node : extraNodes) root["nodes"].push_back(std::move(node));
    root["scenes"] = {{{"nodes", scene.roots}}};
    root["scene"] = 0;
    for (const Animation& animation : scene.animations) root["animations"].push_back(writeAnimation(animation, builder));
    for (const Camera& camera : scene.cameras) root["cameras"].push_back(writeCamera(camera));
    for (const Light& light : scene.lights) root["extensions"]["KHR_lights_punctual"]["lights"].push_back(writeLight(light));
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
