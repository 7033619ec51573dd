// glTF 2.0 writer: .glb (one binary chunk) or .gltf (JSON plus a sibling .bin). Meshes shared by several
// nodes stay shared (instancing, mirrors included: a negative-determinant node matrix is valid glTF and
// renderers flip the winding for it); where many plain leaves draw one mesh, they are one node with
// EXT_mesh_gpu_instancing (gltf_gpu_instancing.cpp; their values through EXT_meshopt_compression where that is
// smaller) unless WriteOptions::gpuInstancing is false. Geometry is
// compressed with KHR_draco_mesh_compression unless WriteOptions::draco is false.
#include "common/image_size.hpp"
#include "common/number_text.hpp"
#include "common/uri_text.hpp"
#include "common/with_threads.hpp"
#include "file_metadata.hpp"
#include "geometry/bounds.hpp"
#include "gltf_animation_keys.hpp"
#include "gltf_builder.hpp"
#include "gltf_gpu_instancing.hpp"
#include "gltf_instance_encoding.hpp"
#include "gltf_integer_positions.hpp"
#include "image_reference.hpp"
#include "primitive_encodings.hpp"
#include "rotation_and_scale.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <nlohmann/json.hpp>

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// Whether a primitive of material `m` is drawn in the order of its triangles: blended (viewers draw a blended
// object's triangles in order, writing no depth) and double-sided, where two of its triangles overlap wherever
// the view lines them up. A single-sided surface's front faces overlap only where it folds over itself; Draco's
// edgebreaker, which reorders triangles, codes it far smaller (the house's glass: 46 KB more in order).
bool drawnInOrder(const Scene& scene, int m) {
    if (!drawnBlended(scene, m)) return false;
    const std::vector<const Material*> drawn = materialsDrawnWith(scene, m);
    return std::any_of(drawn.begin(), drawn.end(), [](const Material* material) { return material->doubleSided; });
}

// A node's translation as printed: at float32's precision (what many glTF readers keep of it) where that is within
// `precision` of it (a distance; 0: always), else the decimals that are: a node far from the origin (a georeferenced
// part 10 km out) would move by float32's spacing there, a millimetre. Float32's precision is that of the largest
// component, in the fewest digits: a component far smaller than the others (1.9e-18 beside 1.2, the rounding of
// the centroids a placement came from) prints as 0.
Eigen::Vector3d printedTranslation(const Eigen::Vector3d& translation, double precision) {
    const double largest = translation.cwiseAbs().maxCoeff();
    const Eigen::Vector3d t = translation.unaryExpr([&](double x) { return atFloat32PrecisionOf(x, largest); });
    if (!(precision > 0) || (t - translation).cwiseAbs().maxCoeff() <= precision) return t;
    const int decimals = std::clamp(int(std::ceil(-std::log10(precision))), 0, 15);
    return translation.unaryExpr(
        [&](double x) { return std::abs(x) * std::pow(10.0, decimals) < 1e15 ? roundedDecimals(x, decimals) : x; });
}

// A node's fields: translation (printedTranslation), rotation quaternion to 1e-7 and scale (float32; none within
// kScaleNoise of 1), each left out when it does nothing. Instance nodes are the common case, where their size
// counts: a rigid or uniformly scaled transform takes about half the bytes of a matrix.
Json transformFields(const Eigen::Vector3d& translation, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& scale,
                     double translationPrecision) {
    Json out = Json::object();
    Eigen::Quaterniond q(rotation);
    if (q.w() < 0) q.coeffs() *= -1;
    const Eigen::Vector3d t = printedTranslation(translation, translationPrecision);
    const Eigen::Vector3d s = (scale.array() - 1).abs().maxCoeff() <= kScaleNoise
                                  ? Eigen::Vector3d(Eigen::Vector3d::Ones())
                                  : Eigen::Vector3d(scale.unaryExpr(&asFloat32));
    const Eigen::Vector4d r = q.coeffs().unaryExpr([](double x) { return roundedDecimals(x, kRotationDecimals); });
    if (!t.isZero(0)) out["translation"] = {t.x(), t.y(), t.z()};
    if (r != Eigen::Vector4d(0, 0, 0, 1)) out["rotation"] = {r.x(), r.y(), r.z(), r.w()};
    if (s == Eigen::Vector3d(-1, 1, 1))
        out["scale"] = {-1, 1, 1};  // a mirror: the common case, short
    else if (s != Eigen::Vector3d::Ones())
        out["scale"] = {s.x(), s.y(), s.z()};
    return out;
}

// Extras as read (JSON text), or nothing where the text is empty or not JSON.
void putExtras(Json& object, const std::string& extrasJson) {
    if (extrasJson.empty()) return;
    Json extras = Json::parse(extrasJson, nullptr, false);
    if (!extras.is_discarded()) object["extras"] = std::move(extras);
}

