// What glTF 2.0 asks of a file's JSON that tinygltf (as packaged) does not check, or refuses without saying where:
// the version, the indices by which geometry is found (a scene's nodes, a node's mesh and children, a primitive's
// accessors, an accessor's buffer views, a view's buffer, an image's view), and accessors' componentType and type.
// Checked before tinygltf parses the JSON: it drops a node's mesh index that names no mesh without a word, and
// refuses a primitive's as "primitive indices accessor out of bounds". Indices of what can be left out without
// losing geometry (cameras, skins, materials, textures, animations) are the reader's, which warns about them.
#include "gltf_constants.hpp"
#include "gltf_reader.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>

namespace symcompress {
namespace fs = std::filesystem;
using Json = nlohmann::json;
namespace {

// "major.minor" as glTF writes versions (its schema's pattern is ^[0-9]+\.[0-9]+$), or nothing.
std::optional<std::pair<int, int>> parsedVersion(const std::string& text) {
    const std::size_t dot = text.find('.');
    auto digits = [](const std::string& part) {
        return !part.empty() && part.size() <= 6 && part.find_first_not_of("0123456789") == std::string::npos;
    };
    if (dot == std::string::npos || !digits(text.substr(0, dot)) || !digits(text.substr(dot + 1))) return std::nullopt;
    return std::make_pair(std::atoi(text.substr(0, dot).c_str()), std::atoi(text.substr(dot + 1).c_str()));
}

// asset.version is required (glTF 2.0, 3.2): a file without it is refused rather than read as 2.0, since the
// likeliest such file is glTF 1.0, where the asset object is optional, and reading that as 2.0 draws nothing.
// A file whose asset.minVersion is above 2.0 asks readers that do not know that version not to load it.
void refuseUnsupportedVersion(const Json& gltf, const fs::path& file) {
    const auto asset = gltf.find("asset");
    const auto version = asset != gltf.end() ? asset->find("version") : gltf.end();
    if (asset == gltf.end() || version == asset->end())
        throw FileError(
            file, "no asset.version, which glTF 2.0 requires; if this is glTF 1.0, " + std::string(kConvertToGltf2));
    const std::optional<std::pair<int, int>> parsed =
        version->is_string() ? parsedVersion(version->get<std::string>()) : std::nullopt;
    if (!parsed) throw FileError(file, "asset.version " + version->dump() + " is not a version such as \"2.0\"");
    if (parsed->first < 2)
        throw FileError(file, "glTF " + version->get<std::string>() + " is not supported; " + kConvertToGltf2);
    if (parsed->first > 2)
        throw FileError(file, "glTF " + version->get<std::string>() + " is not supported (symcompress reads glTF 2.0)");
    const auto minVersion = asset->find("minVersion");
    if (minVersion == asset->end()) return;
    const std::optional<std::pair<int, int>> least =
        minVersion->is_string() ? parsedVersion(minVersion->get<std::string>()) : std::nullopt;
    if (!least) throw FileError(file, "asset.minVersion " + minVersion->dump() + " is not a version such as \"2.0\"");
    if (*least > std::make_pair(2, 0))
        throw FileError(file, "asset.minVersion is " + minVersion->get<std::string>() +
                                  ": the file needs a reader of that glTF version, and symcompress reads glTF 2.0");
}

// object[key] where it is an array, or an empty one.
const Json& arrayIn(const Json& object, const char* key) {
    static const Json none = Json::array();
    const auto found = object.find(key);  // end() for what is not an object
    return found != object.end() && found->is_array() ? *found : none;
}

// The indices by which the file's items refer to others: each must name one of the file's items of its kind.
class ReferenceCheck {
public:
    ReferenceCheck(const Json& gltf, const fs::path& file) : gltf_(gltf), file_(file) {}

    // object[key], when there, must be the index of one of the file's `collection`, items of `kind`; `role`
    // says what for, where the referrer has several.
    void one(const Json& object, const std::string& key, const std::string& referrer, const char* collection,
             const char* kind, const std::string& role = "") const {
        if (const auto found = object.find(key); found != object.end()) index(*found, referrer, collection, kind, role);
    }
    // object[key], when there, must be a list of such indices.
    void list(const Json& object, const char* key, const std::string& referrer, const char* collection,
              const char* kind, const std::string& role = "") const {
        const auto found = object.find(key);
        if (found == object.end()) return;
        if (!found->is_array())
            throw FileError(file_,
                            referrer + ": " + key + " must be a list of " + kind + " indices, not " + found->dump());
        for (const Json& value : *found) index(value, referrer, collection, kind, role);
    }
    // Every member of `names`, when it is an object (a primitive's attributes, a morph target), each for its name.
    void members(const Json& names, const std::string& referrer, const char* collection, const char* kind) const {
        if (names.is_object())
            for (const auto& [name, value] : names.items()) index(value, referrer, collection, kind, name);
    }

private:
    void index(const Json& value, const std::string& referrer, const char* collection, const char* kind,
               const std::string& role) const {
        // tinygltf takes anything but an integer for no index at all.
        if (!value.is_number_integer())
            throw FileError(file_, referrer + " refers to " + kind + " " + value.dump() +
                                       (role.empty() ? "" : " for its " + role) + ", which is not an index");
        const std::int64_t number = value.get<std::int64_t>();
        const std::size_t count = arrayIn(gltf_, collection).size();
        if (number < 0 || std::uint64_t(number) >= count)
            throw FileError(file_, referenceProblem(referrer, kind, number, count, role));
    }

