// glTF 2.0 reader (.gltf with external files or data URIs, .glb), on top of tinygltf's JSON and buffer
// loading. Accessor decoding, Draco decoding and every range check are ours: tinygltf does not check
// that accessors stay inside their buffers.
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "common/mime_type.hpp"

#include <tiny_gltf.h>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <meshoptimizer.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// Keeps images as the bytes of their files: we never decode pixels, and a broken image must not stop
// the geometry from loading. `loading` is the model tinygltf fills: tinygltf hands over an image's buffer
// view without checking that it lies inside its buffer, so that is checked here.
bool keepImageBytes(tinygltf::Image* image, const int index, std::string* error, std::string*, int, int,
                    const unsigned char* bytes, int size, void* loading) {
    if (image->bufferView >= 0) {
        // tinygltf has checked the view's and the buffer's indices.
        const auto& model = *static_cast<const tinygltf::Model*>(loading);
        const tinygltf::BufferView& view = model.bufferViews[std::size_t(image->bufferView)];
        const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
        if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset ||
            view.byteLength > std::size_t(std::numeric_limits<int>::max())) {
            if (error) *error += "image " + std::to_string(index) + ": its buffer view runs past the end of its buffer\n";
            return false;
        }
    }
    if (size < 0) return false;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

class GltfReader {
public:
    GltfReader(const fs::path& file, const tinygltf::Model& model) : file_(file), model_(model) {}

    Scene read();

private:
    [[noreturn]] void fail(const std::string& problem) const { throw FileError(file_, problem); }
    std::vector<double> readAccessor(int accessorIndex, int expectedComponents, const char* what) const;
    std::vector<std::uint32_t> readIndices(int accessorIndex) const;
    void readPrimitive(const tinygltf::Primitive& source, Mesh& mesh, const std::string& where);
    void decodeDracoPrimitive(const tinygltf::Primitive& source, const tinygltf::Value& extension, Primitive& out,
                              std::vector<std::uint32_t>& indices, const std::string& where) const;
    Eigen::Matrix4d nodeTransform(const tinygltf::Node& node) const;
    void readMaterials(Scene& scene);
    void readAnimations(Scene& scene);
    void readCamerasAndLights(Scene& scene);
    void expandGpuInstances(Scene& scene);
    void warnAbout(const std::string& warning) { warnings_.insert(warning); }

    fs::path file_;
    const tinygltf::Model& model_;
    std::set<std::string> warnings_;
    std::map<std::string, int> skippedModes_;
    std::map<int, Eigen::Matrix<double, 2, 3>> texcoordTransforms_;  // material -> its KHR_texture_transform
};

// object[key], or a null value where `object` is not an object or has no such key (tinygltf's Get asserts).
const tinygltf::Value& member(const tinygltf::Value& object, const std::string& key) {
    static const tinygltf::Value none;
    return object.Has(key) ? object.Get(key) : none;
}

double numberOr(const tinygltf::Value& value, double fallback) { return value.IsNumber() ? value.GetNumberAsDouble() : fallback; }

// An index held in an extension's value: -1 unless it is a whole number from 0 to INT_MAX (GetNumberAsInt
// casts a real number unchecked, which is undefined for one that does not fit).
int indexIn(const tinygltf::Value& value) {
    if (value.IsInt()) return value.Get<int>();
    if (!value.IsReal()) return -1;
    const double number = value.Get<double>();
    return number >= 0 && number <= std::numeric_limits<int>::max() && number == std::floor(number) ? int(number) : -1;
}

// How deep the node forest of a glTF file may nest: as deep as X3D's (the X3D reader's limit), so that what
// is read can be written as X3D, nested, and read back.
constexpr std::size_t kMaxNodeDepth = 256;

// KHR_texture_transform's matrix: translation(offset) * rotation(rotation) * scale(scale), on (u, v, 1).
Eigen::Matrix<double, 2, 3> textureTransform(const tinygltf::Value& extension) {
    auto pair = [&](const char* key, Eigen::Vector2d fallback) {
        const tinygltf::Value& value = member(extension, key);
        if (!value.IsArray() || value.ArrayLen() != 2) return fallback;
        return Eigen::Vector2d(numberOr(value.Get(0), fallback.x()), numberOr(value.Get(1), fallback.y()));
    };
    const Eigen::Vector2d offset = pair("offset", Eigen::Vector2d::Zero()), scale = pair("scale", Eigen::Vector2d::Ones());
    const double rotation = numberOr(member(extension, "rotation"), 0);
    Eigen::Matrix<double, 2, 3> matrix;
    const double c = std::cos(rotation), s = std::sin(rotation);
    matrix << c * scale.x(), s * scale.y(), offset.x(), -s * scale.x(), c * scale.y(), offset.y();
    return matrix;
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
        default: return 0;
    }
}

// One component as a double; normalized integers map to [0, 1] or [-1, 1] as the glTF spec says.
double readComponent(const unsigned char* at, int componentType, bool normalized) {
    auto load = [at](auto value) {
        std::memcpy(&value, at, sizeof value);
        return value;
    };
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double v = load(std::int8_t());
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const double v = load(std::uint8_t());
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double v = load(std::int16_t());
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double v = load(std::uint16_t());
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_INT: return load(std::int32_t());
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(std::uint32_t());
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float());
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: return load(double());
        default: return 0;
    }
}