// Writes a node. glTF requires node matrices to decompose into TRS, so a transform that shears (X3D's
// scaleOrientation, a turned child of a non-uniformly scaled parent) is split by the SVD L = U Σ V^T:
// this node takes translation, U and Σ, and a new child, appended to `extra` (its index is firstExtra +
// its position there), takes V^T with the mesh and the children.
Json writeNode(const Node& node, const std::vector<int>& meshIndex, std::size_t firstExtra, std::vector<Json>& extra,
               double translationPrecision = 0) {
    const Eigen::Matrix3d linear = node.transform.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = node.transform.topRightCorner<3, 1>();
    Json out;
    Json* drawing = &out;  // the node that carries the mesh and the children
    if (const auto trs = asRotationAndScale(linear)) {
        out = transformFields(translation, trs->first, trs->second, translationPrecision);
    } else {
        Eigen::JacobiSVD<Eigen::Matrix3d> svd(linear, Eigen::ComputeFullU | Eigen::ComputeFullV);
        Eigen::Matrix3d u = svd.matrixU(), v = svd.matrixV();
        Eigen::Vector3d sigma = svd.singularValues();
        if (v.determinant() < 0) v.col(2) = -v.col(2), u.col(2) = -u.col(2);
        if (u.determinant() < 0) u.col(2) = -u.col(2), sigma[2] = -sigma[2];
        out = transformFields(translation, u, sigma, translationPrecision);
        out["children"] = {firstExtra + extra.size()};
        extra.push_back(transformFields(Eigen::Vector3d::Zero(), v.transpose(), Eigen::Vector3d::Ones(), 0));
        drawing = &extra.back();
    }
    if (!node.name.empty()) out["name"] = node.name;
    putExtras(out, node.extrasJson);
    if (node.mesh >= 0 && meshIndex[node.mesh] >= 0) (*drawing)["mesh"] = meshIndex[node.mesh];
    if (node.skin >= 0) (*drawing)["skin"] = node.skin;
    if (!node.weights.empty()) (*drawing)["weights"] = node.weights;
    if (node.camera >= 0) (*drawing)["camera"] = node.camera;
    if (node.light >= 0) (*drawing)["extensions"]["KHR_lights_punctual"]["light"] = node.light;
    if (!node.children.empty()) (*drawing)["children"] = node.children;
    return out;
}

Json writeCamera(const Camera& camera) {
    Json out = Json::object();
    if (!camera.name.empty()) out["name"] = camera.name;
    if (camera.projection == Camera::Projection::Orthographic) {
        out["type"] = "orthographic";
        out["orthographic"] = {
            {"xmag", camera.xmag}, {"ymag", camera.ymag}, {"znear", camera.znear}, {"zfar", camera.zfar}};
        return out;
    }
    out["type"] = "perspective";
    Json perspective = {{"yfov", asFloat32WhereExact(camera.yfov)}, {"znear", camera.znear}};
    if (camera.aspectRatio > 0) perspective["aspectRatio"] = camera.aspectRatio;
    if (camera.zfar > 0) perspective["zfar"] = camera.zfar;
    out["perspective"] = perspective;
    return out;
}

// A KHR_lights_punctual light, its fields left out where they are the extension's defaults.
Json writeLight(const Light& light) {
    Json out = Json::object();
    if (!light.name.empty()) out["name"] = light.name;
    out["type"] = light.type == Light::Type::Directional ? "directional"
                  : light.type == Light::Type::Spot      ? "spot"
                                                         : "point";
    if (light.color != Eigen::Vector3d::Ones()) out["color"] = {light.color.x(), light.color.y(), light.color.z()};
    if (light.intensity != 1) out["intensity"] = light.intensity;
    if (light.range > 0 && light.type != Light::Type::Directional) out["range"] = light.range;
    if (light.type == Light::Type::Spot)
        out["spot"] = {{"innerConeAngle", asFloat32WhereExact(light.innerConeAngle)},
                       {"outerConeAngle", asFloat32WhereExact(light.outerConeAngle)}};
    return out;
}

// The extensions a file uses, for its extensionsUsed and extensionsRequired.
struct ExtensionsInUse {
    std::set<std::string> used, required;
    void add(const std::string& name, bool isRequired) {
        used.insert(name);
        if (isRequired) required.insert(name);
    }
};

// The extensions passed through on an object (passedThroughExtensions), put on it as they were read.
void putPassedExtensions(Json& object, const std::string& extensionsJson, ExtensionsInUse& extensions) {
    if (extensionsJson.empty()) return;
    const Json passed = Json::parse(extensionsJson);
    for (const auto& [name, value] : passed.items()) {
        object["extensions"][name] = value;
        extensions.add(name, false);
    }
}

// The textures, images and samplers the materials use, each written the first time a material uses it: one
// glTF image per image (textures of the same image share it), one sampler per distinct sampler (none for
// the default one), one glTF texture per scene texture. WebP and KTX2 images are sources of
// EXT_texture_webp and KHR_texture_basisu, with the core image the file had beside them (Texture::fallback) as the
// texture's source; without one the extension is required.
class TextureWriter {
public:
    TextureWriter(const Scene& scene, GltfBuilder& builder, Json& root, const fs::path& file,
                  ExtensionsInUse& extensions)
        : scene_(scene), builder_(builder), root_(root), file_(file), extensions_(extensions),
          sameImage_(firstTextureOfSameImage(scene.textures)), texture_(scene.textures.size(), -1),
          image_(scene.textures.size(), -1) {}

    // The textureInfo of `use`, or null where it has no texture that can be written; `scaleKey` names its
    // scale ("scale" for normal textures, "strength" for occlusion), nullptr where it has none.
    Json textureInfo(const TextureRef& use, const char* scaleKey) {
        const int index = use.texture >= 0 ? textureIndex(use.texture) : -1;
        if (index < 0) return nullptr;
        Json info = {{"index", index}};
        if (use.texCoord != 0) info["texCoord"] = use.texCoord;
        if (scaleKey && use.scale != 1) info[scaleKey] = asFloat32(use.scale);
        if (use.transform) {
            const TextureTransform& t = *use.transform;
            Json transform = Json::object();
            if (!t.offset.isZero(0)) transform["offset"] = {asFloat32(t.offset.x()), asFloat32(t.offset.y())};
            if (t.rotation != 0) transform["rotation"] = asFloat32(t.rotation);
            if (t.scale != Eigen::Vector2d::Ones()) transform["scale"] = {asFloat32(t.scale.x()), asFloat32(t.scale.y())};
            if (t.texCoord >= 0) transform["texCoord"] = t.texCoord;
            info["extensions"]["KHR_texture_transform"] = transform;
            extensions_.add("KHR_texture_transform", false);
        }
        return info;
    }

private:
    int textureIndex(int t) {
        if (texture_[t] >= 0) return texture_[t];
        const Texture& source = scene_.textures[std::size_t(t)];
        const int image = imageIndex(sameImage_[std::size_t(t)]);
        if (image < 0) return -1;
        Json texture = Json::object();
        const char* extension = source.mimeType == "image/webp"   ? "EXT_texture_webp"
                                : source.mimeType == "image/ktx2" ? "KHR_texture_basisu"
                                                                  : nullptr;
        if (extension) {
            texture["extensions"][extension]["source"] = image;
            // A core image beside it keeps the extension optional: viewers without it draw that one.
            const int fallback = source.fallback ? fallbackIndex(*source.fallback) : -1;
            if (fallback >= 0) texture["source"] = fallback;
            extensions_.add(extension, fallback < 0);
        } else {
            texture["source"] = image;
        }
        if (const int sampler = samplerIndex(source.sampler); sampler >= 0) texture["sampler"] = sampler;
        if (!source.name.empty()) texture["name"] = source.name;
        root_["textures"].push_back(texture);
        return texture_[t] = static_cast<int>(root_["textures"].size()) - 1;
    }

