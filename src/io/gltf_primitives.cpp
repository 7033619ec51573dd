// glTF primitives: Draco-compressed (KHR_draco_mesh_compression; the triangles edgebreaker would drop in a
// sequential primitive of their own, those of zero area at one point) or plain accessors.
#include "draco_grid.hpp"
#include "gltf_builder.hpp"
#include "primitive_encodings.hpp"

#include "geometry/bounds.hpp"
#include "symcompress/scene_ops.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/compression/expert_encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <meshoptimizer.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace symcompress {
namespace fs = std::filesystem;
namespace {

const char* accessorType(int components) {
    static const char* types[] = {"SCALAR", "VEC2", "VEC3", "VEC4"};
    return types[std::clamp(components, 1, 4) - 1];
}

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

// The Draco quantization of one of Primitive::attributes: tangents at 8 bits a component (gltfpack's too; the
// lantern's normal-mapped render is as far from its input at 8 bits as unquantized, 0.17% of pixels, for 31.7
// KB against 88.7 KB), further UV sets and colours as the first, weights as the writer bounds them (weightBitsFor);
// 0 (none: as read) for joints and an application's attributes.
constexpr int kTangentBits = 8;
int quantizationBits(const std::string& name, const WriteOptions& options) {
    if (name == "TANGENT") return kTangentBits;
    if (name.rfind("TEXCOORD_", 0) == 0) return options.texcoordBits;
    if (name.rfind("COLOR_", 0) == 0) return options.colorBits;
    if (name.rfind("WEIGHTS_", 0) == 0) return options.weightBits;
    return 0;
}

// One of Primitive::attributes in a Draco soup builder, as float32 (JOINTS as unsigned 16-bit indices),
// GENERIC for Draco (quantizationBits says how it is quantized).
int addDracoAttribute(draco::TriangleSoupMeshBuilder& builder, const Primitive& primitive,
                      const VertexAttribute& attribute) {
    const bool joints = attribute.isJoints();
    const int components = attribute.components;
    const int id = builder.AddAttribute(draco::GeometryAttribute::GENERIC, static_cast<std::int8_t>(components),
                                        joints ? draco::DT_UINT16 : draco::DT_FLOAT32);
    std::vector<float> corner(3 * components);
    std::vector<std::uint16_t> jointCorner(3 * components);
    for (std::size_t f = 0; f < primitive.triangles.size(); ++f) {
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < components; ++c) {
                const double value = attribute.values[primitive.triangles[f][k] * std::size_t(components) + c];
                // Joint indices are whole numbers from 0 to 65535 (refuseBeyondFloat checked them).
                if (joints)
                    jointCorner[k * components + c] = static_cast<std::uint16_t>(value);
                else
                    corner[k * components + c] = static_cast<float>(value);
            }
        const draco::FaceIndex face(static_cast<std::uint32_t>(f));
        if (joints)
            builder.SetAttributeValuesForFace(id, face, jointCorner.data(), jointCorner.data() + components,
                                              jointCorner.data() + 2 * components);
        else
            builder.SetAttributeValuesForFace(id, face, corner.data(), corner.data() + components,
                                              corner.data() + 2 * components);
    }
    return id;
}

// Draco quantizes each attribute in float32 over the span of its values, and dequantizes as min + q * span / qmax:
// with values near float32's limit the span or that sum overflows (its entropy coder then wrote through a null
// pointer, or the decoded positions came back infinite). A quarter of float32's largest leaves room for both.
constexpr double kMaxDracoMagnitude = std::numeric_limits<float>::max() / 4.0;

template <typename Vector>
void refuseBeyondDracoRange(const Primitive& primitive, const std::vector<Vector>& values, const char* name,
                            const fs::path& file) {
    if (values.empty()) return;
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t)
            if (!(values[v].cwiseAbs().maxCoeff() <= kMaxDracoMagnitude))
                throw FileError(file, std::string(name) + " holds values beyond 8.5e37 in magnitude, where Draco's " +
                                          "float32 quantization overflows; write with --no-draco");
}

