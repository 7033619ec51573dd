// symdecompress: reads a symcompress output (or any scene), writes it with every instance expanded, and
// verifies the rebuilt surface against the original or the digest stored in the file.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace fs = std::filesystem;
using namespace symcompress;

namespace {

constexpr int kVerified = 0, kNotVerified = 1, kBadInput = 2;
// Beyond the symmetry tolerance, the rebuilt surface may differ by Draco's quantization: half a step of
// the position grid, 2^-bits of the largest mesh extent; 14 bits and a mesh as large as the scene bound it.
constexpr double kQuantizationAllowance = 1.0 / (1 << 13);
// Share of the area that may face the other way: slivers that quantization turns over.
constexpr double kFlippedAllowance = 1e-4;

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"symdecompress: rebuilds the full geometry of a scene, every instance expanded, and verifies it"};
    app.set_version_flag("--version", "symdecompress 0.1.0");
    fs::path input, output, original;
    bool json = false;
    WriteOptions options;
    options.draco = false;  // the expanded scene is the reference geometry: keep it exact
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
    Scene scene, reference;
    try {
        scene = readScene(input);
        if (!original.empty()) reference = readScene(original);
    } catch (const FileError& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return kBadInput;
    }
    try {
        Scene flat = expandInstances(scene);
        for (std::string& loss : formatLosses(flat, output)) flat.warnings.push_back(std::move(loss));
        for (std::size_t i = scene.warnings.size(); i < flat.warnings.size(); ++i)
            std::fprintf(stderr, "warning: %s\n", flat.warnings[i].c_str());
        writeScene(flat, output, options, {input});
        const TriangleMesh rebuilt = worldMesh(flat);
        const SurfaceDigest rebuiltDigest = digestOf(rebuilt, 0);
        SurfaceDigest stored;
        const bool haveDigest = SurfaceDigest::fromJson(scene.extrasJson, stored);
        nlohmann::json out{{"input", input.string()}, {"output", output.string()}, {"triangles", rebuiltDigest.triangles}};
        bool verified = false;
        double allowed = kQuantizationAllowance;
        if (!original.empty()) {
            const TriangleMesh referenceMesh = worldMesh(reference);
            if (haveDigest) allowed += stored.tolerance;
            const SurfaceComparison comparison = compareSurfaces(rebuilt, referenceMesh, allowed);
            out["against"] = original.string();
            out["max_deviation"] = comparison.maxDeviation;
            out["area_ratio"] = comparison.areaRatio;
            out["same_bounds"] = comparison.sameBounds;
            out["flipped_area"] = comparison.flippedArea;
            out["triangles_original"] = referenceMesh.triangles.size();
            // Triangle counts may differ: fundamental regions split the triangles their planes cut. The
            // surfaces must agree: distance both ways, area, bounds.
            // Orientation: quantization may turn over a sliver or two, not a part.
            verified = comparison.maxDeviation <= allowed && std::abs(comparison.areaRatio - 1) <= 10 * allowed &&
                       comparison.sameBounds && comparison.flippedArea <= kFlippedAllowance;
        } else if (haveDigest) {
            allowed += stored.tolerance;
            const double diagonal = stored.bounds.isEmpty() ? 0 : stored.bounds.diagonal().norm();
            const double boundsError =
                diagonal > 0 ? std::max((rebuiltDigest.bounds.min() - stored.bounds.min()).cwiseAbs().maxCoeff(),
                                        (rebuiltDigest.bounds.max() - stored.bounds.max()).cwiseAbs().maxCoeff()) / diagonal
                             : 0;
            out["against"] = "digest";
            out["area_ratio"] = stored.area > 0 ? rebuiltDigest.area / stored.area : 0;
            out["bounds_deviation"] = boundsError;
            out["max_deviation"] = boundsError;  // the digest has no surface: the bounds are what can be compared
            out["triangles_original"] = stored.triangles;
            verified = boundsError <= allowed && std::abs(out["area_ratio"].get<double>() - 1) <= 10 * allowed;
        } else {
            out["against"] = nullptr;
        }
        out["verified"] = verified;
        out["allowed_deviation"] = allowed;
        if (json) {
            std::cout << out.dump(2) << '\n';
        } else {
            std::printf("%s -> %s: %zu triangles\n", input.string().c_str(), output.string().c_str(), rebuiltDigest.triangles);
            if (out["against"].is_null())
                std::printf("  no original given and no symcompress digest in the file: nothing to verify against\n");
            else
                std::printf("  against %s: max deviation %.2e of the diagonal (allowed %.2e), area ratio %.9f: %s\n",
                            out["against"].get<std::string>().c_str(), out["max_deviation"].get<double>(), allowed,
                            out["area_ratio"].get<double>(), verified ? "verified" : "NOT VERIFIED");
        }
        if (out["against"].is_null()) return kVerified;
        return verified ? kVerified : kNotVerified;
    } catch (const FileError& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return kBadInput;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "symdecompress: %s\n", error.what());
        return 1;
    }
}