std::vector<double> GltfReader::readAccessor(int accessorIndex, int expectedComponents, const char* what) const {
    if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
        fail(std::string(what) + ": accessor " + std::to_string(accessorIndex) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[accessorIndex];
    const std::string where = std::string(what) + " (accessor " + std::to_string(accessorIndex) + ")";
    const int components = componentCount(accessor.type);
    const int size = componentSize(accessor.componentType);
    if (components == 0 || size == 0) fail(where + ": unknown type or component type");
    if (expectedComponents > 0 && components != expectedComponents)
        fail(where + ": has " + std::to_string(components) + " components, expected " +
             std::to_string(expectedComponents));

    // Where `count` elements of `elementComponents` components of `componentType` start in a buffer view
    // (`offset` bytes in) and how far apart they are, every byte checked to lie in the view and the view in
    // its buffer, with no sum or product of the file's numbers that could wrap around.
    struct Elements {
        const unsigned char* first;
        std::size_t stride;
    };
    auto elementsIn = [&](int viewIndex, std::size_t offset, std::size_t count, int componentType,
                          int elementComponents) -> Elements {
        if (viewIndex < 0 || viewIndex >= static_cast<int>(model_.bufferViews.size()))
            fail(where + ": buffer view " + std::to_string(viewIndex) + " does not exist");
        const tinygltf::BufferView& view = model_.bufferViews[viewIndex];
        if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
            fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist");
        const tinygltf::Buffer& buffer = model_.buffers[view.buffer];
        const std::size_t elementSize = static_cast<std::size_t>(componentSize(componentType)) * elementComponents;
        if (elementSize == 0) fail(where + ": unknown component type " + std::to_string(componentType));
        const std::size_t stride = view.byteStride ? view.byteStride : elementSize;
        if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
            fail(where + ": buffer view runs past the end of its buffer (" + std::to_string(buffer.data.size()) +
                 " bytes; missing or truncated .bin?)");
        if (count > 0 && (offset > view.byteLength || elementSize > view.byteLength - offset ||
                          count - 1 > (view.byteLength - offset - elementSize) / stride))
            fail(where + ": " + std::to_string(count) + " elements run past the end of its buffer view");
        return {buffer.data.data() + view.byteOffset + offset, stride};
    };
    auto read = [&](const Elements& elements, std::size_t count, int componentType, int elementComponents, auto&& store) {
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < elementComponents; ++c)
                store(i, c, readComponent(elements.first + i * elements.stride + c * componentSize(componentType),
                                          componentType, accessor.normalized));
    };

    // The count is checked against the bytes before anything is allocated for it. Without a buffer view the
    // elements are zeros (and sparse values): at most as many as the file's buffers could hold.
    Elements dense{nullptr, 0};
    if (accessor.bufferView >= 0) {
        dense = elementsIn(accessor.bufferView, accessor.byteOffset, accessor.count, accessor.componentType, components);
    } else {
        std::size_t bufferBytes = 0;
        for (const tinygltf::Buffer& buffer : model_.buffers) bufferBytes += buffer.data.size();
        if (accessor.count > bufferBytes / (static_cast<std::size_t>(size) * components))
            fail(where + ": a count of " + std::to_string(accessor.count) + " without a buffer view, more than the " +
                 "file's buffers (" + std::to_string(bufferBytes) + " bytes) could hold");
    }
    std::vector<double> values(accessor.count * components, 0.0);
    if (accessor.bufferView >= 0)
        read(dense, accessor.count, accessor.componentType, components,
             [&](std::size_t i, int c, double v) { values[i * components + c] = v; });
    if (accessor.sparse.isSparse) {
        if (accessor.sparse.count < 0 || static_cast<std::size_t>(accessor.sparse.count) > accessor.count)
            fail(where + ": sparse count " + std::to_string(accessor.sparse.count) + " is not between 0 and the count");
        const int indexType = accessor.sparse.indices.componentType;
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            fail(where + ": sparse indices must be unsigned integers");
        const auto sparseCount = static_cast<std::size_t>(accessor.sparse.count);
        const Elements indices = elementsIn(accessor.sparse.indices.bufferView, accessor.sparse.indices.byteOffset,
                                            sparseCount, indexType, 1);
        const Elements sparseValues = elementsIn(accessor.sparse.values.bufferView, accessor.sparse.values.byteOffset,
                                                 sparseCount, accessor.componentType, components);
        std::vector<std::size_t> targets(sparseCount);
        read(indices, sparseCount, indexType, 1, [&](std::size_t i, int, double v) { targets[i] = static_cast<std::size_t>(v); });
        for (std::size_t target : targets)
            if (target >= accessor.count) fail(where + ": sparse index " + std::to_string(target) + " out of range");
        read(sparseValues, sparseCount, accessor.componentType, components,
             [&](std::size_t i, int c, double v) { values[targets[i] * components + c] = v; });
    }
    return values;
}

std::vector<std::uint32_t> GltfReader::readIndices(int accessorIndex) const {
    const std::vector<double> values = readAccessor(accessorIndex, 1, "indices");
    std::vector<std::uint32_t> indices(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i]) || values[i] < 0 || values[i] > 4294967295.0) fail("indices: value out of range");
        indices[i] = static_cast<std::uint32_t>(values[i]);
    }
    return indices;
}