struct DracoAttributeIds {
    int position = -1, normal = -1, texcoord = -1, color = -1;
    std::vector<int> others;  // Primitive::attributes', in order
};

// The primitive's triangles split in two: those Draco's edgebreaker keeps, and those whose corners its
// quantization of positions (`bits` over the box's largest side, or the primitive's own grid) puts on one
// point, which it would drop. The second part goes to the sequential method, so that a few slivers do not
// cost a whole mesh its edgebreaker compression (vertex arrays are shared; Draco takes only the corners
// its triangles use).
std::pair<Primitive, Primitive> splitCollapsingTriangles(const Primitive& primitive, int bits) {
    const DracoGrid grid(primitive, bits);
    std::pair<Primitive, Primitive> parts{primitive, primitive};
    parts.first.triangles.clear();
    parts.second.triangles.clear();
    for (const Triangle& t : primitive.triangles)
        (grid.collapses(primitive, t) ? parts.second : parts.first).triangles.push_back(t);
    return parts;
}

// TEXCOORD_0's grid where WriteOptions::texcoordStep asks for a coarser one than its bits over the coordinates'
// span: the span's corner (as Draco takes it, float32) and a range of that step times 2^bits - 1.
std::optional<QuantizationGrid> texcoordGridFor(const Primitive& primitive, const WriteOptions& options) {
    if (!(options.texcoordStep > 0) || primitive.texcoords.empty()) return std::nullopt;
    Eigen::AlignedBox2f box;
    for (const Eigen::Vector2d& t : primitive.texcoords) box.extend(t.cast<float>());
    const double range = options.texcoordStep * double((1u << options.texcoordBits) - 1);
    if (!(float(range) > box.sizes().maxCoeff())) return std::nullopt;
    return QuantizationGrid{Eigen::Vector3d(box.min().x(), box.min().y(), 0), range, options.texcoordBits};
}

// How to encode: edgebreaker compresses best but drops triangles whose corners its quantization merges;
// the sequential method keeps every triangle.
enum class DracoMethod {
    EdgebreakerOrNothing,       // nothing (no primitive written) when a triangle would be lost
    EdgebreakerElseSequential,  // the sequential method when a triangle would be lost
    Sequential,
};

