// What every fuzz target does with one input: write it as a file of the target's format, read it through
// readScene, and hand whatever is accepted to the writers. A FileError is the expected answer to a bad file;
// any other exception escapes to libFuzzer, which reports it as a finding (as it does crashes, sanitizer
// reports, leaks, timeouts and running out of memory).
#pragma once

#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace symcompress::fuzz {

// A folder of this process's own under the system's temporary folder, removed at exit: the readers take
// paths, so each input is written there first.
class ProcessFolder {
public:
    ProcessFolder() {
        std::string pattern = (std::filesystem::temp_directory_path() / "symcompress-fuzz-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) {
            std::perror("mkdtemp");
            std::abort();
        }
        path_ = pattern;
    }
    ~ProcessFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ProcessFolder(const ProcessFolder&) = delete;
    ProcessFolder& operator=(const ProcessFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline const std::filesystem::path& processFolder() {
    static const ProcessFolder folder;  // one per fuzzing process; libFuzzer runs inputs one at a time
    return folder.path();
}

inline void writeBytes(const std::filesystem::path& file, std::string_view bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
        std::perror(file.c_str());
        std::abort();
    }
}

// Writes `scene` to `output` with `options`. The writer may refuse with a FileError; what it writes must read
// back.
inline void writeAndReadBack(const Scene& scene, const std::filesystem::path& output,
                             const WriteOptions& options = {}) {
    try {
        writeScene(scene, output, options);
    } catch (const FileError&) {
        return;
    }
    try {
        readScene(output);
    } catch (const FileError& error) {
        std::fprintf(stderr, "the writer's own output does not read back: %s\n", error.what());
        std::abort();
    }
}

// Reads `files` (name, bytes; the first is the scene, the others files it may refer to, such as an OBJ's
// .mtl) from the process folder, then writes what was read as .glb and .x3d.
inline int readAndWrite(const std::vector<std::pair<std::string, std::string_view>>& files) {
    const std::filesystem::path& folder = processFolder();
    for (const auto& [name, bytes] : files) writeBytes(folder / name, bytes);
    Scene scene;
    bool accepted = true;
    try {
        scene = readScene(folder / files.front().first);
    } catch (const FileError&) {
        accepted = false;
    }
    if (accepted) {
        validateScene(scene);  // readScene promises it; an exception here is a finding
        writeAndReadBack(scene, folder / "written.glb");
        writeAndReadBack(scene, folder / "written.x3d");
        // Within an error budget, as symcompress writes: Draco's bits, meshopt's filters and integer grids chosen
        // from each primitive's own diagonal.
        WriteOptions budget;
        budget.maxPositionError = std::numeric_limits<double>::max();
        budget.maxRelativePositionError = 5e-5;
        writeAndReadBack(scene, folder / "budget.glb", budget);
    }
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(folder, ignored))
        std::filesystem::remove_all(entry.path(), ignored);
    return 0;
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
    return std::string_view(reinterpret_cast<const char*>(data), size);
}

}  // namespace symcompress::fuzz
