// symcompress's whole job: read, analyse once, plan three ways (the full plan, instancing without regions,
// every tile as it is; the second takes the first's assemblies), write and measure each, keep the smallest
// file, and report.
#include "common/number_text.hpp"
#include "common/uri_text.hpp"
#include "common/with_threads.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/detail/atomic_file.hpp"
#include "symcompress/detail/compression_plan.hpp"
#include "symcompress/html_report.hpp"
#include "symcompress/optimize.hpp"

#include <nlohmann/json.hpp>

#include <tbb/task_group.h>

#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <stdexcept>

namespace symcompress {
namespace fs = std::filesystem;
namespace {

// The shares of the error budget left for the rounding of GPU-instanced rotations (normalized shorts, meshopt's
// quaternion filter) and of their translations and scales (meshopt's exponential filter).
constexpr double kRotationShare = 1.0 / 64, kTranslationShare = 1.0 / 64;
// The finest budget an output can keep, relative to the diagonal: glTF, Draco and viewers hold coordinates in
// float32, whose steps at the scene's size are up to 2^-23 of it; a few of them add up (the input's, Draco's
// dequantization, a node's translation). Finer budgets are not met (the torus knot at 1.2e-7: 1.5e-7).
constexpr double kFloat32Budget = 1.0 / (1 << 21);

// The options with a budget that float32 can keep, said where the one asked for is finer.
CompressOptions withKeepableBudget(const CompressOptions& requested, std::vector<std::string>& warnings) {
    CompressOptions options = requested;
    if (requested.fixedPositionBits || !(requested.maxError < kFloat32Budget)) return options;
    options.maxError = kFloat32Budget;
    std::string asked, used;
    appendShortest(asked, requested.maxError);
    appendShortest(used, rounded(kFloat32Budget, 2));
    warnings.push_back("--max-error " + asked +
                       " is finer than float32, in which glTF, Draco and viewers hold coordinates, keeps a scene: " +
                       used + " of the diagonal used");
    return options;
}

// The share for the rounding of skin weights, in a scene with skins.
constexpr double kSkinWeightShare = 1.0 / 32;
// Of the keys' share, the part that dropping keys may take (the rounding takes the rest and what it leaves).
constexpr double kKeyDroppingShare = 1.0 / 2;
// The share for the rounding of animations' key values, in a scene with animations: of two roundings that share
// an error, the bits are fewest in all where each takes a part in proportion to the values it rounds (n_k
// log(1 / e_k) + n_p log(1 / e_p), least for e_k + e_p = E at e_k / E = n_k / (n_k + n_p)), key values against
// the meshes' coordinates; no less than a 32nd, and no more than half, which the positions keep at rest.
double animationKeyShare(const Scene& scene) {
    double keys = 0, coordinates = 0;
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) keys += double(channel.values.size());
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives) coordinates += 3.0 * double(primitive.positions.size());
    return keys > 0 ? std::clamp(keys / (keys + coordinates), 1.0 / 32, 1.0 / 2) : 0;
}

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The bytes of a scene on disk: the file, and for .gltf the buffers and images it names by relative path.
std::uintmax_t sceneBytes(const fs::path& file) {
    std::error_code error;
    std::uintmax_t total = fs::file_size(file, error);
    if (error) return 0;
    if (formatFromExtension(file) != FileFormat::Gltf) return total;
    std::ifstream in(file);
    const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
    if (json.is_discarded()) return total;
    for (const char* key : {"buffers", "images"})
        if (json.contains(key) && json[key].is_array())
            for (const auto& item : json[key])
                if (item.contains("uri") && item["uri"].is_string()) {
                    const std::string uri = item["uri"];
                    if (uri.rfind("data:", 0) == 0 || uri.find("://") != std::string::npos) continue;
                    const std::uintmax_t size = fs::file_size(file.parent_path() / uriDecoded(uri), error);
                    if (!error) total += size;
                }
    return total;
}