    int imageIndex(int t) {
        if (image_[t] >= 0) return image_[t];
        const Texture& source = scene_.textures[std::size_t(t)];
        return image_[t] = addImage(source.uri, source.mimeType, source.bytes, source.name);
    }

    // Each fallback image written once.
    int fallbackIndex(const ImageFile& fallback) {
        for (const auto& [written, index] : fallbacks_)
            if (*written == fallback) return index;
        const int index = addImage(fallback.uri, fallback.mimeType, fallback.bytes, "");
        if (index >= 0) fallbacks_.emplace_back(&fallback, index);
        return index;
    }

    // An image is embedded; one that could not be read is referred to where it should be.
    int addImage(const std::string& uri, const std::string& mimeType, const std::vector<std::uint8_t>& bytes,
                 const std::string& name) {
        Json image = Json::object();
        if (!bytes.empty()) {
            image["bufferView"] = builder_.addBufferView(bytes.data(), bytes.size());
            image["mimeType"] = mimeType.empty() ? "image/png" : mimeType;
        } else if (!uri.empty()) {
            image["uri"] = imageReference(uri, file_);
        } else {
            return -1;
        }
        if (!name.empty()) image["name"] = name;
        root_["images"].push_back(image);
        return static_cast<int>(root_["images"].size()) - 1;
    }

    int samplerIndex(const TextureSampler& sampler) {
        if (sampler == TextureSampler{}) return -1;  // glTF's default: repeat, filters left to the viewer
        for (std::size_t s = 0; s < samplers_.size(); ++s)
            if (samplers_[s] == sampler) return int(s);
        Json out = Json::object();
        if (sampler.magFilter) out["magFilter"] = sampler.magFilter;
        if (sampler.minFilter) out["minFilter"] = sampler.minFilter;
        if (sampler.wrapS != 10497) out["wrapS"] = sampler.wrapS;
        if (sampler.wrapT != 10497) out["wrapT"] = sampler.wrapT;
        if (!sampler.name.empty()) out["name"] = sampler.name;
        root_["samplers"].push_back(out);
        samplers_.push_back(sampler);
        return int(samplers_.size()) - 1;
    }

    const Scene& scene_;
    GltfBuilder& builder_;
    Json& root_;
    fs::path file_;
    ExtensionsInUse& extensions_;
    std::vector<int> sameImage_, texture_, image_;
    std::vector<std::pair<const ImageFile*, int>> fallbacks_;  // written, and its index
    std::vector<TextureSampler> samplers_;
};

// The scale key of an extension's textureInfo: glTF names normal textures' "scale", occlusion's "strength".
const char* scaleKeyOf(const std::string& key) {
    if (key.find("ormal") != std::string::npos) return "scale";
    if (key.find("cclusion") != std::string::npos) return "strength";
    return nullptr;
}

Json writeMaterial(const Material& material, TextureWriter& textures, ExtensionsInUse& extensions) {
    // Factors as float32 text, and left out where they are glTF's defaults.
    Json pbr = Json::object();
    if (material.baseColorFactor != Eigen::Vector4d::Ones())
        pbr["baseColorFactor"] = {asFloat32(material.baseColorFactor[0]), asFloat32(material.baseColorFactor[1]),
                                  asFloat32(material.baseColorFactor[2]), asFloat32(material.baseColorFactor[3])};
    if (material.metallicFactor != 1) pbr["metallicFactor"] = asFloat32(material.metallicFactor);
    if (material.roughnessFactor != 1) pbr["roughnessFactor"] = asFloat32(material.roughnessFactor);
    Json out = Json::object();
    auto put = [&](Json& object, const char* key, const TextureRef& use, const char* scaleKey) {
        if (Json info = textures.textureInfo(use, scaleKey); !info.is_null()) object[key] = std::move(info);
    };
    put(pbr, "baseColorTexture", material.baseColorTexture, nullptr);
    put(pbr, "metallicRoughnessTexture", material.metallicRoughnessTexture, nullptr);
    if (!pbr.empty()) out["pbrMetallicRoughness"] = pbr;
    put(out, "normalTexture", material.normalTexture, "scale");
    put(out, "occlusionTexture", material.occlusionTexture, "strength");
    put(out, "emissiveTexture", material.emissiveTexture, nullptr);
    if (!material.name.empty()) out["name"] = material.name;
    if (!material.emissiveFactor.isZero())
        out["emissiveFactor"] = {asFloat32(material.emissiveFactor[0]), asFloat32(material.emissiveFactor[1]),
                                 asFloat32(material.emissiveFactor[2])};
    if (material.alphaMode == Material::AlphaMode::Mask) {
        out["alphaMode"] = "MASK";
        out["alphaCutoff"] = asFloat32(material.alphaCutoff);
    } else if (material.alphaMode == Material::AlphaMode::Blend) {
        out["alphaMode"] = "BLEND";
    }
    if (material.doubleSided) out["doubleSided"] = true;
    for (const MaterialExtension& extension : material.extensions) {
        Json object = Json::parse(extension.json, nullptr, false);
        if (!object.is_object()) object = Json::object();
        for (const auto& [key, use] : extension.textures) put(object, key.c_str(), use, scaleKeyOf(key));
        out["extensions"][extension.name] = std::move(object);
        extensions.add(extension.name, extension.required);
    }
    putExtras(out, material.extrasJson);
    return out;
}

