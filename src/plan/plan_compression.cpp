// The plan, in order: the scene's own symmetry, repeated assemblies, then every class; and the short
// sequences that run the stages (docs/compression-plan.md).
#include "plan/member_check.hpp"
#include "plan/planners.hpp"
#include "common/with_threads.hpp"

#include <tbb/task_group.h>

#include <chrono>

namespace symcompress {

const Node* sourceNode(const Scene& input, const SceneAnalysis& analysis, std::size_t t) {
    const Tile& tile = analysis.tiles[t];
    if (tile.sources.empty()) return nullptr;
    const int node = analysis.soup[tile.sources.front().primitive].node;
    return node >= 0 && std::size_t(node) < input.nodes.size() ? &input.nodes[std::size_t(node)] : nullptr;
}

const Mesh* commonSourceMesh(const Scene& input, const SceneAnalysis& analysis, const std::vector<std::size_t>& tiles) {
    int mesh = -1;
    for (std::size_t t : tiles) {
        const Node* source = sourceNode(input, analysis, t);
        if (!source || source->mesh < 0 || (mesh >= 0 && source->mesh != mesh)) return nullptr;
        mesh = source->mesh;
    }
    if (mesh < 0) return nullptr;
    const Mesh& found = input.meshes[std::size_t(mesh)];
    return found.name.empty() && found.extrasJson.empty() ? nullptr : &found;
}

bool PlanContext::reproduces(std::size_t from, std::size_t to, const Isometry& map, double* deviation) const {
    const bool reproduced = symcompress::reproduces(tilePrimitive(analysis.tiles[from], analysis.soup),
                                                    tilePrimitive(analysis.tiles[to], analysis.soup), map,
                                                    tolerance(), options.geometryOnly, deviation);
    if (reproduced && deviation) *deviation = analysis.diagonal > 0 ? *deviation / analysis.diagonal : 0;
    return reproduced;
}

Eigen::Matrix4d translationTo(const Eigen::Vector3d& center) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topRightCorner<3, 1>() = center;
    return m;
}

// The tiles stored as they are that are drawn alone (SceneAnalysis::drawnAlone) moved to plan.tilesAlone.
void setTilesAloneApart(const SceneAnalysis& analysis, CompressionPlan& plan) {
    const auto alone = std::stable_partition(plan.tilesAsTheyAre.begin(), plan.tilesAsTheyAre.end(),
                                             [&](std::size_t t) { return !analysis.drawnAlone(t); });
    plan.tilesAlone.assign(alone, plan.tilesAsTheyAre.end());
    plan.tilesAsTheyAre.erase(alone, plan.tilesAsTheyAre.end());
}

