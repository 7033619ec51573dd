// How the X3D writer draws a material (x3d_materials.hpp).
#include "x3d_materials.hpp"

#include "common/color_space.hpp"

#include <algorithm>
#include <utility>

namespace symcompress::x3d {

bool isUnlit(const Material& material) {
    return !material.phong && std::any_of(material.extensions.begin(), material.extensions.end(),
                                          [](const MaterialExtension& e) { return e.name == "KHR_materials_unlit"; });
}

bool drawnWithoutMaterial(const Material& material) {
    if (!isUnlit(material) || material.baseColorFactor != Eigen::Vector4d::Ones()) return false;
    const auto refs = material.textureRefs();
    return std::none_of(refs.begin() + 1, refs.end(), [](const TextureRef* use) { return use->texture >= 0; });
}

std::optional<Material::AlphaMode> statedAlphaMode(const Material& material, bool translucentContent) {
    const bool autoBlends = material.baseColorFactor[3] < 1 || translucentContent;
    if (material.alphaMode == Material::AlphaMode::Mask ||
        (material.alphaMode == Material::AlphaMode::Blend) != autoBlends)
        return material.alphaMode;
    return std::nullopt;
}

bool needsPhysicalMaterial(const Material& material) {
    if (material.phong || isUnlit(material)) return false;
    const auto refs = material.textureRefs();
    const bool otherTextures =
        std::any_of(refs.begin() + 1, refs.begin() + 5, [](const TextureRef* use) { return use->texture >= 0; });
    return material.metallicFactor != 0 || otherTextures;
}

PhongMaterial phongOf(const Material& material) {
    if (material.phong) return *material.phong;
    // Each field the shortest decimal that reads back to the glTF factor (as float32): glTF -> X3D -> glTF keeps
    // the factors, X3D -> glTF -> X3D the fields.
    PhongMaterial phong;
    for (int c = 0; c < 3; ++c) {
        phong.diffuseColor[c] = linearToSrgbShortest(material.baseColorFactor[c]);
        phong.emissiveColor[c] = linearToSrgbShortest(material.emissiveFactor[c]);
    }
    const auto complement = [](double s) { return 1 - s; };
    phong.transparency = shortestReadingBack(1 - material.baseColorFactor[3], material.baseColorFactor[3], complement);
    phong.shininess = shortestReadingBack(1 - material.roughnessFactor, material.roughnessFactor, complement);
    return phong;
}

PhongMaterial unlitPhongOf(const Material& material) {
    const PhongMaterial lit = phongOf(material);
    PhongMaterial out;
    out.diffuseColor = Eigen::Vector3d::Zero();
    out.emissiveColor = lit.diffuseColor;
    out.transparency = lit.transparency;
    return out;
}

MaterialTextures materialTextures(const Material& material) {
    MaterialTextures out;
    const bool physical = needsPhysicalMaterial(material);
    const bool unlit = isUnlit(material) && !drawnWithoutMaterial(material);  // else the Appearance's texture
    struct Slot {
        const char* physicalField;
        const char* phongField;  // nullptr: Phong's Material has no such field
        const char* unlitField;  // UnlitMaterial's: its emissive texture is the colour drawn
        const TextureRef* use;
    };
    const Slot slots[] = {{"baseTexture", "diffuseTexture", "emissiveTexture", &material.baseColorTexture},
                          {"metallicRoughnessTexture", nullptr, nullptr, &material.metallicRoughnessTexture},
                          {"normalTexture", "normalTexture", nullptr, &material.normalTexture},
                          {"occlusionTexture", "occlusionTexture", nullptr, &material.occlusionTexture},
                          {"emissiveTexture", "emissiveTexture", nullptr, &material.emissiveTexture}};
    for (const Slot& slot : slots) {
        const char* field = unlit ? slot.unlitField : physical ? slot.physicalField : slot.phongField;
        if (!field || slot.use->texture < 0) continue;
        out.x3d4Fields = out.x3d4Fields || physical || unlit || slot.use != &material.baseColorTexture;
        // Uses on the same set with the same transform share their coordinates.
        const int set = slot.use->texCoordSet();
        const auto same = std::find_if(out.channels.begin(), out.channels.end(), [&](const TexcoordChannel& channel) {
            return channel.set == set && channel.transform == slot.use->transform;
        });
        const std::size_t channel = std::size_t(same - out.channels.begin());
        if (same == out.channels.end()) out.channels.push_back({set, slot.use->transform, ""});
        out.fields.push_back({field, slot.use, channel});
    }
    // The sets in order, those without a transform first, so that a reader numbering them as they come (as
    // symcompress's does) gives TEXCOORD_0, _1, ... back as they were.
    std::vector<std::size_t> order(out.channels.size());
    for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::make_pair(out.channels[a].set, out.channels[a].transform.has_value()) <
               std::make_pair(out.channels[b].set, out.channels[b].transform.has_value());
    });
    std::vector<TexcoordChannel> sorted;
    std::vector<std::size_t> position(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
        sorted.push_back(out.channels[order[k]]);
        position[order[k]] = k;
    }
    out.channels = std::move(sorted);
    for (TextureField& field : out.fields) field.channel = position[field.channel];
    // A Phong material's base texture alone stays the Appearance's texture, as X3D 3.3 has it.
    if (!out.x3d4Fields && !out.fields.empty()) out.fields[0].field = "texture";
    // No texture: the coordinates the base colour's use would read, as before.
    if (out.channels.empty())
        out.channels.push_back({material.baseColorTexture.texCoordSet(), material.baseColorTexture.transform, ""});
    if (out.channels.size() > 1)
        for (std::size_t c = 0; c < out.channels.size(); ++c)
            out.channels[c].mapping = "TEXCOORD_" + std::to_string(out.channels[c].set) +
                                      (out.channels[c].transform ? "_" + std::to_string(c) : "");
    return out;
}

bool needsX3d4(const Material& material) {
    return needsPhysicalMaterial(material) || (isUnlit(material) && !drawnWithoutMaterial(material)) ||
           materialTextures(material).x3d4Fields;
}

namespace {

const std::pair<int, const char*> kWraps[] = {{10497, "REPEAT"}, {33071, "CLAMP_TO_EDGE"}, {33648, "MIRRORED_REPEAT"}};
const std::pair<int, const char*> kFilters[] = {{9728, "NEAREST_PIXEL"},
                                                {9729, "AVG_PIXEL"},
                                                {9984, "NEAREST_PIXEL_NEAREST_MIPMAP"},
                                                {9985, "AVG_PIXEL_NEAREST_MIPMAP"},
                                                {9986, "NEAREST_PIXEL_AVG_MIPMAP"},
                                                {9987, "AVG_PIXEL_AVG_MIPMAP"}};

}  // namespace

std::string boundaryModeName(int wrap) {
    for (const auto& [value, name] : kWraps)
        if (value == wrap) return name;
    return "REPEAT";
}

int boundaryModeOf(const std::string& name) {
    if (name.rfind("CLAMP", 0) == 0) return 33071;
    return name == "MIRRORED_REPEAT" ? 33648 : 10497;
}

std::string minificationFilterName(int filter) {
    for (const auto& [value, name] : kFilters)
        if (value == filter) return name;
    return "NICEST";
}

std::string magnificationFilterName(int filter) {
    return filter == 9728 || filter == 9729 ? minificationFilterName(filter) : "NICEST";
}

int filterOf(const std::string& name) {
    for (const auto& [value, filterName] : kFilters)
        if (name == filterName) return value;
    return 0;
}

}  // namespace symcompress::x3d