// Where each scene node goes in the file once batches stand for their instances: the other nodes in the
// scene's order, then a node per batch, then the nodes writeNode adds for shears.
struct NodeNumbering {
    std::vector<int> index;   // per scene node: its index in the file (a batched node: its batch's)
    std::vector<int> batchOf;  // per scene node: its batch, -1
    std::size_t written = 0;  // nodes before the shears' extra nodes

    NodeNumbering(const Scene& scene, const GpuInstancingPlan& plan)
        : index(scene.nodes.size()), batchOf(plan.batchOf) {
        for (std::size_t n = 0; n < scene.nodes.size(); ++n)
            if (batchOf[n] < 0) index[n] = int(written++);
        for (std::size_t n = 0; n < scene.nodes.size(); ++n)
            if (batchOf[n] >= 0) index[n] = int(written) + batchOf[n];
        written += plan.batches.size();
    }

    // A list of scene nodes (children, roots) as the file lists them: a batch once, where its first node was.
    std::vector<int> list(const std::vector<int>& nodes) const {
        std::vector<int> out;
        std::set<int> batches;
        for (int n : nodes)
            if (batchOf[std::size_t(n)] < 0 || batches.insert(batchOf[std::size_t(n)]).second)
                out.push_back(index[std::size_t(n)]);
        return out;
    }
};

std::string glbFile(const Json& root, std::vector<unsigned char> binary) {
    std::string json = jsonText(root);
    while (json.size() % 4) json.push_back(' ');
    while (binary.size() % 4) binary.push_back(0);
    const bool hasBinary = !binary.empty();
    const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + json.size() + (hasBinary ? 8 + binary.size() : 0));
    std::string out;
    auto put32 = [&out](std::uint32_t value) { out.append(reinterpret_cast<const char*>(&value), 4); };
    out.append("glTF");
    put32(2);
    put32(total);
    put32(static_cast<std::uint32_t>(json.size()));
    out.append("JSON");
    out.append(json);
    if (hasBinary) {
        put32(static_cast<std::uint32_t>(binary.size()));
        out.append("BIN", 3);
        out.push_back('\0');
        out.append(reinterpret_cast<const char*>(binary.data()), binary.size());
    }
    return out;
}

// Every material written once: one with variants (KHR_materials_variants) as an earlier one equal to it but for its
// table, where there is one, since its primitives carry the table. Returns each material's index in the file.
std::vector<int> writeMaterials(const Scene& scene, TextureWriter& textures, ExtensionsInUse& extensions, Json& root) {
    std::vector<int> index(scene.materials.size(), -1);
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        for (std::size_t k = 0; k < m && index[m] < 0 && !scene.materialVariants.empty(); ++k) {
            const Material& earlier = scene.materials[k];
            if ((!material.variants.empty() || !earlier.variants.empty()) && earlier.name == material.name &&
                earlier.sameButNameAndVariants(material))
                index[m] = index[k];
        }
        if (index[m] >= 0) continue;
        index[m] = int(root["materials"].size());
        root["materials"].push_back(writeMaterial(material, textures, extensions));
    }
    return index;
}

// A primitive's KHR_materials_variants mappings: for each material its variants draw instead of `material`, which.
void putVariantMappings(const Material& material, const std::vector<int>& materialIndex, Json& primitive) {
    std::map<int, Json> variantsOf;  // written material -> the variants that draw it
    for (std::size_t v = 0; v < material.variants.size(); ++v)
        if (material.variants[v] >= 0) variantsOf[materialIndex[std::size_t(material.variants[v])]].push_back(v);
    if (variantsOf.empty()) return;
    Json& mappings = primitive["extensions"]["KHR_materials_variants"]["mappings"] = Json::array();
    for (auto& [written, variants] : variantsOf) mappings.push_back({{"material", written}, {"variants", variants}});
}

// Draco's texture coordinate bits for a primitive, and the step they are for: steps of 1/16 of a texel of the
// largest texture its material (under any of its variants) reads through TEXCOORD_0 (over the span of its coordinates,
// times a transform's scale), so that a bilinear filter's weights move by 6% at most (12 bits, Draco's usual, are a
// quarter of a texel of a 1024-pixel texture over [0, 1]: 0.57% of the skinned Cesium Man's pixels came out changed);
// never fewer than `bits` (then no step: the bits' own over the span is the finer).
struct TexcoordQuantization {
    int bits = 12;
    double step = 0;
};
TexcoordQuantization texcoordQuantizationFor(const Scene& scene, const Primitive& primitive, int bits) {
    if (primitive.material < 0 || primitive.texcoords.empty()) return {bits, 0};
    double texelsAcross = 0;
    for (const Material* material : materialsDrawnWith(scene, primitive.material))
        for (const TextureRef* use : material->textureRefs()) {
            if (use->texture < 0 || use->texCoordSet() != 0) continue;
            const ImageSize size = imageSizeOfBytes(scene.textures[std::size_t(use->texture)].bytes);
            const double scale = use->transform ? use->transform->scale.cwiseAbs().maxCoeff() : 1;
            texelsAcross = std::max(texelsAcross, std::max(size.width, size.height) * scale);
        }
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& t : primitive.texcoords) box.extend(t);
    const double steps = box.sizes().maxCoeff() * texelsAcross * 16;
    if (!(steps > 1)) return {bits, 0};
    const int fewest = int(std::ceil(std::log2(std::min(steps, 1e9))));
    if (fewest <= bits || fewest > 20) return {std::clamp(fewest, bits, 20), 0};
    return {fewest, 1 / (texelsAcross * 16)};
}

