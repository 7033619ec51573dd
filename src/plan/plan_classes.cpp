// Every congruence class: the members the prototype reproduces are drawn from one stored mesh, the tile or
// its fundamental region, by a node per member (and per region copy), where that costs less than storing
// them as they are.
#include "plan/member_check.hpp"
#include "plan/planners.hpp"
#include "plan/region_choice.hpp"
#include "common/with_threads.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

// The prototype's surface with its hierarchy, built by the first member check that needs it (members are
// checked in parallel).
class LazySurface {
public:
    explicit LazySurface(const Primitive& primitive) : primitive_(primitive) {}
    const TileSurface& get() {
        std::call_once(once_, [&] { surface_ = std::make_unique<TileSurface>(primitive_); });
        return *surface_;
    }

private:
    const Primitive& primitive_;
    std::once_flag once_;
    std::unique_ptr<TileSurface> surface_;
};

// The placement of the prototype onto member i that the member check accepts, if any, and the member's
// deviation under it (relative to the diagonal): every J g (g in the prototype's group) places the geometry
// (paper property 4); the attributes and the faces' orientation pick among them, a placement that reproduces
// the member corner by corner first. A member tessellated otherwise, or whose corners are cut into other
// triangles, is checked as a surface (surfaceDeviation, its surfaces built once), its deviation then measured.
std::optional<std::pair<Isometry, double>> acceptedPlacement(const PlanContext& context, const CongruenceClass& c,
                                                             std::size_t i, const Primitive& prototype,
                                                             const Primitive& member, LazySurface& prototypeSurface) {
    const TileShape& shape = context.analysis.classification.shapes[c.prototype];
    std::vector<Isometry> candidates;  // for the surface check
    // A group not detected (CongruenceOptions::groupUsable) places by J alone.
    const std::vector<Symmetry> identity(1);
    for (const Symmetry& g : shape.symmetry.elements.empty() ? identity : shape.symmetry.elements) {
        Isometry candidate;
        candidate.linear = c.placements[i].linear * g.linear;
        candidate.translation = c.placements[i].linear * (shape.moments.centroid - g.linear * shape.moments.centroid) +
                                c.placements[i].translation;
        const Reproduction corners =
            reproduction(prototype, member, candidate, context.tolerance(), context.options.geometryOnly);
        if (corners == Reproduction::Reproduced) return std::pair{candidate, c.deviations[i]};
        if (corners != Reproduction::AttributesDiffer) candidates.push_back(candidate);
    }
    if (candidates.empty()) return std::nullopt;
    const TileSurface memberSurface(member);
    const double diagonal = context.analysis.diagonal;
    for (const Isometry& candidate : candidates)
        if (const auto deviation = surfaceDeviation(prototypeSurface.get(), memberSurface, candidate, context.tolerance(),
                                                    context.options.geometryOnly))
            return std::pair{candidate, diagonal > 0 ? *deviation / diagonal : 0};
    return std::nullopt;
}

// The prototype's symmetries that also carry its attributes onto themselves: the group its fundamental
// region may use (a textured part is rarely symmetric in its texture coordinates).
std::vector<Eigen::Matrix3d> attributeGroup(const PlanContext& context, const TileShape& shape,
                                            const Primitive& prototype, LazySurface& surface) {
    const Eigen::Vector3d center = shape.moments.centroid;
    const double tolerance = context.tolerance();
    const bool geometryOnly = context.options.geometryOnly;
    const std::vector<Symmetry>& elements = shape.symmetry.elements;
    auto carriesAttributes = [&](std::size_t e) {
        if (elements[e].kind == Symmetry::Kind::Identity) return true;
        Isometry about;
        about.linear = elements[e].linear;
        about.translation = center - about.linear * center;
        // As `reproduces` decides, the surface's hierarchy built once for every element whose image cuts the
        // same corners otherwise (a quad's diagonal turned the other way), not twice for each.
        const Reproduction corners = reproduction(prototype, prototype, about, tolerance, geometryOnly);
        return corners == Reproduction::Reproduced ||
               (corners == Reproduction::CutOtherwise &&
                surfaceDeviation(surface.get(), surface.get(), about, tolerance, geometryOnly));
    };
    // The elements that carry the attributes make a subgroup: a group of 128 whose attributes keep half of it
    // takes a few checks, not 128.
    std::vector<Eigen::Matrix3d> linear;
    for (const Symmetry& element : elements) linear.push_back(element.linear);
    std::vector<char> carries;
    withThreads(context.analysis.options.threads, [&] { carries = subgroupWhere(linear, carriesAttributes); });
    std::vector<Eigen::Matrix3d> group;
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (carries[e]) group.push_back(elements[e].linear);
    return group;
}

