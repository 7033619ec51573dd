// X3D appearances: Phong and physical materials with their X3D 4 texture fields, and image textures (files
// beside the scene, or data: URLs).
#include "x3d_reader.hpp"

#include "common/color_space.hpp"
#include "common/mime_type.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "x3d_materials.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iterator>

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

std::string nodeName(const pugi::xml_node& node) {
    const std::string def = node.attribute("DEF").value();
    return std::string(node.name()) + (def.empty() ? "" : " '" + def + "'");
}

}  // namespace

int X3dReader::readTexture(const pugi::xml_node& appearance) {
    pugi::xml_node texture = appearance.child("ImageTexture");
    if (!texture) {
        for (pugi::xml_node child : appearance.children())
            if (std::strstr(child.name(), "Texture")) notes_.insert(std::string(child.name()) + " not carried through");
        return -1;
    }
    return readTextureNode(texture, "an Appearance's texture");
}

// glTF's sampler of an ImageTexture: its TextureProperties' boundary modes and filters, else its repeatS and
// repeatT (x3d_materials.hpp).
TextureSampler X3dReader::readSampler(const pugi::xml_node& texture) {
    TextureSampler sampler;
    if (!boolean(texture, "repeatS", true)) sampler.wrapS = 33071;
    if (!boolean(texture, "repeatT", true)) sampler.wrapT = 33071;
    pugi::xml_node properties = texture.child("TextureProperties");
    if (!properties || !knownUse(properties, nodeName(texture) + " textureProperties")) return sampler;
    if (const pugi::xml_attribute def = properties.attribute("DEF")) definitions_[def.value()] = properties;
    properties = resolve(properties);
    if (std::strcmp(properties.name(), "TextureProperties") != 0) return sampler;
    sampler.wrapS = x3d::boundaryModeOf(properties.attribute("boundaryModeS").as_string("REPEAT"));
    sampler.wrapT = x3d::boundaryModeOf(properties.attribute("boundaryModeT").as_string("REPEAT"));
    sampler.magFilter = x3d::filterOf(properties.attribute("magnificationFilter").value());
    sampler.minFilter = x3d::filterOf(properties.attribute("minificationFilter").value());
    // Mipmap filters without mipmaps: the browser samples the one level (LINEAR or NEAREST).
    if (!boolean(properties, "generateMipMaps", false) && sampler.minFilter >= 9984)
        sampler.minFilter = sampler.minFilter == 9984 || sampler.minFilter == 9986 ? 9728 : 9729;
    return sampler;
}

bool X3dReader::knownUse(const pugi::xml_node& node, const std::string& where) {
    const pugi::xml_attribute use = node.attribute("USE");
    if (!use || definitions_.count(use.value())) return true;
    notes_.insert(where + ": USE='" + use.value() + "' refers to no DEF before it; left out");
    return false;
}

