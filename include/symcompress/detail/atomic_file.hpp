// Writing output files so that a failure never leaves a broken file behind.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace symcompress {

// Writes `bytes` to a temporary file beside `file`, flushes it, then renames it over `file`.
// Throws FileError (naming `file`) when the folder is missing or read-only, the disk is full, or
// `file` is a directory; the temporary file is removed on failure.
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes);

// Throws FileError when `output` is the same file as one of `inputs` (following links).
void refuseToOverwriteInputs(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs);

// Reads a whole file; throws FileError when it is missing, a directory, or unreadable.
std::vector<unsigned char> readFileBytes(const std::filesystem::path& file);

}  // namespace symcompress
