// glTF materials into the scene model: every core texture slot with its texCoord, scale or strength and
// KHR_texture_transform; each glTF texture as an image with its sampler; material extensions
// (KHR_materials_*, whatever else a material carries) kept as JSON with their textures held apart; extras;
// KHR_materials_variants as materials that carry a table of the materials each variant draws instead.
#include "common/mime_type.hpp"
#include "gltf_reader.hpp"

#include <nlohmann/json.hpp>

#include <limits>

namespace symcompress {
namespace {

using Json = nlohmann::json;

// The JSON text tinygltf kept of an object's extensions or extras, parsed; null where there is none or it
// does not parse (tinygltf has parsed it once already, so it does).
Json parsedOrNull(const std::string& text) {
    if (text.empty()) return nullptr;
    return Json::parse(text, nullptr, false);
}

// A JSON number that is a whole number from 0 to INT_MAX, else -1.
int indexIn(const Json& value) {
    if (value.is_number_unsigned() && value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<int>::max()))
        return int(value.get<std::uint64_t>());
    if (value.is_number_float()) {
        const double number = value.get<double>();
        if (number >= 0 && number <= std::numeric_limits<int>::max() && number == std::floor(number))
            return int(number);
    }
    return -1;
}

double numberOr(const Json& object, const char* key, double fallback) {
    const auto found = object.find(key);
    return found != object.end() && found->is_number() && std::isfinite(found->get<double>()) ? found->get<double>()
                                                                                              : fallback;
}

// A sampler's enum, or `fallback` where it is not one glTF knows.
int samplerEnum(int value, std::initializer_list<int> allowed, int fallback) {
    for (int a : allowed)
        if (value == a) return value;
    return fallback;
}

}  // namespace

std::optional<TextureTransform> GltfReader::readTextureTransform(const std::string& extensionsJson,
                                                                 const std::string& where) {
    const Json extensions = parsedOrNull(extensionsJson);
    if (!extensions.is_object() || !extensions.contains("KHR_texture_transform")) return std::nullopt;
    const Json& source = extensions["KHR_texture_transform"];
    if (!source.is_object()) {
        warnAbout(where + ": KHR_texture_transform is not an object, ignored");
        return std::nullopt;
    }
    auto pair = [&](const char* key, Eigen::Vector2d fallback) {
        const auto found = source.find(key);
        if (found == source.end() || !found->is_array() || found->size() != 2 || !(*found)[0].is_number() ||
            !(*found)[1].is_number())
            return fallback;
        const Eigen::Vector2d value((*found)[0].get<double>(), (*found)[1].get<double>());
        return value.allFinite() ? value : fallback;
    };
    TextureTransform transform;
    transform.offset = pair("offset", Eigen::Vector2d::Zero());
    transform.scale = pair("scale", Eigen::Vector2d::Ones());
    transform.rotation = numberOr(source, "rotation", 0);
    if (source.contains("texCoord")) transform.texCoord = indexIn(source["texCoord"]);
    return transform;
}

ImageFile GltfReader::readImageFile(int imageIndex) {
    const tinygltf::Image& image = model_.images[std::size_t(imageIndex)];
    ImageFile out;
    const bool embedded = image.uri.empty() || image.uri.rfind("data:", 0) == 0;
    // Where the file is (or should be): the writers refer to it from there, relative to their output.
    out.uri = embedded ? "" : (file_.parent_path() / image.uri).lexically_normal().string();
    out.bytes = image.image;
    out.mimeType = !image.mimeType.empty() ? image.mimeType : imageMimeType(image.uri);
    if (out.bytes.empty()) {
        warnAbout("image " + std::to_string(imageIndex) + " ('" + image.uri + "') could not be read; its " +
                  (embedded ? "texture is left out" : "reference is kept"));
    } else if (const std::string sniffed = imageMimeTypeOfBytes(out.bytes); sniffed.empty()) {
        warnAbout("image " + std::to_string(imageIndex) +
                  ": its bytes are no PNG, JPEG, WebP or KTX2 image (kept as they are)");
    } else {
        out.mimeType = sniffed;
    }
    return out;
}

