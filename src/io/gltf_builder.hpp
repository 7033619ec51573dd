// What the glTF writer's parts share: the JSON and the growing binary buffer (GltfBuilder), and the
// primitives' encoding (gltf_primitives.cpp: Draco or plain accessors).
#pragma once

#include "common/number_text.hpp"
#include "gltf_constants.hpp"
#include "gltf_vertex_rounding.hpp"
#include "symcompress/io.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace symcompress {

using Json = nlohmann::json;

// Whole numbers as integers: 1 for 1.0, as glTF readers take any JSON number; two bytes each, in every factor,
// transform and bound of a small file. Only within a 32-bit int: readers (tinygltf, ours) refuse or cut down
// larger integers, which they take for indices (a bound of 12147483648 would not read back).
inline void writeWholeNumbersAsIntegers(Json& json) {
    if (json.is_number_float()) {
        const double x = json.get<double>();
        if (std::abs(x) <= 2147483647.0 && x == std::trunc(x)) json = static_cast<std::int64_t>(x);
    } else if (json.is_structured()) {
        for (Json& item : json) writeWholeNumbersAsIntegers(item);
    }
}

// The JSON's text. Names come from files that need not be UTF-8 (X3D's DEFs, OBJ's groups): bytes that are
// not UTF-8 are written as U+FFFD instead of making dump() throw.
inline std::string jsonText(Json json, int indent = -1) {
    writeWholeNumbersAsIntegers(json);
    return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

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

    // A view of EXT_meshopt_compression's fallback buffer (buffer 1, which holds no data) decoded from
    // `encoded`, meshopt's ATTRIBUTES of `count` elements of `stride` bytes under `filter` ("NONE": none), or its
    // `mode` TRIANGLES or INDICES of indices, which goes in the binary buffer; returns its index.
    int addMeshoptBufferView(const std::vector<unsigned char>& encoded, std::size_t count, std::size_t stride,
                             const std::string& filter, int target = 0, const char* mode = "ATTRIBUTES") {
        while (binary_.size() % 4) binary_.push_back(0);
        Json compressed = {
            {"buffer", 0}, {"byteLength", encoded.size()}, {"byteStride", stride}, {"count", count}, {"mode", mode}};
        if (!binary_.empty()) compressed["byteOffset"] = binary_.size();
        if (filter != "NONE") compressed["filter"] = filter;
        Json view = {{"buffer", 1}, {"byteLength", count * stride}};
        if (fallbackBytes_) view["byteOffset"] = fallbackBytes_;
        if (target) view["target"] = target;
        view["extensions"]["EXT_meshopt_compression"] = compressed;
        binary_.insert(binary_.end(), encoded.begin(), encoded.end());
        fallbackBytes_ += (count * stride + 3) / 4 * 4;
        root_["bufferViews"].push_back(view);
        return static_cast<int>(root_["bufferViews"].size()) - 1;
    }
    // The bytes the fallback buffer stands for (0: no view is meshopt's), data that is no vertex attribute written.
    std::size_t fallbackBytes() {
        writePendingData();
        return fallbackBytes_;
    }

    void setByteStride(int view, std::size_t stride) { root_["bufferViews"][std::size_t(view)]["byteStride"] = stride; }

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
    // The same over values already flat; `target` 0 for data that is no vertex attribute (animations, skins'
    // matrices): written once for every use of the same values (an animation's channels share their key times).
    int addFloatAccessor(const std::vector<float>& flat, int components, const char* type, bool withBounds,
                         int target) {
        Json accessor = {{"componentType", kFloat}, {"count", flat.size() / std::size_t(components)}, {"type", type}};
        if (withBounds) addBounds(accessor, flat, components);
        const auto* bytes = reinterpret_cast<const unsigned char*>(flat.data());
        return addPendingAccessor(std::move(accessor), {bytes, bytes + flat.size() * sizeof(float)},
                                  std::size_t(components) * sizeof(float), "", target,
                                  std::to_string(target) + type + (withBounds ? "+" : "-"));
    }

    // Data rounded by one of meshopt's filters (QUATERNION, EXPONENTIAL): `filtered`, the filter's elements of
    // `elementBytes`, which only a meshopt view holds (dataEncoder must be set), one for each target, filter and
    // layout. `accessor`: its JSON but its view; `target`: kArrayBuffer for vertex attributes, 0 for other data.
    int addFilteredAccessor(Json accessor, const std::vector<unsigned char>& filtered, std::size_t elementBytes,
                            const std::string& filter, int target = 0) {
        const std::string group = std::to_string(target) + filter + std::to_string(elementBytes) +
                                  accessor["type"].get<std::string>() +
                                  std::to_string(accessor["componentType"].get<int>());
        const bool padded = elementBytes != packedBytes(accessor);
        const int index = addPendingAccessor(std::move(accessor), filtered, elementBytes, filter, target, group);
        pendingData_[group].padded = pendingData_[group].padded || padded;
        return index;
    }

    // The bytes of one element of `accessor` packed tight: its components' sizes.
    static std::size_t packedBytes(const Json& accessor) {
        static const std::map<std::string, std::size_t> kComponents = {
            {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
        return std::size_t(componentBytes(accessor["componentType"].get<int>())) *
               kComponents.at(accessor["type"].get<std::string>());
    }

    // Where set, float data is stored encoded by it (the writer's meshopt ATTRIBUTES, filter NONE: lossless) where
    // that is smaller: an animation's keys, a skin's matrices, a plain primitive's vertices. Its arguments: the
    // bytes and an element's size.
    std::function<std::vector<unsigned char>(const std::vector<unsigned char>&, std::size_t)> dataEncoder;

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

    // The binary buffer, complete: data that is no vertex attribute is written first.
    std::vector<unsigned char>& binary() {
        writePendingData();
        return binary_;
    }

private:
    // An accessor whose data waits in its group's view (`group`: target or filter, and layout); data that is no
    // vertex attribute (`target` 0) is written once for every accessor of the same group and bytes.
    int addPendingAccessor(Json accessor, const std::vector<unsigned char>& bytes, std::size_t elementBytes,
                           const std::string& filter, int target, const std::string& group) {
        std::string key = group;
        if (target == 0) {
            key.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
            if (const auto found = dataAccessors_.find(key); found != dataAccessors_.end()) return found->second;
        }
        const int index = addAccessor(std::move(accessor));
        PendingData& pending = pendingData_[group];
        pending.target = target;
        pending.elementBytes = elementBytes;
        pending.filter = filter;
        pending.accessors.emplace_back(index, pending.bytes.size());
        pending.bytes.insert(pending.bytes.end(), bytes.begin(), bytes.end());
        if (target == 0) dataAccessors_.emplace(std::move(key), index);
        return index;
    }

    // A view of a group's data: filtered data meshopt's, float data encoded where dataEncoder makes it smaller by
    // more than the extension's JSON (some 100 bytes).
    int addDataView(const std::vector<unsigned char>& bytes, std::size_t element, const std::string& filter,
                    int target) {
        const std::size_t count = bytes.size() / element;
        if (!filter.empty()) return addMeshoptBufferView(dataEncoder(bytes, element), count, element, filter, target);
        if (dataEncoder && element % 4 == 0 && element <= 256 && !bytes.empty()) {
            const std::vector<unsigned char> encoded = dataEncoder(bytes, element);
            constexpr std::size_t kExtensionJson = 100;
            if (encoded.size() + kExtensionJson < bytes.size())
                return addMeshoptBufferView(encoded, count, element, "NONE", target);
        }
        return addBufferView(bytes.data(), bytes.size(), target);
    }

    // Data goes in one view for each target or filter and type (an animation's key times, its rotations; the
    // positions of plain primitives and their morph targets' displacements): a view's JSON is written once, and
    // meshopt codes one long stream better than many short ones. Its accessors name their view once it is written.
    struct PendingData {
        int target = 0;
        std::size_t elementBytes = 4;
        std::string filter;  // meshopt's, for data already filtered; empty: float data
        bool padded = false;  // elements longer than their components (3 shorts in 8 bytes, as vertex strides ask)
        std::vector<unsigned char> bytes;
        std::vector<std::pair<int, std::size_t>> accessors;  // each accessor and its offset in bytes
    };
    void writePendingData() {
        for (auto& [group, pending] : pendingData_) {
            const int view = addDataView(pending.bytes, pending.elementBytes, pending.filter, pending.target);
            // Vertex attributes that share a view, or are padded, are read at its stride, which glTF then asks
            // to be given.
            if (pending.target == kArrayBuffer && (pending.accessors.size() > 1 || pending.padded))
                setByteStride(view, pending.elementBytes);
            for (const auto& [accessor, offset] : pending.accessors) {
                Json& json = root_["accessors"][std::size_t(accessor)];
                json["bufferView"] = view;
                if (offset) json["byteOffset"] = offset;
            }
        }
        pendingData_.clear();
    }

    Json& root_;
    std::vector<unsigned char> binary_;
    std::size_t fallbackBytes_ = 0;
    std::map<std::string, int> dataAccessors_;  // the accessors of data that is no vertex attribute, by content
    std::map<std::string, PendingData> pendingData_;  // by group: target or filter, and layout
};

// One Draco-compressed glTF primitive, encoded but not yet in the builder: its bytes, its accessors (name and
// description, in the order they are added) and KHR_draco_mesh_compression's attribute ids.
struct DracoPart {
    int material = -1;
    std::vector<unsigned char> bytes;
    std::vector<std::pair<std::string, Json>> accessors;
    Json dracoAttributes = Json::object();
    Json indices;
};

// A Draco-coded primitive's triangles with two corners at one point, which edgebreaker drops (its corner table
// joins equal positions): zero area, they draw nothing (unless skinned: those stay as they are). Kept as as many
// triangles of zero area at one corner of theirs, `vertex` (a primitive of that one vertex, its position and
// texture coordinates, no triangles), in a glTF primitive whose indices are zeros, an accessor without a buffer
// view: viewers draw and count them as before.
struct ZeroAreaPart {
    Primitive vertex;
    std::size_t triangles = 0;
};

// What stores a primitive, made without the builder (so that a scene's primitives can be encoded in
// parallel): plain accessors (written when added), or one Draco part, or two when edgebreaker would drop
// some triangles, and a ZeroAreaPart where the primitive has triangles of zero area.
struct EncodedPrimitive {
    bool plain = false;
    std::vector<DracoPart> parts;
    std::optional<ZeroAreaPart> zeroArea;
    // A plain primitive's vertices rounded (roundedPlainVertices), used where the builder codes data by meshopt.
    RoundedVertices rounded;
};
EncodedPrimitive encodePrimitive(const Primitive& primitive, const WriteOptions& options, const std::filesystem::path& file);
// Appends the glTF primitives of `encoded` (made from `primitive`) to `primitives`, and their data to the builder.
void addPrimitive(GltfBuilder& builder, const Primitive& primitive, const EncodedPrimitive& encoded, Json& primitives);

// Both: appends the glTF primitives that store `primitive` to `primitives`.
void writePrimitive(GltfBuilder& builder, const Primitive& primitive, const WriteOptions& options,
                    const std::filesystem::path& file, Json& primitives);

}  // namespace symcompress