// The placed member with the fewest triangles, where it has fewer than the prototype and reproduces every placed
// member as the member check decides (corner by corner, else as a surface), each under its placement composed
// with the inverse of the stand-in's: copies tessellated each on its own then store the lightest (issue 17).
// Its index into c.members, and each placed member's placement from it and deviation (relative).
struct StandIn {
    std::size_t member = 0;
    Primitive primitive;  // its tile's
    std::vector<Isometry> placements;
    std::vector<double> deviations;
};
std::optional<StandIn> lightestStandIn(const PlanContext& context, const CongruenceClass& c,
                                       const std::vector<std::size_t>& placed,
                                       const std::vector<Isometry>& placements) {
    const SceneAnalysis& analysis = context.analysis;
    auto trianglesOf = [&](std::size_t i) { return analysis.classification.shapes[c.members[i]].triangles; };
    std::size_t lightest = placed.front();
    for (std::size_t i : placed)
        if (trianglesOf(i) < trianglesOf(lightest)) lightest = i;
    if (!(trianglesOf(lightest) < analysis.classification.shapes[c.prototype].triangles)) return std::nullopt;
    StandIn result{lightest, tilePrimitive(analysis.tiles[c.members[lightest]], analysis.soup), placements,
                   std::vector<double>(c.members.size(), 0)};
    const Primitive& standIn = result.primitive;
    const Isometry fromStandIn = placements[lightest].inverse();  // from the stand-in to the prototype
    LazySurface standInSurface(standIn);
    std::vector<char> reproduced(c.members.size(), 0);
    withThreads(analysis.options.threads, [&] {
        tbb::parallel_for(std::size_t(0), placed.size(), [&](std::size_t p) {
            const std::size_t i = placed[p];
            const Isometry& placement = result.placements[i] = placements[i] * fromStandIn;
            const Primitive member = tilePrimitive(analysis.tiles[c.members[i]], analysis.soup);
            double deviation = 0;
            const Reproduction corners =
                reproduction(standIn, member, placement, context.tolerance(), context.options.geometryOnly, &deviation);
            std::optional<double> surface;
            if (corners == Reproduction::Reproduced)
                surface = deviation;
            else if (corners != Reproduction::AttributesDiffer)
                surface = surfaceDeviation(standInSurface.get(), TileSurface(member), placement, context.tolerance(),
                                           context.options.geometryOnly);
            if (!surface) return;
            reproduced[i] = 1;
            result.deviations[i] = analysis.diagonal > 0 ? *surface / analysis.diagonal : 0;
        });
    });
    for (std::size_t i : placed)
        if (!reproduced[i]) return std::nullopt;
    return result;
}

// Whether some placed member's input node has a name or extras (what its instance node would keep).
bool anyNamed(const PlanContext& context, const CongruenceClass& c, const std::vector<std::size_t>& placed) {
    return std::any_of(placed.begin(), placed.end(), [&](std::size_t i) {
        const Node* source = context.sourceOf(c.members[i]);
        return source && hasNodeNotes(*source);
    });
}

// What a class's members stored as they are cost beside their triangles: the primitives they would be alone in (a
// part in a material of its own, a family's members in other materials); the others' primitives are written
// anyway. `storedIn` counts by primitive (StorageCosts::primitiveOf) the tiles that may be stored as they are.
struct PrimitivesOpened {
    std::map<std::size_t, std::pair<std::size_t, std::size_t>> members;  // primitive -> (members in it, one of them)
    double bytes(StorageCosts& costs, const std::vector<std::size_t>& storedIn) const {
        double total = 0;
        for (const auto& [primitive, inIt] : members)
            if (inIt.first == storedIn[primitive]) total += costs.primitiveOverhead(inIt.second);
        return total;
    }
};