int GltfReader::sceneTexture(int gltfTexture, Scene& scene, const std::string& where) {
    if (gltfTexture < 0 || gltfTexture >= static_cast<int>(model_.textures.size())) {
        warnAbout(where + ": texture index " + std::to_string(gltfTexture) + " does not exist, left out");
        return -1;
    }
    if (const auto found = textureOfGltfTexture_.find(gltfTexture); found != textureOfGltfTexture_.end())
        return found->second;
    const tinygltf::Texture& source = model_.textures[std::size_t(gltfTexture)];
    // An image in a format the core does not list is the source of an extension; the core source, if any, is its
    // fallback for viewers without the extension.
    const auto inRange = [&](int image) { return image >= 0 && image < static_cast<int>(model_.images.size()); };
    int imageIndex = source.source;
    for (const char* extension : {"EXT_texture_webp", "KHR_texture_basisu", "MSFT_texture_dds"})
        if (const auto found = source.extensions.find(extension); found != source.extensions.end()) {
            const int image = indexIn(member(found->second, "source"));
            if (inRange(image)) imageIndex = image;
        }
    if (!inRange(imageIndex)) {
        warnAbout(where + ": texture " + std::to_string(gltfTexture) + " has no image, left out");
        textureOfGltfTexture_[gltfTexture] = -1;
        return -1;
    }
    Texture out;
    out.name = !source.name.empty() ? source.name : model_.images[std::size_t(imageIndex)].name;
    ImageFile image = readImageFile(imageIndex);
    out.uri = std::move(image.uri);
    out.mimeType = std::move(image.mimeType);
    out.bytes = std::move(image.bytes);
    if (imageIndex != source.source && inRange(source.source)) {
        // Kept where a viewer can draw it: read, or referred to where it should be.
        ImageFile fallback = readImageFile(source.source);
        if (!fallback.bytes.empty() || !fallback.uri.empty()) out.fallback = std::move(fallback);
    }
    if (source.sampler >= 0 && source.sampler < static_cast<int>(model_.samplers.size())) {
        const tinygltf::Sampler& sampler = model_.samplers[std::size_t(source.sampler)];
        out.sampler.name = sampler.name;
        out.sampler.magFilter = samplerEnum(sampler.magFilter, {9728, 9729}, 0);
        out.sampler.minFilter = samplerEnum(sampler.minFilter, {9728, 9729, 9984, 9985, 9986, 9987}, 0);
        out.sampler.wrapS = samplerEnum(sampler.wrapS, {10497, 33071, 33648}, 10497);
        out.sampler.wrapT = samplerEnum(sampler.wrapT, {10497, 33071, 33648}, 10497);
    } else if (source.sampler >= 0) {
        warnAbout("texture " + std::to_string(gltfTexture) + ": sampler " + std::to_string(source.sampler) +
                  " does not exist, the default one used");
    }
    const int index = out.bytes.empty() && out.uri.empty() ? -1 : static_cast<int>(scene.textures.size());
    if (index >= 0) scene.textures.push_back(std::move(out));
    textureOfGltfTexture_[gltfTexture] = index;
    return index;
}

TextureRef GltfReader::readTextureUse(int gltfTexture, int texCoord, double scale, const std::string& extensionsJson,
                                      Scene& scene, const std::string& where) {
    TextureRef use;
    if (gltfTexture == -1) return use;  // none
    use.texture = sceneTexture(gltfTexture, scene, where);
    if (use.texture < 0) return use;
    use.texCoord = texCoord >= 0 ? texCoord : 0;
    use.scale = std::isfinite(scale) ? scale : 1;
    use.transform = readTextureTransform(extensionsJson, where);
    return use;
}

// An extension's textureInfos, by the glTF convention that their keys end in "Texture", are taken out of its
// JSON into TextureRefs; the rest of its JSON is kept as it is.
std::optional<MaterialExtension> GltfReader::readMaterialExtension(const std::string& name, Json object, Scene& scene,
                                                                   const std::string& where) {
    if (!object.is_object()) {
        warnAbout(where + ": extension " + name + " is not an object, left out");
        return std::nullopt;
    }
    MaterialExtension extension;
    extension.name = name;
    for (auto item = object.begin(); item != object.end();) {
        const std::string& key = item.key();
        const bool textureInfo = key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0 &&
                                 item->is_object() && item->contains("index");
        if (!textureInfo) {
            ++item;
            continue;
        }
        const Json& info = *item;
        const int index = indexIn(info["index"]);
        const int texCoord = info.contains("texCoord") ? indexIn(info["texCoord"]) : 0;
        const double scale = numberOr(info, "scale", numberOr(info, "strength", 1));
        const std::string extensions = info.contains("extensions") ? info["extensions"].dump() : "";
        const TextureRef use = readTextureUse(index < 0 ? -2 : index, texCoord, scale, extensions, scene,
                                              where + " " + name + "." + key);  // -2: a bad index, warned of
        if (use.texture >= 0) extension.textures.emplace_back(key, use);
        item = object.erase(item);
    }
    extension.json = object.dump();
    for (const std::string& required : model_.extensionsRequired) extension.required |= required == name;
    return extension;
}

