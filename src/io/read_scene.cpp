#include "symcompress/atomic_file.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <cctype>

namespace symcompress {
namespace fs = std::filesystem;

FileFormat formatFromExtension(const fs::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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

void writeScene(const Scene& scene, const fs::path& file, const WriteOptions& options,
                const std::vector<fs::path>& inputs) {
    refuseToOverwriteInputs(file, inputs);
    switch (formatFromExtension(file)) {
        case FileFormat::Gltf:
        case FileFormat::Glb: writeGltf(scene, file, options); break;
        case FileFormat::X3d: writeX3d(scene, file, options); break;
        case FileFormat::Obj: writeObj(scene, file, options); break;
        case FileFormat::Ply: writePly(scene, file, options); break;
        case FileFormat::Stl: throw FileError(file, "writing STL is not supported (use .glb, .gltf, .x3d, .obj or .ply)");
    }
}

}  // namespace symcompress
