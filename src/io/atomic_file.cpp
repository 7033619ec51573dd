#include "symcompress/detail/atomic_file.hpp"

#include "symcompress/io.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <random>
#include <sys/stat.h>
#include <unistd.h>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

std::string systemError(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

// A temporary name beside `file`, so that the final rename stays within one file system.
fs::path temporaryNameBeside(const fs::path& file) {
    std::random_device entropy;
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, ".%08x.tmp", static_cast<unsigned>(entropy()));
    return file.parent_path() / ("." + file.filename().string() + suffix);
}

bool writeAll(int descriptor, std::string_view bytes) {
    while (!bytes.empty()) {
        ssize_t written = ::write(descriptor, bytes.data(), bytes.size());
        if (written < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        bytes.remove_prefix(static_cast<std::size_t>(written));
    }
    return true;
}

}  // namespace

void writeFileAtomically(const fs::path& file, std::string_view bytes) {
    std::error_code error;
    if (fs::is_directory(file, error)) throw FileError(file, "is a directory, not a file");
    fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    if (!fs::is_directory(folder, error)) throw FileError(file, "the folder " + folder.string() + " does not exist");

    const fs::path temporary = temporaryNameBeside(file);
    int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor < 0) throw FileError(file, systemError("cannot create a file in its folder"));
    bool ok = writeAll(descriptor, bytes);
    std::string problem = ok ? "" : systemError("cannot write");
    if (ok && ::fsync(descriptor) != 0) {
        ok = false;
        problem = systemError("cannot flush to disk");
    }
    if (::close(descriptor) != 0 && ok) {
        ok = false;
        problem = systemError("cannot close");
    }
    if (ok && std::rename(temporary.c_str(), file.c_str()) != 0) {
        ok = false;
        problem = systemError("cannot rename the finished temporary file into place");
    }
    if (!ok) {
        ::unlink(temporary.c_str());
        throw FileError(file, problem);
    }
}

void refuseToOverwriteInputs(const fs::path& output, const std::vector<fs::path>& inputs) {
    std::error_code error;
    for (const fs::path& input : inputs) {
        if (fs::exists(output, error) && fs::equivalent(output, input, error))
            throw FileError(output, "is an input file; refusing to overwrite it");
    }
}

std::vector<unsigned char> readFileBytes(const fs::path& file) {
    std::error_code error;
    if (!fs::exists(file, error)) throw FileError(file, "no such file");
    if (fs::is_directory(file, error)) throw FileError(file, "is a directory, not a file");
    std::FILE* stream = std::fopen(file.c_str(), "rb");
    if (!stream) throw FileError(file, systemError("cannot open"));
    std::vector<unsigned char> bytes;
    unsigned char buffer[1 << 16];
    std::size_t got;
    while ((got = std::fread(buffer, 1, sizeof buffer, stream)) > 0) bytes.insert(bytes.end(), buffer, buffer + got);
    bool failed = std::ferror(stream) != 0;
    std::fclose(stream);
    if (failed) throw FileError(file, "read error");
    return bytes;
}

}  // namespace symcompress