void GltfReader::readMaterials(Scene& scene) {
    for (std::size_t m = 0; m < model_.materials.size(); ++m) {
        const tinygltf::Material& source = model_.materials[m];
        const std::string where =
            "material " + std::to_string(m) + (source.name.empty() ? "" : " '" + source.name + "'");
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
        auto use = [&](const auto& info, double scale, const char* slot) {
            return readTextureUse(info.index, info.texCoord, scale, info.extensions_json_string, scene,
                                  where + " " + slot);
        };
        material.baseColorTexture = use(pbr.baseColorTexture, 1, "baseColorTexture");
        material.metallicRoughnessTexture = use(pbr.metallicRoughnessTexture, 1, "metallicRoughnessTexture");
        material.normalTexture = use(source.normalTexture, source.normalTexture.scale, "normalTexture");
        material.occlusionTexture = use(source.occlusionTexture, source.occlusionTexture.strength, "occlusionTexture");
        material.emissiveTexture = use(source.emissiveTexture, 1, "emissiveTexture");
        const Json extensions = parsedOrNull(source.extensions_json_string);
        if (extensions.is_object())
            for (const auto& [name, object] : extensions.items())
                if (auto extension = readMaterialExtension(name, object, scene, where)) {
                    materialExtensions_.insert(name);
                    material.extensions.push_back(std::move(*extension));
                }
        if (const Json extras = parsedOrNull(source.extras_json_string); !extras.is_null())
            material.extrasJson = extras.dump();
        scene.materials.push_back(std::move(material));
    }
}

void GltfReader::readMaterialVariants(Scene& scene) {
    const Json extensions = parsedOrNull(model_.extensions_json_string);
    if (!extensions.is_object() || !extensions.contains("KHR_materials_variants")) return;
    const Json& source = extensions["KHR_materials_variants"];
    if (!source.is_object() || !source.contains("variants") || !source["variants"].is_array()) {
        warnAbout("KHR_materials_variants has no array of variants, ignored");
        return;
    }
    for (const Json& variant : source["variants"]) {
        MaterialVariant read;
        if (variant.is_object() && variant.contains("name") && variant["name"].is_string())
            read.name = variant["name"].get<std::string>();
        else
            warnAbout("KHR_materials_variants: variant " + std::to_string(scene.materialVariants.size()) +
                      " has no name");
        if (variant.is_object() && variant.contains("extras")) read.extrasJson = variant["extras"].dump();
        scene.materialVariants.push_back(std::move(read));
    }
}

int GltfReader::materialUnderVariants(int material, const std::string& extensionsJson, Scene& scene,
                                      const std::string& where) {
    const Json extensions = parsedOrNull(extensionsJson);
    if (!extensions.is_object() || !extensions.contains("KHR_materials_variants")) return material;
    const Json& source = extensions["KHR_materials_variants"];
    if (!source.is_object() || !source.contains("mappings") || !source["mappings"].is_array()) {
        warnAbout(where + ": KHR_materials_variants has no array of mappings, ignored");
        return material;
    }
    std::vector<int> table(scene.materialVariants.size(), -1);
    std::vector<bool> mapped(table.size(), false);
    for (const Json& mapping : source["mappings"]) {
        const int to = mapping.is_object() && mapping.contains("material") ? indexIn(mapping["material"]) : -1;
        if (to < 0 || to >= static_cast<int>(model_.materials.size()) || !mapping.contains("variants") ||
            !mapping["variants"].is_array()) {
            warnAbout(where + ": a KHR_materials_variants mapping without a material or variants, ignored");
            continue;
        }
        for (const Json& index : mapping["variants"]) {
            const int v = indexIn(index);
            if (v < 0 || v >= static_cast<int>(table.size())) {
                warnAbout(where + ": KHR_materials_variants maps a variant that is not in the file's list, ignored");
            } else if (mapped[std::size_t(v)]) {
                warnAbout(where + ": KHR_materials_variants maps variant " + std::to_string(v) +
                          " twice; the first mapping kept");
            } else {
                mapped[std::size_t(v)] = true;
                table[std::size_t(v)] = to == material ? -1 : to;
            }
        }
    }
    if (std::all_of(table.begin(), table.end(), [](int m) { return m < 0; })) return material;
    // The default material with the table, made once for every primitive of the same two.
    const auto [entry, added] = materialWithVariants_.try_emplace({material, table}, int(scene.materials.size()));
    if (added) {
        Material withVariants = material >= 0 ? scene.materials[std::size_t(material)] : Material{};
        withVariants.variants = std::move(table);
        scene.materials.push_back(std::move(withVariants));
    }
    return entry->second;
}

std::string GltfReader::extrasOf(const std::string& extrasJson) {
    const Json extras = parsedOrNull(extrasJson);
    return extras.is_null() ? "" : extras.dump();
}

}  // namespace symcompress
