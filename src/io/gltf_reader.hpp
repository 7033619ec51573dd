// The glTF reader's parts (gltf_loading.cpp: the file to a tinygltf model; gltf_accessors.cpp: vertex data
// from accessors and Draco; gltf_reader.cpp: the model to a Scene), and the helpers they share.
#pragma once

#include "symcompress/io.hpp"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <Eigen/Core>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace symcompress {

// The file's bytes, checked and mended where tinygltf would fail on a valid file or crash on a broken one,
// parsed by tinygltf, EXT_meshopt_compression views decoded. Throws FileError.
tinygltf::Model loadGltfModel(const std::filesystem::path& file);

// What to do with a glTF 1.0 file, which symcompress does not read: gltf-pipeline (CesiumGS) upgrades it as it writes.
inline constexpr const char* kConvertToGltf2 =
    "convert it to glTF 2.0 (for example with gltf-pipeline: gltf-pipeline -i old.gltf -o new.glb)";

// Refuses (FileError) what glTF 2.0 does not allow in the file's JSON and tinygltf takes, or refuses without saying
// where: another glTF version, an index by which geometry is found that names nothing, an accessor's componentType
// or type that glTF has not (gltf_structure.cpp).
void refuseBrokenStructure(const nlohmann::json& gltf, const std::filesystem::path& file);

// "node 0 refers to mesh 5, but the file has 1 mesh" (`referrer` "node 0", `kind` "mesh"), with " for its ROLE"
// after the index where `role` is given (a primitive's "indices", an attribute's name).
std::string referenceProblem(const std::string& referrer, const std::string& kind, std::int64_t index,
                             std::size_t count, const std::string& role = "");

// Whether symcompress reads the extension (the others are warned about, or refused where required).
bool readExtension(const std::string& name);

// object[key], or a null value where `object` is not an object or has no such key (tinygltf's Get asserts).
inline const tinygltf::Value& member(const tinygltf::Value& object, const std::string& key) {
    static const tinygltf::Value none;
    return object.Has(key) ? object.Get(key) : none;
}

inline double numberOr(const tinygltf::Value& value, double fallback) {
    return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

// An index held in an extension's value: -1 unless it is a whole number from 0 to INT_MAX (GetNumberAsInt
// casts a real number unchecked, which is undefined for one that does not fit).
inline int indexIn(const tinygltf::Value& value) {
    if (value.IsInt()) return value.Get<int>();
    if (!value.IsReal()) return -1;
    const double number = value.Get<double>();
    return number >= 0 && number <= std::numeric_limits<int>::max() && number == std::floor(number) ? int(number) : -1;
}

// The components of an accessor type (TINYGLTF_TYPE_SCALAR: 1, ..., MAT4: 16; 0 for an unknown one).
int componentCount(int type);

// glTF's triangle topologies (list, strip, fan) as a triangle list.
std::vector<Triangle> trianglesFromIndices(const std::vector<std::uint32_t>& indices, int mode);
// The same for glTF's line topologies (LINES, LINE_LOOP, LINE_STRIP): the segments they draw.
std::vector<Segment> segmentsFromIndices(const std::vector<std::uint32_t>& indices, int mode);

// Flat components as vectors (components beyond the vector's size dropped, missing ones 0).
template <typename Vector>
std::vector<Vector> toVectors(const std::vector<double>& flat, int components) {
    std::vector<Vector> out(flat.size() / components, Vector::Zero());
    for (std::size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < std::min<int>(components, Vector::RowsAtCompileTime); ++c)
            out[i][c] = flat[i * components + c];
    return out;
}

// RGB or RGBA components as RGBA colours (alpha 1 where there is none).
std::vector<Eigen::Vector4d> toColors(const std::vector<double>& flat, int components);

class GltfReader {
public:
    GltfReader(const std::filesystem::path& file, const tinygltf::Model& model) : file_(file), model_(model) {}

    Scene read();

private:
    [[noreturn]] void fail(const std::string& problem) const { throw FileError(file_, problem); }
    std::vector<double> readAccessor(int accessorIndex, int expectedComponents, const char* what) const;
    std::vector<std::uint32_t> readIndices(int accessorIndex) const;
    void readPrimitive(const tinygltf::Primitive& source, Mesh& mesh, Scene& scene, const std::string& where);
    void decodeDracoPrimitive(const tinygltf::Primitive& source, const tinygltf::Value& extension, Primitive& out,
                              std::vector<std::uint32_t>& indices, const std::string& where);
    // The attributes the scene model has fields for (the others are Primitive::attributes).
    static bool isCoreAttribute(const std::string& name) {
        return name == "POSITION" || name == "NORMAL" || name == "TEXCOORD_0" || name == "COLOR_0";
    }
    // The components of the accessor an attribute `name` names, or 0 (with a warning) where that is no vertex
    // attribute (a matrix, an unknown type; a missing accessor is refused when read).
    int vertexAttributeComponents(int accessor, const std::string& name, const std::string& where);
    std::vector<MorphTarget> readMorphTargets(const tinygltf::Primitive& source, std::size_t vertices,
                                              const std::string& where);
    void keepConsistentMorphTargets(Mesh& mesh, const std::string& where);
    void readSkins(Scene& scene);
    Eigen::Matrix4d nodeTransform(const tinygltf::Node& node) const;
    void readMaterials(Scene& scene);
    void readMaterialVariants(Scene& scene);
    // The material a primitive of `material` draws with, given its extensions: one with the table of the materials
    // KHR_materials_variants maps it to (Material::variants), where it maps any.
    int materialUnderVariants(int material, const std::string& extensionsJson, Scene& scene, const std::string& where);
    int sceneTexture(int gltfTexture, Scene& scene, const std::string& where);
    // The file's image `imageIndex` (in range): its bytes as read (none, with a warning, where they could not be),
    // their type, and where the file is when it is not embedded.
    ImageFile readImageFile(int imageIndex);
    TextureRef readTextureUse(int gltfTexture, int texCoord, double scale, const std::string& extensionsJson,
                              Scene& scene, const std::string& where);
    std::optional<TextureTransform> readTextureTransform(const std::string& extensionsJson, const std::string& where);
    std::optional<MaterialExtension> readMaterialExtension(const std::string& name, nlohmann::json object, Scene& scene,
                                                           const std::string& where);
    static std::string extrasOf(const std::string& extrasJson);  // tinygltf's extras text as compact JSON
    void readAnimations(Scene& scene);
    void readCamerasAndLights(Scene& scene);
    void expandGpuInstances(Scene& scene);
    void warnAbout(const std::string& warning) { warnings_.insert(warning); }

    std::filesystem::path file_;
    const tinygltf::Model& model_;
    std::set<std::string> warnings_;
    std::map<std::string, int> skippedModes_;
    std::size_t primitivesWithExtras_ = 0;
    std::map<int, int> textureOfGltfTexture_;  // glTF texture -> scene texture (-1: none)
    std::set<std::string> materialExtensions_;  // the names of the extensions kept on materials
    std::map<std::pair<int, std::vector<int>>, int> materialWithVariants_;  // (default, table) -> scene material
};

}  // namespace symcompress