CompressionPlan planCompression(const Scene& input, const SceneAnalysis& analysis, const PlanOptions& options) {
    CompressionPlan plan;
    plan.maxError = options.maxError;
    plan.instanceShare = options.instanceShare;
    plan.joinByBaseColor = options.joinByBaseColor;
    const std::vector<int> joinGroups =
        options.joinByBaseColor ? baseColorJoinGroups(input.materials) : std::vector<int>();
    if (!options.instancing || !analysis.options.classify) {
        // Every copy as it is, as Draco alone stores it, the author's shared meshes too: their sharing may
        // cost more than it saves (hundreds of small scaled copies), and this plan stores nothing shared.
        plan.shareInputInstances = false;
        for (std::size_t t = 0; t < analysis.tiles.size(); ++t) plan.tilesAsTheyAre.push_back(t);
        setTilesAloneApart(analysis, plan);
        StorageCosts costs(analysis, options.costs, joinGroups);
        withThreads(analysis.options.threads, [&] { planSourceFrames(input, analysis, costs, plan); });
        return plan;
    }
    if (options.progress) options.progress("planning", analysis.classification.classes.size(), "classes");
    StorageCosts costs(analysis, options.costs, joinGroups);
    const PlanContext context{input, analysis, options, costs};
    std::vector<bool> drawn(analysis.tiles.size(), false);  // by the scene's symmetry or a repeated assembly
    // Tiles drawn alone are in no assembly (each would lose its own node) and stay for the classes.
    for (std::size_t t = 0; t < drawn.size(); ++t) drawn[t] = analysis.drawnAlone(t);
    CompressionPlan classes = withThreads(analysis.options.threads, [&] {
        // The kinds' measures (the writer on a sample of up to 20000 triangles) beside the planners, which
        // ask for them under StorageCosts' lock.
        tbb::task_group measuring;
        measuring.run([&] { costs.measureKinds(); });
        try {
            if (options.assemblies && options.sharedPartsFrom) {
                const CompressionPlan& from = *options.sharedPartsFrom;
                plan.sceneGroup = from.sceneGroup;
                for (const SharedPart& part : from.shared)
                    if (part.mechanism == SharedPart::Mechanism::SceneSymmetry ||
                        part.mechanism == SharedPart::Mechanism::Assembly) {
                        for (std::size_t t : part.tiles) drawn[t] = true;
                        plan.shared.push_back(part);
                    }
            } else if (options.assemblies) {
                if (std::optional<SharedPart> part = planSceneSymmetry(context)) {
                    for (std::size_t t : part->tiles) drawn[t] = true;
                    plan.sceneGroup = part->group;
                    plan.shared.push_back(std::move(*part));
                }
                for (SharedPart& part : planAssemblies(context, drawn)) plan.shared.push_back(std::move(part));
            }
            for (std::size_t t = 0; t < drawn.size(); ++t)
                if (analysis.drawnAlone(t)) drawn[t] = false;
            CompressionPlan planned = planClasses(context, drawn);
            measuring.wait();
            return planned;
        } catch (...) {
            measuring.wait();  // costs outlives the measure
            throw;
        }
    });
    for (SharedPart& part : classes.shared) plan.shared.push_back(std::move(part));
    plan.tilesAsTheyAre = std::move(classes.tilesAsTheyAre);
    setTilesAloneApart(analysis, plan);
    plan.classes = classes.classes;
    plan.symmetricClasses = classes.symmetricClasses;
    plan.attributeMismatches = classes.attributeMismatches;
    plan.notWorthInstancing = classes.notWorthInstancing;
    withThreads(analysis.options.threads, [&] { planSourceFrames(input, analysis, costs, plan); });
    return plan;
}

CompressedScene compressAnalyzed(const Scene& input, const SceneAnalysis& analysis, const PlanOptions& options,
                                 CompressionPlan* decisions) {
    const auto start = std::chrono::steady_clock::now();
    CompressionPlan plan = planCompression(input, analysis, options);
    CompressedScene result = emitScene(input, analysis, plan, options.costs);
    result.stats.secondsPlan = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (decisions) *decisions = std::move(plan);
    return result;
}

AnalysisOptions analysisOptionsOf(const CompressOptions& options) {
    AnalysisOptions analysis;
    analysis.tolerance = options.congruenceTolerance();
    analysis.classify = options.instancing;
    analysis.keepInputInstances = options.keepInputInstances;
    analysis.elementDeviations = !options.htmlReport.empty();  // only the HTML report shows them
    analysis.threads = options.threads;
    analysis.progress = options.progress;
    return analysis;
}

PlanOptions planOptionsOf(const CompressOptions& options) {
    PlanOptions plan;
    plan.instancing = options.instancing;
    plan.geometryOnly = options.geometryOnly;
    plan.regions = options.regions;
    plan.cutTriangles = options.cutTriangles;
    plan.assemblies = options.assemblies;
    plan.maxError = options.fixedPositionBits ? 0 : options.maxError;
    plan.progress = options.progress;
    return plan;
}

CompressedScene compressInMemory(const Scene& input, const CompressOptions& options) {
    return compressAnalyzed(input, analyzeScene(input, analysisOptionsOf(options)), planOptionsOf(options));
}

}  // namespace symcompress
