// Repeated assemblies (tiles that recur together in one relative placement): each worth it becomes one mesh
// (its first copy, about its anchor's centroid) drawn by a node per copy, or, where the first copy is symmetric in
// itself, one part of it drawn by a node per copy and element of its group.
#include "plan/member_check.hpp"
#include "plan/planners.hpp"
#include "symcompress/assembly.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <limits>
#include <map>
#include <mutex>
#include <set>

namespace symcompress {
namespace {

// Where a tile stands in the classification: its class and its index among the class's members.
struct Membership {
    std::size_t klass = 0, member = 0;
};

// The assembly without the classes whose tiles cost less drawn by their class's mesh, a node each (batched where
// the writer batches), than in the assembly's mesh once per tile of copy 0: the five lamps of a room copied five
// times are one lamp and 25 instances, the rest of the room one mesh and 5 nodes. Empty when fewer than two
// tiles a copy are left.
RepeatedAssembly withoutClassesBetterApart(const RepeatedAssembly& assembly, const PlanContext& context,
                                           const std::vector<Membership>& membership) {
    const std::vector<std::size_t>& first = assembly.copies[0];
    std::map<std::size_t, std::vector<std::size_t>> positionsByClass;  // positions in copy 0
    for (std::size_t i = 0; i < first.size(); ++i) positionsByClass[membership[first[i]].klass].push_back(i);
    std::vector<bool> leftOut(first.size(), false);
    for (const auto& [klass, positions] : positionsByClass) {
        const CongruenceClass& c = context.analysis.classification.classes[klass];
        std::vector<PlacedCopy> drawing;
        for (const std::vector<std::size_t>& copy : assembly.copies)
            for (std::size_t i : positions)
                drawing.push_back(
                    {c.placements[membership[copy[i]].member].matrix(), context.sourceOf(copy[i]), std::nullopt});
        const std::size_t tile = first[positions.front()];
        if (context.costs.alone(tile) + context.costs.nodes(drawing) <
            double(positions.size()) * context.costs.merged(tile))
            for (std::size_t i : positions) leftOut[i] = true;
    }
    RepeatedAssembly kept{std::vector<std::vector<std::size_t>>(assembly.copies.size()), assembly.placements,
                          assembly.deviation};
    for (std::size_t i = 0; i < first.size(); ++i)
        if (!leftOut[i])
            for (std::size_t j = 0; j < assembly.copies.size(); ++j) kept.copies[j].push_back(assembly.copies[j][i]);
    if (kept.copies[0].size() < 2) kept.copies.clear();
    return kept;
}

// A frame whose axes are the group's: its main axis (the rotation of the highest fold, else a mirror's normal) and
// an axis or mirror normal across it where there is one. A room's walls then lie along the frame's axes, and
// Draco codes its boxes as it would the room unturned. The identity when the group has no axis.
Eigen::Matrix3d frameOfAxes(const SymmetryGroup& group) {
    const Symmetry* main = nullptr;
    for (const Symmetry& element : group.elements) {
        if (element.kind == Symmetry::Kind::Identity || element.kind == Symmetry::Kind::Inversion) continue;
        const bool rotation = element.kind == Symmetry::Kind::Rotation;
        if (!main || (rotation && (main->kind != Symmetry::Kind::Rotation || element.fold > main->fold)))
            main = &element;
    }
    if (!main) return Eigen::Matrix3d::Identity();
    const Eigen::Vector3d z = main->axis.normalized();
    Eigen::Vector3d x = Eigen::Vector3d::UnitX() - z.x() * z;  // any direction across z, unless the group has one
    if (x.norm() < 0.5) x = Eigen::Vector3d::UnitY() - z.y() * z;
    for (const Symmetry& element : group.elements)
        if (element.axis.norm() > 0.5 && std::abs(element.axis.normalized().dot(z)) < 1e-6) {
            x = element.axis;
            break;
        }
    x.normalize();
    Eigen::Matrix3d frame;
    frame << x, z.cross(x), z;
    return frame;
}

// The principal axes of the tiles' surface together (their second moments about their common centroid): a
// room of boxes has them along its walls, wherever it stands turned.
Eigen::Matrix3d principalFrame(const TileClassification& classification, const std::vector<std::size_t>& tiles) {
    double area = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (std::size_t t : tiles) {
        area += classification.shapes[t].moments.area;
        weighted += classification.shapes[t].moments.area * classification.shapes[t].moments.centroid;
    }
    if (!(area > 0)) return Eigen::Matrix3d::Identity();
    const Eigen::Vector3d center = weighted / area;
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (std::size_t t : tiles) {
        const TileShape& shape = classification.shapes[t];
        const Eigen::Vector3d offset = shape.moments.centroid - center;
        second += shape.secondMoments + shape.moments.area * offset * offset.transpose();
    }
    Eigen::Matrix3d frame = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(second).eigenvectors();
    if (frame.determinant() < 0) frame.col(2) = -frame.col(2);
    return frame;
}

// The part's mesh written in `frame` where Draco codes it smaller there (the shared mesh's tiles come from one
// input node or none, as when baked: planSourceFrames tries the nodes' frame, and this the one the geometry gives).
void useFrameIfSmaller(SharedPart& part, const Eigen::Matrix3d& frame, const StorageCosts& costs) {
    Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
    turn.topLeftCorner<3, 3>() = frame;
    if (costs.meshBytesQuickly(meshInFrame(part.mesh, turn)) < costs.meshBytesQuickly(part.mesh)) part.frame = frame;
}

}  // namespace

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
    std::vector<Membership> membership(tiles.size());
    for (std::size_t k = 0; k < classification.classes.size(); ++k) {
        const CongruenceClass& c = classification.classes[k];
        for (std::size_t i = 0; i < c.members.size(); ++i) {
            classDeviation[c.members[i]] = c.deviations[i];
            membership[c.members[i]] = {k, i};
        }
    }