// A verdict of "as they are" that fewer tiles stored as they are could turn: storing the members costs
// `triangles` plus the primitives they open, sharing them `shared`.
struct AsTheyAreVerdict {
    double triangles = 0, shared = 0;
    PrimitivesOpened opened;
    bool turns(StorageCosts& costs, const std::vector<std::size_t>& storedIn) const {
        return triangles + opened.bytes(costs, storedIn) > shared;
    }
};

// One class (or family of classes, as one), numbered k: its stored part, if any, and the members stored as they
// are appended to `plan`. `storedIn` counts by primitive the tiles that may be stored as they are (at first every
// tile not `drawn`); a verdict of as they are that weighed more than one member is kept in `verdict`.
void planClass(const PlanContext& context, std::size_t k, const CongruenceClass& c, const std::vector<bool>& drawn,
               const std::vector<std::size_t>& storedIn, CompressionPlan& plan,
               std::optional<AsTheyAreVerdict>& verdict) {
    verdict.reset();
    const SceneAnalysis& analysis = context.analysis;
    const std::vector<Tile>& tiles = analysis.tiles;
    const TileShape& shape = analysis.classification.shapes[c.prototype];
    StorageCosts& costs = context.costs;
    const PlanOptions& options = context.options;
    // A tile drawn alone is drawn whole, by one node: not as a region's copies.
    const bool regions = options.regions && std::none_of(c.members.begin(), c.members.end(),
                                                         [&](std::size_t t) { return analysis.drawnAlone(t); });
    if (c.members.size() == 1 && !(regions && shape.symmetry.order() > 1)) {
        // A single copy with no symmetry to use: stored as it is (most classes of a big scene).
        if (!drawn[c.prototype]) plan.tilesAsTheyAre.push_back(c.prototype);
        return;
    }
    const Primitive prototype = tilePrimitive(tiles[c.prototype], analysis.soup);
    // Indices into c.members drawn from the prototype's mesh (members already drawn are left out).
    std::vector<std::size_t> placed;
    if (!drawn[c.prototype]) placed.push_back(0);
    std::vector<Isometry> placements = c.placements;
    std::vector<double> deviations = c.deviations;
    // The member checks are independent: in parallel, their verdicts then taken in the members' order.
    LazySurface prototypeSurface(prototype);  // built for the first member tessellated otherwise
    std::vector<std::optional<std::pair<Isometry, double>>> accepted(c.members.size());
    withThreads(analysis.options.threads, [&] {
        tbb::parallel_for(std::size_t(1), std::max<std::size_t>(1, c.members.size()), [&](std::size_t i) {
            if (drawn[c.members[i]]) return;
            accepted[i] = acceptedPlacement(context, c, i, prototype, tilePrimitive(tiles[c.members[i]], analysis.soup),
                                            prototypeSurface);
        });
    });
    for (std::size_t i = 1; i < c.members.size(); ++i) {
        if (drawn[c.members[i]]) continue;
        if (accepted[i]) {
            std::tie(placements[i], deviations[i]) = *accepted[i];
            placed.push_back(i);
        } else {
            ++plan.attributeMismatches;
            plan.tilesAsTheyAre.push_back(c.members[i]);
        }
    }
    if (placed.empty()) return;

    // The nodes drawing the class's mesh: one per placed member and copy in its tile, each with the name and
    // extras of the input node its member came from when `named`.
    auto nodesOf = [&](const std::vector<Eigen::Matrix4d>& copiesInTile, bool named) {
        std::vector<PlacedCopy> nodes;
        for (std::size_t i : placed)
            for (const Eigen::Matrix4d& copy : copiesInTile)
                nodes.push_back({placements[i].matrix() * copy, named ? context.sourceOf(c.members[i]) : nullptr,
                                 tiles[c.members[i]].material});
        return nodes;
    };
    // A family's members in materials other than the stored mesh's: a mesh each over the same geometry.
    std::set<int> materials;
    for (std::size_t i : placed) materials.insert(tiles[c.members[i]].material);
    const double variants =
        materials.size() > 1 ? double(materials.size() - 1) * options.costs.materialVariantBytes(prototype) : 0;
    auto regionCopies = [](const FundamentalRegion& r) {
        std::vector<Eigen::Matrix4d> copiesInTile;
        for (std::size_t j = 0; j < r.instances.size(); ++j) copiesInTile.push_back(instanceTransform(r, j));
        return copiesInTile;
    };
    const Eigen::Vector3d center = shape.moments.centroid;
    const Eigen::Matrix4d atCenter = translationTo(center);
    // Store whichever costs least: every copy as it is, the tile once with a node per copy, or a fundamental
    // region once with a node per copy and group element. A single copy with no symmetry is stored as it is
    // without measuring (most classes of a big scene).
    constexpr double kNever = std::numeric_limits<double>::infinity();
    const double copies = double(placed.size());
    std::optional<FundamentalRegion> region;
    double regional = kNever;
    double instanced = kNever;
    if (placed.size() > 1 || (regions && shape.symmetry.order() > 1))
        instanced = costs.alone(c.prototype) + costs.nodes(nodesOf({atCenter}, true)) + variants;
    if (regions && shape.symmetry.order() > 1) {
        const std::vector<Eigen::Matrix3d> group = attributeGroup(context, shape, prototype, prototypeSurface);
        auto regionNodes = [&](const FundamentalRegion& r) {
            return costs.nodes(nodesOf(regionCopies(r), true)) + variants;
        };
        const double alone = costs.alone(c.prototype), perNode = (instanced - alone) / copies;
        double placedDeviation = 0;
        for (std::size_t i : placed) placedDeviation = std::max(placedDeviation, deviations[i]);
        const double gridError =
            options.maxError > 0
                ? (options.maxError - options.instanceShare - placedDeviation) * analysis.diagonal
                : 0;
        if (group.size() > 1)
            std::tie(region, regional) = cheapestRegion(
                {prototype, group, center, context.tolerance(), options.costs.seamGridBits, gridError,
                 options.costs.seamGridRelativeError, options.cutTriangles},
                costs, alone, perNode, std::min(instanced, copies * costs.merged(c.prototype)), regionNodes);
    }
    const bool single = placed.size() == 1 && !region;
    PrimitivesOpened opened;
    for (std::size_t i : placed) {
        auto& inIt = opened.members[costs.primitiveOf(c.members[i])];
        ++inIt.first;
        inIt.second = c.members[i];
    }
    const double triangles = copies * costs.merged(c.prototype);
    double asTheyAre = triangles + opened.bytes(costs, storedIn);
    bool named = true;
    if (!single && asTheyAre <= std::min(instanced, regional) && anyNamed(context, c, placed)) {
        // Stored as they are, the members lose their nodes' names and extras anyway (one mesh per material):
        // shared without them where that is what makes sharing pay (731 named grass cards: 16.6 KB of Draco
        // against 6 KB of GPU instances, 9.5 KB more with their names).
        const double unnamed = costs.alone(c.prototype) + costs.nodes(nodesOf({atCenter}, false)) + variants;
        const double unnamedRegion =
            region ? costs.asMesh(region->region) + costs.nodes(nodesOf(regionCopies(*region), false)) + variants
                   : kNever;
        if (std::min(unnamed, unnamedRegion) < asTheyAre) named = false, instanced = unnamed, regional = unnamedRegion;
        else if (!single)
            verdict = AsTheyAreVerdict{triangles, std::min(unnamed, unnamedRegion), opened};
    }
    if (single || asTheyAre <= std::min(instanced, regional)) {
        if (placed.size() > 1) plan.notWorthInstancing += placed.size();
        if (!single && !verdict) verdict = AsTheyAreVerdict{triangles, std::min(instanced, regional), opened};
        for (std::size_t i : placed) plan.tilesAsTheyAre.push_back(c.members[i]);
        return;
    }
    const bool useRegion = regional < instanced;
    // The shared mesh is stored about the prototype's centroid (a small range for quantization); a region in
    // its aligned frame, also about the centroid (see RegionFrame::Aligned); a lighter stand-in about its own.
    SharedPart shared;
    shared.mechanism = useRegion ? SharedPart::Mechanism::Region : SharedPart::Mechanism::Class;
    std::vector<std::size_t> placedTiles;
    for (std::size_t i : placed) placedTiles.push_back(c.members[i]);
    if (const Mesh* source = commonSourceMesh(context.input, analysis, placedTiles)) {
        shared.mesh.name = source->name;
        shared.mesh.extrasJson = source->extrasJson;
    } else {
        shared.mesh.name = "class " + std::to_string(k) + (useRegion ? " (fundamental region)" : "");
    }
    Primitive local = useRegion ? region->region : prototype;
    Eigen::Vector3d storedAbout = center;
    if (!useRegion)
        if (std::optional<StandIn> standIn = lightestStandIn(context, c, placed, placements);
            standIn && costs.asMesh(standIn->primitive) < costs.alone(c.prototype)) {
            local = std::move(standIn->primitive);
            storedAbout = analysis.classification.shapes[c.members[standIn->member]].moments.centroid;
            placements = std::move(standIn->placements);
            deviations = std::move(standIn->deviations);
        }
    if (!useRegion)
        for (auto& p : local.positions) p -= storedAbout;
    shared.mesh.primitives.push_back(std::move(local));
    shared.nodes =
        nodesOf(useRegion ? regionCopies(*region) : std::vector<Eigen::Matrix4d>{translationTo(storedAbout)}, named);
    shared.named = named;
    for (std::size_t i : placed) {
        shared.tiles.push_back(c.members[i]);
        shared.deviation = std::max(shared.deviation, deviations[i]);
    }
    if (useRegion && analysis.diagonal > 0) shared.deviation += region->deviation / analysis.diagonal;
    shared.copies = placed.size();
    plan.shared.push_back(std::move(shared));
}