// Draco's bits for the skin weights of mesh `m`'s primitive: the fewest (of 8 to 24) whose rounding, half a step
// d of the weights' span for each of a vertex's k weights, moves no vertex by more than `error` at rest and at any
// key (k d skinWeightSensitivity / (1 - k d / s), s the least sum of a vertex's weights), and twice that for the
// motion between keys. 0 (float32 as read) where no skin draws the mesh, where even 24 bits do not, or where no
// error is allowed.
int weightBitsFor(const Scene& scene, const std::vector<std::vector<int>>& skinsOfMesh, std::size_t m,
                  const Primitive& primitive, double error) {
    if (!(error > 0) || skinsOfMesh[m].empty()) return 0;
    std::size_t weights = 0;
    double span = 0;
    std::vector<double> sums(primitive.positions.size(), 0.0);
    for (const VertexAttribute& attribute : primitive.attributes)
        if (attribute.name.rfind("WEIGHTS_", 0) == 0 && !attribute.values.empty()) {
            weights += std::size_t(attribute.components);
            const auto [lo, hi] = std::minmax_element(attribute.values.begin(), attribute.values.end());
            span = std::max(span, *hi - *lo);
            for (std::size_t v = 0; v < sums.size() && v < attribute.count(); ++v)
                for (int c = 0; c < attribute.components; ++c) sums[v] += attribute.vertex(v)[c];
        }
    double leastSum = std::numeric_limits<double>::infinity();
    for (double sum : sums)
        if (sum > 0) leastSum = std::min(leastSum, sum);
    if (weights == 0 || !std::isfinite(leastSum)) return 0;
    double sensitivity = 0;
    for (int skin : skinsOfMesh[m])
        sensitivity = std::max(sensitivity, skinWeightSensitivity(scene, primitive, scene.skins[std::size_t(skin)]));
    for (int bits = 8; bits <= 24; ++bits) {
        const double rounding = double(weights) * span / (2 * ((1 << bits) - 1));
        if (rounding < leastSum && 2 * rounding * sensitivity / (1 - rounding / leastSum) <= error) return bits;
    }
    return 0;
}

}  // namespace

std::size_t gltfMeshBytes(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.drawsNothing()) return 0;
    Json root = Json::object(), primitives = Json::array();
    GltfBuilder builder(root);
    // Far from the origin, measured about its centre, as the plan's scene stores it (emitScene): at its place,
    // float32 rounds the corners beyond any bits, and Draco took seconds over 24 of them for a part 1e5 units away.
    const double bound = positionErrorBound(primitive, options);
    const Eigen::Vector3d centre =
        bound > 0 ? centreIfFloat32RoundsBeyond(boundsOfCorners(primitive.positions, primitive.triangles),
                                                kFloat32RoundingShare * bound)
                  : Eigen::Vector3d::Zero();
    if (!centre.isZero(0) && !primitive.positionGrid) {
        Primitive centred = primitive;
        for (Eigen::Vector3d& p : centred.positions) p -= centre;
        writePrimitive(builder, centred, options, "(a mesh measured for the plan)", primitives);
    } else {
        writePrimitive(builder, primitive, options, "(a mesh measured for the plan)", primitives);
    }
    const Json mesh = {{"primitives", primitives}};
    const std::size_t binary = builder.binary().size();  // first: it writes the views the JSON names
    return jsonText(root).size() + jsonText(mesh).size() + binary;
}

// Animation channels as glTF samplers (float keys, in the views of their types; values as `stored` says, float as
// read where it has no filter) and channels.
Json writeAnimation(const Animation& animation, const std::vector<KeyValues>& stored, GltfBuilder& builder) {
    Json channels = Json::array(), samplers = Json::array();
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const AnimationChannel& channel = animation.channels[c];
        const bool rotation = channel.path == AnimationChannel::Path::Rotation,
                   weights = channel.path == AnimationChannel::Path::Weights;
        const std::vector<float> times(channel.times.begin(), channel.times.end()),
            values(channel.values.begin(), channel.values.end());
        // Morph weights are scalars, as many a key as the targets.
        const char* type = weights ? "SCALAR" : rotation ? "VEC4" : "VEC3";
        const int components = weights ? 1 : int(channel.components());
        int output = -1;
        if (c < stored.size() && !stored[c].filter.empty()) {
            Json accessor = {{"componentType", stored[c].componentType},
                             {"count", values.size() / std::size_t(components)},
                             {"type", type}};
            if (stored[c].componentType != kFloat) accessor["normalized"] = true;
            output = builder.addFilteredAccessor(std::move(accessor), stored[c].filtered, stored[c].elementBytes,
                                                 stored[c].filter);
        } else {
            output = builder.addFloatAccessor(values, components, type, false, 0);
        }
        Json sampler = {{"input", builder.addFloatAccessor(times, 1, "SCALAR", true, 0)}, {"output", output}};
        if (channel.interpolation == AnimationChannel::Interpolation::Step) sampler["interpolation"] = "STEP";
        if (channel.interpolation == AnimationChannel::Interpolation::CubicSpline)
            sampler["interpolation"] = "CUBICSPLINE";
        const char* path = rotation                                        ? "rotation"
                           : weights                                       ? "weights"
                           : channel.path == AnimationChannel::Path::Scale ? "scale"
                                                                           : "translation";
        channels.push_back({{"sampler", samplers.size()}, {"target", {{"node", channel.node}, {"path", path}}}});
        samplers.push_back(std::move(sampler));
    }
    Json out = {{"channels", channels}, {"samplers", samplers}};
    if (!animation.name.empty()) out["name"] = animation.name;
    return out;
}