// Encodes one primitive with Draco and describes it in glTF: the accessors carry counts and bounds
// (decoded from our own output, since Draco merges equal corners) but no buffer view. Nothing touches the
// builder here (the primitives of a scene are encoded in parallel); `addDracoPart` adds it.
std::optional<DracoPart> encodeDracoPrimitive(const Primitive& primitive, const WriteOptions& options, const fs::path& file,
                                              DracoMethod method) {
    refuseBeyondDracoRange(primitive, primitive.positions, "POSITION", file);
    refuseBeyondDracoRange(primitive, primitive.normals, "NORMAL", file);
    refuseBeyondDracoRange(primitive, primitive.texcoords, "TEXCOORD_0", file);
    refuseBeyondDracoRange(primitive, primitive.colors, "COLOR_0", file);
    draco::TriangleSoupMeshBuilder soup;
    soup.Start(static_cast<int>(primitive.triangles.size()));
    DracoAttributeIds ids;
    addDracoAttribute(soup, primitive, primitive.positions, draco::GeometryAttribute::POSITION, 3, ids.position);
    addDracoAttribute(soup, primitive, primitive.normals, draco::GeometryAttribute::NORMAL, 3, ids.normal);
    addDracoAttribute(soup, primitive, primitive.texcoords, draco::GeometryAttribute::TEX_COORD, 2, ids.texcoord);
    addDracoAttribute(soup, primitive, primitive.colors, draco::GeometryAttribute::COLOR, 4, ids.color);
    for (const VertexAttribute& attribute : primitive.attributes)
        ids.others.push_back(addDracoAttribute(soup, primitive, attribute));
    std::unique_ptr<draco::Mesh> mesh = soup.Finalize();
    if (!mesh) throw FileError(file, "Draco could not build a mesh from a primitive");

    // Primitive::attributes near float32's limit stay unquantized (Draco stores them as read), where quantizing
    // overflowed as above; the core attributes were refused instead, since glTF's viewers expect them quantized.
    std::vector<int> otherBits;
    for (const VertexAttribute& attribute : primitive.attributes) {
        const bool withinRange = std::all_of(attribute.values.begin(), attribute.values.end(),
                                             [](double value) { return std::abs(value) <= kMaxDracoMagnitude; });
        otherBits.push_back(withinRange ? quantizationBits(attribute.name, options) : 0);
    }
    const int positionBits =
        primitive.positionGrid ? primitive.positionGrid->bits : positionBitsFor(primitive, options);
    const std::optional<QuantizationGrid> texcoordGrid = texcoordGridFor(primitive, options);
    const std::vector<int> speeds = dracoSpeedsWorthTrying(primitive, options);
    // False when the encoder refuses (edgebreaker: "all triangles are degenerate"). Encoders only read the mesh:
    // several may encode it at once.
    // `grid`: the positions' grid where not the primitive's own (Primitive::positionGrid) or Draco's at `bits`.
    auto encode = [&](int encoding, int speed, int bits, draco::EncoderBuffer& encoded,
                      const QuantizationGrid* grid = nullptr) {
        draco::ExpertEncoder encoder(*mesh);
        encoder.SetSpeedOptions(speed, speed);
        encoder.SetEncodingMethod(encoding);
        if (!grid && primitive.positionGrid) grid = &*primitive.positionGrid;
        if (grid) {
            const float origin[3] = {float(grid->origin.x()), float(grid->origin.y()), float(grid->origin.z())};
            encoder.SetAttributeExplicitQuantization(ids.position, grid->bits, 3, origin, float(grid->range));
        } else {
            encoder.SetAttributeQuantization(ids.position, bits);
        }
        const std::pair<int, int> quantized[] = {{ids.normal, options.normalBits},
                                                 {ids.texcoord, options.texcoordBits},
                                                 {ids.color, colorBitsFor(primitive, options)}};
        for (const auto& [id, attributeBits] : quantized)
            if (id >= 0) encoder.SetAttributeQuantization(id, attributeBits);
        if (texcoordGrid) {
            const float origin[2] = {float(texcoordGrid->origin.x()), float(texcoordGrid->origin.y())};
            encoder.SetAttributeExplicitQuantization(ids.texcoord, texcoordGrid->bits, 2, origin,
                                                     float(texcoordGrid->range));
        }
        for (std::size_t a = 0; a < primitive.attributes.size(); ++a)
            if (otherBits[a] > 0) encoder.SetAttributeQuantization(ids.others[a], otherBits[a]);
        const draco::Status status = encoder.EncodeToBuffer(&encoded);
        if (!status.ok() && encoding != draco::MESH_EDGEBREAKER_ENCODING)
            throw FileError(file, "Draco encoding failed: " + status.error_msg_string());
        return status.ok();
    };
    auto decode = [&](const draco::EncoderBuffer& encoded) {
        draco::DecoderBuffer decoderBuffer;
        decoderBuffer.Init(encoded.data(), encoded.size());
        auto decoded = draco::Decoder().DecodeMeshFromBuffer(&decoderBuffer);
        if (!decoded.ok())
            throw FileError(file, "Draco cannot decode what it encoded: " + decoded.status().error_msg_string());
        return std::move(decoded).value();
    };
    auto complete = [&](const std::unique_ptr<draco::Mesh>& decoded) {
        return decoded && decoded->num_faces() == primitive.triangles.size();
    };
    draco::EncoderBuffer encoded;
    std::unique_ptr<draco::Mesh> result;
    if (method != DracoMethod::Sequential) {
        if (encode(draco::MESH_EDGEBREAKER_ENCODING, speeds.front(), positionBits, encoded)) result = decode(encoded);
        if (!complete(result) && method == DracoMethod::EdgebreakerOrNothing) return std::nullopt;
        // Other speeds (dracoSpeedsWorthTrying), then more bits within the bound at the best of them
        // (positionBitsWorthTrying) and a coarser grid of the fewest bits (coarserPositionGrid), may encode
        // smaller. Each round's trials are encoded at once; in their order, one is kept where it is smaller than
        // the best so far and decodes whole: the first smallest.
        auto tryEach = [&](const std::vector<std::pair<int, int>>& trials,
                           const QuantizationGrid* grid = nullptr) {  // (speed, bits)
            std::vector<draco::EncoderBuffer> buffers(trials.size());
            std::vector<char> encodedWell(trials.size(), 0);
            tbb::parallel_for(std::size_t(0), trials.size(), [&](std::size_t t) {
                encodedWell[t] =
                    encode(draco::MESH_EDGEBREAKER_ENCODING, trials[t].first, trials[t].second, buffers[t], grid);
            });
            std::optional<std::pair<int, int>> kept;
            for (std::size_t t = 0; t < trials.size(); ++t) {
                if (!encodedWell[t] || buffers[t].size() >= encoded.size()) continue;
                std::unique_ptr<draco::Mesh> decoded = decode(buffers[t]);
                if (!complete(decoded)) continue;
                encoded = std::move(buffers[t]);
                result = std::move(decoded);
                kept = trials[t];
            }
            return kept;
        };
        if (complete(result)) {
            std::vector<std::pair<int, int>> otherSpeeds;
            for (std::size_t s = 1; s < speeds.size(); ++s) otherSpeeds.push_back({speeds[s], positionBits});
            const int speed = tryEach(otherSpeeds).value_or(std::pair{speeds.front(), positionBits}).first;
            std::vector<std::pair<int, int>> moreBits;
            for (const int more : positionBitsWorthTrying(primitive, options, positionBits))
                moreBits.push_back({speed, more});
            tryEach(moreBits);
            if (const std::optional<QuantizationGrid> coarser = coarserPositionGrid(primitive, options, positionBits))
                tryEach({{speed, positionBits}}, &*coarser);
        }
    }
    if (!complete(result)) {
        encoded.Clear();
        encode(draco::MESH_SEQUENTIAL_ENCODING, speeds.front(), positionBits, encoded);
        result = decode(encoded);
    }
    if (result->num_faces() != primitive.triangles.size())
        throw FileError(file, "Draco lost " + std::to_string(primitive.triangles.size() - result->num_faces()) +
                                  " triangles of a primitive; write with --no-draco");

    DracoPart part;
    part.material = primitive.material;
    part.bytes.assign(encoded.data(), encoded.data() + encoded.size());
    auto describe = [&](const char* name, int sourceId, draco::GeometryAttribute::Type type, const char* accessorType) {
        if (sourceId < 0) return;
        const draco::PointAttribute* attribute = result->GetNamedAttribute(type);
        Json accessor = {{"componentType", kFloat}, {"count", result->num_points()}, {"type", accessorType}};
        if (type == draco::GeometryAttribute::POSITION) {
            std::vector<float> flat(result->num_points() * 3);
            for (draco::PointIndex p(0); p < result->num_points(); ++p)
                attribute->ConvertValue<float>(attribute->mapped_index(p), 3, &flat[p.value() * 3]);
            GltfBuilder::addBounds(accessor, flat, 3);
        }
        part.accessors.emplace_back(name, std::move(accessor));
        part.dracoAttributes[name] = attribute->unique_id();
    };
    describe("POSITION", ids.position, draco::GeometryAttribute::POSITION, "VEC3");
    describe("NORMAL", ids.normal, draco::GeometryAttribute::NORMAL, "VEC3");
    describe("TEXCOORD_0", ids.texcoord, draco::GeometryAttribute::TEX_COORD, "VEC2");
    describe("COLOR_0", ids.color, draco::GeometryAttribute::COLOR, "VEC4");
    for (std::size_t a = 0; a < primitive.attributes.size(); ++a) {
        const VertexAttribute& source = primitive.attributes[a];
        const draco::PointAttribute* attribute = result->GetAttributeByUniqueId(mesh->attribute(ids.others[a])->unique_id());
        if (!attribute) throw FileError(file, "Draco lost the attribute " + source.name + " of a primitive");
        part.accessors.emplace_back(source.name, Json{{"componentType", source.isJoints() ? kUnsignedShort : kFloat},
                                                      {"count", result->num_points()},
                                                      {"type", accessorType(source.components)}});
        part.dracoAttributes[source.name] = attribute->unique_id();
    }
    const int indexType = result->num_points() <= 65535 ? kUnsignedShort : kUnsignedInt;
    part.indices = {{"componentType", indexType}, {"count", result->num_faces() * 3}, {"type", "SCALAR"}};
    return part;
}