// Converts glTF's triangle topologies into a triangle list.
std::vector<Triangle> trianglesFromIndices(const std::vector<std::uint32_t>& indices, int mode) {
    std::vector<Triangle> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (std::size_t i = 0; i + 2 < indices.size(); i += 3)
            triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle of a strip is wound the other way round (glTF spec 3.7.2.1).
        for (std::size_t i = 0; i + 2 < indices.size(); ++i)
            triangles.push_back(i % 2 == 0 ? Triangle{indices[i], indices[i + 1], indices[i + 2]}
                                           : Triangle{indices[i + 1], indices[i], indices[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (std::size_t i = 1; i + 1 < indices.size(); ++i)
            triangles.push_back({indices[0], indices[i], indices[i + 1]});
    }
    // Degenerate strip/fan joints carry no area: drop triangles with repeated corners.
    if (mode != TINYGLTF_MODE_TRIANGLES)
        triangles.erase(std::remove_if(triangles.begin(), triangles.end(),
                                       [](const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }),
                        triangles.end());
    return triangles;
}

template <typename Vector>
std::vector<Vector> toVectors(const std::vector<double>& flat, int components) {
    std::vector<Vector> out(flat.size() / components, Vector::Zero());
    for (std::size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < std::min<int>(components, Vector::RowsAtCompileTime); ++c) out[i][c] = flat[i * components + c];
    return out;
}

std::vector<Eigen::Vector4d> toColors(const std::vector<double>& flat, int components) {
    std::vector<Eigen::Vector4d> colors = toVectors<Eigen::Vector4d>(flat, components);
    if (components == 3)
        for (Eigen::Vector4d& color : colors) color.w() = 1;
    return colors;
}

void GltfReader::decodeDracoPrimitive(const tinygltf::Primitive& source, const tinygltf::Value& extension,
                                      Primitive& out, std::vector<std::uint32_t>& indices,
                                      const std::string& where) const {
    const int viewIndex = indexIn(member(extension, "bufferView"));
    if (viewIndex < 0 || viewIndex >= static_cast<int>(model_.bufferViews.size()))
        fail(where + ": KHR_draco_mesh_compression has no valid bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[viewIndex];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()) ||
        view.byteOffset > model_.buffers[view.buffer].data.size() ||
        view.byteLength > model_.buffers[view.buffer].data.size() - view.byteOffset)
        fail(where + ": the Draco buffer view runs past the end of its buffer");
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(model_.buffers[view.buffer].data.data() + view.byteOffset),
                view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) fail(where + ": Draco cannot decode the mesh: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();

    const tinygltf::Value& attributes = member(extension, "attributes");
    auto readDracoAttribute = [&](const char* name, int components) -> std::vector<double> {
        if (!member(attributes, name).IsInt()) return {};
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(attributes.Get(name).Get<int>());
        if (!attribute) fail(where + ": Draco attribute " + name + " is missing from the compressed data");
        const int stored = attribute->num_components();
        std::vector<double> values(mesh->num_points() * static_cast<std::size_t>(components), 0.0);
        std::vector<float> element(std::max(stored, 4));
        for (draco::PointIndex point(0); point < mesh->num_points(); ++point) {
            attribute->ConvertValue<float>(attribute->mapped_index(point), stored, element.data());
            for (int c = 0; c < std::min(stored, components); ++c) values[point.value() * components + c] = element[c];
            if (components == 4 && stored == 3) values[point.value() * components + 3] = 1;
            // Draco stores normalized integer colours as integers: bring them to [0, 1].
            if (std::string(name) == "COLOR_0" && attribute->normalized()) {
                const double scale = attribute->data_type() == draco::DT_UINT8 ? 255.0 : 65535.0;
                for (int c = 0; c < std::min(stored, components); ++c) values[point.value() * components + c] /= scale;
            }
        }
        return values;
    };
    out.positions = toVectors<Eigen::Vector3d>(readDracoAttribute("POSITION", 3), 3);
    out.normals = toVectors<Eigen::Vector3d>(readDracoAttribute("NORMAL", 3), 3);
    out.texcoords = toVectors<Eigen::Vector2d>(readDracoAttribute("TEXCOORD_0", 2), 2);
    out.colors = toColors(readDracoAttribute("COLOR_0", 4), 4);
    if (out.positions.empty()) fail(where + ": Draco mesh has no POSITION");
    indices.clear();
    for (draco::FaceIndex face(0); face < mesh->num_faces(); ++face)
        for (int corner = 0; corner < 3; ++corner) indices.push_back(mesh->face(face)[corner].value());
    (void)source;
}

void GltfReader::readPrimitive(const tinygltf::Primitive& source, Mesh& mesh, const std::string& where) {
    const int mode = source.mode < 0 ? TINYGLTF_MODE_TRIANGLES : source.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        static const char* names[] = {"points", "lines", "line loops", "line strips"};
        ++skippedModes_[mode >= 0 && mode < 4 ? names[mode] : "primitives of unknown mode"];
        return;
    }
    if (!source.targets.empty()) warnAbout("morph targets ignored (the base shape is kept)");
    Primitive out;
    std::vector<std::uint32_t> indices;
    auto draco = source.extensions.find("KHR_draco_mesh_compression");
    if (draco != source.extensions.end()) {
        decodeDracoPrimitive(source, draco->second, out, indices, where);
    } else {
        auto attribute = [&](const char* name) {
            auto found = source.attributes.find(name);
            return found == source.attributes.end() ? -1 : found->second;
        };
        if (attribute("POSITION") < 0) fail(where + ": primitive has no POSITION");
        out.positions = toVectors<Eigen::Vector3d>(readAccessor(attribute("POSITION"), 3, "POSITION"), 3);
        if (attribute("NORMAL") >= 0)
            out.normals = toVectors<Eigen::Vector3d>(readAccessor(attribute("NORMAL"), 3, "NORMAL"), 3);
        if (attribute("TEXCOORD_0") >= 0)
            out.texcoords = toVectors<Eigen::Vector2d>(readAccessor(attribute("TEXCOORD_0"), 2, "TEXCOORD_0"), 2);
        if (const int colors = attribute("COLOR_0"); colors >= 0) {
            // An index out of range is refused by readAccessor, by its name.
            const int components = colors < static_cast<int>(model_.accessors.size()) ? componentCount(model_.accessors[colors].type) : 3;
            if (components != 3 && components != 4) fail(where + ": COLOR_0 must be VEC3 or VEC4");
            out.colors = toColors(readAccessor(attribute("COLOR_0"), components, "COLOR_0"), components);
        }
        if (source.indices >= 0) {
            indices = readIndices(source.indices);
        } else {
            indices.resize(out.positions.size());
            for (std::uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
        }
    }
    const std::size_t vertexCount = out.positions.size();
    for (const Eigen::Vector3d& p : out.positions)
        if (!p.allFinite()) fail(where + ": POSITION contains NaN or infinite values");
    // A broken attribute is dropped rather than the whole file refused: the geometry is still right.
    auto dropIfNotFinite = [&](auto& attribute, const char* name) {
        for (const auto& value : attribute)
            if (!value.allFinite()) {
                warnAbout(std::string(name) + " with NaN or infinite values dropped (" + where + ")");
                attribute.clear();
                return;
            }
    };
    dropIfNotFinite(out.normals, "NORMAL");
    dropIfNotFinite(out.texcoords, "TEXCOORD_0");
    dropIfNotFinite(out.colors, "COLOR_0");
    auto sameCount = [&](auto& attribute, const char* name) {
        if (!attribute.empty() && attribute.size() != vertexCount)
            fail(where + ": " + name + " has " + std::to_string(attribute.size()) + " elements for " +
                 std::to_string(vertexCount) + " positions");
    };
    sameCount(out.normals, "NORMAL");
    sameCount(out.texcoords, "TEXCOORD_0");
    sameCount(out.colors, "COLOR_0");
    for (std::uint32_t index : indices)
        if (index >= vertexCount)
            fail(where + ": index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount) +
                 " vertices)");
    out.triangles = trianglesFromIndices(indices, mode);
    out.material = source.material >= 0 && source.material < static_cast<int>(model_.materials.size()) ? source.material
                                                                                                      : -1;
    // KHR_texture_transform on the base colour texture (how gltfpack dequantizes texture coordinates),
    // applied to the coordinates themselves: the writers have no such transform to give.
    if (const auto transform = texcoordTransforms_.find(out.material); transform != texcoordTransforms_.end())
        for (Eigen::Vector2d& t : out.texcoords) t = transform->second * t.homogeneous();
    for (const auto& [name, accessor] : source.attributes)
        if (name != "POSITION" && name != "NORMAL" && name != "TEXCOORD_0" && name != "COLOR_0")
            warnAbout("attribute " + name + " not carried through");
    mesh.primitives.push_back(std::move(out));
}

Eigen::Matrix4d GltfReader::nodeTransform(const tinygltf::Node& node) const {
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
        for (int i = 0; i < 16; ++i) transform(i % 4, i / 4) = node.matrix[i];  // column-major
    } else {
        Eigen::Affine3d trs = Eigen::Affine3d::Identity();
        if (node.translation.size() == 3) trs.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4)
            trs.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
        if (node.scale.size() == 3) trs.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
        transform = trs.matrix();
    }
    if (!transform.allFinite()) fail("node '" + node.name + "': transform contains NaN or infinite values");
    return transform;
}

