// Whether an image draws anything translucent: what X3D's alpha mode AUTO (X3D 3's only rule) decides
// blending by, as X_ITE does (an image is transparent where some pixel's alpha is below 255).
#pragma once

#include "symcompress/scene.hpp"

#include <cstdint>
#include <map>
#include <vector>

namespace symcompress {

// PNG: decoded (libpng) where its header gives an alpha channel or a transparent colour, true where some pixel's
// alpha is below 255; true, undecoded, beyond 2^25 pixels. WebP: its header's alpha flag (not decoded). JPEG, KTX2,
// bytes that are no image or do not decode: false.
bool imageHasTranslucentPixels(const std::vector<std::uint8_t>& bytes);

// imageHasTranslucentPixels of a scene's textures by index (false for none, -1), each image decoded once.
class TranslucentTextures {
public:
    explicit TranslucentTextures(const std::vector<Texture>& textures) : textures_(textures) {}
    bool operator()(int texture);

private:
    const std::vector<Texture>& textures_;  // may grow while read: held as the vector, not its elements
    std::map<int, bool> known_;
};

}  // namespace symcompress
