// A glTF file to a tinygltf model: the bytes checked and mended before tinygltf parses them (JSON depth,
// integers beyond an int, a GLB's BIN chunk, Draco's index accessors, indices without a buffer view, meshopt's fallback
// buffer), the images kept as bytes, EXT_ and KHR_meshopt_compression decoded.
#include "gltf_constants.hpp"
#include "gltf_reader.hpp"
#include "meshopt_vertex_codec.hpp"

#include "symcompress/detail/atomic_file.hpp"

#include <meshoptimizer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>

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
            if (error)
                *error += "image " + std::to_string(index) + ": its buffer view runs past the end of its buffer\n";
            return false;
        }
    }
    if (size < 0) return false;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

// The files a glTF refers to (buffers, images), read by our own callbacks: tinygltf's ReadWholeFile opens a
// folder as a file and asks for 2^63 bytes (a URI naming "." or a path cut short by a NUL, found by
// fuzz_obj once unread images kept their references). Only regular files exist; paths are used as they are.
bool externalFileExists(const std::string& path, void*) {
    std::error_code error;
    return path.find('\0') == std::string::npos && fs::is_regular_file(path, error);
}

std::string externalFilePath(const std::string& path, void*) { return path; }

bool readExternalFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void*) {
    if (!externalFileExists(path, nullptr)) {
        if (error) *error += "'" + path + "' is not a file\n";
        return false;
    }
    try {
        *out = readFileBytes(path);
    } catch (const FileError& failure) {
        if (error) *error += std::string(failure.what()) + "\n";
        return false;
    }
    return true;
}

bool refuseToWrite(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Extensions that change how a surface looks, never where it is: kept on their materials as the file has
// them (gltf_materials.cpp), so a file that requires one is read.
bool appearanceOnly(const std::string& name) { return name.rfind("KHR_materials_", 0) == 0; }

// The two extensions of meshoptimizer's codecs: KHR's adds version 1 of the vertex codec and the colour filter.
constexpr std::array<const char*, 2> kMeshoptExtensions = {"EXT_meshopt_compression", "KHR_meshopt_compression"};

// EXT_ or KHR_meshopt_compression: each compressed buffer view decoded into a buffer of its own, which the view
// then points at, so that accessors read it as any other. EXT's vertex streams (version 0) and every index
// stream by meshoptimizer, KHR's vertex streams by meshopt_vertex_codec.hpp (the packaged library has no
// version 1).
void decodeMeshopt(tinygltf::Model& model, const fs::path& file) {
    for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        auto found = view.extensions.end();
        for (const char* name : kMeshoptExtensions)
            if (const auto named = view.extensions.find(name); named != view.extensions.end()) found = named;
        if (found == view.extensions.end()) continue;
        const bool khr = found->first == kMeshoptExtensions[1];
        const tinygltf::Value& extension = found->second;
        const std::string where = "buffer view " + std::to_string(v) + " (" + found->first + ")";
        auto number = [&](const char* key, double fallback) { return numberOr(member(extension, key), fallback); };
        auto text = [&](const char* key, const char* fallback) {
            const tinygltf::Value& value = member(extension, key);
            return value.IsString() ? value.Get<std::string>() : std::string(fallback);
        };
        const double buffer = number("buffer", -1), offset = number("byteOffset", 0), length = number("byteLength", -1),
                     stride = number("byteStride", -1), count = number("count", -1);
        // Whole numbers in range before any is converted to an integer (meshopt's largest stride is 256).
        auto whole = [](double value) { return value == std::floor(value); };
        if (buffer < 0 || buffer >= double(model.buffers.size()) || offset < 0 || length < 0 || stride <= 0 ||
            stride > 256 || count < 0 || !whole(buffer) || !whole(offset) || !whole(length) || !whole(stride) ||
            !whole(count) || offset + length > double(model.buffers[std::size_t(buffer)].data.size()))
            throw FileError(file,
                            where + ": buffer, byteOffset, byteLength, byteStride or count missing or out of range");
        // The decoded data fills the view (glTF's byteLength, bounded so that a broken file cannot ask for more).
        if (stride * count > double(view.byteLength) || stride * count > double(1u << 31))
            throw FileError(file, where + ": count times byteStride (" + std::to_string(std::size_t(stride * count)) +
                                      ") exceeds the buffer view's byteLength (" + std::to_string(view.byteLength) +
                                      ")");
        const unsigned char* source = model.buffers[std::size_t(buffer)].data.data() + std::size_t(offset);
        const std::string mode = text("mode", ""), filter = text("filter", "NONE");
        // meshoptimizer asserts what its decoders take (the packaged library aborts): the strides are checked
        // below, and TRIANGLES, as EXT_meshopt_compression says, holds whole triangles.
        if (mode == "TRIANGLES" && std::size_t(count) % 3 != 0)
            throw FileError(file, where + ": mode TRIANGLES with a count of " + std::to_string(std::size_t(count)) +
                                      ", which is not a multiple of 3");
        tinygltf::Buffer decoded;
        decoded.data.resize(std::size_t(stride) * std::size_t(count));
        int status = -1;
        if (mode == "ATTRIBUTES" && int(stride) % 4 == 0 && stride <= 256)
            status = khr ? (decodeMeshoptVertexStream(decoded.data.data(), std::size_t(count), std::size_t(stride),
                                                      source, std::size_t(length))
                                ? 0
                                : -1)
                         : meshopt_decodeVertexBuffer(decoded.data.data(), std::size_t(count), std::size_t(stride),
                                                      source, std::size_t(length));
        else if (mode == "TRIANGLES" && (stride == 2 || stride == 4))
            status = meshopt_decodeIndexBuffer(decoded.data.data(), std::size_t(count), std::size_t(stride), source,
                                               std::size_t(length));
        else if (mode == "INDICES" && (stride == 2 || stride == 4))
            status = meshopt_decodeIndexSequence(decoded.data.data(), std::size_t(count), std::size_t(stride), source,
                                                 std::size_t(length));
        if (status != 0) throw FileError(file, where + ": cannot be decoded (mode '" + mode + "')");
        if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8))
            meshopt_decodeFilterOct(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter == "QUATERNION" && stride == 8)
            meshopt_decodeFilterQuat(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter == "EXPONENTIAL" && int(stride) % 4 == 0)
            meshopt_decodeFilterExp(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (khr && filter == "COLOR" && (stride == 4 || stride == 8))
            decodeMeshoptColorFilter(decoded.data.data(), std::size_t(count), std::size_t(stride));
        else if (filter != "NONE")
            throw FileError(file, where + ": unknown filter '" + filter + "'");
        model.buffers.push_back(std::move(decoded));
        view.buffer = int(model.buffers.size()) - 1;
        view.byteOffset = 0;
        // The view keeps its own byteStride, or none (elements packed tight): the extension's is its stream's, and
        // a view of scalars may be coded as vectors (morph weights, a key's weights sharing an exponent).
        view.byteLength = std::size_t(stride) * std::size_t(count);
    }
}

