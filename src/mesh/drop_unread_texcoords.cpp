#include "symcompress/scene_ops.hpp"

namespace symcompress {

std::size_t dropUnreadTexcoords(Scene& scene) {
    // Only the base colour texture is carried through, and a texture whose image could not be read is
    // written without it: nothing else reads TEXCOORD_0.
    auto readsTexcoords = [&scene](int material) {
        if (material < 0) return false;
        const int texture = scene.materials[material].baseColorTexture;
        return texture >= 0 && !scene.textures[texture].bytes.empty();
    };
    std::size_t dropped = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives)
            if (!primitive.texcoords.empty() && !readsTexcoords(primitive.material)) {
                primitive.texcoords.clear();
                primitive.texcoords.shrink_to_fit();
                ++dropped;
            }
    return dropped;
}

}  // namespace symcompress