// The glTF primitive of an encoded part: its buffer view, then its accessors in the order they were described.
Json addDracoPart(GltfBuilder& builder, const DracoPart& part) {
    const int view = builder.addBufferView(part.bytes.data(), part.bytes.size());
    Json attributes = Json::object();
    for (const auto& [name, accessor] : part.accessors) attributes[name] = builder.addAccessor(accessor);
    Json out = {{"attributes", attributes},
                {"indices", builder.addAccessor(part.indices)},
                {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", part.dracoAttributes}}}}}};
    return out;
}

// glTF stores attributes as float32: a value beyond its range would be written as infinite (and converting it
// is undefined).
template <typename Vector>
void refuseBeyondFloat(const std::vector<Vector>& values, const char* name, const fs::path& file) {
    for (const Vector& value : values)
        if (!(value.cwiseAbs().maxCoeff() <= std::numeric_limits<float>::max()))
            throw FileError(file, std::string(name) + " holds values beyond float32's range (3.4e38), in which glTF " +
                                      "stores them");
}

// One of Primitive::attributes (or of a morph target) as an accessor: JOINTS as unsigned bytes or shorts, glTF's
// only types for them, the others as float32 (which every semantic allows), a POSITION with its bounds.
int addAttribute(GltfBuilder& builder, const VertexAttribute& attribute) {
    if (!attribute.isJoints()) {
        const std::vector<float> flat(attribute.values.begin(), attribute.values.end());
        return builder.addFloatAccessor(flat, attribute.components, accessorType(attribute.components),
                                        attribute.name == "POSITION", kArrayBuffer);
    }
    const double largest =
        attribute.values.empty() ? 0 : *std::max_element(attribute.values.begin(), attribute.values.end());
    // Each element 4-byte aligned, as glTF asks of vertex attributes (JOINTS are VEC4: no padding in valid files).
    const bool bytes = largest <= 255;
    const std::size_t size = bytes ? 1 : 2, stride = (size * std::size_t(attribute.components) + 3) / 4 * 4;
    std::vector<unsigned char> data(stride * attribute.count(), 0);
    for (std::size_t v = 0; v < attribute.count(); ++v)
        for (int c = 0; c < attribute.components; ++c) {
            const auto value = static_cast<std::uint16_t>(attribute.values[v * std::size_t(attribute.components) + c]);
            std::memcpy(&data[v * stride + std::size_t(c) * size], &value, size);  // little-endian, as glTF
        }
    const int view = builder.addBufferView(data.data(), data.size(), kArrayBuffer);
    if (stride != size * std::size_t(attribute.components)) builder.setByteStride(view, stride);
    return builder.addAccessor({{"bufferView", view},
                                {"componentType", bytes ? kUnsignedByte : kUnsignedShort},
                                {"count", attribute.count()},
                                {"type", accessorType(attribute.components)}});
}

void refuseBeyondFloat(const VertexAttribute& attribute, const fs::path& file) {
    for (double value : attribute.values)
        if (!(std::abs(value) <= std::numeric_limits<float>::max()))
            throw FileError(file, attribute.name + " holds values beyond float32's range (3.4e38), in which glTF " +
                                      "stores them");
    if (attribute.isJoints())
        for (double value : attribute.values)
            if (!(value >= 0 && value <= 65535 && value == std::floor(value)))
                throw FileError(file, attribute.name + " holds a joint index that is no whole number from 0 to 65535");
}

// Attribute `name` of target `target` (-1: the primitive's own) as `rounded` holds it, where it does and the builder
// codes data by meshopt; else -1.
int addRoundedAttribute(GltfBuilder& builder, const RoundedVertices& rounded, int target, const std::string& name) {
    const auto found = rounded.find({target, name});
    if (!builder.dataEncoder || found == rounded.end()) return -1;
    const RoundedAttribute& values = found->second;
    Json accessor = {{"componentType", values.componentType},
                     {"count", values.decoded.size() / std::size_t(values.components)},
                     {"type", accessorType(values.components)}};
    if (values.normalized) accessor["normalized"] = true;
    if (name == "POSITION") GltfBuilder::addBounds(accessor, values.decoded, values.components);  // as a viewer reads
    return builder.addFilteredAccessor(std::move(accessor), values.filtered, values.elementBytes, values.filter,
                                       kArrayBuffer);
}

// An accessor of `indices` (of triangles, else of segments) into `vertices` vertices: 16 bits where they suffice; coded
// by meshopt's index codecs where the builder codes data by meshopt and that is smaller.
int addIndices(GltfBuilder& builder, const std::vector<std::uint32_t>& indices, std::size_t vertices, bool triangles) {
    const bool shorts = vertices <= 65535;
    const std::size_t stride = shorts ? 2 : 4;
    Json accessor = {
        {"componentType", shorts ? kUnsignedShort : kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}};
    if (builder.dataEncoder) {
        std::vector<unsigned char> encoded(triangles ? meshopt_encodeIndexBufferBound(indices.size(), vertices)
                                                     : meshopt_encodeIndexSequenceBound(indices.size(), vertices));
        encoded.resize(
            triangles ? meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), indices.size())
                      : meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), indices.size()));
        constexpr std::size_t kExtensionJson = 100;  // the view's EXT_meshopt_compression object
        if (!encoded.empty() && encoded.size() + kExtensionJson < indices.size() * stride) {
            accessor["bufferView"] = builder.addMeshoptBufferView(
                encoded, indices.size(), stride, "NONE", kElementArrayBuffer, triangles ? "TRIANGLES" : "INDICES");
            return builder.addAccessor(accessor);
        }
    }
    if (shorts) {
        const std::vector<std::uint16_t> values(indices.begin(), indices.end());
        accessor["bufferView"] = builder.addBufferView(values.data(), values.size() * 2, kElementArrayBuffer);
    } else {
        accessor["bufferView"] = builder.addBufferView(indices.data(), indices.size() * 4, kElementArrayBuffer);
    }
    return builder.addAccessor(accessor);
}