// JSON nested deeper than this is refused: tinygltf turns extras and extensions into its Values recursively.
constexpr int kMaxJsonDepth = 512;

// How deep arrays and objects nest in JSON text, in one pass (strings skipped): nlohmann's parser with a
// callback, which could tell, takes time quadratic in the number of objects (100000 nodes: 8 s).
int jsonDepth(const unsigned char* begin, const unsigned char* end) {
    int depth = 0, deepest = 0;
    bool inString = false;
    for (const unsigned char* c = begin; c < end; ++c) {
        if (inString) {
            if (*c == '\\' && c + 1 < end)
                ++c;
            else if (*c == '"')
                inString = false;
        } else if (*c == '"') {
            inString = true;
        } else if (*c == '[' || *c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if (*c == ']' || *c == '}') {
            --depth;
        }
    }
    return deepest;
}

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

// Indices without a buffer view are zeros (glTF 2.0, 3.6.2.1; symcompress writes triangles of zero area so),
// which tinygltf refuses: they get a view of a buffer of zeros. False where there are none. At most 64 MiB of
// them, so that a few bytes of JSON cannot ask for any memory at all.
bool giveZerosABufferView(nlohmann::json& json, const std::vector<std::size_t>& accessors, const fs::path& file) {
    std::uint64_t bytes = 0;
    for (std::size_t a : accessors) {
        const nlohmann::json& accessor = json["accessors"][a];
        const auto type = accessor.find("componentType");
        const int componentType = type != accessor.end() && type->is_number_integer() ? type->get<int>() : 0;
        const int size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : componentType == 5125 ? 4 : 0;
        if (!size || !accessor.contains("count") || !accessor["count"].is_number_unsigned()) continue;  // tinygltf says
        const std::uint64_t count = accessor["count"].get<std::uint64_t>();
        if (count > kMostZeroBytes / std::uint64_t(size))
            throw FileError(file, "accessor " + std::to_string(a) + ": " + std::to_string(count) +
                                      " indices without a buffer view, more than symcompress reads (64 MiB)");
        bytes = std::max(bytes, count * std::uint64_t(size));
    }
    if (accessors.empty() || bytes == 0) return false;
    if (!json.contains("buffers") || !json["buffers"].is_array()) json["buffers"] = nlohmann::json::array();
    if (!json.contains("bufferViews") || !json["bufferViews"].is_array()) json["bufferViews"] = nlohmann::json::array();
    std::string base64((bytes + 2) / 3 * 4, 'A');  // zero bytes are "A"s, padded
    if (bytes % 3) base64.replace(base64.size() - (3 - bytes % 3), 3 - bytes % 3, 3 - bytes % 3, '=');
    json["buffers"].push_back({{"byteLength", bytes}, {"uri", "data:application/octet-stream;base64," + base64}});
    json["bufferViews"].push_back({{"buffer", json["buffers"].size() - 1}, {"byteLength", bytes}});
    for (std::size_t a : accessors) json["accessors"][a]["bufferView"] = json["bufferViews"].size() - 1;
    return true;
}

// A buffer's uri that is neither a data: URI nor a path relative to the glTF file refused, saying so: tinygltf
// looks for it in the glTF file's folder, and would report a file that is there as "File not found".
void refuseBuffersOutsideTheFolder(const nlohmann::json& json, const fs::path& file) {
    const auto buffers = json.find("buffers");
    if (buffers == json.end() || !buffers->is_array()) return;
    for (std::size_t b = 0; b < buffers->size(); ++b) {
        const auto uri = (*buffers)[b].find("uri");  // end() for what is not an object
        if (uri == (*buffers)[b].end() || !uri->is_string()) continue;
        const std::string text = uri->get<std::string>();
        // A scheme (RFC 3986: a relative path has no ':' before its first '/'), or a path from the root.
        const std::size_t colon = text.find(':');
        const bool scheme = colon != std::string::npos && colon < text.find('/');
        if ((scheme && text.rfind("data:", 0) != 0) || text.rfind('/', 0) == 0 || text.rfind('\\', 0) == 0)
            throw FileError(file, "buffer " + std::to_string(b) + ": its uri " + uri->dump() +
                                      " is not relative to the glTF file; symcompress reads buffers from data: "
                                      "URIs and from files named relative to it");
    }
}

// A required extension that symcompress neither reads nor may leave out (appearanceOnly) refused.
void refuseUnreadable(const std::string& required, const fs::path& file) {
    if (!readExtension(required) && !appearanceOnly(required))
        throw FileError(file, "requires the extension " + required + ", which symcompress cannot read");
}

// What tinygltf (as packaged) would refuse in a valid file, mended in the JSON before it sees it:
// - a primitive whose indices accessor has no bufferView, which is how KHR_draco_mesh_compression files
//   are written: the indices come from the Draco data anyway, so they are removed; any other primitive's
//   indices without a buffer view are zeros, given a buffer of them;
// - EXT_ or KHR_meshopt_compression's fallback buffer, which has no data (no uri, or more bytes than a GLB's binary
//   chunk): it gets one byte of its own; decodeMeshopt gives its buffer views their data.
// It also refuses (FileError) what tinygltf would take badly: JSON nested too deep, integers beyond an int.
std::vector<unsigned char> preparedForTinygltf(const std::vector<unsigned char>& bytes, bool binary,
                                               const fs::path& file) {
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
    if (jsonDepth(bytes.data() + jsonBegin, bytes.data() + jsonBegin + jsonLength) > kMaxJsonDepth)
        throw FileError(file, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    nlohmann::json json =
        nlohmann::json::parse(bytes.begin() + static_cast<std::ptrdiff_t>(jsonBegin),
                              bytes.begin() + static_cast<std::ptrdiff_t>(jsonBegin + jsonLength), nullptr, false);
    if (json.is_discarded() || !json.is_object()) return bytes;
    refuseIntegersBeyondInt(json, "", file);
    refuseBrokenStructure(json, file);
    refuseBuffersOutsideTheFolder(json, file);
    // Before tinygltf, which would report what an unknown extension's data does to the file's layout instead (the
    // fallback buffer of KHR_meshopt_compression: "Invalid `byteLength'").
    if (json.contains("extensionsRequired") && json["extensionsRequired"].is_array())
        for (const auto& required : json["extensionsRequired"])
            if (required.is_string()) refuseUnreadable(required.get<std::string>(), file);
    bool changed = false;
    if (json.contains("buffers") && json["buffers"].is_array())
        for (auto& buffer : json["buffers"]) {
            if (!buffer.is_object() || !buffer.contains("extensions") || !buffer["extensions"].is_object()) continue;
            // A "fallback" that is not a boolean (fuzz_gltf: a number) is no fallback, not an exception.
            const bool fallback =
                std::any_of(kMeshoptExtensions.begin(), kMeshoptExtensions.end(), [&](const char* name) {
                    const auto meshopt = buffer["extensions"].find(name);
                    return meshopt != buffer["extensions"].end() && meshopt->is_object() &&
                           meshopt->contains("fallback") && (*meshopt)["fallback"] == true;
                });
            if (!fallback) continue;
            buffer["uri"] = "data:application/octet-stream;base64,AA==";
            buffer["byteLength"] = 1;
            changed = true;
        }
    nlohmann::json noMeshes = nlohmann::json::array();
    std::vector<std::size_t> zeroIndices;  // accessors of indices without a buffer view
    for (auto& mesh : json.contains("meshes") && json["meshes"].is_array() ? json["meshes"] : noMeshes) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (auto& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("indices")) continue;
            const auto extensions = primitive.find("extensions");
            if (extensions != primitive.end() && extensions->is_object() &&
                extensions->contains("KHR_draco_mesh_compression")) {
                primitive.erase("indices");
                changed = true;
            } else if (primitive["indices"].is_number_unsigned() && json.contains("accessors") &&
                       json["accessors"].is_array() &&
                       primitive["indices"].get<std::size_t>() < json["accessors"].size()) {
                const std::size_t accessor = primitive["indices"].get<std::size_t>();
                if (json["accessors"][accessor].is_object() && !json["accessors"][accessor].contains("bufferView"))
                    zeroIndices.push_back(accessor);
            }
        }
    }
    changed = giveZerosABufferView(json, zeroIndices, file) || changed;
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
    if (rest < bytes.size())
        rebuilt.insert(rebuilt.end(), bytes.begin() + static_cast<std::ptrdiff_t>(rest), bytes.end());
    const auto total = static_cast<std::uint32_t>(rebuilt.size());
    std::memcpy(rebuilt.data() + 8, &total, 4);
    return rebuilt;
}

}  // namespace