namespace {

// Undoes `grid` (of the mesh `node` draws, written as `writtenMesh`) in `node`'s transform where that moves nothing
// else: no children, camera or light, not `animated`; else in a child of its own that takes the mesh, appended to
// `extra` (its index: firstExtra + its position there).
void undoGrid(Node& node, bool animated, const IntegerPositionGrid& grid, int writtenMesh, std::size_t firstExtra,
              std::vector<Json>& extra) {
    if (node.children.empty() && node.camera < 0 && node.light < 0 && !animated) {
        node.transform = node.transform * grid.dequantization();
        return;
    }
    Json child = transformFields(grid.origin, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Constant(grid.step), 0);
    child["mesh"] = writtenMesh;
    node.children.push_back(int(firstExtra + extra.size()));
    extra.push_back(std::move(child));
    node.mesh = -1;
}

Json writeSkin(const Skin& skin, GltfBuilder& builder) {
    Json out = {{"joints", skin.joints}};
    if (!skin.name.empty()) out["name"] = skin.name;
    if (skin.skeleton >= 0) out["skeleton"] = skin.skeleton;
    if (!skin.inverseBindMatrices.empty()) {
        std::vector<float> flat;
        for (const Eigen::Matrix4d& matrix : skin.inverseBindMatrices)
            for (int i = 0; i < 16; ++i) flat.push_back(static_cast<float>(matrix(i % 4, i / 4)));  // column-major
        out["inverseBindMatrices"] = builder.addFloatAccessor(flat, 16, "MAT4", false, 0);
    }
    return out;
}

}  // namespace

std::size_t gltfNodeBytes(const Node& node) {
    Node drawing = node;
    drawing.mesh = 0;
    drawing.children.clear();
    std::vector<Json> extra;
    std::size_t bytes = jsonText(writeNode(drawing, {0}, 1, extra)).size() + 1;  // and its comma
    for (const Json& child : extra) bytes += jsonText(child).size() + 1;
    return bytes + 3;  // its index in the scene's list of nodes, typically
}

