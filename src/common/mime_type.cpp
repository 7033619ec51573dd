#include "common/mime_type.hpp"

#include <cctype>

namespace symcompress {

std::string imageMimeType(const std::string& nameOrUri) {
    const std::size_t dot = nameOrUri.find_last_of('.');
    if (dot == std::string::npos) return "";
    std::string extension = nameOrUri.substr(dot + 1);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == "png") return "image/png";
    if (extension == "jpg" || extension == "jpeg") return "image/jpeg";
    return "";
}

}  // namespace symcompress