// The extensions we read.
bool readExtension(const std::string& name) {
    static const std::set<std::string> read = {
        "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression", "KHR_mesh_quantization",
        "EXT_mesh_gpu_instancing",    "KHR_lights_punctual",     "KHR_texture_transform",   "EXT_texture_webp",
        "KHR_texture_basisu",         "KHR_materials_variants",  "KHR_xmp_json_ld"};
    return read.count(name) > 0;
}

tinygltf::Model loadGltfModel(const fs::path& file) {
    const std::vector<unsigned char> bytes = readFileBytes(file);
    if (bytes.empty()) throw FileError(file, "the file is empty");
    const bool binary = formatFromExtension(file) == FileFormat::Glb ||
                        (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0);
    if (formatFromExtension(file) == FileFormat::Glb &&
        (bytes.size() < 12 || std::memcmp(bytes.data(), "glTF", 4) != 0))
        throw FileError(file, "not a GLB file (wrong magic number; expected 'glTF')");

    // GLB version 1 is glTF 1.0's binary form (KHR_binary_glTF), whose JSON tinygltf would read as 2.0's: nothing.
    if (binary && bytes.size() >= 8) {
        std::uint32_t version;
        std::memcpy(&version, bytes.data() + 4, 4);
        if (version == 1)
            throw FileError(file, std::string("glTF 1.0 (GLB version 1) is not supported; ") + kConvertToGltf2);
        if (version != 2)
            throw FileError(file, "GLB version " + std::to_string(version) +
                                      " is not supported (symcompress reads GLB version 2, glTF 2.0)");
    }

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keepImageBytes, &model);
    loader.SetFsCallbacks({externalFileExists, externalFilePath, readExternalFile, refuseToWrite, nullptr});
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
                throw FileError(
                    file, "the BIN chunk (" + std::to_string(binLength) + " bytes) runs past the end of the file");
        }
    }
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, parsed.data(),
                                             static_cast<unsigned int>(parsed.size()), baseDir)
               : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(parsed.data()),
                                            static_cast<unsigned int>(parsed.size()), baseDir);
    if (!ok) {
        while (!error.empty() && error.back() == '\n') error.pop_back();
        throw FileError(file, "invalid glTF: " + (error.empty() ? std::string("cannot be parsed") : error));
    }
    for (const std::string& required : model.extensionsRequired) refuseUnreadable(required, file);
    decodeMeshopt(model, file);
    return model;
}

}  // namespace symcompress
