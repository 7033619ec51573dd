// Vertex data of glTF primitives: accessors (every byte range checked, with no sum or product of the file's
// numbers that could wrap), sparse accessors, index topologies, and Draco-compressed primitives.
#include "draco_stream_checks.hpp"
#include "gltf_constants.hpp"
#include "gltf_reader.hpp"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cstring>

namespace symcompress {
namespace {

// The bytes of one component of the types glTF allows (int and double, which tinygltf knows, are not); 0 for others.
int componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
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
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(std::uint32_t());
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load(float());
    default: return 0;
    }
}

}  // namespace

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

std::vector<double> GltfReader::readAccessor(int accessorIndex, int expectedComponents, const char* what) const {
    if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
        fail(std::string(what) + ": accessor " + std::to_string(accessorIndex) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[accessorIndex];
    const std::string where = std::string(what) + " (accessor " + std::to_string(accessorIndex) + ")";
    const int components = componentCount(accessor.type);
    const int size = componentSize(accessor.componentType);
    // Both refused before tinygltf parsed the file (refuseBrokenStructure), along with what glTF allows.
    if (size == 0)
        fail(where + ": componentType " + std::to_string(accessor.componentType) + " is not one glTF allows");
    if (components == 0) fail(where + ": its type is not one glTF allows");
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
    auto read = [&](const Elements& elements, std::size_t count, int componentType, int elementComponents,
                    auto&& store) {
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < elementComponents; ++c)
                store(i, c,
                      readComponent(elements.first + i * elements.stride + c * componentSize(componentType),
                                    componentType, accessor.normalized));
    };

    // The count is checked against the bytes before anything is allocated for it. Without a buffer view the
    // elements are zeros (and sparse values): at most as many as kMostZeroBytes or the file's buffers could hold
    // (symcompress writes the one point of a primitive's triangles of zero area so, in files of a few bytes).
    Elements dense{nullptr, 0};
    if (accessor.bufferView >= 0) {
        dense =
            elementsIn(accessor.bufferView, accessor.byteOffset, accessor.count, accessor.componentType, components);
    } else {
        std::size_t bufferBytes = 0;
        for (const tinygltf::Buffer& buffer : model_.buffers) bufferBytes += buffer.data.size();
        const std::size_t allowed = std::max<std::size_t>(bufferBytes, kMostZeroBytes);
        if (accessor.count > allowed / (static_cast<std::size_t>(size) * components))
            fail(where + ": a count of " + std::to_string(accessor.count) + " without a buffer view, more than " +
                 std::to_string(allowed) + " bytes of zeros");
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
        read(indices, sparseCount, indexType, 1,
             [&](std::size_t i, int, double v) { targets[i] = static_cast<std::size_t>(v); });
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
    // A strip's or fan's joints with repeated corners stay: they draw nothing, but viewers count them (three.js
    // turns a strip of n indices into n - 2 triangles), and the writers keep triangles of zero area.
    return triangles;
}

std::vector<Segment> segmentsFromIndices(const std::vector<std::uint32_t>& indices, int mode) {
    std::vector<Segment> segments;
    if (mode == TINYGLTF_MODE_LINE) {
        for (std::size_t i = 0; i + 1 < indices.size(); i += 2) segments.push_back({indices[i], indices[i + 1]});
        return segments;
    }
    for (std::size_t i = 0; i + 1 < indices.size(); ++i) segments.push_back({indices[i], indices[i + 1]});
    if (mode == TINYGLTF_MODE_LINE_LOOP && indices.size() > 2) segments.push_back({indices.back(), indices.front()});
    return segments;
}

std::vector<Eigen::Vector4d> toColors(const std::vector<double>& flat, int components) {
    std::vector<Eigen::Vector4d> colors = toVectors<Eigen::Vector4d>(flat, components);
    if (components == 3)
        for (Eigen::Vector4d& color : colors) color.w() = 1;
    return colors;
}

void GltfReader::decodeDracoPrimitive(const tinygltf::Primitive& source, const tinygltf::Value& extension,
                                      Primitive& out, std::vector<std::uint32_t>& indices,
                                      const std::string& where) {
    const int viewIndex = indexIn(member(extension, "bufferView"));
    if (viewIndex < 0 || viewIndex >= static_cast<int>(model_.bufferViews.size()))
        fail(where + ": KHR_draco_mesh_compression has no valid bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[viewIndex];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()) ||
        view.byteOffset > model_.buffers[view.buffer].data.size() ||
        view.byteLength > model_.buffers[view.buffer].data.size() - view.byteOffset)
        fail(where + ": the Draco buffer view runs past the end of its buffer");
    const char* stream = reinterpret_cast<const char*>(model_.buffers[view.buffer].data.data() + view.byteOffset);

    // libdraco's work follows the counts the stream claims; they are checked first against what the primitive's
    // POSITION accessor declares and what the stream's bytes could code.
    const auto position = source.attributes.find("POSITION");
    if (position == source.attributes.end() || position->second < 0 ||
        position->second >= static_cast<int>(model_.accessors.size()))
        fail(where + ": a KHR_draco_mesh_compression primitive needs its POSITION accessor");
    const std::size_t declared = model_.accessors[position->second].count;
    if (const std::string problem = dracoStreamProblem(stream, view.byteLength, declared); !problem.empty())
        fail(where + ": " + problem);
    draco::DecoderBuffer buffer;
    buffer.Init(stream, view.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) fail(where + ": Draco cannot decode the mesh: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    // Fewer points than declared is tolerated (an encoder may have merged some); more is what the checks refuse.
    if (mesh->num_points() > declared)
        fail(where + ": the Draco mesh has " + std::to_string(mesh->num_points()) + " points, more than the " +
             std::to_string(declared) + " its POSITION accessor declares");

    const tinygltf::Value& attributes = member(extension, "attributes");
    auto readDracoAttribute = [&](const std::string& name, int components) -> std::vector<double> {
        if (!member(attributes, name).IsInt()) return {};
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(attributes.Get(name).Get<int>());
        if (!attribute) fail(where + ": Draco attribute " + name + " is missing from the compressed data");
        const int stored = attribute->num_components();
        // Draco stores normalized integers as integers: bring them to [0, 1] (or [-1, 1]), as glTF reads them.
        double scale = 1;
        if (attribute->normalized()) {
            const draco::DataType type = attribute->data_type();
            scale = type == draco::DT_UINT8 ? 255.0 : type == draco::DT_UINT16 ? 65535.0 : type == draco::DT_INT8 ? 127.0
                    : type == draco::DT_INT16 ? 32767.0 : 1.0;
        }
        std::vector<double> values(mesh->num_points() * static_cast<std::size_t>(components), 0.0);
        std::vector<float> element(std::max(stored, 4));
        for (draco::PointIndex point(0); point < mesh->num_points(); ++point) {
            attribute->ConvertValue<float>(attribute->mapped_index(point), stored, element.data());
            for (int c = 0; c < std::min(stored, components); ++c) {
                const double value = element[c] / scale;
                values[point.value() * components + c] = scale > 1 ? std::max(value, -1.0) : value;
            }
            if (components == 4 && stored == 3) values[point.value() * components + 3] = 1;
        }
        return values;
    };
    out.positions = toVectors<Eigen::Vector3d>(readDracoAttribute("POSITION", 3), 3);
    out.normals = toVectors<Eigen::Vector3d>(readDracoAttribute("NORMAL", 3), 3);
    out.texcoords = toVectors<Eigen::Vector2d>(readDracoAttribute("TEXCOORD_0", 2), 2);
    out.colors = toColors(readDracoAttribute("COLOR_0", 4), 4);
    for (const auto& [name, accessor] : source.attributes) {
        if (isCoreAttribute(name) || !member(attributes, name).IsInt()) continue;
        const int components = vertexAttributeComponents(accessor, name, where);
        if (components > 0) out.attributes.push_back({name, components, readDracoAttribute(name, components)});
    }
    if (out.positions.empty()) fail(where + ": Draco mesh has no POSITION");
    indices.clear();
    for (draco::FaceIndex face(0); face < mesh->num_faces(); ++face)
        for (int corner = 0; corner < 3; ++corner) indices.push_back(mesh->face(face)[corner].value());
}

}  // namespace symcompress