    std::vector<SharedPart> stored;
    for (const RepeatedAssembly& found : findRepeatedAssemblies(tiles, classification, assemblyOptions)) {
        if (std::any_of(found.copies.begin(), found.copies.end(), [&](const std::vector<std::size_t>& copy) {
                return std::any_of(copy.begin(), copy.end(), [&](std::size_t t) { return bool(drawn[t]); });
            }))
            continue;
        const RepeatedAssembly assembly = withoutClassesBetterApart(found, context, membership);
        if (assembly.copies.empty()) continue;
        const std::vector<std::size_t>& first = assembly.copies[0];
        double apart = 0;  // every tile of every copy stored apart
        for (const std::vector<std::size_t>& copy : assembly.copies)
            for (std::size_t t : copy) apart += context.costs.apart(t);
        // Copy 0 as one mesh (about its anchor's centroid), drawn by a node per copy.
        const Eigen::Vector3d anchorCenter = classification.shapes[first[0]].moments.centroid;
        std::vector<PlacedCopy> copyNodes;
        for (std::size_t j = 0; j < assembly.copies.size(); ++j)
            copyNodes.push_back({assembly.placements[j].matrix() * translationTo(anchorCenter),
                                 context.sourceOf(assembly.copies[j][0]), std::nullopt});
        const double whole = context.costs.meshOf(first) + context.costs.nodes(copyNodes);
        // Or, where copy 0 is symmetric (a room of mirrored quadrants, copied), one part of it drawn by a node per
        // copy and element of its group.
        const SymmetryGroup group = assemblySymmetries(classification, first);
        FreeOrbits orbits;
        std::vector<PlacedCopy> symmetricNodes;
        std::vector<bool> inOrbit(first.size(), true);
        // Copy 0's tiles on the group's planes and axes (a room's floor and walls): one mesh drawn by a node per
        // copy, as the whole copy would be. Left to their classes, they would be quantized with the scene's
        // tiles stored as they are, within the budget but coarser (a room copied five times: a fifth of a
        // pixel at the floor's edges, 0.58% of its pixels in render_compare.sh, for 20 bytes).
        std::vector<std::size_t> rest;
        double symmetric = std::numeric_limits<double>::infinity();
        if (group.elements.size() >= 2) orbits = freeOrbits(context, group, first);
        if (!orbits.part.empty()) {
            for (std::size_t j = 0; j < assembly.copies.size(); ++j)
                for (const PlacedCopy& element : elementNodes(group))
                    symmetricNodes.push_back({assembly.placements[j].matrix() * element.transform,
                                              context.sourceOf(assembly.copies[j][0]), std::nullopt});
            const std::set<std::size_t> orbitTiles(orbits.orbitTiles.begin(), orbits.orbitTiles.end());
            for (std::size_t i = 0; i < first.size(); ++i) {
                inOrbit[i] = orbitTiles.count(first[i]) > 0;
                if (!inOrbit[i]) rest.push_back(first[i]);
            }
            symmetric = context.costs.meshOf(orbits.part) + context.costs.nodes(symmetricNodes) +
                        (rest.empty() ? 0 : context.costs.meshOf(rest) + context.costs.nodes(copyNodes));
        }
        if (std::min(whole, symmetric) >= apart) continue;
        // A part drawn in every copy: the tiles of copy 0 at the positions `at`, their copies marked drawn.
        auto share = [&](SharedPart shared, const std::vector<bool>& at, double ownDeviation) {
            shared.mechanism = SharedPart::Mechanism::Assembly;
            shared.copies = assembly.copies.size();
            for (std::size_t j = 0; j < assembly.copies.size(); ++j) {
                double worst = 0;
                for (std::size_t i = 0; i < first.size(); ++i) {
                    if (!at[i]) continue;
                    drawn[assembly.copies[j][i]] = true;
                    shared.tiles.push_back(assembly.copies[j][i]);
                    worst = std::max(worst, classDeviation[first[i]] + classDeviation[assembly.copies[j][i]]);
                }
                // Every tile of every copy was also verified vertex by vertex (assemblyOptions.accept), and
                // every element's copy of a representative in copy 0 (freeOrbits).
                const double copyDeviation = (j > 0 ? assembly.deviation + worst : 0) + ownDeviation;
                shared.deviation = std::max(shared.deviation, std::min(copyDeviation, analysis.options.tolerance));
            }
            stored.push_back(std::move(shared));
        };
        const std::string name = "assembly " + std::to_string(stored.size()) + " (";
        if (symmetric < whole) {
            SharedPart shared;
            shared.mesh = partAbout(analysis, orbits.part, group.centroid);
            shared.mesh.name = name + "1/" + std::to_string(group.elements.size()) + " of " +
                               std::to_string(first.size()) + " tiles, " + group.name + ")";
            shared.nodes = std::move(symmetricNodes);
            shared.group = group.name;
            useFrameIfSmaller(shared, frameOfAxes(group), context.costs);
            share(std::move(shared), inOrbit, orbits.deviation);
            if (rest.empty()) continue;
            SharedPart onPlanes;
            onPlanes.mesh = partAbout(analysis, rest, anchorCenter);
            onPlanes.mesh.name =
                name + std::to_string(rest.size()) + " tiles on the planes and axes of " + group.name + ")";
            onPlanes.nodes = std::move(copyNodes);
            std::vector<bool> onPlane(inOrbit.size());
            for (std::size_t i = 0; i < inOrbit.size(); ++i) onPlane[i] = !inOrbit[i];
            share(std::move(onPlanes), onPlane, 0);
        } else {
            SharedPart shared;
            shared.mesh = partAbout(analysis, first, anchorCenter);
            shared.mesh.name = name + std::to_string(first.size()) + " tiles)";
            shared.nodes = std::move(copyNodes);
            useFrameIfSmaller(shared, principalFrame(classification, first), context.costs);
            share(std::move(shared), std::vector<bool>(first.size(), true), 0);
        }
    }
    return stored;
}

}  // namespace symcompress