int X3dReader::readTextureNode(const pugi::xml_node& node, const std::string& where) {
    if (!knownUse(node, where)) return -1;
    if (const pugi::xml_attribute def = node.attribute("DEF")) definitions_[def.value()] = node;
    const pugi::xml_node texture = resolve(node);
    if (std::strcmp(texture.name(), "ImageTexture") != 0) {
        if (std::strstr(texture.name(), "Texture"))
            notes_.insert(where + ": " + texture.name() + " not carried through (only ImageTexture is read)");
        else
            notes_.insert(where + " holds a " + texture.name() + ", not a texture node; left out");
        return -1;
    }
    auto [entry, inserted] = textureOfNode_.try_emplace(texture.internal_object(), -1);
    if (!inserted) return entry->second;
    Texture out;
    out.sampler = readSampler(texture);
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

namespace {

// The X3D 4 fields of a material that hold a texture, and the core slot each fills (none: the scene model has
// no slot for it). Material's diffuse texture is its base colour's, as the Appearance's texture is.
struct TextureField {
    const char* field;
    TextureRef Material::*slot;
};
const TextureField kPhysicalTextureFields[] = {{"baseTexture", &Material::baseColorTexture},
                                               {"metallicRoughnessTexture", &Material::metallicRoughnessTexture},
                                               {"normalTexture", &Material::normalTexture},
                                               {"occlusionTexture", &Material::occlusionTexture},
                                               {"emissiveTexture", &Material::emissiveTexture}};
// UnlitMaterial draws its emissive texture: glTF's unlit base colour texture.
const TextureField kUnlitTextureFields[] = {{"emissiveTexture", &Material::baseColorTexture},
                                            {"normalTexture", nullptr}};
const TextureField kPhongTextureFields[] = {{"diffuseTexture", &Material::baseColorTexture},
                                            {"normalTexture", &Material::normalTexture},
                                            {"occlusionTexture", &Material::occlusionTexture},
                                            {"emissiveTexture", &Material::emissiveTexture},
                                            {"ambientTexture", nullptr},
                                            {"specularTexture", nullptr},
                                            {"shininessTexture", nullptr}};

}  // namespace

// An X3D 4 material's textures (child nodes whose containerField names the field), each with its *Mapping (the
// texture coordinate set), the normal texture's normalScale and the occlusion texture's occlusionStrength.
void X3dReader::readMaterialTextures(const pugi::xml_node& node, Material& material,
                                     const std::vector<std::string>& texcoordMappings) {
    const bool physical = std::strcmp(node.name(), "PhysicalMaterial") == 0;
    const bool unlit = std::strcmp(node.name(), "UnlitMaterial") == 0;
    const std::vector<TextureField> fields =
        physical ? std::vector<TextureField>(std::begin(kPhysicalTextureFields), std::end(kPhysicalTextureFields))
        : unlit  ? std::vector<TextureField>(std::begin(kUnlitTextureFields), std::end(kUnlitTextureFields))
                 : std::vector<TextureField>(std::begin(kPhongTextureFields), std::end(kPhongTextureFields));
    const std::string what = nodeName(node);
    for (pugi::xml_node child : node.children()) {
        if (child.type() != pugi::node_element || std::strncmp(child.name(), "Metadata", 8) == 0 ||
            std::strcmp(child.name(), "IS") == 0)
            continue;
        const std::string field = child.attribute("containerField").value();
        const auto found = std::find_if(fields.begin(), fields.end(),
                                        [&](const TextureField& candidate) { return field == candidate.field; });
        if (found == fields.end()) {
            notes_.insert(what + ": a " + child.name() +
                          (field.empty() ? " without containerField" : " in field '" + field + "'") +
                          " is in no texture field of the material; left out");
            continue;
        }
        if (!found->slot) {
            notes_.insert(what + ": " + field + " not carried through (no such slot in glTF's material)");
            continue;
        }
        const int texture = readTextureNode(child, what + " " + field);
        if (texture < 0) continue;
        TextureRef& use = material.*(found->slot);
        use = TextureRef{};
        use.texture = texture;
        const std::string mapping = node.attribute((field + "Mapping").c_str()).value();
        if (!mapping.empty()) {
            const auto set = std::find(texcoordMappings.begin(), texcoordMappings.end(), mapping);
            if (set != texcoordMappings.end())
                use.texCoord = static_cast<int>(set - texcoordMappings.begin());
            else
                notes_.insert(what + ": " + field + "Mapping '" + mapping +
                              "' names no texture coordinates of its geometry; the first set used");
        }
    }
    if (material.normalTexture.texture >= 0) material.normalTexture.scale = scalar(node, "normalScale", 1);
    if (material.occlusionTexture.texture >= 0) material.occlusionTexture.scale = scalar(node, "occlusionStrength", 1);
}

// X3D's TextureTransform (X3D 4.0 18.4.10): Tc' = -C × S × R × C × T × Tc on X3D's (s, t), t up, where glTF's v
// points down: baked into every texture coordinate set, or into the set its `mapping` names, as X_ITE draws it.
// Exact for any transform (KHR_texture_transform, which scales before it turns, has no place for S × R).
bool X3dReader::applyTextureTransform(const pugi::xml_node& shape, const std::vector<std::string>& texcoordMappings,
                                      Primitive& primitive) {
    pugi::xml_node appearance = shape.child("Appearance");
    if (!appearance || !knownUse(appearance, "a Shape's Appearance")) return false;
    appearance = resolve(appearance);
    pugi::xml_node transform = appearance.child("TextureTransform");
    if (!transform) {
        if (appearance.child("MultiTextureTransform")) notes_.insert("MultiTextureTransform not carried through");
        return false;
    }
    if (!knownUse(transform, "an Appearance's TextureTransform")) return false;
    if (const pugi::xml_attribute def = transform.attribute("DEF")) definitions_[def.value()] = transform;
    transform = resolve(transform);
    const Eigen::Vector2d translation = vector2(transform, "translation", Eigen::Vector2d::Zero());
    const Eigen::Vector2d center = vector2(transform, "center", Eigen::Vector2d::Zero());
    const Eigen::Vector2d scale = vector2(transform, "scale", Eigen::Vector2d::Ones());
    const double rotation = scalar(transform, "rotation", 0);
    if (translation.isZero(0) && scale == Eigen::Vector2d::Ones() && rotation == 0) return false;
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(rotation).toRotationMatrix();
    const auto transformed = [&](const Eigen::Vector2d& uv) -> Eigen::Vector2d {
        const Eigen::Vector2d st(uv.x(), 1 - uv.y());
        const Eigen::Vector2d out = (turn * (st + translation + center)).cwiseProduct(scale) - center;
        return {out.x(), 1 - out.y()};
    };
    // The sets it applies to: all, or the one its mapping names (0 is Primitive::texcoords, n TEXCOORD_n).
    const std::string mapping = transform.attribute("mapping").value();
    const auto named = std::find(texcoordMappings.begin(), texcoordMappings.end(), mapping);
    if (!mapping.empty() && named == texcoordMappings.end()) {
        notes_.insert("a TextureTransform's mapping '" + mapping + "' names no texture coordinates of its geometry; " +
                      "left out");
        return false;
    }
    const auto applies = [&](int set) { return mapping.empty() || set == int(named - texcoordMappings.begin()); };
    bool changed = false;
    if (applies(0))
        for (Eigen::Vector2d& uv : primitive.texcoords) uv = transformed(uv), changed = true;
    for (VertexAttribute& attribute : primitive.attributes) {
        if (attribute.name.rfind("TEXCOORD_", 0) != 0 || attribute.components != 2) continue;
        if (!applies(std::atoi(attribute.name.c_str() + 9))) continue;
        for (std::size_t v = 0; v + 1 < attribute.values.size(); v += 2) {
            const Eigen::Vector2d uv = transformed({attribute.values[v], attribute.values[v + 1]});
            attribute.values[v] = uv.x();
            attribute.values[v + 1] = uv.y();
            changed = true;
        }
    }
    return changed;
}

// X3D draws lines and points unlit (X3D 3.3's line and point sets: "lines are not lit"): in the Material's
// emissive colour, or in their Color's, which takes its place (PhysicalMaterial's emissive colour is linear;
// UnlitMaterial's, and a missing Material's white, is the base colour already). glTF's viewers (three.js) draw
// them in the base colour times COLOR_0: that colour, white where the vertex colours replace it, without
// textures (X3D maps none onto lines and points) and without what lighting reads.
Material X3dReader::unlitMaterial(const Material& read, bool physical, bool colored) const {
    Material out;
    out.name = read.name;
    out.metallicFactor = 0;
    Eigen::Vector3d color = read.baseColorFactor.head<3>();
    if (read.phong) color = srgbToLinear(read.phong->emissiveColor);
    if (physical) color = read.emissiveFactor;
    if (colored) color = Eigen::Vector3d::Ones();
    out.baseColorFactor << color, read.baseColorFactor[3];
    out.alphaMode = read.alphaMode;
    out.alphaCutoff = read.alphaCutoff;
    return out;
}

int X3dReader::readMaterial(const pugi::xml_node& shape, const std::vector<std::string>& texcoordMappings,
                            const Primitive& geometry) {
    // A Shape without an Appearance (or whose Appearance is a USE of nothing) is drawn as one without a material:
    // unlit white (X3D 4.0 12.4.1, as 3.3), and double-sided where its geometry is not solid; a material of
    // its own says so, where none would be glTF's lit default, one-sided.
    pugi::xml_node appearance = shape.child("Appearance");
    if (appearance && !knownUse(appearance, "a Shape's Appearance")) appearance = pugi::xml_node();
    if (const pugi::xml_attribute def = appearance.attribute("DEF")) definitions_[def.value()] = appearance;
    if (appearance) appearance = resolve(appearance);
    const bool unlitGeometry = geometry.topology != Topology::Triangles;
    const int lighting = unlitGeometry ? (geometry.colors.empty() ? 1 : 2) : 0;
    const bool translucentColors = std::any_of(geometry.colors.begin(), geometry.colors.end(),
                                               [](const Eigen::Vector4d& color) { return color[3] < 1; });
    auto [entry, inserted] =
        materialOfAppearance_.try_emplace({appearance.internal_object(), lighting, translucentColors}, -1);
    if (!inserted) return entry->second;
    Material material;
    material.name = appearance.attribute("DEF").value();
    pugi::xml_node phong = appearance.child("Material");
    pugi::xml_node physical = appearance.child("PhysicalMaterial");
    pugi::xml_node unlit = appearance.child("UnlitMaterial");
    pugi::xml_node twoSided = appearance.child("TwoSidedMaterial");
    if (twoSided) {
        phong = twoSided;
        material.doubleSided = true;
    }
    for (pugi::xml_node* node : {&phong, &physical, &unlit})
        if (*node) {
            if (!knownUse(*node, "an Appearance's " + std::string(node->name()))) {
                *node = pugi::xml_node();
                continue;
            }
            if (const pugi::xml_attribute def = node->attribute("DEF")) definitions_[def.value()] = *node;
            *node = resolve(*node);
        }
    // Phong's colours are sRGB-encoded, glTF's factors linear (docs/scene-model.md, "Colour spaces"); the
    // fields are kept as they are for the X3D writer.
    if (phong) {
        PhongMaterial fields;
        fields.diffuseColor = vector3(phong, "diffuseColor", fields.diffuseColor);
        fields.specularColor = vector3(phong, "specularColor", fields.specularColor);
        fields.emissiveColor = vector3(phong, "emissiveColor", fields.emissiveColor);
        fields.ambientIntensity = scalar(phong, "ambientIntensity", fields.ambientIntensity);
        fields.shininess = scalar(phong, "shininess", fields.shininess);
        fields.transparency = scalar(phong, "transparency", fields.transparency);
        material.baseColorFactor << srgbToLinear(fields.diffuseColor), 1 - fields.transparency;
        material.emissiveFactor = srgbToLinear(fields.emissiveColor);
        material.metallicFactor = 0;
        material.roughnessFactor = 1 - fields.shininess;
        material.phong = fields;
        if (material.name.empty()) material.name = phong.attribute("DEF").value();
    } else if (physical) {
        // PhysicalMaterial is glTF's metallic-roughness material, its colours linear as glTF's factors.
        const double transparency = scalar(physical, "transparency", 0);
        material.baseColorFactor << vector3(physical, "baseColor", Eigen::Vector3d::Ones()), 1 - transparency;
        material.metallicFactor = scalar(physical, "metallic", 1);
        material.roughnessFactor = scalar(physical, "roughness", 1);
        material.emissiveFactor = vector3(physical, "emissiveColor", Eigen::Vector3d::Zero());
        if (material.name.empty()) material.name = physical.attribute("DEF").value();
    } else if (unlit) {
        // UnlitMaterial draws its emissive colour, sRGB-encoded as Phong's (X_ITE draws it so), as glTF's
        // KHR_materials_unlit draws the base colour.
        material.baseColorFactor << srgbToLinear(vector3(unlit, "emissiveColor", Eigen::Vector3d::Ones())),
            1 - scalar(unlit, "transparency", 0);
        material.metallicFactor = 0;
        material.extensions.push_back({"KHR_materials_unlit", "{}", {}, false});
        if (material.name.empty()) material.name = unlit.attribute("DEF").value();
    } else {
        // An Appearance without a material is unlit white in X3D, its texture drawn as it is.
        material.metallicFactor = 0;
        material.extensions.push_back({"KHR_materials_unlit", "{}", {}, false});
    }
    if (material.baseColorFactor[3] < 1) material.alphaMode = Material::AlphaMode::Blend;
    // X3D 4's Appearance holds glTF's alpha modes (AUTO, the default, as X3D 3 decides: blend when transparent).
    const std::string alphaMode = appearance.attribute("alphaMode").value();
    if (alphaMode == "OPAQUE") material.alphaMode = Material::AlphaMode::Opaque;
    if (alphaMode == "BLEND") material.alphaMode = Material::AlphaMode::Blend;
    if (alphaMode == "MASK") {
        material.alphaMode = Material::AlphaMode::Mask;
        material.alphaCutoff = scalar(appearance, "alphaCutoff", 0.5);
    }
    if (unlitGeometry) {
        material = unlitMaterial(material, bool(physical), lighting == 2);
    } else {
        // The material's own base texture (X3D 4) takes the place of the Appearance's texture.
        if (phong || physical || unlit)
            readMaterialTextures(phong ? phong : physical ? physical : unlit, material, texcoordMappings);
        if (material.baseColorTexture.texture < 0) material.baseColorTexture.texture = readTexture(appearance);
    }
    // AUTO (X3D 3's only rule) blends a shape whose material is transparent (above), whose base texture has
    // translucent pixels or whose vertex colours are translucent, as X_ITE decides (Shape's set_transparent__).
    if ((alphaMode.empty() || alphaMode == "AUTO") && material.alphaMode == Material::AlphaMode::Opaque &&
        (translucentColors || translucentTexture_(material.baseColorTexture.texture)))
        material.alphaMode = Material::AlphaMode::Blend;
    // Appearances written out one per Shape, with the same Material and texture USEd in each, are one
    // material (else every Shape would look like its own part). Double-sidedness comes from the geometry
    // (solid="false" makes the material double-sided, below in readShape), so it is not compared.
    const auto same = std::find_if(scene_.materials.begin(), scene_.materials.end(), [&](const Material& existing) {
        Material candidate = material;
        candidate.doubleSided = existing.doubleSided;
        return candidate == existing;
    });
    if (same != scene_.materials.end()) {
        entry->second = static_cast<int>(same - scene_.materials.begin());
        if (physical) physicalMaterials_.insert(entry->second);
        return entry->second;
    }
    scene_.materials.push_back(material);
    entry->second = static_cast<int>(scene_.materials.size()) - 1;
    if (physical) physicalMaterials_.insert(entry->second);
    return entry->second;
}

}  // namespace symcompress
