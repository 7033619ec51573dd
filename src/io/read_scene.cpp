#include "file_metadata.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "x3d_materials.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

std::string lowercaseExtension(const fs::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

}  // namespace

FileFormat formatFromExtension(const fs::path& file) {
    const std::string extension = lowercaseExtension(file);
    if (extension == ".gltf") return FileFormat::Gltf;
    if (extension == ".glb") return FileFormat::Glb;
    if (extension == ".x3d" || extension == ".x3dz") return FileFormat::X3d;
    if (extension == ".obj") return FileFormat::Obj;
    if (extension == ".ply") return FileFormat::Ply;
    if (extension == ".stl") return FileFormat::Stl;
    throw FileError(file, "unknown file type '" + extension +
                              "' (expected .gltf, .glb, .x3d, .x3dz, .obj, .ply or .stl)");
}

Scene readScene(const fs::path& file) {
    const FileFormat format = formatFromExtension(file);
    std::error_code error;
    if (!fs::exists(file, error)) throw FileError(file, "no such file");
    if (fs::is_directory(file, error)) throw FileError(file, "is a directory, not a file");
    Scene scene;
    switch (format) {
        case FileFormat::Gltf:
        case FileFormat::Glb: scene = readGltf(file); break;
        case FileFormat::X3d: scene = readX3d(file); break;
        case FileFormat::Obj: scene = readObj(file); break;
        case FileFormat::Ply: scene = readPly(file); break;
        case FileFormat::Stl: scene = readStl(file); break;
    }
    if (const std::size_t replaced = repairNormals(scene))
        scene.warnings.push_back(file.filename().string() + ": " + std::to_string(replaced) +
                                 " normals of zero length replaced by the normals of their triangles");
    try {
        validateScene(scene);
    } catch (const std::invalid_argument& broken) {
        throw FileError(file, std::string("the reader produced an inconsistent scene: ") + broken.what());
    }
    return scene;
}

