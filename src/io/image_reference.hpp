// Where a writer points at an image it could not embed (Texture::bytes empty, Texture::uri where the reader
// looked for it): a URL as it is, a path relative to the output file's folder.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace symcompress {

inline std::string imageReference(const std::string& uri, const std::filesystem::path& output) {
    if (uri.empty() || uri.find("://") != std::string::npos || uri.rfind("data:", 0) == 0) return uri;
    std::error_code error;
    const std::filesystem::path image = std::filesystem::absolute(uri, error);
    const std::filesystem::path relative =
        std::filesystem::relative(image, std::filesystem::absolute(output, error).parent_path(), error);
    return (error || relative.empty() ? image : relative).generic_string();
}

}  // namespace symcompress