// Attribute `name` of target `target` as `rounded` holds it, else as read (added by `asRead`).
template <typename AsRead>
int addRoundedElse(GltfBuilder& builder, const RoundedVertices& rounded, int target, const std::string& name,
                   AsRead asRead) {
    const int accessor = addRoundedAttribute(builder, rounded, target, name);
    return accessor >= 0 ? accessor : asRead();
}

// A plain primitive's vertex attributes, each rounded where `rounded` has it, else as read.
Json plainAttributes(GltfBuilder& builder, const Primitive& primitive, const RoundedVertices& rounded) {
    Json attributes = Json::object();
    auto add = [&](const std::string& name, int target, auto asRead) {
        return addRoundedElse(builder, rounded, target, name, asRead);
    };
    attributes["POSITION"] =
        add("POSITION", -1, [&] { return builder.addFloatAccessor(primitive.positions, 3, "VEC3", true); });
    if (!primitive.normals.empty())
        attributes["NORMAL"] =
            add("NORMAL", -1, [&] { return builder.addFloatAccessor(primitive.normals, 3, "VEC3", false); });
    if (!primitive.texcoords.empty())
        attributes["TEXCOORD_0"] =
            add("TEXCOORD_0", -1, [&] { return builder.addFloatAccessor(primitive.texcoords, 2, "VEC2", false); });
    if (!primitive.colors.empty())
        attributes["COLOR_0"] =
            add("COLOR_0", -1, [&] { return builder.addFloatAccessor(primitive.colors, 4, "VEC4", false); });
    for (const VertexAttribute& attribute : primitive.attributes)
        attributes[attribute.name] = add(attribute.name, -1, [&] { return addAttribute(builder, attribute); });
    return attributes;
}

