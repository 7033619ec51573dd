// The texture of an image file a scene file names (OBJ's map_Kd, PLY's TextureFile comment), read beside it.
#pragma once

#include "symcompress/scene.hpp"

#include <filesystem>
#include <string>

namespace symcompress {

// The image `name` (as the file writes it, '\' read as '/') in `folder`: its bytes and type; where it is not
// there, no bytes and the path it was looked for at (the writers refer to it relative to their output), and
// `found` false, for the caller's warning.
Texture textureOfImageFile(const std::filesystem::path& folder, std::string name, bool& found);

}  // namespace symcompress
