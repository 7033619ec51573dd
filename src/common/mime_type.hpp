// The image type a file name or URI says, for the readers that find images by name (glTF URIs, X3D
// urls, OBJ's map_Kd).
#pragma once

#include <string>

namespace symcompress {

// "image/png" or "image/jpeg" by the extension (any case), else "" (unknown: the writer's default).
std::string imageMimeType(const std::string& nameOrUri);

}  // namespace symcompress