namespace {

// A glTF file's JSON and binary buffer, before the buffers are described.
struct GltfFile {
    Json root;
    std::vector<unsigned char> binary;
    std::size_t fallbackBytes = 0;  // EXT_meshopt_compression's fallback buffer
    // EXT_meshopt_compression's views are of buffer 1, whose data only the binary buffer's encoded bytes hold.
    Json fallbackBuffer() const {
        return {{"byteLength", fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    }
    std::size_t bytes() const {
        return jsonText(root).size() + binary.size() + (fallbackBytes ? jsonText(fallbackBuffer()).size() + 1 : 0);
    }
};

// The file of `scene`; with `codeData`, the data that neither Draco nor an image codes (animations' keys, skins'
// matrices, the vertices of morphed primitives, lines and points) coded by meshopt without loss where each view is
// smaller for it.
GltfFile buildGltf(const Scene& scene, const fs::path& file, const WriteOptions& options, bool codeData) {
    GltfFile out;
    Json& root = out.root;
    root = {{"asset", {{"version", "2.0"}}}};
    if (!scene.copyright.empty()) root["asset"]["copyright"] = scene.copyright;
    if (Json extras = writtenExtras(scene.extrasJson, options.extrasJson); !extras.is_null())
        root["asset"]["extras"] = std::move(extras);
    // The digest in the extras says who wrote the file: the optional generator would say it again in 26 bytes,
    // which on a small file at a peer's deviation are the difference.
    if (!root["asset"].contains("extras") || !root["asset"]["extras"].is_object() ||
        !root["asset"]["extras"].contains(kDigestMember))
        root["asset"]["generator"] = "symcompress";
    GltfBuilder builder(root);
    if (codeData) builder.dataEncoder = meshoptEncoded;
    ExtensionsInUse extensions;
    TextureWriter textures(scene, builder, root, file, extensions);
    const std::vector<int> materialIndex = writeMaterials(scene, textures, extensions, root);

    // Meshes with no triangles are left out (glTF requires at least one primitive), and so is the
    // reference to them from nodes.
    std::vector<int> meshIndex(scene.meshes.size(), -1);
    bool usedDraco = false, usesQuantization = false;
    // Every primitive encoded first, in parallel (Draco's work: each on its own), then added to the buffer in
    // order; an encoding's error is thrown where writing one after the other would have thrown it.
    struct Encoding {
        const Primitive* primitive;
        WriteOptions options;
        EncodedPrimitive encoded;
        std::exception_ptr error;
        std::vector<double> morphWeights;  // a morphed primitive's largest weights (largestMorphWeights)
        std::optional<Primitive> sorted;   // lines or points in spatial order, written in their place
        const IntegerPositionGrid* integerGrid = nullptr;  // its mesh's (integerGrids)
    };
    std::vector<Encoding> encodings;
    // Primitives equal but for their material (one part drawn in several: a family of classes, or an input's meshes
    // that share accessors) are encoded once and name the same accessors, at the texture coordinate bits the
    // finest of their materials asks. Morph targets are no part of the fingerprint: their primitives stay apart.
    std::unordered_map<PrimitiveFingerprint, std::size_t, PrimitiveFingerprintHash> byGeometry;
    std::vector<std::size_t> encodingOf;  // of each primitive written, in order
    std::vector<std::vector<int>> skinsOfMesh(scene.meshes.size());
    for (const Node& node : scene.nodes)
        if (node.mesh >= 0 && node.skin >= 0) skinsOfMesh[std::size_t(node.mesh)].push_back(node.skin);
    // Meshes of lines and points, where meshopt codes their vertices, on a grid of integers that their nodes undo (a
    // skinned mesh is drawn by its joints, not its node).
    std::vector<std::optional<IntegerPositionGrid>> integerGrids(scene.meshes.size());
    if (codeData && options.draco)
        for (std::size_t m = 0; m < scene.meshes.size(); ++m)
            if (skinsOfMesh[m].empty()) integerGrids[m] = integerPositionGridFor(scene.meshes[m], options);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& primitive : scene.meshes[m].primitives) {
            if (primitive.drawsNothing()) continue;
            const TexcoordQuantization texcoords = texcoordQuantizationFor(scene, primitive, options.texcoordBits);
            const int weightBits = weightBitsFor(scene, skinsOfMesh, m, primitive, options.skinWeightError);
            if (primitive.targets.empty() && primitive.topology == Topology::Triangles) {
                const auto [first, added] =
                    byGeometry.try_emplace(fingerprintOf(primitive, options, false), encodings.size());
                if (!added) {
                    WriteOptions& shared = encodings[first->second].options;
                    // The finer of two: more bits, and the shorter step (none: the bits' own over the span).
                    if (texcoords.bits != shared.texcoordBits || texcoords.step != shared.texcoordStep)
                        shared.texcoordStep =
                            texcoords.bits == shared.texcoordBits ? std::min(shared.texcoordStep, texcoords.step) : 0;
                    shared.texcoordBits = std::max(shared.texcoordBits, texcoords.bits);
                    // The finer of two: none (float32 as read) is the finest.
                    shared.weightBits =
                        shared.weightBits == 0 || weightBits == 0 ? 0 : std::max(shared.weightBits, weightBits);
                    shared.keepTriangleOrder = shared.keepTriangleOrder || drawnInOrder(scene, primitive.material);
                    encodingOf.push_back(first->second);
                    continue;
                }
            }
            encodingOf.push_back(encodings.size());
            WriteOptions forPrimitive = options;
            forPrimitive.texcoordBits = texcoords.bits;
            forPrimitive.texcoordStep = texcoords.step;
            forPrimitive.weightBits = weightBits;
            forPrimitive.keepTriangleOrder = drawnInOrder(scene, primitive.material);
            encodings.push_back({&primitive,
                                 std::move(forPrimitive),
                                 {},
                                 nullptr,
                                 {},
                                 {},
                                 integerGrids[m] ? &*integerGrids[m] : nullptr});
            if (!primitive.targets.empty()) encodings.back().morphWeights = largestMorphWeights(scene, m);
        }
    withThreads(options.threads, [&] {
        tbb::parallel_for(std::size_t(0), encodings.size(), [&](std::size_t e) {
            Encoding& encoding = encodings[e];
            try {
                encoding.encoded = encodePrimitive(*encoding.primitive, encoding.options, file);
                // Vertices Draco does not hold rounded by meshopt's filter, where meshopt codes the data.
                if (codeData && encoding.encoded.plain && options.draco) {
                    if (encoding.primitive->topology != Topology::Triangles)
                        encoding.primitive =
                            &encoding.sorted.emplace(spatiallySorted(*encoding.primitive, encoding.integerGrid));
                    encoding.encoded.rounded = roundedPlainVertices(*encoding.primitive, encoding.options,
                                                                    encoding.morphWeights, encoding.integerGrid);
                }
            } catch (...) {
                encoding.error = std::current_exception();
            }
        });
    });
    std::vector<Json> written(encodings.size());  // each encoding's primitives as written, without a material
    std::size_t next = 0;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        Json primitives = Json::array();
        for (const Primitive& primitive : scene.meshes[m].primitives) {
            if (primitive.drawsNothing()) continue;
            const std::size_t e = encodingOf[next++];
            Encoding& encoding = encodings[e];
            if (encoding.error) std::rethrow_exception(encoding.error);
            if (written[e].is_null()) {
                usesQuantization = usesQuantization || needsMeshQuantization(encoding.encoded.rounded);
                written[e] = Json::array();
                addPrimitive(builder, *encoding.primitive, encoding.encoded, written[e]);
                for (Json& part : written[e]) part.erase("material");
                encoding.encoded = {};  // its bytes are in the buffer now
            }
            for (Json part : written[e]) {
                if (primitive.material >= 0) {
                    part["material"] = materialIndex[std::size_t(primitive.material)];
                    putVariantMappings(scene.materials[std::size_t(primitive.material)], materialIndex, part);
                }
                // Only where a primitive is Draco's (a morphed one never is): a required extension names what a
                // viewer must decode.
                usedDraco = usedDraco ||
                            (part.contains("extensions") && part["extensions"].contains("KHR_draco_mesh_compression"));
                primitives.push_back(std::move(part));
            }
        }
        if (primitives.empty()) continue;
        Json mesh = {{"primitives", primitives}};
        if (!scene.meshes[m].name.empty()) mesh["name"] = scene.meshes[m].name;
        if (!scene.meshes[m].weights.empty()) mesh["weights"] = scene.meshes[m].weights;
        putExtras(mesh, scene.meshes[m].extrasJson);
        root["meshes"].push_back(mesh);
        meshIndex[m] = static_cast<int>(root["meshes"].size()) - 1;
    }
    const GpuInstancingPlan gpu = planGpuInstancing(scene, meshIndex, options);
    const NodeNumbering numbering(scene, gpu);
    // A node's translation moves all it draws: it takes a small share of the budget for positions.
    const double translationPrecision = options.maxPositionError / 16;
    std::vector<Json> extraNodes;
    const std::vector<bool> animated = nodesAnimationsAndSkinsMove(scene);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        if (gpu.batchOf[n] >= 0) continue;
        Node node = scene.nodes[n];
        node.children = numbering.list(node.children);
        if (node.mesh >= 0 && meshIndex[std::size_t(node.mesh)] >= 0 && integerGrids[std::size_t(node.mesh)])
            undoGrid(node, animated[n], *integerGrids[std::size_t(node.mesh)], meshIndex[std::size_t(node.mesh)],
                     numbering.written, extraNodes);
        root["nodes"].push_back(writeNode(node, meshIndex, numbering.written, extraNodes, translationPrecision));
        putPassedExtensions(root["nodes"].back(), node.extensionsJson, extensions);
    }
    if (usesQuantization) extensions.add("KHR_mesh_quantization", true);
    writeGpuBatches(gpu, scene, meshIndex, builder, root);
    if (!gpu.batches.empty()) extensions.add("EXT_mesh_gpu_instancing", true);
    for (Json& node : extraNodes) root["nodes"].push_back(std::move(node));
    // A scene of no nodes leaves them out: glTF's `nodes`, where given, holds one at least.
    root["scenes"] = Json::array({Json::object()});
    if (!scene.roots.empty()) root["scenes"][0]["nodes"] = numbering.list(scene.roots);
    if (!scene.name.empty()) root["scenes"][0]["name"] = scene.name;
    putExtras(root["scenes"][0], scene.sceneExtrasJson);
    putPassedExtensions(root["scenes"][0], scene.sceneExtensionsJson, extensions);
    putPassedExtensions(root["asset"], scene.assetExtensionsJson, extensions);
    putPassedExtensions(root, scene.extensionsJson, extensions);
    putExtras(root, scene.rootExtrasJson);
    root["scene"] = 0;
    // Animations and skins name nodes that are never batched, renumbered as the nodes are.
    // Their key values rounded within the budget where meshopt's filters can hold them.
    for (Animation animation : scene.animations) {
        const std::vector<KeyValues> stored =
            codeData ? withThreads(options.threads,
                                   [&] { return roundedKeyValues(scene, animation, options.animationKeyError); })
                     : std::vector<KeyValues>();
        for (AnimationChannel& channel : animation.channels) channel.node = numbering.index[std::size_t(channel.node)];
        root["animations"].push_back(writeAnimation(animation, stored, builder));
    }
    for (Skin skin : scene.skins) {
        for (int& joint : skin.joints) joint = numbering.index[std::size_t(joint)];
        if (skin.skeleton >= 0) skin.skeleton = numbering.index[std::size_t(skin.skeleton)];
        root["skins"].push_back(writeSkin(skin, builder));
    }
    for (const Camera& camera : scene.cameras) root["cameras"].push_back(writeCamera(camera));
    for (const Light& light : scene.lights)
        root["extensions"]["KHR_lights_punctual"]["lights"].push_back(writeLight(light));
    if (usedDraco) extensions.add("KHR_draco_mesh_compression", true);
    // Required: the fallback buffer holds no data for a viewer that cannot decode the views (GPU batches,
    // animations, skins).
    if (builder.fallbackBytes()) extensions.add("EXT_meshopt_compression", true);
    if (!scene.lights.empty()) extensions.add("KHR_lights_punctual", false);
    if (!scene.materialVariants.empty()) {
        Json& variants = root["extensions"]["KHR_materials_variants"]["variants"] = Json::array();
        for (const MaterialVariant& variant : scene.materialVariants) {
            Json written = {{"name", variant.name}};
            putExtras(written, variant.extrasJson);
            variants.push_back(std::move(written));
        }
        extensions.add("KHR_materials_variants", false);
    }
    for (const std::string& extension : extensions.used) root["extensionsUsed"].push_back(extension);
    for (const std::string& extension : extensions.required) root["extensionsRequired"].push_back(extension);

