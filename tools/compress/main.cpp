// symcompress: command-line front end. Thin: parses arguments, calls the library (symcompress.hpp), prints.
#include "symcompress/symcompress.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

namespace fs = std::filesystem;
using namespace symcompress;

namespace {

constexpr int kExitBadInput = 2;

nlohmann::json vectorJson(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

int runInfo(const fs::path& file, bool json) {
    const Scene scene = readScene(file);
    const SceneStatistics statistics = sceneStatistics(scene);
    if (json) {
        nlohmann::json out;
        out["file"] = file.string();
        out["triangles"] = statistics.trianglesDrawn;
        out["triangles_stored"] = statistics.trianglesStored;
        out["nodes"] = statistics.nodes;
        out["meshes"] = statistics.meshes;
        out["materials"] = statistics.materials;
        out["textures"] = scene.textures.size();
        out["animations"] = scene.animations.size();
        out["cameras"] = scene.cameras.size();
        out["lights"] = scene.lights.size();
        if (statistics.bounds.isEmpty())
            out["bbox"] = nullptr;
        else
            out["bbox"] = {{"min", vectorJson(statistics.bounds.min())}, {"max", vectorJson(statistics.bounds.max())}};
        out["warnings"] = scene.warnings;
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::printf("%s\n", file.string().c_str());
    std::printf("  triangles drawn   %zu\n", statistics.trianglesDrawn);
    std::printf("  triangles stored  %zu\n", statistics.trianglesStored);
    std::printf("  nodes             %zu\n", statistics.nodes);
    std::printf("  meshes            %zu\n", statistics.meshes);
    std::printf("  materials         %zu\n", statistics.materials);
    std::printf("  textures          %zu\n", scene.textures.size());
    std::printf("  animations        %zu\n", scene.animations.size());
    std::printf("  cameras           %zu\n", scene.cameras.size());
    std::printf("  lights            %zu\n", scene.lights.size());
    if (statistics.bounds.isEmpty()) {
        std::printf("  bounding box      (empty)\n");
    } else {
        const Eigen::Vector3d lo = statistics.bounds.min(), hi = statistics.bounds.max();
        std::printf("  bounding box      [%g %g %g] .. [%g %g %g], diagonal %g\n", lo.x(), lo.y(), lo.z(), hi.x(),
                    hi.y(), hi.z(), statistics.bounds.diagonal().norm());
    }
    for (const std::string& warning : scene.warnings) std::printf("  warning: %s\n", warning.c_str());
    return 0;
}

int runConvert(const fs::path& input, const fs::path& output, const WriteOptions& options, bool quiet) {
    Scene scene = readScene(input);
    for (std::string& loss : formatLosses(scene, output)) scene.warnings.push_back(std::move(loss));
    if (!quiet)
        for (const std::string& warning : scene.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    writeScene(scene, output, options, {input});
    if (!quiet) {
        const SceneStatistics statistics = sceneStatistics(scene);
        std::error_code error;
        std::printf("%s -> %s: %zu triangles drawn, %zu stored, %ju bytes -> %ju bytes\n", input.string().c_str(),
                    output.string().c_str(), statistics.trianglesDrawn, statistics.trianglesStored,
                    static_cast<std::uintmax_t>(fs::file_size(input, error)),
                    static_cast<std::uintmax_t>(fs::file_size(output, error)));
    }
    return 0;
}

nlohmann::json symmetryJson(const Symmetry& s) {
    nlohmann::json out{{"type", kindName(s.kind)}};
    switch (s.kind) {
    case Symmetry::Kind::Rotation:
        out["axis"] = vectorJson(s.axis);
        out["angle"] = s.angle;
        out["fold"] = s.fold;
        break;
    case Symmetry::Kind::Mirror: out["normal"] = vectorJson(s.axis); break;
    case Symmetry::Kind::Rotoreflection:
        out["axis"] = vectorJson(s.axis);
        out["angle"] = s.angle;
        break;
    default: break;
    }
    out["deviation"] = s.deviation;
    return out;
}

nlohmann::json groupJson(const SymmetryGroup& group) {
    nlohmann::json out{{"group", group.name},
                       {"order", group.order()},
                       {"centroid", vectorJson(group.centroid)},
                       {"symmetries", nlohmann::json::array()}};
    for (const Symmetry& s : group.elements)
        if (s.kind != Symmetry::Kind::Identity) out["symmetries"].push_back(symmetryJson(s));
    return out;
}

// detect --tiles: tiles, congruence classes with the placement of every member, and the assembly's group.
int runDetectTiles(const fs::path& file, const SymmetryOptions& options, bool json) {
    const Scene scene = readScene(file);
    const auto soup = flattenScene(scene);
    const std::vector<Tile> tiles = splitIntoTiles(soup);
    CongruenceOptions congruenceOptions;
    congruenceOptions.tolerance = options.tolerance;
    congruenceOptions.threads = options.threads;
    const TileClassification classification = classifyTiles(tiles, congruenceOptions);
    const SymmetryGroup assembly = assemblySymmetries(classification);
    std::vector<std::string> warnings = scene.warnings;
    if (json) {
        nlohmann::json out{{"file", file.string()},
                           {"tiles", tiles.size()},
                           {"classes", nlohmann::json::array()},
                           {"tolerance", options.tolerance},
                           {"warnings", warnings},
                           // Tile pairs that passed area, material and descriptor, and how many of them the
                           // geometric check found congruent.
                           {"descriptor_matches", classification.descriptorMatches},
                           {"verified_matches", classification.verifiedMatches}};
        for (const CongruenceClass& c : classification.classes) {
            const TileShape& prototype = classification.shapes[c.prototype];
            nlohmann::json entry{{"prototype", c.prototype},
                                 {"members", c.members.size()},
                                 {"triangles", prototype.triangles},
                                 {"group", prototype.symmetry.name},
                                 {"instances", nlohmann::json::array()}};
            for (std::size_t i = 0; i < c.members.size(); ++i) {
                const Eigen::Matrix4d m = c.placements[i].matrix();
                entry["instances"].push_back({{"tile", c.members[i]},
                                              {"matrix", std::vector<double>(m.data(), m.data() + 16)},
                                              {"mirror", c.placements[i].mirrors()},
                                              {"deviation", c.deviations[i]}});
            }
            out["classes"].push_back(entry);
        }
        out["assembly"] = groupJson(assembly);
        out["assembly"]["method"] = "constructive (paper 6.3): tiles mapped onto congruent tiles";
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::size_t repeated = 0;
    for (const CongruenceClass& c : classification.classes) repeated += c.members.size() > 1 ? c.members.size() : 0;
    std::printf("%s: %zu tiles in %zu classes (%zu tiles in classes of 2 or more), tolerance %g\n",
                file.string().c_str(), tiles.size(), classification.classes.size(), repeated, options.tolerance);
    for (std::size_t k = 0; k < classification.classes.size(); ++k) {
        const CongruenceClass& c = classification.classes[k];
        const TileShape& prototype = classification.shapes[c.prototype];
        const auto mirrored =
            std::count_if(c.placements.begin(), c.placements.end(), [](const Isometry& j) { return j.mirrors(); });
        std::printf("  class %zu: %zu x tile %zu (%zu triangles, group %s), %td mirrored\n", k, c.members.size(),
                    c.prototype, prototype.triangles, prototype.symmetry.name.c_str(), mirrored);
    }
    std::printf("  assembly: group %s, order %d\n", assembly.name.c_str(), assembly.order());
    for (const std::string& warning : warnings) std::printf("  warning: %s\n", warning.c_str());
    return 0;
}

int runDetect(const fs::path& file, const SymmetryOptions& options, bool json, const fs::path& html) {
    const Scene scene = readScene(file);
    const TriangleMesh mesh = worldMesh(scene);
    const SymmetryGroup group = detectSymmetries(mesh, options);
    if (!html.empty()) writeDetectionReport(html, mesh, group, file, options.tolerance);
    std::vector<std::string> warnings = scene.warnings;
    warnings.insert(warnings.end(), group.warnings.begin(), group.warnings.end());
    if (json) {
        nlohmann::json out = groupJson(group);
        out["file"] = file.string();
        out["tolerance"] = options.tolerance;
        out["warnings"] = warnings;
        std::cout << out.dump(2) << '\n';
        return 0;
    }
    std::printf("%s: group %s, order %d (tolerance %g of the diagonal %g)\n", file.string().c_str(), group.name.c_str(),
                group.order(), options.tolerance, group.diagonal);
    std::printf("  centroid [%.9g %.9g %.9g]\n", group.centroid.x(), group.centroid.y(), group.centroid.z());
    for (const Symmetry& s : group.elements) {
        const Eigen::Vector3d& a = s.axis;
        switch (s.kind) {
        case Symmetry::Kind::Identity: continue;
        case Symmetry::Kind::Rotation:
            std::printf("  rotation        %3d-fold axis [% .9f % .9f % .9f] by %8.4f deg", s.fold, a.x(), a.y(), a.z(),
                        s.angle * 180 / 3.14159265358979323846);
            break;
        case Symmetry::Kind::Mirror:
            std::printf("  mirror          normal [% .9f % .9f % .9f]                  ", a.x(), a.y(), a.z());
            break;
        case Symmetry::Kind::Rotoreflection:
            std::printf("  rotoreflection  axis   [% .9f % .9f % .9f] by %8.4f deg", a.x(), a.y(), a.z(),
                        s.angle * 180 / 3.14159265358979323846);
            break;
        case Symmetry::Kind::Inversion:
            std::printf("  inversion                                                        ");
            break;
        }
        std::printf("  deviation %.2e\n", s.deviation);
    }
    for (const std::string& warning : warnings) std::printf("  warning: %s\n", warning.c_str());
    return 0;
}

struct CompressRequest {
    fs::path input, output, report;
    CompressOptions options;
    bool quiet = false;
};

// One line on stderr, rewritten as each stage starts, with the time so far; only on a terminal.
class ProgressLine {
public:
    explicit ProgressLine(bool wanted) : shown_(wanted && isatty(fileno(stderr))) {}
    ~ProgressLine() { clear(); }
    void stage(const char* name, std::size_t count = 0, const char* unit = "") {
        if (!shown_) return;
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (count)
            std::fprintf(stderr, "\r\033[Ksymcompress: %s %zu %s (%.1f s)", name, count, unit, seconds);
        else
            std::fprintf(stderr, "\r\033[Ksymcompress: %s (%.1f s)", name, seconds);
        std::fflush(stderr);
    }
    void clear() {
        if (shown_) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
    }

private:
    bool shown_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

void printReport(const CompressionReport& report) {
    const CompressionStats& stats = report.stats;
    std::printf("%s -> %s\n", report.input.string().c_str(), report.output.string().c_str());
    std::printf("  size            %ju -> %ju bytes, ratio %.2f\n", report.inputBytes, report.outputBytes,
                report.ratio);
    if (report.plan != "final") {
        const std::map<std::string, const char*> plans{
            {"draco_alone", "every tile as it is"},
            {"instancing", "instancing without regions"},
            {"world_frame", "the tiles stored as they are all in the world's frame"}};
        const auto plan = plans.find(report.plan);
        std::printf("  plan            %s: its file was smaller than the full plan's\n",
                    plan != plans.end() ? plan->second : report.plan.c_str());
    }
    std::printf("  triangles       %zu drawn, %zu stored\n", stats.trianglesIn, stats.trianglesStored);
    if (stats.lineSegmentsKept || stats.pointsKept)
        std::printf("  lines, points   %zu line segments and %zu points stored as they are\n", stats.lineSegmentsKept,
                    stats.pointsKept);
    std::printf("  tiles           %zu in %zu classes; %zu classes stored once for %zu instances\n", stats.tiles,
                stats.classes, stats.instancedClasses, stats.instances);
    std::printf("  symmetric       %zu classes, %zu stored as their fundamental region\n", stats.symmetricClasses,
                stats.regionClasses);
    if (stats.tilesInSceneSymmetry)
        std::printf("  scene symmetry  %s: one part of the scene stored for %zu tiles\n", stats.sceneGroup.c_str(),
                    stats.tilesInSceneSymmetry);
    if (stats.assemblies)
        std::printf(
            "  assemblies      %zu groups of tiles that recur together, stored once for %zu copies (%zu tiles)\n",
            stats.assemblies, stats.assemblyCopies, stats.tilesInAssemblies);
    if (stats.materialVariants)
        std::printf("  materials       %zu meshes draw a shared geometry in another material, stored once\n",
                    stats.materialVariants);
    if (stats.inputInstancesKept)
        std::printf("  kept            %zu nodes of meshes the input already shares\n", stats.inputInstancesKept);
    if (stats.nodeFrames)
        std::printf(
            "  node frames     %zu meshes (for %zu tiles) written in the frame of the nodes their tiles came from\n",
            stats.nodeFrames, stats.tilesInNodeFrames);
    if (stats.animatedNodesKept)
        std::printf("  animated        %zu nodes kept as they are, for the scene's animations (%zu)\n",
                    stats.animatedNodesKept, report.animations);
    if (stats.camerasAndLightsKept)
        std::printf("  cameras, lights %zu nodes kept where they were (%zu cameras, %zu lights)\n",
                    stats.camerasAndLightsKept, report.cameras, report.lights);
    for (const std::string& line : report.optimizations.lines()) std::printf("  optimized       %s\n", line.c_str());
    if (stats.instances) std::printf("  per instance    %.0f bytes\n", report.bytesPerInstance);
    if (report.gpuInstancing.batches)
        std::printf("  GPU instancing  %zu instances in %zu batches (EXT_mesh_gpu_instancing)\n",
                    report.gpuInstancing.instances, report.gpuInstancing.batches);
    if (stats.attributeMismatches)
        std::printf(
            "  kept apart      %zu congruent tiles whose normals, texture coordinates or colours differ "
            "(--geometry-only instances them anyway)\n",
            stats.attributeMismatches);
    if (stats.notWorthInstancing)
        std::printf("  stored apart    %zu tiles of classes too small for a node per copy to pay\n",
                    stats.notWorthInstancing);
    if (report.maxError > 0) {
        std::string motion;  // the shares of what moves vertices in the poses
        auto share = [&](const char* what, double value) {
            char text[64];
            std::snprintf(text, sizeof text, ", %s %g", what, value);
            if (value > 0) motion += text;
        };
        share("animation keys", report.animationKeyShare);
        share("animation keys beside it", report.animationError);
        share("skin weights", report.skinWeightShare);
        std::printf("  budget          %g of the diagonal: tolerance %g%s, the rest to quantization; the "
                    "placements use %.2e (symdecompress --verify measures the whole)\n",
                    report.maxError, report.tolerance, motion.c_str(), stats.maxDeviation);
    } else
        std::printf("  placements      deviate %.2e of the diagonal (tolerance %g)\n", stats.maxDeviation,
                    report.tolerance);
    const auto& ablation = report.ablation;
    if (ablation.instancingAndRegions)
        std::printf("  ablation        every tile as it is %ju bytes, with instancing %ju, with regions too %ju\n",
                    *ablation.dracoAlone, *ablation.instancing, *ablation.instancingAndRegions);
    else if (ablation.instancing)
        std::printf("  ablation        every tile as it is %ju bytes, with instancing %ju\n", *ablation.dracoAlone,
                    *ablation.instancing);
    std::printf("  seconds         read %.2f, tiles %.2f, classes %.2f, plan %.2f, write %.2f\n", report.secondsRead,
                stats.secondsTiles, stats.secondsClasses, stats.secondsPlan, report.secondsWrite);
}

int runCompress(CompressRequest request) {
    ProgressLine progress(!request.quiet);
    request.options.progress = [&progress](const char* stage, std::size_t count, const char* unit) {
        progress.stage(stage, count, unit);
    };
    const CompressionReport report = compressFile(request.input, request.output, request.options);
    progress.clear();
    if (!request.report.empty()) {
        std::ofstream out(request.report);
        out << report.json() << '\n';
        if (!out) throw FileError(request.report, "cannot write the report");
    }
    if (request.quiet) return 0;
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
    printReport(report);
    return 0;
}

void addWriteOptions(CLI::App& command, WriteOptions& options) {
    command.add_flag(
        "--no-draco", [&options](std::int64_t) { options.draco = false; },
        "glTF: write plain accessors instead of KHR_draco_mesh_compression");
    command.add_flag(
        "--no-gpu-instancing", [&options](std::int64_t) { options.gpuInstancing = false; },
        "glTF: a node per instance, never EXT_mesh_gpu_instancing nor EXT_meshopt_compression (for viewers "
        "without them)");
    command.add_option("--position-bits", options.positionBits,
                       "Draco position quantization bits for every mesh (compress: in place of the bits the error "
                       "budget gives each mesh)")
        ->check(CLI::Range(8, 30))
        ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"symcompress: makes 3D scenes smaller by finding what repeats in them"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "symcompress 0.1.0");

    bool json = false, quiet = false;
    fs::path infoFile, input, output;
    WriteOptions writeOptions;

    CLI::App* info = app.add_subcommand("info", "Describe a scene: nodes, meshes, materials, triangles, bounds");
    info->add_option("FILE", infoFile, "scene file (.gltf .glb .x3d .x3dz .obj .ply .stl)")->required();
    info->add_flag("--json", json, "print one JSON object");

    CLI::App* convert = app.add_subcommand("convert", "Convert between formats through the scene model");
    convert->add_option("IN", input, "input scene file")->required();
    convert->add_option("-o,--output", output, "output file; its extension picks the format")->required();
    convert->add_flag("-q,--quiet", quiet, "print nothing but errors");
    addWriteOptions(*convert, writeOptions);

    fs::path detectFile;
    SymmetryOptions symmetryOptions;
    CLI::App* detect = app.add_subcommand("detect", "Find the symmetries of the whole scene taken as one shape");
    detect->add_option("FILE", detectFile, "scene file")->required();
    detect->add_flag("--json", json, "print one JSON object");
    detect
        ->add_option("--tolerance", symmetryOptions.tolerance,
                     "largest deviation accepted, relative to the bounding-box diagonal")
        ->check(CLI::Range(1e-9, 0.5))
        ->capture_default_str();
    detect->add_option("--max-order", symmetryOptions.maxOrder, "highest moment order used for candidate axes")
        ->check(CLI::Range(4, 16))
        ->capture_default_str();
    detect->add_option("--threads", symmetryOptions.threads, "threads (0: all cores)")->capture_default_str();
    bool tiles = false;
    auto* tilesFlag =
        detect->add_flag("--tiles", tiles, "split into tiles: congruence classes, placements, the assembly's group");
    fs::path detectHtml;
    detect
        ->add_option("--html", detectHtml,
                     "also write an HTML page (self-contained, offline) showing the shape with its planes and axes")
        ->excludes(tilesFlag);

    CompressRequest compressRequest;
    CLI::App* compress = app.add_subcommand(
        "compress", "Store every repeated part once (the default command: symcompress IN -o OUT works too)");
    compress->add_option("IN", compressRequest.input, "input scene file")->required();
    compress->add_option("-o,--output", compressRequest.output, "output file (.glb .gltf .x3d)")->required();
    compress
        ->add_option("--max-error", compressRequest.options.maxError,
                     "how far the rebuilt surface may lie from the input, relative to the scene's bounding-box "
                     "diagonal: shared by the tolerance and each mesh's position quantization (below 4.8e-7, what "
                     "float32 keeps, with a warning)")
        ->check(CLI::Range(1e-9, 0.5))
        ->capture_default_str();
    compress
        ->add_option("--tolerance", compressRequest.options.tolerance,
                     "congruence and symmetry tolerance, relative to the diagonal (default: half of --max-error)")
        ->check(CLI::Range(1e-9, 0.5));
    compress
        ->add_option("--animation-error", compressRequest.options.animationError,
                     "glTF: how much farther animation keys may move a vertex in a pose, relative to the diagonal, "
                     "beside --max-error, which the meshes then keep whole (default: the keys take a share of it)")
        ->check(CLI::Range(1e-9, 0.5));
    compress->add_flag(
        "--no-instancing", [&](std::int64_t) { compressRequest.options.instancing = false; },
        "store every tile as it is (Draco alone)");
    compress->add_flag(
        "--no-symmetry", [&](std::int64_t) { compressRequest.options.regions = false; },
        "instancing only: no fundamental regions");
    compress->add_flag("--cut-triangles", compressRequest.options.cutTriangles,
                       "let fundamental regions cut the triangles their planes cross where the tessellation is not "
                       "itself symmetric (smaller; the copies then draw other triangles than the input's)");
    compress->add_flag("--geometry-only", compressRequest.options.geometryOnly,
                       "instance congruent tiles even when their normals, texture coordinates or colours differ");
    compress->add_flag("--keep-unused-attributes", [&](std::int64_t) { compressRequest.options.optimize.pruneAttributes = false; },
                       "keep texture coordinates that no texture reads (dropped by default)");
    compress->add_flag("--keep-flat-normals", [&](std::int64_t) { compressRequest.options.optimize.dropFlatNormals = false; },
                       "keep normals equal to their triangles' own (dropped by default: viewers shade flat without them)");
    compress->add_flag(
        "--no-prune", [&](std::int64_t) { compressRequest.options.optimize.prune = false; },
        "keep materials no primitive uses, textures no material uses and animation channels that "
        "hold their node where it rests");
    compress->add_flag(
        "--keep-animation-keys", [&](std::int64_t) { compressRequest.options.optimize.dropKeys = false; },
        "keep animation keys that interpolation gives back, and channels that hardly leave their node's rest "
        "(dropped by default within the budget)");
    compress->add_flag("--no-dedup", [&](std::int64_t) { compressRequest.options.optimize.dedup = false; },
                       "keep materials equal but for their names, and textures of the same image, apart");
    compress->add_flag(
        "--no-color-join", [&](std::int64_t) { compressRequest.options.optimize.joinByBaseColor = false; },
        "glTF: keep primitives of one mesh in materials that differ only in base colour apart (joined by default, "
        "each vertex given its colour, where that is smaller)");
    compress->add_flag("--drop-unused-texcoords", compressRequest.options.optimize.pruneAttributes,
                       "the default now (texture coordinates no texture reads are dropped); kept for scripts");
    compress->add_option("--report", compressRequest.report, "also write the size report as JSON");
    compress->add_option("--html", compressRequest.options.htmlReport,
                         "also write an HTML page (self-contained, offline) showing the classes, symmetries and sizes");
    compress->add_option("--threads", compressRequest.options.threads, "threads (0: all cores)")->capture_default_str();
    compress->add_flag("-q,--quiet", compressRequest.quiet, "print nothing but errors");
    addWriteOptions(*compress, compressRequest.options.write);

    // symcompress IN -o OUT: the compress command without its name.
    std::vector<std::string> arguments(argv + 1, argv + argc);
    const std::set<std::string> commands{"info", "convert", "detect", "compress"};
    const bool named =
        std::any_of(arguments.begin(), arguments.end(), [&](const std::string& a) { return commands.count(a) > 0; });
    const bool onlyAsking =
        !arguments.empty() && (arguments[0] == "-h" || arguments[0] == "--help" || arguments[0] == "--version");
    if (!arguments.empty() && !named && !onlyAsking) arguments.insert(arguments.begin(), "compress");
    std::reverse(arguments.begin(), arguments.end());  // CLI11 takes them last first

    try {
        app.parse(arguments);
    } catch (const CLI::ParseError& error) {
        const int status = app.exit(error);
        return status == 0 ? 0 : kExitBadInput;
    }

    try {
        if (*info) return runInfo(infoFile, json);
        if (*convert) return runConvert(input, output, writeOptions, quiet);
        if (*compress) {
            // Bits given: every mesh quantized with them, as before the budget, and verified as then.
            compressRequest.options.fixedPositionBits = compress->count("--position-bits") > 0;
            // A tolerance at or above the default budget leaves quantization nothing: the budget is raised to
            // twice it, as the default split would have it, unless the budget was given too.
            CompressOptions& asked = compressRequest.options;
            if (compress->count("--tolerance") && !compress->count("--max-error") && !asked.fixedPositionBits &&
                asked.tolerance >= asked.maxError) {
                asked.maxError = std::min(0.5, 2 * asked.tolerance);
                if (!compressRequest.quiet)
                    std::fprintf(stderr,
                                 "note: --tolerance %g is not below the default --max-error: the budget is %g\n",
                                 asked.tolerance, asked.maxError);
            }
            return runCompress(compressRequest);
        }
        if (*detect)
            return tiles ? runDetectTiles(detectFile, symmetryOptions, json)
                         : runDetect(detectFile, symmetryOptions, json, detectHtml);
    } catch (const FileError& error) {
        std::fprintf(stderr, "symcompress: %s\n", error.what());
        return kExitBadInput;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "symcompress: error: %s\n", error.what());
        return 1;
    }
    return 0;
}
