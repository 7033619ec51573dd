#include "symcompress/compress.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/io.hpp"

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

using namespace symcompress;
using symcompress::testing::TemporaryFolder;

namespace {
std::size_t fileCount(const std::filesystem::path& folder) {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(folder), {}));
}
}  // namespace

TEST_CASE("writeFileAtomically replaces a file whole", "[atomic]") {
    TemporaryFolder folder;
    const auto file = folder / "out.bin";
    writeFileAtomically(file, "first");
    writeFileAtomically(file, "second version");
    CHECK(symcompress::testing::readTextFile(file) == "second version");
    CHECK(fileCount(folder.path()) == 1);  // no temporary left behind
}

TEST_CASE("writeFileAtomically fails cleanly", "[atomic]") {
    TemporaryFolder folder;
    SECTION("missing folder") {
        CHECK_THROWS_AS(writeFileAtomically(folder / "no/such/out.bin", "x"), FileError);
    }
    SECTION("a directory as the file") {
        std::filesystem::create_directory(folder / "dir");
        CHECK_THROWS_WITH(writeFileAtomically(folder / "dir", "x"), Catch::Contains("directory"));
    }
    SECTION("read-only folder leaves the old file untouched") {
        if (::geteuid() == 0) {
            // root ignores permissions; the check would not test anything
            SUCCEED("skipped: running as root");
        } else {
            const auto file = folder / "out.bin";
            writeFileAtomically(file, "old");
            std::filesystem::permissions(folder.path(), std::filesystem::perms::owner_read |
                                                            std::filesystem::perms::owner_exec);
            CHECK_THROWS_AS(writeFileAtomically(file, "new"), FileError);
            std::filesystem::permissions(folder.path(), std::filesystem::perms::owner_all);
            CHECK(symcompress::testing::readTextFile(file) == "old");
        }
    }
}

TEST_CASE("refuseToOverwriteInputs recognises the input under another name", "[atomic]") {
    TemporaryFolder folder;
    const auto input = folder / "in.glb";
    symcompress::testing::writeTextFile(input, "data");
    std::filesystem::create_symlink(input, folder / "link.glb");
    CHECK_THROWS_WITH(refuseToOverwriteInputs(folder / "link.glb", {input}), Catch::Contains("input"));
    CHECK_NOTHROW(refuseToOverwriteInputs(folder / "other.glb", {input}));
}

TEST_CASE("readFileBytes reports missing files and directories", "[atomic]") {
    TemporaryFolder folder;
    CHECK_THROWS_WITH(readFileBytes(folder / "missing.obj"), Catch::Contains("no such file"));
    CHECK_THROWS_WITH(readFileBytes(folder.path()), Catch::Contains("directory"));
}

TEST_CASE("A compression whose output cannot be written says so of the output, before reading the input", "[atomic]") {
    TemporaryFolder folder;
    const auto input = testing::modelPath("menger_sponge/Menger_sponge-Binary.stl");
    auto refusal = [&](const std::filesystem::path& output) {
        try {
            compressFile(input, output);
        } catch (const FileError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    // Before, the first of these named the temporary file of a measure ('.symcompress-draco_alone-x.glb').
    const std::string missing = refusal(folder / "nowhere" / "x.glb");
    CHECK_THAT(missing,
               Catch::Contains("x.glb") && Catch::Contains("does not exist") && !Catch::Contains(".symcompress-"));
    CHECK_THAT(refusal(folder / "x.stl"),
               Catch::Contains("writing STL is not supported") && !Catch::Contains(".symcompress-"));
    CHECK_THAT(refusal(folder / "x.fbx"), Catch::Contains("cannot write a file of type '.fbx'"));
    CHECK(std::filesystem::is_empty(folder.path()));
}