// The classes as planned: each as it is, or, where the writer stores a part's geometry once for every material
// it is drawn in, a family of classes as one class in the place of its first (the others left empty). Its
// prototype is that of a class whose tiles have texture coordinates where some have them (it can then draw
// those without: member_check's carriesAttributes), every member placed from it through the family's first.
std::vector<CongruenceClass> classesToPlan(const PlanContext& context) {
    const std::vector<CongruenceClass>& classes = context.analysis.classification.classes;
    if (!context.options.costs.materialVariantBytes) return classes;
    std::map<std::size_t, std::vector<std::size_t>> families;  // first class -> its classes, in order
    for (std::size_t k = 0; k < classes.size(); ++k) families[classes[k].family].push_back(k);
    auto hasTexcoords = [&](std::size_t k) {
        const Tile& tile = context.analysis.tiles[classes[k].prototype];
        return !context.analysis.soup[tile.sources.front().primitive].primitive.texcoords.empty();
    };
    std::vector<CongruenceClass> planned(classes.size());
    for (const auto& [first, members] : families) {
        if (members.size() == 1) {
            planned[first] = classes[first];
            continue;
        }
        std::vector<std::size_t> order = members;
        const auto head = std::find_if(order.begin(), order.end(), hasTexcoords);
        if (head != order.end()) std::rotate(order.begin(), head, head + 1);
        const CongruenceClass& lead = classes[order.front()];
        const Isometry toHead = lead.fromFamily.inverse();
        CongruenceClass& into = planned[first];
        into.prototype = lead.prototype;
        for (std::size_t k : order) {
            const CongruenceClass& c = classes[k];
            const bool same = k == order.front();
            for (std::size_t i = 0; i < c.members.size(); ++i) {
                into.members.push_back(c.members[i]);
                into.placements.push_back(same ? c.placements[i] : c.placements[i] * c.fromFamily * toHead);
                into.deviations.push_back(same ? c.deviations[i]
                                               : c.deviations[i] + c.familyDeviation + lead.familyDeviation);
            }
        }
    }
    return planned;
}

}  // namespace