Json writePlainPrimitive(GltfBuilder& builder, const Primitive& primitive, const RoundedVertices& rounded) {
    Json out = {{"attributes", plainAttributes(builder, primitive, rounded)}};
    // Points draw every vertex, in order: no indices. TRIANGLES is the default mode.
    if (primitive.topology == Topology::Points) out["mode"] = kModePoints;
    std::vector<std::uint32_t> flat;
    if (primitive.topology == Topology::Lines) {
        out["mode"] = kModeLines;
        for (const Segment& s : primitive.lines) flat.insert(flat.end(), s.begin(), s.end());
    }
    for (const Triangle& t : primitive.triangles) flat.insert(flat.end(), t.begin(), t.end());
    if (primitive.topology != Topology::Points)
        out["indices"] =
            addIndices(builder, flat, primitive.positions.size(), primitive.topology == Topology::Triangles);
    for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
        Json displaced = Json::object();
        for (const VertexAttribute& attribute : primitive.targets[t])
            displaced[attribute.name] = addRoundedElse(builder, rounded, int(t), attribute.name,
                                                       [&] { return addAttribute(builder, attribute); });
        out["targets"].push_back(std::move(displaced));
    }
    return out;
}

// Its one vertex, and indices that are zeros: an accessor without a buffer view is zeros (glTF 2.0, 3.6.2.1),
// so that the triangles cost their JSON alone. A vertex at the origin with nothing but its position is zeros too:
// then a few triangles are drawn without indices, each corner a zero position (one accessor less: 61 bytes; a
// viewer then holds 36 bytes of zeros a triangle, not 3).
Json writeZeroAreaPrimitive(GltfBuilder& builder, const ZeroAreaPart& part) {
    constexpr std::size_t kMostWithoutIndices = 1024;
    const Primitive& vertex = part.vertex;
    if (vertex.positions.front().isZero(0) && vertex.texcoords.empty() && vertex.attributes.empty() &&
        part.triangles <= kMostWithoutIndices)
        return {{"attributes",
                 {{"POSITION", builder.addAccessor({{"componentType", kFloat},
                                                    {"count", 3 * part.triangles},
                                                    {"type", "VEC3"},
                                                    {"min", {0, 0, 0}},
                                                    {"max", {0, 0, 0}}})}}}};
    return {{"attributes", plainAttributes(builder, vertex, {})},
            {"indices", builder.addAccessor(
                            {{"componentType", kUnsignedByte}, {"count", 3 * part.triangles}, {"type", "SCALAR"}})}};
}

