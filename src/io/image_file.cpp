#include "image_file.hpp"

#include "common/mime_type.hpp"
#include "symcompress/detail/atomic_file.hpp"

#include <algorithm>
#include <system_error>

namespace symcompress {
namespace fs = std::filesystem;

Texture textureOfImageFile(const fs::path& folder, std::string name, bool& found) {
    std::replace(name.begin(), name.end(), '\\', '/');  // paths written on Windows
    Texture texture;
    texture.uri = name;
    const fs::path image = folder / name;
    texture.mimeType = imageMimeType(image.string());
    std::error_code error;
    found = fs::is_regular_file(image, error);
    if (found)
        texture.bytes = readFileBytes(image);
    else
        texture.uri = image.lexically_normal().string();
    return texture;
}

}  // namespace symcompress