void GltfReader::readMaterials(Scene& scene) {
    std::map<int, int> textureOfImage;
    for (const tinygltf::Material& source : model_.materials) {
        Material material;
        material.name = source.name;
        const auto& pbr = source.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4)
            material.baseColorFactor = {pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                        pbr.baseColorFactor[3]};
        material.metallicFactor = pbr.metallicFactor;
        material.roughnessFactor = pbr.roughnessFactor;
        if (source.emissiveFactor.size() == 3)
            material.emissiveFactor = {source.emissiveFactor[0], source.emissiveFactor[1], source.emissiveFactor[2]};
        material.alphaMode = source.alphaMode == "MASK"    ? Material::AlphaMode::Mask
                             : source.alphaMode == "BLEND" ? Material::AlphaMode::Blend
                                                           : Material::AlphaMode::Opaque;
        material.alphaCutoff = source.alphaCutoff;
        material.doubleSided = source.doubleSided;
        const int texture = pbr.baseColorTexture.index;
        if (texture >= 0 && texture < static_cast<int>(model_.textures.size())) {
            const int imageIndex = model_.textures[texture].source;
            if (imageIndex >= 0 && imageIndex < static_cast<int>(model_.images.size())) {
                auto [entry, inserted] = textureOfImage.try_emplace(imageIndex, static_cast<int>(scene.textures.size()));
                if (inserted) {
                    const tinygltf::Image& image = model_.images[imageIndex];
                    Texture out;
                    out.name = image.name;
                    out.uri = image.uri.rfind("data:", 0) == 0 ? "" : image.uri;
                    out.mimeType = image.mimeType.empty() ? imageMimeType(image.uri) : image.mimeType;
                    out.bytes = image.image;
                    if (out.bytes.empty()) warnAbout("image '" + image.uri + "' could not be read; materials using it are written without it");
                    scene.textures.push_back(std::move(out));
                }
                material.baseColorTexture = entry->second;
            }
            if (pbr.baseColorTexture.texCoord != 0) warnAbout("base colour textures on TEXCOORD_1 or higher are not carried through");
            const auto transform = pbr.baseColorTexture.extensions.find("KHR_texture_transform");
            if (transform != pbr.baseColorTexture.extensions.end())
                texcoordTransforms_[scene.materials.size()] = textureTransform(transform->second);
        }
        if (source.normalTexture.index >= 0 || source.occlusionTexture.index >= 0 || source.emissiveTexture.index >= 0 ||
            pbr.metallicRoughnessTexture.index >= 0)
            warnAbout("normal, occlusion, emissive and metallic-roughness textures are not carried through");
        scene.materials.push_back(std::move(material));
    }
}