// A primitive's triangles of zero area at one vertex, that vertex alone. What shades a triangle shades none of
// them: its texture coordinates stay for the validator (a material's textures need their sets), the rest goes.
// (A skinned primitive keeps its triangles of zero area as they are: encodePrimitive.)
ZeroAreaPart zeroAreaPart(const Primitive& primitive, const ZeroAreaTriangles& zeroArea) {
    ZeroAreaPart part{primitive, zeroArea.count};
    Primitive& vertex = part.vertex;
    vertex.triangles.clear();
    keepVertices(vertex, {zeroArea.vertex});
    vertex.normals.clear();
    vertex.colors.clear();
    vertex.attributes.erase(std::remove_if(vertex.attributes.begin(), vertex.attributes.end(),
                                           [](const VertexAttribute& a) { return a.name.rfind("TEXCOORD_", 0) != 0; }),
                            vertex.attributes.end());
    // Where the primitive has a vertex at the origin, the point may as well be that one (writeZeroAreaPrimitive):
    // it must be one of its points, which the verification measures.
    if (vertex.texcoords.empty() && vertex.attributes.empty() &&
        std::any_of(primitive.positions.begin(), primitive.positions.end(),
                    [](const Eigen::Vector3d& p) { return p.isZero(0); }))
        vertex.positions.front().setZero();
    return part;
}

}  // namespace