std::vector<std::string> formatLosses(const Scene& scene, const fs::path& file) {
    const FileFormat format = formatFromExtension(file);
    std::vector<std::string> losses;
    if (format != FileFormat::X3d && !scene.x3dEnvironment.empty()) {
        // Each is the XML text of one node: its type is the element's name.
        std::map<std::string, int> types;
        for (const std::string& node : scene.x3dEnvironment) ++types[node.substr(1, node.find_first_of(" />") - 1)];
        std::string list;
        for (const auto& [type, count] : types) list += (list.empty() ? "" : ", ") + std::to_string(count) + " " + type;
        losses.push_back("X3D's " + list + " not written: " + file.extension().string() + " output has no place for them");
    }
    if (format != FileFormat::X3d) {
        const std::size_t attenuated = std::count_if(scene.lights.begin(), scene.lights.end(),
                                                     [](const Light& light) { return light.x3dAttenuation.has_value(); });
        if (attenuated)
            losses.push_back(std::to_string(attenuated) + " X3D lights' attenuation not written: " +
                             file.extension().string() + " lights fall off with the inverse square of the distance");
    }
    if (format == FileFormat::Ply) {
        // A PLY file holds lines nowhere, and points only as the vertices of a file without faces.
        std::size_t segments = 0, points = 0, triangles = 0;
        for (const Mesh& mesh : scene.meshes)
            for (const Primitive& primitive : mesh.primitives) {
                segments += primitive.lines.size();
                triangles += primitive.triangles.size();
                if (primitive.topology == Topology::Points) points += primitive.positions.size();
            }
        const std::size_t lostPoints = triangles || segments ? points : 0;
        if (segments || lostPoints)
            losses.push_back(std::to_string(segments) + " line segments and " + std::to_string(lostPoints) +
                             " points not written: PLY output holds faces, and points only in a file without them");
    }
    if (format == FileFormat::Glb || format == FileFormat::Gltf) return losses;
    const std::string extension = file.extension().string();
    if (format != FileFormat::X3d) {
        const std::size_t notes = metaTags(writtenExtras(scene.extrasJson, "")).size() + !scene.copyright.empty();
        if (notes)
            losses.push_back(std::to_string(notes) + " notes of what the file says about itself (copyright, asset " +
                             "extras, X3D meta tags) not written: " + extension + " output has no place for them");
    }
    const std::size_t passed =
        !scene.extensionsJson.empty() + !scene.assetExtensionsJson.empty() + !scene.sceneExtensionsJson.empty() +
        std::count_if(scene.nodes.begin(), scene.nodes.end(), [](const Node& n) { return !n.extensionsJson.empty(); });
    if (passed)
        losses.push_back("glTF extensions passed through on " + std::to_string(passed) +
                         " objects (the file, its asset, scene or nodes: KHR_xmp_json_ld) not written: " + extension +
                         " output has no place for them");
    if (!scene.materialVariants.empty())
        losses.push_back(std::to_string(scene.materialVariants.size()) +
                         " material variants (KHR_materials_variants) not written: " + extension +
                         " output draws each primitive's default material");
    std::set<std::string> attributes;
    std::size_t morphed = 0, weightChannels = 0;
    for (const Mesh& mesh : scene.meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            // X3D writes the texture coordinate sets its material's textures read (x3d_materials.hpp).
            std::set<std::string> written;
            // And TANGENT, as X3D 4's Tangent, where a normal texture reads it (with the normals).
            if (format == FileFormat::X3d && primitive.material >= 0) {
                const x3d::MaterialTextures textures =
                    x3d::materialTextures(scene.materials[std::size_t(primitive.material)]);
                for (const x3d::TexcoordChannel& channel : textures.channels)
                    written.insert("TEXCOORD_" + std::to_string(channel.set));
                for (const x3d::TextureField& field : textures.fields)
                    if (std::string(field.field) == "normalTexture" && !primitive.normals.empty())
                        written.insert("TANGENT");
            }
            for (const VertexAttribute& attribute : primitive.attributes)
                if (!written.count(attribute.name)) attributes.insert(attribute.name);
        }
        morphed += morphTargetCount(mesh) > 0;
    }
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels)
            weightChannels += channel.path == AnimationChannel::Path::Weights;
    if (!attributes.empty()) {
        std::string list;
        for (const std::string& name : attributes) list += (list.empty() ? "" : ", ") + name;
        losses.push_back("vertex attributes " + list + " not written: " + extension + " output has no place for them");
    }
    if (morphed)
        losses.push_back(std::to_string(morphed) + " meshes' morph targets not written (" + std::to_string(weightChannels) +
                         " animation channels of their weights with them): " + extension + " output draws the base shape");
    if (!scene.skins.empty())
        losses.push_back(std::to_string(scene.skins.size()) + " skins not written: " + extension +
                         " output draws skinned meshes where their nodes place them, unskinned");
    // OBJ's and PLY's materials hold a colour and one texture (transformed into the coordinates). X3D's hold the
    // five core textures with their samplers (x3d_materials.hpp), transformed into the coordinates, but a Phong
    // material (one read from X3D) no metallic-roughness texture, and no X3D material glTF's extensions.
    const bool x3d = format == FileFormat::X3d;
    const std::size_t richer = std::count_if(scene.materials.begin(), scene.materials.end(), [&](const Material& m) {
        const auto refs = m.textureRefs();
        const auto firstDropped = x3d ? refs.begin() + 5 : refs.begin() + 1;
        bool dropped = std::any_of(firstDropped, refs.end(), [](const TextureRef* use) { return use->texture >= 0; });
        if (x3d && m.phong) dropped = dropped || m.metallicRoughnessTexture.texture >= 0;
        const bool sampled = !x3d && m.baseColorTexture.texture >= 0 &&
                             !(scene.textures[std::size_t(m.baseColorTexture.texture)].sampler == TextureSampler{});
        const bool extended = std::any_of(m.extensions.begin(), m.extensions.end(), [&](const MaterialExtension& e) {
            return !(x3d && e.name == "KHR_materials_unlit" && x3d::isUnlit(m));  // X3D's UnlitMaterial
        });
        return dropped || sampled || extended;
    });
    if (richer)
        losses.push_back(std::to_string(richer) + " materials written " +
                         (x3d ? "with their core textures only: their extensions and other textures have"
                              : "with their base colour only: their other textures, samplers and extensions have") +
                         " no place in " + file.extension().string() + " output");
    if (format == FileFormat::Obj) {
        std::size_t translucent = 0;  // meshes with vertex colours that are not opaque
        for (const Mesh& mesh : scene.meshes)
            translucent += std::any_of(mesh.primitives.begin(), mesh.primitives.end(), [](const Primitive& p) {
                return std::any_of(p.colors.begin(), p.colors.end(),
                                   [](const Eigen::Vector4d& c) { return c[3] != 1; });
            });
        if (translucent)
            losses.push_back(std::to_string(translucent) + " meshes' vertex colours written without their alpha: " +
                             extension + " output holds red, green and blue only");
    }
    if (format != FileFormat::X3d) {
        if (!scene.animations.empty())
            losses.push_back(std::to_string(scene.animations.size()) + " animations not written: " + extension +
                             " output is drawn at rest");
        if (!scene.cameras.empty() || !scene.lights.empty())
            losses.push_back(std::to_string(scene.cameras.size()) + " cameras and " + std::to_string(scene.lights.size()) +
                             " lights not written: " + extension + " output holds geometry only");
        return losses;
    }
    std::size_t cubic = 0;
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels)
            cubic += channel.interpolation == AnimationChannel::Interpolation::CubicSpline;
    if (cubic)
        losses.push_back(std::to_string(cubic) + " cubic-spline animation channels written as linear between " +
                         "their keys (X3D 3.3 has no cubic orientation interpolator)");
    const std::size_t bright = std::count_if(scene.lights.begin(), scene.lights.end(), [](const Light& light) { return light.intensity > 1; });
    if (bright)
        losses.push_back(std::to_string(bright) + " lights brighter than 1 written with intensity 1 (X3D's largest; " +
                         "glTF's intensities are in candela or lux)");
    return losses;
}