// Node transform channels are kept; a channel the scene model cannot hold (morph weights, a target other
// than a node) or a broken one is left out with a warning.
void GltfReader::readAnimations(Scene& scene) {
    std::size_t weights = 0;
    for (std::size_t a = 0; a < model_.animations.size(); ++a) {
        const tinygltf::Animation& source = model_.animations[a];
        Animation animation;
        animation.name = source.name;
        for (std::size_t c = 0; c < source.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = source.channels[c];
            const std::string where = "animation " + std::to_string(a) + " channel " + std::to_string(c);
            if (channel.target_path == "weights") {
                ++weights;
                continue;
            }
            AnimationChannel out;
            out.node = channel.target_node;
            // The file's own nodes (the scene has the GPU instances' after them).
            if (out.node < 0 || out.node >= static_cast<int>(model_.nodes.size())) {
                warnAbout(where + " ignored: it targets no node of the file");
                continue;
            }
            if (channel.target_path == "translation") out.path = AnimationChannel::Path::Translation;
            else if (channel.target_path == "rotation") out.path = AnimationChannel::Path::Rotation;
            else if (channel.target_path == "scale") out.path = AnimationChannel::Path::Scale;
            else {
                warnAbout(where + " ignored: unknown path '" + channel.target_path + "'");
                continue;
            }
            if (channel.sampler < 0 || channel.sampler >= static_cast<int>(source.samplers.size())) {
                warnAbout(where + " ignored: its sampler does not exist");
                continue;
            }
            const tinygltf::AnimationSampler& sampler = source.samplers[channel.sampler];
            if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") out.interpolation = AnimationChannel::Interpolation::Linear;
            else if (sampler.interpolation == "STEP") out.interpolation = AnimationChannel::Interpolation::Step;
            else if (sampler.interpolation == "CUBICSPLINE") out.interpolation = AnimationChannel::Interpolation::CubicSpline;
            else {
                warnAbout(where + " ignored: unknown interpolation '" + sampler.interpolation + "'");
                continue;
            }
            out.times = readAccessor(sampler.input, 1, "animation input");
            out.values = readAccessor(sampler.output, int(out.components()), "animation output");
            if (const std::string problem = animationChannelProblem(out, scene.nodes.size()); !problem.empty())
                warnAbout(where + " ignored: " + problem);
            else
                animation.channels.push_back(std::move(out));
        }
        for (const AnimationChannel& channel : animation.channels) {
            // Written back, a node's transform is a rotation and a scale with the mirror on x: the same
            // rest pose, but not the same parts for a channel to replace when the file put it elsewhere.
            const std::vector<double>& scale = model_.nodes[std::size_t(channel.node)].scale;
            if (scale.size() == 3 && (scale[1] < 0 || scale[2] < 0))
                warnAbout("node " + std::to_string(channel.node) + " is animated with a negative scale on y or z: its " +
                          "animation may play differently once written back");
        }
        if (!animation.channels.empty()) scene.animations.push_back(std::move(animation));
    }
    if (weights) warnAbout(std::to_string(weights) + " animation channels of morph target weights ignored");
}

// glTF's cameras and KHR_lights_punctual lights, with the nodes that carry them. One that breaks the
// rules of scene.hpp (a yfov of 0, an unknown light type) is left out with a warning.
void GltfReader::readCamerasAndLights(Scene& scene) {
    std::vector<int> cameraIndex(model_.cameras.size(), -1), lightIndex(model_.lights.size(), -1);
    // Adds `item` to `into`, its index to `indexOf[i]`, or leaves it out with a warning naming `problem`.
    auto keep = [&](const char* what, std::size_t i, const std::string& problem, auto item, auto& into, std::vector<int>& indexOf) {
        if (!problem.empty()) {
            warnAbout(std::string(what) + " " + std::to_string(i) + " ignored: " + problem);
            return;
        }
        indexOf[i] = int(into.size());
        into.push_back(std::move(item));
    };
    for (std::size_t c = 0; c < model_.cameras.size(); ++c) {
        const tinygltf::Camera& source = model_.cameras[c];
        Camera camera;
        camera.name = source.name;
        if (source.type == "orthographic") {
            camera.projection = Camera::Projection::Orthographic;
            camera.xmag = source.orthographic.xmag;
            camera.ymag = source.orthographic.ymag;
            camera.znear = source.orthographic.znear;
            camera.zfar = source.orthographic.zfar;
        } else {
            camera.yfov = source.perspective.yfov;
            camera.aspectRatio = source.perspective.aspectRatio;
            camera.znear = source.perspective.znear;
            camera.zfar = source.perspective.zfar;
        }
        keep("camera", c,
             source.type == "orthographic" || source.type == "perspective" ? cameraProblem(camera) : "unknown type '" + source.type + "'",
             camera, scene.cameras, cameraIndex);
    }
    for (std::size_t l = 0; l < model_.lights.size(); ++l) {
        const tinygltf::Light& source = model_.lights[l];
        Light light;
        light.name = source.name;
        light.type = source.type == "directional" ? Light::Type::Directional
                     : source.type == "spot"      ? Light::Type::Spot
                                                  : Light::Type::Point;
        if (source.color.size() == 3) light.color = {source.color[0], source.color[1], source.color[2]};
        light.intensity = source.intensity;
        light.range = source.range;
        light.innerConeAngle = source.spot.innerConeAngle;
        light.outerConeAngle = source.spot.outerConeAngle;
        const bool known = source.type == "directional" || source.type == "spot" || source.type == "point";
        keep("light", l,
             !known                                              ? "unknown type '" + source.type + "'"
             : !source.color.empty() && source.color.size() != 3 ? "a colour needs 3 values"
                                                                 : lightProblem(light),
             light, scene.lights, lightIndex);
    }
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        const tinygltf::Node& source = model_.nodes[n];
        if (source.camera >= 0 && std::size_t(source.camera) < cameraIndex.size()) scene.nodes[n].camera = cameraIndex[source.camera];
        else if (source.camera >= 0) warnAbout("node " + std::to_string(n) + ": camera index out of range, ignored");
        const auto extension = source.extensions.find("KHR_lights_punctual");
        if (extension == source.extensions.end()) continue;
        const int light = indexIn(member(extension->second, "light"));
        if (light >= 0 && std::size_t(light) < lightIndex.size())
            scene.nodes[n].light = lightIndex[std::size_t(light)];
        else
            warnAbout("node " + std::to_string(n) + ": KHR_lights_punctual light index missing or out of range, ignored");
    }
}