    const Json& gltf_;
    const fs::path& file_;
};

void refuseBrokenReferences(const Json& gltf, const fs::path& file) {
    const ReferenceCheck check(gltf, file);
    check.one(gltf, "scene", "the file's \"scene\"", "scenes", "scene");
    // Each element of a top-level array, with its index (those that are no object tinygltf refuses).
    auto each = [&](const char* collection, auto&& visit) {
        const Json& items = arrayIn(gltf, collection);
        for (std::size_t i = 0; i < items.size(); ++i)
            if (items[i].is_object()) visit(items[i], std::to_string(i));
    };
    each("scenes",
         [&](const Json& scene, const std::string& i) { check.list(scene, "nodes", "scene " + i, "nodes", "node"); });
    each("nodes", [&](const Json& node, const std::string& i) {
        check.one(node, "mesh", "node " + i, "meshes", "mesh");
        check.list(node, "children", "node " + i, "nodes", "node", "children");
    });
    each("meshes", [&](const Json& mesh, const std::string& m) {
        const Json& primitives = arrayIn(mesh, "primitives");
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const std::string where = "mesh " + m + " primitive " + std::to_string(p);
            if (const auto attributes = primitives[p].find("attributes"); attributes != primitives[p].end())
                check.members(*attributes, where, "accessors", "accessor");
            check.one(primitives[p], "indices", where, "accessors", "accessor", "indices");
            const Json& targets = arrayIn(primitives[p], "targets");
            for (std::size_t t = 0; t < targets.size(); ++t)
                check.members(targets[t], where + " morph target " + std::to_string(t), "accessors", "accessor");
        }
    });
    each("accessors", [&](const Json& accessor, const std::string& a) {
        check.one(accessor, "bufferView", "accessor " + a, "bufferViews", "buffer view");
        const auto sparse = accessor.find("sparse");
        if (sparse == accessor.end() || !sparse->is_object()) return;
        for (const char* part : {"indices", "values"})
            if (const auto found = sparse->find(part); found != sparse->end() && found->is_object())
                check.one(*found, "bufferView", "accessor " + a + " (its sparse " + part + ")", "bufferViews",
                          "buffer view");
    });
    each("bufferViews", [&](const Json& view, const std::string& v) {
        check.one(view, "buffer", "buffer view " + v, "buffers", "buffer");
    });
    each("images", [&](const Json& image, const std::string& i) {
        check.one(image, "bufferView", "image " + i, "bufferViews", "buffer view");
    });
}

// An accessor's componentType and type, when there, must be ones glTF 2.0 allows: tinygltf takes any componentType
// from 5120 to 5130, int (5124) and double (5130) among them, and refuses the others, and a count that is no whole
// number from 0, without naming the accessor.
void refuseUnknownAccessorTypes(const Json& gltf, const fs::path& file) {
    static const std::array<int, 6> componentTypes = {kByte,          kUnsignedByte, kShort,
                                                      kUnsignedShort, kUnsignedInt,  kFloat};
    static const std::array<const char*, 7> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    const Json& accessors = arrayIn(gltf, "accessors");
    for (std::size_t a = 0; a < accessors.size(); ++a) {
        if (!accessors[a].is_object()) continue;
        const std::string where = "accessor " + std::to_string(a);
        if (const auto type = accessors[a].find("componentType"); type != accessors[a].end())
            if (!type->is_number_integer() || std::find(componentTypes.begin(), componentTypes.end(),
                                                        type->get<std::int64_t>()) == componentTypes.end())
                throw FileError(file, where + ": componentType " + type->dump() +
                                          " is not one glTF allows (5120-5123, 5125, 5126)");
        if (const auto type = accessors[a].find("type"); type != accessors[a].end())
            if (!type->is_string() || std::find(types.begin(), types.end(), type->get<std::string>()) == types.end())
                throw FileError(file, where + ": type " + type->dump() +
                                          " is not one glTF allows (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4)");
        if (const auto count = accessors[a].find("count"); count != accessors[a].end())
            if (!count->is_number_unsigned() && !(count->is_number_integer() && count->get<std::int64_t>() >= 0))
                throw FileError(file, where + ": count " + count->dump() + " is not a number of elements");
    }
}

}  // namespace

std::string referenceProblem(const std::string& referrer, const std::string& kind, std::int64_t index,
                             std::size_t count, const std::string& role) {
    const std::string kinds = kind + (kind.size() >= 2 && kind.compare(kind.size() - 2, 2, "sh") == 0 ? "es" : "s");
    return referrer + " refers to " + kind + " " + std::to_string(index) + (role.empty() ? "" : " for its " + role) +
           ", but the file has " +
           (count == 0 ? "no " + kinds : std::to_string(count) + " " + (count == 1 ? kind : kinds));
}

void refuseBrokenStructure(const Json& gltf, const fs::path& file) {
    refuseUnsupportedVersion(gltf, file);
    refuseUnknownAccessorTypes(gltf, file);
    refuseBrokenReferences(gltf, file);
}

}  // namespace symcompress