void checkOutputFile(const fs::path& file, const std::vector<fs::path>& inputs) {
    const std::string extension = lowercaseExtension(file);
    if (extension == ".stl")
        throw FileError(file, "writing STL is not supported (use .glb, .gltf, .x3d, .obj or .ply)");
    if (extension != ".gltf" && extension != ".glb" && extension != ".x3d" && extension != ".x3dz" &&
        extension != ".obj" && extension != ".ply")
        throw FileError(
            file, "cannot write a file of type '" + extension + "' (expected .glb, .gltf, .x3d, .x3dz, .obj or .ply)");
    std::error_code error;
    if (fs::is_directory(file, error)) throw FileError(file, "is a directory, not a file");
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    if (!fs::is_directory(folder, error)) throw FileError(file, "the folder " + folder.string() + " does not exist");
    refuseToOverwriteInputs(file, inputs);
}

void writeScene(const Scene& scene, const fs::path& file, const WriteOptions& options,
                const std::vector<fs::path>& inputs) {
    checkOutputFile(file, inputs);
    switch (formatFromExtension(file)) {
        case FileFormat::Gltf:
        case FileFormat::Glb: writeGltf(scene, file, options); break;
        case FileFormat::X3d: writeX3d(scene, file, options); break;
        case FileFormat::Obj: writeObj(scene, file, options); break;
        case FileFormat::Ply: writePly(scene, file, options); break;
        case FileFormat::Stl: break;  // refused by checkOutputFile
    }
}

}  // namespace symcompress