// EXT_mesh_gpu_instancing (gltfpack -mi, glTF-Transform instance): each instance of a node's mesh becomes
// a child node of its own with the instance's translation, rotation and scale, which apply before the
// node's transform, as the extension says. The new nodes come after the file's, whose indices stay.
void GltfReader::expandGpuInstances(Scene& scene) {
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        const auto found = model_.nodes[n].extensions.find("EXT_mesh_gpu_instancing");
        if (found == model_.nodes[n].extensions.end() || scene.nodes[n].mesh < 0) continue;
        const tinygltf::Value& attributes = member(found->second, "attributes");
        const std::string where = "node " + std::to_string(n) + " (EXT_mesh_gpu_instancing)";
        std::map<std::string, std::vector<double>> values;
        for (const std::string& name : attributes.Keys()) {
            const int components = name == "ROTATION" ? 4 : 3;
            if (name != "TRANSLATION" && name != "ROTATION" && name != "SCALE") {
                warnAbout("instance attribute " + name + " not carried through");
                continue;
            }
            if (!attributes.Get(name).IsNumber()) fail(where + ": " + name + " is not an accessor index");
            values[name] = readAccessor(indexIn(attributes.Get(name)), components, name.c_str());
        }
        std::size_t count = 0;
        for (const auto& [name, list] : values) count = std::max(count, list.size() / (name == "ROTATION" ? 4 : 3));
        for (const auto& [name, list] : values)
            if (list.size() / (name == "ROTATION" ? 4 : 3) != count) fail(where + ": attributes of different counts");
        auto component = [&](const char* name, std::size_t i, int c, double fallback) {
            const auto list = values.find(name);
            return list == values.end() ? fallback : list->second[i * (std::strcmp(name, "ROTATION") == 0 ? 4 : 3) + std::size_t(c)];
        };
        for (std::size_t i = 0; i < count; ++i) {
            Eigen::Affine3d trs = Eigen::Affine3d::Identity();
            trs.translate(Eigen::Vector3d(component("TRANSLATION", i, 0, 0), component("TRANSLATION", i, 1, 0), component("TRANSLATION", i, 2, 0)));
            const Eigen::Quaterniond rotation(component("ROTATION", i, 3, 1), component("ROTATION", i, 0, 0),
                                              component("ROTATION", i, 1, 0), component("ROTATION", i, 2, 0));
            if (!(rotation.norm() > 0)) fail(where + ": instance " + std::to_string(i) + " has a rotation of length 0");
            trs.rotate(rotation.normalized());
            trs.scale(Eigen::Vector3d(component("SCALE", i, 0, 1), component("SCALE", i, 1, 1), component("SCALE", i, 2, 1)));
            if (!trs.matrix().allFinite()) fail(where + ": instance " + std::to_string(i) + " has NaN or infinite values");
            Node instance;
            instance.transform = trs.matrix();
            instance.mesh = scene.nodes[n].mesh;
            scene.nodes[n].children.push_back(int(scene.nodes.size()));
            scene.nodes.push_back(std::move(instance));
        }
        scene.nodes[n].mesh = -1;
    }
}

Scene GltfReader::read() {
    Scene scene;
    readMaterials(scene);
    for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
        Mesh mesh;
        mesh.name = model_.meshes[m].name;
        for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p)
            readPrimitive(model_.meshes[m].primitives[p], mesh,
                          "mesh " + std::to_string(m) + " primitive " + std::to_string(p));
        scene.meshes.push_back(std::move(mesh));
    }
    std::vector<int> parentCount(model_.nodes.size(), 0);
    for (const tinygltf::Node& source : model_.nodes) {
        Node node;
        node.name = source.name;
        node.transform = nodeTransform(source);
        node.mesh = source.mesh >= 0 && source.mesh < static_cast<int>(scene.meshes.size()) ? source.mesh : -1;
        for (int child : source.children) {
            if (child < 0 || child >= static_cast<int>(model_.nodes.size())) fail("node '" + source.name + "': child out of range");
            if (++parentCount[child] > 1) fail("node " + std::to_string(child) + " has more than one parent");
            node.children.push_back(child);
        }
        if (source.skin >= 0) warnAbout("skins ignored: skinned meshes are drawn in their bind pose");
        scene.nodes.push_back(std::move(node));
    }
    // Deep chains are refused here, level by level without recursion, before any code that walks the
    // hierarchy recursively sees them (a node in a cycle is never reached; validateScene refuses cycles).
    std::vector<int> level;
    for (int n = 0; n < static_cast<int>(parentCount.size()); ++n)
        if (parentCount[n] == 0) level.push_back(n);
    for (std::size_t depth = 1; !level.empty(); ++depth) {
        if (depth > kMaxNodeDepth) fail("nodes nested deeper than " + std::to_string(kMaxNodeDepth) + " levels");
        std::vector<int> next;
        for (int n : level) next.insert(next.end(), scene.nodes[n].children.begin(), scene.nodes[n].children.end());
        level = std::move(next);
    }
    readCamerasAndLights(scene);
    expandGpuInstances(scene);
    const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (sceneIndex < static_cast<int>(model_.scenes.size())) {
        for (int root : model_.scenes[sceneIndex].nodes) {
            if (root < 0 || root >= static_cast<int>(model_.nodes.size())) fail("scene: root node out of range");
            scene.roots.push_back(root);
        }
    } else {
        // No scene: every node of the file without a parent is drawn (the GPU instances' have theirs).
        for (int n = 0; n < static_cast<int>(parentCount.size()); ++n)
            if (parentCount[n] == 0) scene.roots.push_back(n);
    }
    if (model_.scenes.size() > 1) warnAbout(std::to_string(model_.scenes.size() - 1) + " scenes besides the default one ignored");
    readAnimations(scene);
    if (!model_.skins.empty()) warnAbout(std::to_string(model_.skins.size()) + " skins ignored");
    for (const auto& [mode, count] : skippedModes_)
        warnAbout(std::to_string(count) + " " + mode + " skipped (only triangles are kept)");
    for (const std::string& warning : warnings_) scene.warnings.push_back(file_.filename().string() + ": " + warning);
    return scene;
}