CompressionPlan planClasses(const PlanContext& context, const std::vector<bool>& drawn) {
    StorageCosts& costs = context.costs;
    const std::vector<CongruenceClass>& classes = context.analysis.classification.classes;
    const std::vector<CongruenceClass> planned = classesToPlan(context);
    std::map<std::size_t, std::vector<std::size_t>> families;  // first class -> its classes, where planned as one
    for (std::size_t k = 0; k < classes.size(); ++k)
        if (planned[classes[k].family].members.size() > classes[classes[k].family].members.size())
            families[classes[k].family].push_back(k);
    std::vector<std::size_t> storedIn(costs.primitives(), 0);
    for (std::size_t t = 0; t < drawn.size(); ++t)
        if (!drawn[t]) ++storedIn[costs.primitiveOf(t)];

    // Each class into its own plan, a family as one into its first's; verdicts of as they are kept to be weighed
    // again.
    std::vector<CompressionPlan> ofClass(classes.size());
    std::vector<std::optional<AsTheyAreVerdict>> verdicts(classes.size()), familyVerdicts(classes.size());
    auto planAlone = [&](std::size_t k) {
        CompressionPlan one;
        planClass(context, k, classes[k], drawn, storedIn, one, verdicts[k]);
        return one;
    };
    auto planFamily = [&](std::size_t k) {
        CompressionPlan one;
        planClass(context, k, planned[k], drawn, storedIn, one, familyVerdicts[k]);
        return one;
    };
    // The classes are independent (StorageCosts is safe to share: a class measures its own mesh, the kinds'
    // measures are taken under a lock): planned in parallel, each into its own plan, then appended in order.
    withThreads(context.analysis.options.threads, [&] {
        tbb::parallel_for(std::size_t(0), classes.size(), [&](std::size_t k) {
            if (planned[k].members.empty()) return;  // merged into its family's
            ofClass[k] = families.count(k) ? planFamily(k) : planAlone(k);
        });
    });
    // A family that shares nothing is planned class by class, as without families: its members stored as they
    // are then come in their classes' order.
    std::set<std::size_t> familiesApart;
    for (const auto& [first, members] : families)
        if (ofClass[first].shared.empty()) {
            familiesApart.insert(first);
            for (std::size_t k : members) ofClass[k] = planAlone(k);
        }

    // A second look, once the verdicts tell which tiles are stored as they are: where none of a material but a
    // class's members are (the others shared), storing them opens a primitive the first look counted as written
    // anyway (a class of small parts beside shared large ones in each of their materials). Fewer tiles stored as
    // they are only make sharing pay more: verdicts turn one way, a few looks settle them.
    constexpr int kLooks = 4;
    for (int look = 0; look < kLooks; ++look) {
        std::fill(storedIn.begin(), storedIn.end(), 0);
        for (const CompressionPlan& one : ofClass)
            for (std::size_t t : one.tilesAsTheyAre) ++storedIn[costs.primitiveOf(t)];
        bool turned = false;
        auto takeIfShared = [&](std::size_t k, CompressionPlan&& again) {
            if (again.shared.empty()) return false;
            ofClass[k] = std::move(again);
            return turned = true;
        };
        for (auto first = familiesApart.begin(); first != familiesApart.end();)
            if (familyVerdicts[*first] && familyVerdicts[*first]->turns(costs, storedIn) &&
                takeIfShared(*first, planFamily(*first))) {
                for (std::size_t k : families[*first])
                    if (k != *first) ofClass[k] = CompressionPlan();
                first = familiesApart.erase(first);
            } else {
                ++first;
            }
        for (std::size_t k = 0; k < classes.size(); ++k) {
            const auto family = families.find(classes[k].family);
            const bool alone = family == families.end() || familiesApart.count(family->first);
            if (alone && verdicts[k] && verdicts[k]->turns(costs, storedIn)) takeIfShared(k, planAlone(k));
        }
        if (!turned) break;
    }

    CompressionPlan plan;
    const TileClassification& classification = context.analysis.classification;
    for (std::size_t k = 0; k < classes.size(); ++k) {
        ++plan.classes;
        if (classification.shapes[classes[k].prototype].symmetry.order() > 1) ++plan.symmetricClasses;
        CompressionPlan& one = ofClass[k];
        for (SharedPart& part : one.shared) plan.shared.push_back(std::move(part));
        plan.tilesAsTheyAre.insert(plan.tilesAsTheyAre.end(), one.tilesAsTheyAre.begin(), one.tilesAsTheyAre.end());
        plan.attributeMismatches += one.attributeMismatches;
        plan.notWorthInstancing += one.notWorthInstancing;
        one = CompressionPlan();
    }
    return plan;
}

}  // namespace symcompress