// The input's bytes: the scene's files, and the images OBJ, PLY, STL and X3D name by path, each image once
// however many textures show it.
std::uintmax_t inputBytesOf(const Scene& scene, const fs::path& input) {
    std::uintmax_t bytes = sceneBytes(input);
    const FileFormat format = formatFromExtension(input);
    const std::vector<int> sameImage = firstTextureOfSameImage(scene.textures);
    if (format != FileFormat::Gltf && format != FileFormat::Glb)
        for (std::size_t t = 0; t < scene.textures.size(); ++t)
            if (sameImage[t] == int(t)) bytes += scene.textures[t].bytes.size();
    return bytes;
}

// The output's bytes: the file, and the image files it refers to (a .gltf's names; X3D's, which the input's
// size counts as well).
std::uintmax_t outputBytesOf(const Scene& scene, const fs::path& output) {
    const FileFormat format = formatFromExtension(output);
    return sceneBytes(output) + (format == FileFormat::X3d ? x3dReferencedImageBytes(scene) : 0);
}

// A plan written to a file beside the output (named after it and the plan: plans are measured at once), measured,
// and removed.
std::uintmax_t measuredBytes(const CompressedScene& plan, const fs::path& output, const std::string& name,
                             const WriteOptions& write, const std::vector<fs::path>& inputs) {
    const fs::path temporary = output.parent_path() / (".symcompress-" + name + "-" + output.filename().string());
    writeScene(plan.scene, temporary, write, inputs);
    const std::uintmax_t size = outputBytesOf(plan.scene, temporary);  // with a .gltf's .bin
    std::error_code error;
    fs::remove(temporary, error);
    // And the file written beside it: a .gltf's buffer, an OBJ's material library.
    if (const FileFormat format = formatFromExtension(temporary);
        format == FileFormat::Gltf || format == FileFormat::Obj)
        fs::remove(fs::path(temporary).replace_extension(format == FileFormat::Gltf ? ".bin" : ".mtl"), error);
    return size;
}

// The mean of the writer's measure over the nodes that draw a shared mesh, the nodes of each mesh measured
// together (GPU-instanced batches cost a few bytes an instance).
double bytesPerInstance(const CompressedScene& compressed, const StorageCostModel& costs) {
    if (compressed.instanceNodes.empty()) return 0;
    std::map<int, std::vector<Node>> byMesh;  // instance nodes are roots
    for (int node : compressed.instanceNodes)
        byMesh[compressed.scene.nodes[std::size_t(node)].mesh].push_back(compressed.scene.nodes[std::size_t(node)]);
    double total = 0;
    for (const auto& [mesh, nodes] : byMesh) {
        if (costs.nodesBytes) {
            total += costs.nodesBytes(nodes);
            continue;
        }
        for (const Node& drawing : nodes) total += costs.nodeBytes ? costs.nodeBytes(drawing) : costs.bytesPerInstance;
    }
    return total / double(compressed.instanceNodes.size());
}