// The extensions we read.
bool readExtension(const std::string& name) {
    static const std::set<std::string> read = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                               "KHR_mesh_quantization", "EXT_mesh_gpu_instancing",
                                               "KHR_lights_punctual", "KHR_texture_transform"};
    return read.count(name) > 0;
}

// Extensions that change how a surface looks, never where it is: a file that requires one is still read,
// its geometry right, with a warning that the extension is left out.
bool appearanceOnly(const std::string& name) { return name.rfind("KHR_materials_", 0) == 0; }

// EXT_meshopt_compression: each compressed buffer view decoded (meshoptimizer) into a buffer of its own,
// which the view then points at, so that accessors read it as any other.
void decodeMeshopt(tinygltf::Model& model, const fs::path& file) {
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        const auto found = view.extensions.find("EXT_meshopt_compression");
        if (found == view.extensions.end()) continue;
        const tinygltf::Value& extension = found->second;
        const std::string where = "buffer view " + std::to_string(v) + " (EXT_meshopt_compression)";
        auto number = [&](const char* key, double fallback) { return numberOr(member(extension, key), fallback); };
        auto text = [&](const char* key, const char* fallback) {
            const tinygltf::Value& value = member(extension, key);
            return value.IsString() ? value.Get<std::string>() : std::string(fallback);
        };
        const double buffer = number("buffer", -1), offset = number("byteOffset", 0), length = number("byteLength", -1),
                     stride = number("byteStride", -1), count = number("count", -1);
        // Whole numbers in range before any is converted to an integer (meshopt's largest stride is 256).
        auto whole = [](double value) { return value == std::floor(value); };
        if (buffer < 0 || buffer >= double(model.buffers.size()) || offset < 0 || length < 0 || stride <= 0 || stride > 256 ||
            count < 0 || !whole(buffer) || !whole(offset) || !whole(length) || !whole(stride) || !whole(count) ||
            offset + length > double(model.buffers[std::size_t(buffer)].data.size()))
            throw FileError(file, where + ": buffer, byteOffset, byteLength, byteStride or count missing or out of range");
        // The decoded data fills the view (glTF's byteLength, bounded so that a broken file cannot ask for more).
        if (stride * count > double(view.byteLength) || stride * count > double(1u << 31))
            throw FileError(file, where + ": count times byteStride (" + std::to_string(std::size_t(stride * count)) +
                                      ") exceeds the buffer view's byteLength (" + std::to_string(view.byteLength) + ")");
        const unsigned char* source = model.buffers[std::size_t(buffer)].data.data() + std::size_t(offset);
        const std::string mode = text("mode", ""), filter = text("filter", "NONE");
        tinygltf::Buffer decoded;
        decoded.data.resize(std::size_t(stride) * std::size_t(count));
        int status = -1;
        if (mode == "ATTRIBUTES" && int(stride) % 4 == 0 && stride <= 256)
            status = meshopt_decodeVertexBuffer(decoded.data.data(), std::size_t(count), std::size_t(stride), source, std::size_t(length));
        else if (mode == "TRIANGLES" && (stride == 2 || stride == 4))
            status = meshopt_decodeIndexBuffer(decoded.data.data(), std::size_t(count), std::size_t(stride), source, std::size_t(length));
        else if (mode == "INDICES" && (stride == 2 || stride == 4))
            status = meshopt_decodeIndexSequence(decoded.data.data(), std::size_t(count), std::size_t(stride), source, std::size_t(length));
        if (status != 0) throw FileError(file, where + ": cannot be decoded (mode '" + mode + "')");
        if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) meshopt_decodeFilterOct(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter == "QUATERNION" && stride == 8) meshopt_decodeFilterQuat(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter == "EXPONENTIAL" && int(stride) % 4 == 0) meshopt_decodeFilterExp(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter != "NONE") throw FileError(file, where + ": unknown filter '" + filter + "'");
        model.buffers.push_back(std::move(decoded));
        view.buffer = int(model.buffers.size()) - 1;
        view.byteOffset = 0;
        view.byteLength = std::size_t(stride) * std::size_t(count);
        if (mode == "ATTRIBUTES") view.byteStride = std::size_t(stride);
    }
}

// JSON nested deeper than this is refused: tinygltf turns extras and extensions into its Values recursively.
constexpr int kMaxJsonDepth = 512;

// Refuses the integers that tinygltf would cut down to an int without a word (a node index of 2^32 would
// become node 0): all outside int's range, except byte offsets, lengths, strides and counts (read as size_t)
// and what extras hold (never interpreted). Recursive, over JSON already checked to nest at most kMaxJsonDepth.
void refuseIntegersBeyondInt(const nlohmann::json& value, const std::string& key, const fs::path& file) {
    if (value.is_object()) {
        for (const auto& [name, member] : value.items())
            if (name != "extras") refuseIntegersBeyondInt(member, name, file);
    } else if (value.is_array()) {
        for (const auto& element : value) refuseIntegersBeyondInt(element, key, file);
    } else if (value.is_number_integer() && key != "byteOffset" && key != "byteLength" && key != "byteStride" &&
               key != "count") {
        const bool fits = value.is_number_unsigned()
                              ? value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max())
                              : value.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                    value.get<std::int64_t>() <= std::numeric_limits<int>::max();
        if (!fits) throw FileError(file, "\"" + key + "\": " + value.dump() + " does not fit a 32-bit integer");
    }
}

