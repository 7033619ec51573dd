// X3D appearances: materials and image textures (files beside the scene, or data: URLs).
#include "x3d_reader.hpp"

#include "common/mime_type.hpp"
#include "symcompress/detail/atomic_file.hpp"

#include <algorithm>
#include <cctype>

namespace symcompress {
namespace fs = std::filesystem;
namespace {

// RFC 4648 base64 (whitespace skipped, padding optional); false on any other character.
bool decodeBase64(const std::string& text, std::vector<std::uint8_t>& bytes) {
    bytes.clear();
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        int value;
        if (c >= 'A' && c <= 'Z')
            value = c - 'A';
        else if (c >= 'a' && c <= 'z')
            value = c - 'a' + 26;
        else if (c >= '0' && c <= '9')
            value = c - '0' + 52;
        else if (c == '+')
            value = 62;
        else if (c == '/')
            value = 63;
        else if (c == '=' || std::isspace(static_cast<unsigned char>(c)))
            continue;
        else
            return false;
        bits = (bits << 6) | std::uint32_t(value);
        if (++count == 4) {
            bytes.insert(bytes.end(), {std::uint8_t(bits >> 16), std::uint8_t(bits >> 8), std::uint8_t(bits)});
            bits = 0;
            count = 0;
        }
    }
    if (count == 1) return false;
    if (count == 2) bytes.push_back(std::uint8_t(bits >> 4));
    if (count == 3) bytes.insert(bytes.end(), {std::uint8_t(bits >> 10), std::uint8_t(bits >> 2)});
    return !bytes.empty();
}

}  // namespace

int X3dReader::readTexture(const pugi::xml_node& appearance) {
    pugi::xml_node texture = appearance.child("ImageTexture");
    if (!texture) {
        for (pugi::xml_node child : appearance.children())
            if (std::strstr(child.name(), "Texture")) notes_.insert(std::string(child.name()) + " not carried through");
        return -1;
    }
    if (const pugi::xml_attribute def = texture.attribute("DEF")) definitions_[def.value()] = texture;
    texture = resolve(texture);
    auto [entry, inserted] = textureOfNode_.try_emplace(texture.internal_object(), -1);
    if (!inserted) return entry->second;
    Texture out;
    for (const std::string& url : x3d::parseStrings(texture.attribute("url").value())) {
        if (url.compare(0, 5, "data:") == 0) {
            // An image inside the file (how the X3D writer embeds them): data:[mime type][;base64],bytes.
            const std::size_t comma = url.find(',');
            const std::string header = url.substr(5, comma == std::string::npos ? 0 : comma - 5);
            const std::size_t base64At = header.rfind(";base64");
            if (comma == std::string::npos || base64At == std::string::npos || base64At + 7 != header.size() ||
                !decodeBase64(url.substr(comma + 1), out.bytes)) {
                notes_.insert("an ImageTexture's data: URL that is not valid base64 was skipped");
                continue;
            }
            out.uri.clear();
            out.mimeType = header.substr(0, base64At);
            return addTexture(entry->second, std::move(out));
        }
        if (out.uri.empty()) out.uri = url;
        const fs::path image = file_.parent_path() / url;
        std::error_code error;
        if (url.find("://") == std::string::npos && fs::is_regular_file(image, error)) {
            out.uri = image.lexically_normal().string();  // where it was read: writers refer to it from there
            out.bytes = readFileBytes(image);
            break;
        }
    }
    if (out.uri.empty()) return -1;
    if (out.bytes.empty()) {
        notes_.insert("texture '" + out.uri + "' not found; its reference is kept");
        // Where it was looked for: the writers refer to it relative to their output.
        if (out.uri.find("://") == std::string::npos) out.uri = (file_.parent_path() / out.uri).lexically_normal().string();
    }
    out.mimeType = imageMimeType(out.uri);
    return addTexture(entry->second, std::move(out));
}

int X3dReader::addTexture(int& index, Texture texture) {
    scene_.textures.push_back(std::move(texture));
    index = static_cast<int>(scene_.textures.size()) - 1;
    return index;
}

int X3dReader::readMaterial(const pugi::xml_node& shape) {
    pugi::xml_node appearance = shape.child("Appearance");
    if (!appearance) return -1;
    if (const pugi::xml_attribute def = appearance.attribute("DEF")) definitions_[def.value()] = appearance;
    appearance = resolve(appearance);
    auto [entry, inserted] = materialOfAppearance_.try_emplace(appearance.internal_object(), -1);
    if (!inserted) return entry->second;
    Material material;
    material.name = appearance.attribute("DEF").value();
    pugi::xml_node phong = appearance.child("Material");
    pugi::xml_node physical = appearance.child("PhysicalMaterial");
    pugi::xml_node twoSided = appearance.child("TwoSidedMaterial");
    if (twoSided) {
        phong = twoSided;
        material.doubleSided = true;
    }
    for (pugi::xml_node* node : {&phong, &physical})
        if (*node) {
            if (const pugi::xml_attribute def = node->attribute("DEF")) definitions_[def.value()] = *node;
            *node = resolve(*node);
        }
    if (phong) {
        PhongMaterial fields;
        fields.diffuseColor = vector3(phong, "diffuseColor", fields.diffuseColor);
        fields.specularColor = vector3(phong, "specularColor", fields.specularColor);
        fields.emissiveColor = vector3(phong, "emissiveColor", fields.emissiveColor);
        fields.ambientIntensity = scalar(phong, "ambientIntensity", fields.ambientIntensity);
        fields.shininess = scalar(phong, "shininess", fields.shininess);
        fields.transparency = scalar(phong, "transparency", fields.transparency);
        material.baseColorFactor << fields.diffuseColor, 1 - fields.transparency;
        material.emissiveFactor = fields.emissiveColor;
        material.metallicFactor = 0;
        material.roughnessFactor = 1 - fields.shininess;
        material.phong = fields;
        if (material.name.empty()) material.name = phong.attribute("DEF").value();
    } else if (physical) {
        const double transparency = scalar(physical, "transparency", 0);
        material.baseColorFactor << vector3(physical, "baseColor", Eigen::Vector3d::Ones()), 1 - transparency;
        material.metallicFactor = scalar(physical, "metallic", 1);
        material.roughnessFactor = scalar(physical, "roughness", 1);
        material.emissiveFactor = vector3(physical, "emissiveColor", Eigen::Vector3d::Zero());
        if (material.name.empty()) material.name = physical.attribute("DEF").value();
    } else {
        // An Appearance without a material is unlit white in X3D.
        material.metallicFactor = 0;
    }
    if (material.baseColorFactor[3] < 1) material.alphaMode = Material::AlphaMode::Blend;
    material.baseColorTexture.texture = readTexture(appearance);
    // Appearances written out one per Shape, with the same Material and texture USEd in each, are one
    // material (else every Shape would look like its own part). Double-sidedness comes from the geometry
    // (solid="false" makes the material double-sided, below in readShape), so it is not compared.
    const auto same = std::find_if(scene_.materials.begin(), scene_.materials.end(), [&](const Material& existing) {
        Material candidate = material;
        candidate.doubleSided = existing.doubleSided;
        return candidate == existing;
    });
    if (same != scene_.materials.end()) return entry->second = static_cast<int>(same - scene_.materials.begin());
    scene_.materials.push_back(material);
    entry->second = static_cast<int>(scene_.materials.size()) - 1;
    return entry->second;
}

}  // namespace symcompress
