// The image type a file name or URI says, for the readers that find images by name (glTF URIs, X3D
// urls, OBJ's map_Kd).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace symcompress {

// "image/png", "image/jpeg", "image/webp" or "image/ktx2" by the extension (any case), else "" (unknown: the
// writer's default).
std::string imageMimeType(const std::string& nameOrUri);

// The same types by the bytes' signature, else "" (bytes that are none of these images).
std::string imageMimeTypeOfBytes(const std::vector<std::uint8_t>& bytes);

}  // namespace symcompress
