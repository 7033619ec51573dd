// A relative URI reference as glTF names its buffers and images by: RFC 3986 percent-encoding of a file name.
#pragma once

#include <cctype>
#include <string>

namespace symcompress {

// `uri` with each %XX replaced by its byte (a % not followed by two hex digits is kept as it is).
inline std::string uriDecoded(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(uri[i]);
        }
    }
    return out;
}

// A relative path as a URI reference: every byte but RFC 3986's unreserved ones and '/' percent-encoded (a space,
// '%', '#', '?' and non-ASCII bytes would otherwise be read as something else).
inline std::string uriEncodedPath(const std::string& path) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (const char c : path) {
        const auto byte = static_cast<unsigned char>(c);
        if (std::isalnum(byte) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            out.push_back(c);
        } else {
            out.push_back('%');
            out.push_back(hex[byte >> 4]);
            out.push_back(hex[byte & 15]);
        }
    }
    return out;
}

}  // namespace symcompress
