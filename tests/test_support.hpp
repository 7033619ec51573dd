// Shared helpers for the tests: temporary folders, the shared models, running the tools.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace symcompress::testing {

inline std::filesystem::path sharedDir() { return SYMCOMPRESS_SHARED_DIR; }
inline std::filesystem::path modelPath(const std::string& relative) { return sharedDir() / "models" / relative; }

// A fresh folder under the system's temporary folder, removed when the object goes out of scope.
class TemporaryFolder {
public:
    TemporaryFolder() {
        std::random_device entropy;
        path_ = std::filesystem::temp_directory_path() / ("symcompress-test-" + std::to_string(entropy()));
        std::filesystem::create_directories(path_);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ignored);
        std::filesystem::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

inline void writeTextFile(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
}

inline std::string readTextFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct CommandResult {
    int status = -1;
    std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing what it prints.
inline CommandResult runCommand(const std::string& commandLine) {
    CommandResult result;
    std::FILE* pipe = ::popen((commandLine + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t got;
    while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, got);
    const int status = ::pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

// The peers in ../shared/bench (Node.js tools) are used when installed and not switched off.
inline bool interopAvailable() {
    if (std::getenv("SYMCOMPRESS_SKIP_INTEROP")) return false;
    return std::filesystem::exists(sharedDir() / "bench/node/node_modules/gltf-validator") &&
           runCommand("node --version").status == 0;
}
inline bool x3dInteropAvailable() {
    if (std::getenv("SYMCOMPRESS_SKIP_INTEROP")) return false;
    return std::filesystem::exists(sharedDir() / "bench/x3d/node_modules/x_ite-node") &&
           runCommand("node --version").status == 0;
}

}  // namespace symcompress::testing
