// Repeated assemblies (tiles that recur together in one relative placement): each worth it becomes one mesh
// (its first copy, about its anchor's centroid) drawn by a node per copy.
#include "plan/member_check.hpp"
#include "plan/planners.hpp"
#include "plan/primitives_by_kind.hpp"
#include "symcompress/assembly.hpp"

#include <algorithm>
#include <mutex>

namespace symcompress {

std::vector<SharedPart> planAssemblies(const PlanContext& context, std::vector<bool>& drawn) {
    const SceneAnalysis& analysis = context.analysis;
    const std::vector<Tile>& tiles = analysis.tiles;
    const TileClassification& classification = analysis.classification;
    // Each tile's primitive made by the first check that asks for it (the checks run in parallel).
    std::vector<std::optional<Primitive>> primitives(tiles.size());
    std::vector<std::once_flag> made(tiles.size());
    auto primitiveOf = [&](std::size_t t) -> const Primitive& {
        std::call_once(made[t], [&] { primitives[t] = tilePrimitive(tiles[t], analysis.soup); });
        return *primitives[t];
    };
    AssemblyOptions assemblyOptions;
    assemblyOptions.accept = [&](std::size_t from, std::size_t to, const Isometry& map) {
        return reproduces(primitiveOf(from), primitiveOf(to), map, context.tolerance(), context.options.geometryOnly);
    };
    std::vector<double> classDeviation(tiles.size(), 0);
    for (const CongruenceClass& c : classification.classes)
        for (std::size_t i = 0; i < c.members.size(); ++i) classDeviation[c.members[i]] = c.deviations[i];

    std::vector<SharedPart> stored;
    for (const RepeatedAssembly& assembly : findRepeatedAssemblies(tiles, classification, assemblyOptions)) {
        if (std::any_of(assembly.copies.begin(), assembly.copies.end(), [&](const std::vector<std::size_t>& copy) {
                return std::any_of(copy.begin(), copy.end(), [&](std::size_t t) { return bool(drawn[t]); });
            }))
            continue;
        // Once with a node per copy, against storing every tile of every copy apart.
        const Eigen::Vector3d center = classification.shapes[assembly.copies[0][0]].moments.centroid;
        SharedPart shared;
        shared.mechanism = SharedPart::Mechanism::Assembly;
        double apart = 0;
        for (std::size_t j = 0; j < assembly.copies.size(); ++j) {
            for (std::size_t t : assembly.copies[j]) apart += context.costs.apart(t);
            shared.nodes.push_back({assembly.placements[j].matrix() * translationTo(center),
                                    context.sourceOf(assembly.copies[j][0]), std::nullopt});
        }
        const double nodes = context.costs.nodes(shared.nodes);
        if (context.costs.meshOf(assembly.copies[0]) + nodes >= apart) continue;
        PrimitivesByKind parts;
        for (std::size_t t : assembly.copies[0]) {
            Primitive local = primitiveOf(t);
            for (auto& p : local.positions) p -= center;
            parts.add(local);
        }
        shared.mesh.name =
            "assembly " + std::to_string(stored.size()) + " (" + std::to_string(assembly.copies[0].size()) + " tiles)";
        parts.moveInto(shared.mesh);
        shared.copies = assembly.copies.size();
        for (std::size_t j = 0; j < assembly.copies.size(); ++j) {
            double worst = 0;
            for (std::size_t i = 0; i < assembly.copies[j].size(); ++i) {
                drawn[assembly.copies[j][i]] = true;
                shared.tiles.push_back(assembly.copies[j][i]);
                worst = std::max(worst, classDeviation[assembly.copies[0][i]] + classDeviation[assembly.copies[j][i]]);
            }
            // Every tile of every copy was also verified vertex by vertex (assemblyOptions.accept).
            if (j > 0)
                shared.deviation =
                    std::max(shared.deviation, std::min(assembly.deviation + worst, analysis.options.tolerance));
        }
        stored.push_back(std::move(shared));
    }
    return stored;
}

}  // namespace symcompress