// compressToFile, with the time the input took to read (in the report before the HTML report shows it).
CompressionReport compressRead(Scene scene, const fs::path& output, const CompressOptions& requested,
                               const std::vector<fs::path>& inputs, double secondsRead) {
    if (!requested.fixedPositionBits && requested.tolerance >= requested.maxError) {
        std::string tolerance, budget;
        appendShortest(tolerance, requested.tolerance);
        appendShortest(budget, requested.maxError);
        throw std::invalid_argument("--tolerance " + tolerance + " must be below --max-error " + budget +
                                    ", the error budget it is a part of");
    }
    const CompressOptions options = withKeepableBudget(requested, scene.warnings);
    CompressionReport report;
    report.secondsRead = secondsRead;
    report.input = inputs.empty() ? fs::path() : inputs.front();
    report.output = output;
    report.tolerance = options.congruenceTolerance();
    report.maxError = options.fixedPositionBits ? 0 : options.maxError;
    report.inputBytes = inputs.empty() ? 0 : inputBytesOf(scene, inputs.front());
    OptimizeOptions optimize = options.optimize;
    // X3D writes indices as text: two materials merged put their parts in one IndexedFaceSet with larger
    // indices, which costs more than the Material it saves (the cat: +2.2 KB, the house: +11 KB).
    if (formatFromExtension(output) == FileFormat::X3d) optimize.dedup = false;
    // X3D output writes an X3D input's Box, Extrusion, ... again as they were, kept whole (X3dGeometrySource); any
    // other output tiles, shares and cuts their triangles as every mesh's.
    if (formatFromExtension(output) != FileFormat::X3d)
        for (Mesh& mesh : scene.meshes)
            for (Primitive& primitive : mesh.primitives) primitive.x3dSource.reset();
    // OBJ and PLY viewers smooth a mesh that has no normals.
    if (formatFromExtension(output) == FileFormat::Obj || formatFromExtension(output) == FileFormat::Ply)
        optimize.dropFlatNormals = false;
    report.optimizations = optimizeScene(scene, optimize);
    splitLinesAndPoints(scene);
    // What the output's format cannot hold, said before the writer leaves it out.
    for (std::string& loss : formatLosses(scene, output)) scene.warnings.push_back(std::move(loss));
    report.readerWarnings = scene.warnings.size();
    if (!options.htmlReport.empty()) {
        // Before the work: a report path that is the input or the output is refused at once.
        std::vector<fs::path> notOverwritten = inputs;
        notOverwritten.push_back(output);
        refuseToOverwriteInputs(options.htmlReport, notOverwritten);
        if (!htmlReportAvailable()) throw std::runtime_error("--html: symcompress was built without Node.js and npm");
    }

    AnalysisOptions analysisOptions = analysisOptionsOf(options);
    // Groups no plan could use are not sought; the HTML report shows every class's group.
    // The cost models and the plans measured below write many of the same primitives: each is encoded once.
    const std::shared_ptr<PrimitiveEncodings> encodings = makePrimitiveEncodings();
    if (options.htmlReport.empty()) {
        WriteOptions groupWrite = options.write;
        groupWrite.encodings = encodings;
        analysisOptions.groupCosts = costModelFor(formatFromExtension(output), groupWrite);
    }
    // The HTML report draws the input itself; the job alone needs the tiled meshes' geometry only in the soup.
    const SceneAnalysis analysis = options.htmlReport.empty() ? analyzeSceneTakingGeometry(scene, analysisOptions)
                                                              : analyzeScene(scene, analysisOptions);
    WriteOptions write = options.write;
    write.threads = options.threads;
    write.encodings = encodings;
    PlanOptions planOptions = planOptionsOf(options);
    if (!options.fixedPositionBits) {
        // Of the budget, shares for the rounding of skin weights and animations' keys, which move vertices in the
        // poses; a share for the rounding of GPU-instanced rotations and one for their translations and scales, kept
        // by the meshes that several nodes draw; the rest for the placements and each mesh's quantization (the
        // meshes the plan does not bound take all of that).
        // Only the glTF writer rounds them, and only with meshopt (X3D holds no skins and writes keys as text).
        const FileFormat format = formatFromExtension(output);
        const bool rounds = (format == FileFormat::Gltf || format == FileFormat::Glb) && write.draco;
        const double skinShare = !rounds || scene.skins.empty() ? 0 : options.maxError * kSkinWeightShare;
        // The keys' allowance: a share of the budget, or one of its own beside it (--animation-error).
        const bool keysRounded = rounds && write.gpuInstancing && !scene.animations.empty();
        const bool ownAllowance = keysRounded && options.animationError > 0;
        const double keyShare = keysRounded && !ownAllowance ? options.maxError * animationKeyShare(scene) : 0;
        write.skinWeightError = skinShare * analysis.diagonal;
        write.animationKeyError = (ownAllowance ? options.animationError : keyShare) * analysis.diagonal;
        report.animationError = ownAllowance ? options.animationError : 0;
        // Keys that interpolation gives back dropped with a share of the keys' allowance; their rounding takes what
        // the dropping leaves of it.
        if (options.optimize.dropKeys && write.animationKeyError > 0) {
            const RedundantKeys dropped = withThreads(
                options.threads, [&] { return dropRedundantKeys(scene, write.animationKeyError * kKeyDroppingShare); });
            report.optimizations.animationKeysDropped = dropped.keysDropped;
            report.optimizations.animationChannelsRemoved = dropped.channelsRemoved;
            write.animationKeyError -= dropped.deviation;
        }
        report.skinWeightShare = skinShare;
        report.animationKeyShare = keyShare;
        planOptions.maxError = options.maxError - skinShare - keyShare;
        planOptions.instanceShare = options.maxError * (kRotationShare + kTranslationShare);
        write.instanceRotationDeviation = options.maxError * kRotationShare;
        write.instanceTranslationDeviation = options.maxError * kTranslationShare;
        write.maxPositionError = (planOptions.maxError - planOptions.instanceShare) * analysis.diagonal;
        write.maxRelativePositionError = options.closeUpError * options.maxError;
    }
    if (options.animationError > 0 && !(report.animationError > 0))
        scene.warnings.push_back(std::string("--animation-error changes nothing: ") +
                                 (scene.animations.empty()
                                      ? "the scene has no animations"
                                      : "only glTF output with Draco and meshopt rounds animation keys (not X3D, "
                                        "--no-draco, --no-gpu-instancing or --position-bits)"));
    // Draco codes a colour that holds over a part in a few bytes; plain accessors would take 16 bytes a vertex.
    const FileFormat format = formatFromExtension(output);
    planOptions.joinByBaseColor =
        options.optimize.joinByBaseColor && (format == FileFormat::Gltf || format == FileFormat::Glb) && write.draco;
    planOptions.costs = costModelFor(format, write);
    // The decoder verifies against the whole budget (without tiles, there is no diagonal to scale it by).
    SurfaceDigest digest = analysis.digest;
    if (!options.fixedPositionBits && analysis.diagonal > 0) {
        digest.maxError = options.maxError;
        if (report.animationError > 0) digest.poseError = options.maxError + report.animationError;
    }
    write.extrasJson = digest.json();

    // The ablation: the same scene with every tile stored as it is (Draco alone), and with instancing but no
    // fundamental regions. The cost model only estimates: where a simpler plan's file is smaller, that file
    // is the output (the report says which plan it is).
    struct Variant {
        const char* name = "";
        CompressedScene plan;
        std::uintmax_t bytes = 0;
        CompressionPlan decisions;
    };
    auto variantOf = [&](const char* name, CompressedScene plan, CompressionPlan decisions) {
        const std::uintmax_t bytes = measuredBytes(plan, output, name, write, inputs);
        return Variant{name, std::move(plan), bytes, std::move(decisions)};
    };
    CompressionPlan fullPlan;  // the other plans are made from its decisions
    auto planned = [&](const char* name, PlanOptions variant) {
        variant.progress = nullptr;
        CompressionPlan decisions;
        CompressedScene plan = compressAnalyzed(scene, analysis, variant, &decisions);
        return variantOf(name, std::move(plan), std::move(decisions));
    };
    // Draco alone needs only the analysis: it is planned and measured beside the full plan.
    std::optional<Variant> dracoAlone;
    CompressedScene compressed = withThreads(options.threads, [&] {
        tbb::task_group beside;
        if (options.instancing)
            beside.run([&] {
                PlanOptions variant = planOptions;
                variant.instancing = false;
                dracoAlone = planned("draco_alone", variant);
            });
        try {
            CompressedScene full = compressAnalyzed(scene, analysis, planOptions, &fullPlan);
            const auto writeStart = std::chrono::steady_clock::now();
            if (options.progress) options.progress("writing", full.stats.trianglesStored, "triangles");
            writeScene(full.scene, output, write, inputs);
            report.secondsWrite = since(writeStart);
            beside.wait();
            return full;
        } catch (...) {
            beside.wait();  // it refers to what unwinding destroys
            throw;
        }
    });

    if (options.progress) options.progress("measuring the ablation", 0, "");
    const std::uintmax_t fullPlanBytes = outputBytesOf(compressed.scene, output);
    // The smallest plan measured so far, where smaller than the full plan: each other one is freed at once, so
    // that the job does not hold every plan it measures.
    std::optional<Variant> smallest;
    auto consider = [&](Variant variant) {
        if (variant.bytes < (smallest ? smallest->bytes : fullPlanBytes)) smallest = std::move(variant);
    };
    if (dracoAlone) {
        report.ablation.dracoAlone = dracoAlone->bytes;
        consider(std::move(*dracoAlone));
        dracoAlone.reset();
        if (options.regions) {
            PlanOptions instancingOnly = planOptions;
            instancingOnly.regions = false;
            instancingOnly.sharedPartsFrom = &fullPlan;
            Variant instancing = planned("instancing", instancingOnly);
            report.ablation.instancing = instancing.bytes;
            report.ablation.instancingAndRegions = fullPlanBytes;
            consider(std::move(instancing));
        } else {
            report.ablation.instancing = fullPlanBytes;
        }
    } else {
        report.ablation.dracoAlone = fullPlanBytes;
    }
    // A plan weighs each group of tiles it stores in its node's frame alone, with one quick encoding each way; the
    // file weighs them together: the smallest plan's decisions with every tile stored as it is in the world's
    // frame too.
    auto inFrames = [](const CompressionPlan& plan) {
        return !plan.framedTiles.empty() ||
               std::any_of(plan.shared.begin(), plan.shared.end(),
                           [](const SharedPart& part) { return !part.frame.isIdentity(); });
    };
    if (const CompressionPlan& best = smallest ? smallest->decisions : fullPlan; inFrames(best)) {
        CompressionPlan world = best;
        world.framedTiles.clear();
        world.sharedPartFrames = false;
        CompressedScene plan = emitScene(scene, analysis, world, planOptions.costs);
        plan.stats.secondsPlan = compressed.stats.secondsPlan;
        consider(variantOf(smallest ? smallest->name : "world_frame", std::move(plan), std::move(world)));
    }
    report.outputBytes = fullPlanBytes;
    const CompressionPlan* writtenPlan = &fullPlan;
    if (smallest) {
        writeScene(smallest->plan.scene, output, write, inputs);
        compressed = std::move(smallest->plan);
        writtenPlan = &smallest->decisions;
        report.plan = smallest->name;
        report.outputBytes = outputBytesOf(compressed.scene, output);
    }

    report.stats = compressed.stats;
    report.optimizations.primitivesJoinedByColor = compressed.stats.baseColorJoins.primitivesJoined;
    report.optimizations.joinedPrimitives = compressed.stats.baseColorJoins.joinedPrimitives;
    report.warnings = std::move(compressed.scene.warnings);
    report.animations = compressed.scene.animations.size();
    report.cameras = compressed.scene.cameras.size();
    report.lights = compressed.scene.lights.size();
    report.bytesPerInstance = bytesPerInstance(compressed, planOptions.costs);
    if (const FileFormat format = formatFromExtension(output); format == FileFormat::Glb || format == FileFormat::Gltf)
        report.gpuInstancing = gltfGpuInstancing(compressed.scene, write);
    report.ratio = report.outputBytes ? double(report.inputBytes) / double(report.outputBytes) : 0;
    if (!options.htmlReport.empty()) {
        if (options.progress) options.progress("writing the HTML report", 0, "");
        writeFileAtomically(options.htmlReport,
                            compressionReportHtml({scene, analysis, *writtenPlan, report, &planOptions.costs}));
    }
    return report;
}

}  // namespace

CompressionReport compressToFile(Scene scene, const fs::path& output, const CompressOptions& options,
                                 const std::vector<fs::path>& inputs) {
    return compressRead(std::move(scene), output, options, inputs, 0);
}

CompressionReport compressFile(const fs::path& input, const fs::path& output, const CompressOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    // Before the reading (a large scene takes a while) and before any temporary file beside it is named in an error.
    checkOutputFile(output, {input});
    if (options.progress) options.progress("reading", 0, "");
    Scene scene = readScene(input);
    return compressRead(std::move(scene), output, options, {input}, since(start));
}

}  // namespace symcompress
