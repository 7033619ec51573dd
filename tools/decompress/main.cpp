// symdecompress: reads a symcompress output (or any scene), writes it with every instance expanded, and
// verifies the rebuilt surface against the original or the digest stored in the file. Argument parsing and
// printing over the library's decompressFile.
#include "symcompress/symcompress.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

namespace fs = std::filesystem;
using namespace symcompress;

namespace {

constexpr int kVerified = 0, kNotVerified = 1, kBadInput = 2;

void print(const RebuildReport& report) {
    std::printf("%s -> %s: %zu triangles\n", report.input.string().c_str(), report.output.string().c_str(),
                report.triangles);
    if (report.against == RebuildReport::Against::Nothing) {
        std::printf("  no original given and no symcompress digest in the file: nothing to verify against\n");
        return;
    }
    const std::string against = report.against == RebuildReport::Against::Digest ? "digest" : report.original.string();
    std::printf("  against %s: max deviation %.2e of the diagonal (allowed %.2e), area ratio %.9f: %s\n",
                against.c_str(), report.maxDeviation, report.allowedDeviation, report.areaRatio,
                report.verified ? "verified" : "NOT VERIFIED");
    if (report.posesCompared > 0)
        std::printf("  animations: %zu poses drawn, max deviation %.2e of the diagonal (allowed %.2e)\n",
                    report.posesCompared, report.posedDeviation, report.allowedPosedDeviation);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"symdecompress: rebuilds the full geometry of a scene, every instance expanded, and verifies it"};
    app.set_version_flag("--version", "symdecompress 0.1.0");
    fs::path input, output, original;
    bool json = false;
    app.add_option("IN", input, "scene file (.gltf .glb .x3d .x3dz .obj .ply .stl)")->required();
    app.add_option("-o,--output", output, "output file; its extension picks the format")->required();
    app.add_option("--verify", original, "the original scene to verify against (else the digest stored in IN)");
    app.add_flag("--json", json, "print one JSON object");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        const int status = app.exit(error);
        return status == 0 ? 0 : kBadInput;
    }
    try {
        const RebuildReport report = decompressFile(input, output, original);
        for (const std::string& warning : report.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
        if (json)
            std::cout << report.json() << '\n';
        else
            print(report);
        if (report.against == RebuildReport::Against::Nothing) return kVerified;
        return report.verified ? kVerified : kNotVerified;
    } catch (const FileError& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return kBadInput;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return 1;
    }
}