    out.binary = std::move(builder.binary());
    out.fallbackBytes = builder.fallbackBytes();
    return out;
}

}  // namespace

void writeGltf(const Scene& scene, const fs::path& file, const WriteOptions& options) {
    // Compressed output with data Draco does not code is built twice, that data plain and coded by meshopt, and
    // the smaller kept (a file with no other meshopt view pays for its fallback buffer and the extension's names);
    // the primitives' Draco encodings are made once for both.
    const bool dataToCode =
        options.draco && options.gpuInstancing &&
        (!scene.animations.empty() || !scene.skins.empty() ||
         std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& mesh) {
             return std::any_of(mesh.primitives.begin(), mesh.primitives.end(), [](const Primitive& p) {
                 return !p.targets.empty() || p.topology != Topology::Triangles;
             });
         }));
    WriteOptions once = options;
    if (dataToCode && !once.encodings) once.encodings = makePrimitiveEncodings();
    GltfFile built = buildGltf(scene, file, once, false);
    if (dataToCode)
        if (GltfFile coded = buildGltf(scene, file, once, true); coded.bytes() < built.bytes())
            built = std::move(coded);
    Json& root = built.root;
    const std::vector<unsigned char>& binary = built.binary;
    const Json fallback = built.fallbackBuffer();
    if (formatFromExtension(file) == FileFormat::Glb) {
        if (!binary.empty()) root["buffers"] = {{{"byteLength", binary.size()}}};
        if (built.fallbackBytes) root["buffers"].push_back(fallback);
        writeFileAtomically(file, glbFile(root, binary));
        return;
    }
    // .gltf: the binary data in a .bin beside it, written first so that the JSON never points at nothing.
    if (!binary.empty()) {
        const fs::path bin = fs::path(file).replace_extension(".bin");
        root["buffers"] = {{{"byteLength", binary.size()}, {"uri", uriEncodedPath(bin.filename().string())}}};
        if (built.fallbackBytes) root["buffers"].push_back(fallback);
        writeFileAtomically(bin, std::string_view(reinterpret_cast<const char*>(binary.data()), binary.size()));
    }
    writeFileAtomically(file, jsonText(root, 1));
}

}  // namespace symcompress
