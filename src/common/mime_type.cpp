#include "common/mime_type.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>

namespace symcompress {

std::string imageMimeType(const std::string& nameOrUri) {
    const std::size_t dot = nameOrUri.find_last_of('.');
    if (dot == std::string::npos) return "";
    std::string extension = nameOrUri.substr(dot + 1);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension == "png") return "image/png";
    if (extension == "jpg" || extension == "jpeg") return "image/jpeg";
    if (extension == "webp") return "image/webp";
    if (extension == "ktx2") return "image/ktx2";
    return "";
}

std::string imageMimeTypeOfBytes(const std::vector<std::uint8_t>& bytes) {
    auto startsWith = [&bytes](std::size_t at, std::string_view magic) {
        return bytes.size() >= at + magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin() + long(at),
                                                               [](char a, std::uint8_t b) { return std::uint8_t(a) == b; });
    };
    if (startsWith(0, "\x89PNG\r\n\x1a\n")) return "image/png";
    if (startsWith(0, "\xff\xd8\xff")) return "image/jpeg";
    if (startsWith(0, "RIFF") && startsWith(8, "WEBP")) return "image/webp";
    if (startsWith(0, "\xabKTX 20\xbb\r\n\x1a\n")) return "image/ktx2";
    return "";
}

}  // namespace symcompress