EncodedPrimitive encodePrimitive(const Primitive& primitive, const WriteOptions& options, const fs::path& file) {
    refuseBeyondFloat(primitive.positions, "POSITION", file);
    refuseBeyondFloat(primitive.normals, "NORMAL", file);
    refuseBeyondFloat(primitive.texcoords, "TEXCOORD_0", file);
    refuseBeyondFloat(primitive.colors, "COLOR_0", file);
    for (const VertexAttribute& attribute : primitive.attributes) refuseBeyondFloat(attribute, file);
    for (const MorphTarget& target : primitive.targets)
        for (const VertexAttribute& attribute : target) refuseBeyondFloat(attribute, file);
    EncodedPrimitive encoded;
    // Morph targets stay plain accessors, which Draco's reordering of the vertices would no longer match; lines
    // and points too, which KHR_draco_mesh_compression does not hold.
    if (!options.draco || !primitive.targets.empty() || primitive.topology != Topology::Triangles) {
        encoded.plain = true;
        return encoded;
    }
    std::optional<PrimitiveFingerprint> key;
    if (options.encodings) {
        key = fingerprintOf(primitive, options);
        if (std::optional<EncodedPrimitive> found = options.encodings->find(*key)) return std::move(*found);
    }
    // A skinned primitive's corners at one point may part once it moves: its triangles stay as they are (those
    // edgebreaker would drop in a sequential part, below).
    const bool skinned = std::any_of(primitive.attributes.begin(), primitive.attributes.end(),
                                     [](const VertexAttribute& a) { return a.isJoints(); });
    const std::optional<std::pair<Primitive, ZeroAreaTriangles>> split =
        skinned ? std::nullopt : withoutZeroAreaTriangles(primitive);
    const Primitive& drawing = split ? split->first : primitive;
    if (split) encoded.zeroArea = zeroAreaPart(primitive, split->second);
    if (drawing.triangles.empty()) {
    } else if (options.keepTriangleOrder) {
        encoded.parts.push_back(*encodeDracoPrimitive(drawing, options, file, DracoMethod::Sequential));
    } else if (auto whole = encodeDracoPrimitive(drawing, options, file, DracoMethod::EdgebreakerOrNothing)) {
        encoded.parts.push_back(std::move(*whole));
    } else {
        // Edgebreaker would drop some triangles (whose corners its quantization merges): they go to a sequential
        // primitive of their own.
        const auto [kept, collapsing] = splitCollapsingTriangles(drawing, positionBitsFor(drawing, options));
        for (const auto& [part, method] : {std::pair{&kept, DracoMethod::EdgebreakerElseSequential},
                                           std::pair{&collapsing, DracoMethod::Sequential}})
            if (!part->triangles.empty()) encoded.parts.push_back(*encodeDracoPrimitive(*part, options, file, method));
    }
    if (key) options.encodings->insert(*key, encoded);
    return encoded;
}

void addPrimitive(GltfBuilder& builder, const Primitive& primitive, const EncodedPrimitive& encoded, Json& primitives) {
    auto add = [&](Json out, int material) {
        if (material >= 0) out["material"] = material;
        primitives.push_back(std::move(out));
    };
    if (encoded.plain) {
        add(writePlainPrimitive(builder, primitive, encoded.rounded), primitive.material);
        return;
    }
    for (const DracoPart& part : encoded.parts) add(addDracoPart(builder, part), part.material);
    if (encoded.zeroArea) add(writeZeroAreaPrimitive(builder, *encoded.zeroArea), primitive.material);
}

void writePrimitive(GltfBuilder& builder, const Primitive& primitive, const WriteOptions& options, const fs::path& file,
                    Json& primitives) {
    addPrimitive(builder, primitive, encodePrimitive(primitive, options, file), primitives);
}

}  // namespace symcompress
