// The material model's helpers (scene.hpp): a material's texture uses, KHR_texture_transform's matrix.
#include "symcompress/scene.hpp"

#include <cmath>

namespace symcompress {

Eigen::Matrix<double, 2, 3> TextureTransform::matrix() const {
    // translation(offset) * rotation(rotation) * scale(scale), as KHR_texture_transform defines it.
    const double c = std::cos(rotation), s = std::sin(rotation);
    Eigen::Matrix<double, 2, 3> out;
    out << c * scale.x(), s * scale.y(), offset.x(), -s * scale.x(), c * scale.y(), offset.y();
    return out;
}

std::vector<TextureRef*> Material::textureRefs() {
    std::vector<TextureRef*> out = {&baseColorTexture, &metallicRoughnessTexture, &normalTexture, &occlusionTexture,
                                    &emissiveTexture};
    for (MaterialExtension& extension : extensions)
        for (auto& [key, texture] : extension.textures) out.push_back(&texture);
    return out;
}

std::vector<const TextureRef*> Material::textureRefs() const {
    std::vector<TextureRef*> refs = const_cast<Material*>(this)->textureRefs();
    return std::vector<const TextureRef*>(refs.begin(), refs.end());
}

}  // namespace symcompress