// What tinygltf (as packaged) would refuse in a valid file, mended in the JSON before it sees it:
// - a primitive whose indices accessor has no bufferView, which is how KHR_draco_mesh_compression files
//   are written: the indices come from the Draco data anyway, so they are removed;
// - EXT_meshopt_compression's fallback buffer, which has no data (no uri, or more bytes than a GLB's binary
//   chunk): it gets one byte of its own; decodeMeshopt gives its buffer views their data.
// It also refuses (FileError) what tinygltf would take badly: JSON nested too deep, integers beyond an int.
std::vector<unsigned char> preparedForTinygltf(const std::vector<unsigned char>& bytes, bool binary, const fs::path& file) {
    auto readU32 = [&](std::size_t at) {
        std::uint32_t value;
        std::memcpy(&value, bytes.data() + at, 4);
        return value;
    };
    std::size_t jsonBegin = 0, jsonLength = bytes.size();
    if (binary) {
        if (bytes.size() < 20) return bytes;  // tinygltf reports the broken header
        jsonBegin = 20;
        jsonLength = readU32(12);
        if (readU32(16) != 0x4E4F534Au || jsonBegin + jsonLength > bytes.size()) return bytes;
    }
    int depth = 0;
    nlohmann::json json = nlohmann::json::parse(bytes.begin() + static_cast<std::ptrdiff_t>(jsonBegin),
                                                bytes.begin() + static_cast<std::ptrdiff_t>(jsonBegin + jsonLength),
                                                [&depth](int level, nlohmann::json::parse_event_t, nlohmann::json&) {
                                                    depth = std::max(depth, level);
                                                    return true;
                                                },
                                                false);
    if (depth > kMaxJsonDepth) throw FileError(file, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    if (json.is_discarded() || !json.is_object()) return bytes;
    refuseIntegersBeyondInt(json, "", file);
    bool changed = false;
    if (json.contains("buffers") && json["buffers"].is_array())
        for (auto& buffer : json["buffers"]) {
            if (!buffer.is_object() || !buffer.contains("extensions") || !buffer["extensions"].is_object()) continue;
            const auto meshopt = buffer["extensions"].find("EXT_meshopt_compression");
            if (meshopt == buffer["extensions"].end() || !meshopt->is_object() || !meshopt->value("fallback", false)) continue;
            buffer["uri"] = "data:application/octet-stream;base64,AA==";
            buffer["byteLength"] = 1;
            changed = true;
        }
    nlohmann::json noMeshes = nlohmann::json::array();
    for (auto& mesh : json.contains("meshes") && json["meshes"].is_array() ? json["meshes"] : noMeshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (auto& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("extensions") || !primitive.contains("indices")) continue;
            const auto& extensions = primitive["extensions"];
            if (extensions.is_object() && extensions.contains("KHR_draco_mesh_compression")) {
                primitive.erase("indices");
                changed = true;
            }
        }
    }
    if (!changed) return bytes;
    std::string text = json.dump();
    if (!binary) return std::vector<unsigned char>(text.begin(), text.end());
    while (text.size() % 4) text.push_back(' ');
    std::vector<unsigned char> rebuilt(bytes.begin(), bytes.begin() + 12);
    auto appendU32 = [&](std::uint32_t value) {
        const auto* raw = reinterpret_cast<const unsigned char*>(&value);
        rebuilt.insert(rebuilt.end(), raw, raw + 4);
    };
    appendU32(static_cast<std::uint32_t>(text.size()));
    appendU32(0x4E4F534Au);
    rebuilt.insert(rebuilt.end(), text.begin(), text.end());
    std::size_t rest = jsonBegin + jsonLength;
    rest += (4 - rest % 4) % 4;
    if (rest < bytes.size()) rebuilt.insert(rebuilt.end(), bytes.begin() + static_cast<std::ptrdiff_t>(rest), bytes.end());
    const auto total = static_cast<std::uint32_t>(rebuilt.size());
    std::memcpy(rebuilt.data() + 8, &total, 4);
    return rebuilt;
}

}  // namespace

Scene readGltf(const fs::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    if (bytes.empty()) throw FileError(file, "the file is empty");
    const bool binary = formatFromExtension(file) == FileFormat::Glb ||
                        (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
    if (formatFromExtension(file) == FileFormat::Glb && (bytes.size() < 12 || std::memcmp(bytes.data(), "glTF", 4) != 0))
        throw FileError(file, "not a GLB file (wrong magic number; expected 'glTF')");

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, &model);
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);  // asset.extras carries symcompress's digest
    std::string error, warning;
    const std::string baseDir = file.parent_path().empty() ? "." : file.parent_path().string();
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw FileError(file, "larger than 4 GiB");
    const std::vector<unsigned char> parsed = preparedForTinygltf(bytes, binary, file);
    // tinygltf checks that a GLB's BIN chunk ends inside the file without its 8-byte header, and then reads
    // up to 8 bytes past the end: the chunk is checked here first.
    if (binary && parsed.size() >= 20) {
        std::uint32_t jsonLength, binLength;
        std::memcpy(&jsonLength, parsed.data() + 12, 4);
        const std::uint64_t binHeader = 20 + std::uint64_t(jsonLength);
        if (binHeader + 8 <= parsed.size()) {
            std::memcpy(&binLength, parsed.data() + binHeader, 4);
            if (binHeader + 8 + binLength > parsed.size())
                throw FileError(file, "the BIN chunk (" + std::to_string(binLength) + " bytes) runs past the end of the file");
        }
    }
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, parsed.data(),
                                                         static_cast<unsigned int>(parsed.size()), baseDir)
                           : loader.LoadASCIIFromString(&model, &error, &warning,
                                                        reinterpret_cast<const char*>(parsed.data()),
                                                        static_cast<unsigned int>(parsed.size()), baseDir);
    if (!ok) {
        while (!error.empty() && error.back() == '\n') error.pop_back();
        throw FileError(file, "invalid glTF: " + (error.empty() ? std::string("cannot be parsed") : error));
    }
    for (const std::string& required : model.extensionsRequired)
        if (!readExtension(required) && !appearanceOnly(required))
            throw FileError(file, "requires the extension " + required + ", which symcompress cannot read");
    decodeMeshopt(model, file);
    Scene scene = GltfReader(file, model).read();
    scene.extrasJson = model.asset.extras_json_string;
    for (const std::string& used : model.extensionsUsed)
        if (!readExtension(used))
            scene.warnings.push_back(file.filename().string() + ": extension " + used + " ignored");
    return scene;
}

}  // namespace symcompress
