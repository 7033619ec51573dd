// The compression plan: tiles, classes, the members their prototype reproduces, and the scene that draws
// every class once per member.
#include "symcompress/compress.hpp"

#include "symcompress/assembly.hpp"
#include "symcompress/fundamental_region.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/symmetry.hpp"
#include "../io/rounded.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

constexpr double kNormalCosine = 0.999;  // normals within 2.6 degrees are the same
constexpr double kTexcoordTolerance = 1e-4;
constexpr double kColorTolerance = 1e-3;
// The fundamental region of a tile under a group, if its copies rebuild the tile within the tolerance.
std::optional<FundamentalRegion> regionOf(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                          const Eigen::Vector3d& center, double tolerance) {
    try {
        RegionOptions regionOptions;
        // Instances that are signed permutations in the region's frame map Draco's grid onto itself, so
        // seams on coordinate planes stay closed after quantization.
        regionOptions.frame = RegionFrame::Aligned;
        regionOptions.groupTolerance = 1e-5;
        // Float32 coordinates put a symmetric model's vertices on its planes only to about 1e-7 of its size;
        // cut points that close to a vertex become zero-area triangles once quantized, which Draco's
        // edgebreaker cannot keep (the coffee cup's region tripled in size).
        regionOptions.snapTolerance = 1e-6;
        FundamentalRegion region = computeFundamentalRegion(tile, group, center, regionOptions);
        const Primitive rebuilt = rebuildFromRegion(region);
        TriangleMesh a{rebuilt.positions, rebuilt.triangles}, b{tile.positions, tile.triangles};
        const SurfaceComparison check = compareSurfaces(a, b, 1e-6);
        const double diagonal = digestOf(b, 0).bounds.diagonal().norm();
        if (check.maxDeviation * diagonal > tolerance || std::abs(check.areaRatio - 1) > 1e-6) return std::nullopt;
        return region;
    } catch (const std::invalid_argument&) {
        return std::nullopt;  // a group the region code does not take (e.g. not closed within its tolerance)
    }
}

// The surface's orientation, independent of how it is cut into triangles: its vector area S = ∫ n dA and
// M = ∫ n (x - c)^T dA about its area centroid c (for a closed part, its volume times the identity).
struct OrientedMoments {
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    Eigen::Matrix3d first = Eigen::Matrix3d::Zero();
};

OrientedMoments orientedMoments(const Primitive& part) {
    double total = 0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    for (const Triangle& t : part.triangles) {
        const Eigen::Vector3d &a = part.positions[t[0]], &b = part.positions[t[1]], &c = part.positions[t[2]];
        const double area = 0.5 * (b - a).cross(c - a).norm();
        total += area;
        weighted += area * (a + b + c) / 3;
    }
    const Eigen::Vector3d centre = total > 0 ? Eigen::Vector3d(weighted / total) : Eigen::Vector3d::Zero();
    OrientedMoments moments;
    for (const Triangle& t : part.triangles) {
        const Eigen::Vector3d &a = part.positions[t[0]], &b = part.positions[t[1]], &c = part.positions[t[2]];
        const Eigen::Vector3d vectorArea = 0.5 * (b - a).cross(c - a);
        moments.area += vectorArea;
        moments.first += vectorArea * ((a + b + c) / 3 - centre).transpose();
    }
    return moments;
}

// Whether the member faces the way the prototype placed by j does (a mirrored placement is drawn with
// its winding reversed, as glTF and X3D viewers do for a negative determinant, so both map as j): a flat
// part turned over matches its copy as a point set, not in orientation. Parts that look the same both
// ways (two-faced sheets) pass.
bool sameOrientation(const Primitive& prototype, const Primitive& member, const Isometry& j, double radius) {
    const OrientedMoments p = orientedMoments(prototype), m = orientedMoments(member);
    const Eigen::Vector3d expectedArea = j.linear * p.area;
    const Eigen::Matrix3d expectedFirst = j.linear * p.first * j.linear.transpose();
    const double difference = (m.area - expectedArea).norm() + (m.first - expectedFirst).norm() / radius;
    const double size = p.area.norm() + p.first.norm() / radius;
    return difference <= 0.5 * size;
}

// Whether the prototype placed by j reproduces the member one vertex to one vertex, attributes included,
// facing the same way.
bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance) {
    if (prototype.triangles.size() != member.triangles.size() || prototype.positions.size() != member.positions.size() ||
        prototype.normals.empty() != member.normals.empty() || prototype.texcoords.empty() != member.texcoords.empty() ||
        prototype.colors.empty() != member.colors.empty())
        return false;
    std::vector<Eigen::Vector3d> both;
    both.reserve(prototype.positions.size() + member.positions.size());
    for (const auto& p : prototype.positions) both.push_back(j.linear * p + j.translation);
    both.insert(both.end(), member.positions.begin(), member.positions.end());
    const std::vector<std::uint32_t> representative = weldPositions(both, tolerance);
    // Prototype vertices by position (seams put several vertices, with different attributes, at one place).
    std::multimap<std::uint32_t, std::uint32_t> atPosition;
    for (std::uint32_t u = 0; u < prototype.positions.size(); ++u) atPosition.emplace(representative[u], u);
    auto same = [&](std::uint32_t u, std::uint32_t v) {
        if (!prototype.normals.empty() && (j.linear * prototype.normals[u]).dot(member.normals[v]) < kNormalCosine) return false;
        if (!prototype.texcoords.empty() &&
            (prototype.texcoords[u] - member.texcoords[v]).cwiseAbs().maxCoeff() > kTexcoordTolerance)
            return false;
        if (!prototype.colors.empty() && (prototype.colors[u] - member.colors[v]).cwiseAbs().maxCoeff() > kColorTolerance)
            return false;
        return true;
    };
    for (std::uint32_t v = 0; v < member.positions.size(); ++v) {
        const auto [first, last] = atPosition.equal_range(representative[prototype.positions.size() + v]);
        bool found = false;
        for (auto it = first; it != last && !found; ++it) found = same(it->second, v);
        if (!found) return false;
    }
    Eigen::AlignedBox3d box;
    for (const auto& p : member.positions) box.extend(p);
    return sameOrientation(prototype, member, j, std::max(box.diagonal().norm(), tolerance));
}

// Primitives gathered by material and by which attributes they carry, so that merging never drops an
// attribute some of them have (a tile without normals next to tiles with them gets a primitive of its own).
class PrimitivesByKind {
public:
    void add(const Primitive& part) {
        append(parts_[{part.material, !part.normals.empty(), !part.texcoords.empty(), !part.colors.empty()}], part);
    }
    // `part` appended to `into`, which carries the same attributes.
    static void append(Primitive& into, const Primitive& part) {
        const auto offset = static_cast<std::uint32_t>(into.positions.size());
        into.material = part.material;
        into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
        into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
        into.texcoords.insert(into.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
        into.colors.insert(into.colors.end(), part.colors.begin(), part.colors.end());
        for (const Triangle& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
    bool empty() const { return parts_.empty(); }
    void moveInto(Mesh& mesh) {
        for (auto& [kind, primitive] : parts_) mesh.primitives.push_back(std::move(primitive));
        parts_.clear();
    }

private:
    std::map<std::tuple<int, bool, bool, bool>, Primitive> parts_;
};

// Triangle t of the part on its own: its three vertices with their attributes (writers store every
// vertex a primitive lists, used or not).
Primitive triangleOf(const Primitive& part, std::size_t t) {
    Primitive one;
    one.material = part.material;
    for (std::uint32_t v : part.triangles[t]) {
        one.positions.push_back(part.positions[v]);
        if (!part.normals.empty()) one.normals.push_back(part.normals[v]);
        if (!part.texcoords.empty()) one.texcoords.push_back(part.texcoords[v]);
        if (!part.colors.empty()) one.colors.push_back(part.colors[v]);
    }
    one.triangles = {{0, 1, 2}};
    return one;
}

// The plan's measure of what storing parts costs, in bytes of output: CompressOptions::meshBytes where the
// writer gives one, else its constants. A part's triangles merged into a mesh with other parts cost what
// the scene's parts with the same attributes cost a triangle (measured on a sample of them together, as
// Draco codes them: a box among boxes in far fewer bytes than alone); a part as a mesh of its own costs
// what the writer measures for it, its class's prototype measured once.
class StorageCosts {
public:
    StorageCosts(const SceneAnalysis& analysis, const CompressOptions& options)
        : analysis_(analysis), options_(options), classOf_(analysis.tiles.size(), kNone), memberOf_(analysis.tiles.size(), 0) {
        const auto& classes = analysis.classification.classes;
        for (std::size_t k = 0; k < classes.size(); ++k)
            for (std::size_t i = 0; i < classes[k].members.size(); ++i) {
                classOf_[classes[k].members[i]] = k;
                memberOf_[classes[k].members[i]] = i;
            }
        classMesh_.assign(classes.size(), -1);
    }

    double asMesh(const Primitive& part) const {
        if (options_.meshBytes) return options_.meshBytes(part);
        return double(part.triangles.size()) * options_.bytesPerTriangle + options_.bytesPerMesh;
    }
    double instance() const { return options_.bytesPerInstance; }
    // A node drawing a shared mesh with this transform and name, as the writer measures it.
    double node(const Eigen::Matrix4d& transform, const std::string& name) const {
        if (!options_.nodeBytes) return instance();
        Node node;
        node.transform = transform;
        node.name = name;
        return options_.nodeBytes(node);
    }

    // Tile t's triangles in a mesh with other parts.
    double merged(std::size_t t) { return double(analysis_.tiles[t].mesh.triangles.size()) * kindOf(t).perTriangle; }
    // Tile t as a mesh of its own (its class's prototype).
    double alone(std::size_t t) {
        const std::size_t k = classOf_[t];
        if (k == kNone) return asMesh(tilePrimitive(analysis_.tiles[t], analysis_.soup));
        if (classMesh_[k] < 0) {
            const std::size_t prototype = analysis_.classification.classes[k].prototype;
            classMesh_[k] = asMesh(tilePrimitive(analysis_.tiles[prototype], analysis_.soup));
        }
        return classMesh_[k];
    }
    // The cheaper way of storing tile t apart from a group of tiles: as it is, or drawn by its class's
    // mesh (a node placing it, and its share of the mesh).
    double apart(std::size_t t) {
        if (classOf_[t] == kNone) return std::min(merged(t), instance() + alone(t));
        const CongruenceClass& c = analysis_.classification.classes[classOf_[t]];
        return std::min(merged(t), node(c.placements[memberOf_[t]].matrix(), "") + alone(t) / double(c.members.size()));
    }
    // A mesh of these tiles: their triangles, and with `overhead` that of a primitive per material and
    // attributes.
    double meshOf(const std::vector<std::size_t>& tiles, bool overhead = true) {
        double bytes = 0;
        std::set<std::pair<int, Attributes>> primitives;
        for (std::size_t t : tiles) {
            bytes += merged(t);
            if (overhead && primitives.insert({analysis_.tiles[t].material, attributesOf(t)}).second) bytes += kindOf(t).overhead;
        }
        return bytes;
    }

private:
    static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    static constexpr std::size_t kSampleTriangles = 20000;
    using Attributes = std::tuple<bool, bool, bool>;  // normals, texture coordinates, colours
    struct KindCosts {
        double perTriangle = 0, overhead = 0;
    };

    Attributes attributesOf(std::size_t t) const {
        const WorldPrimitive& from = analysis_.soup[analysis_.tiles[t].sources.front().primitive];
        return {!from.primitive.normals.empty(), !from.primitive.texcoords.empty(), !from.primitive.colors.empty()};
    }
    // Measured on tiles spread over the scene, up to kSampleTriangles, merged as the writer would.
    const KindCosts& kindOf(std::size_t t) {
        const Attributes attributes = attributesOf(t);
        if (const auto known = kinds_.find(attributes); known != kinds_.end()) return known->second;
        std::vector<std::size_t> same;
        std::size_t triangles = 0;
        for (std::size_t u = 0; u < analysis_.tiles.size(); ++u)
            if (attributesOf(u) == attributes) {
                same.push_back(u);
                triangles += analysis_.tiles[u].mesh.triangles.size();
            }
        const std::size_t step = std::max<std::size_t>(1, triangles / kSampleTriangles);
        Primitive sample;
        for (std::size_t i = 0; i < same.size(); i += step) {
            Primitive part = tilePrimitive(analysis_.tiles[same[i]], analysis_.soup);
            part.material = -1;
            PrimitivesByKind::append(sample, part);
        }
        const Primitive one = triangleOf(sample, 0);
        KindCosts costs;
        costs.overhead = asMesh(one);
        costs.perTriangle = sample.triangles.size() > 1
                                ? std::max(0.0, (asMesh(sample) - costs.overhead) / double(sample.triangles.size() - 1))
                                : costs.overhead;
        return kinds_[attributes] = costs;
    }

    const SceneAnalysis& analysis_;
    const CompressOptions& options_;
    std::vector<std::size_t> classOf_, memberOf_;  // a tile's class, and its index among the class's members
    std::vector<double> classMesh_;  // < 0: not measured yet
    std::map<Attributes, KindCosts> kinds_;
};

// The fundamental region of a tile under `group`, on the grid that keeps its seams closed where its frame
// allows (CompressOptions::seamGridBits): as it would be stored.
std::optional<FundamentalRegion> storableRegion(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                                const Eigen::Vector3d& center, double tolerance, int seamGridBits) {
    std::optional<FundamentalRegion> region = regionOf(tile, group, center, tolerance);
    if (region && seamGridBits > 0 && region->signedPermutationFrame) {
        RegionInGridSteps onGrid = inGridSteps(*region, seamPreservingGrid(*region, seamGridBits));
        region = std::move(onGrid.region);
        region->region.positionGrid = onGrid.grid;
    }
    return region;
}

// The fundamental region that stores a class's copies in the fewest bytes, of G itself or of a subgroup
// H of G, and what it costs (`nodes` prices the nodes that draw a region's copies in every tile). A region
// of H is about 1/|H| of the tile and costs |H| nodes a copy, so the best |H| balances mesh and nodes: a
// 960-triangle sphere (D32h) drawn once is not worth 128 nodes, but may be worth 4. Subgroups are tried
// only where their estimate (tileBytes / |H| + |H| nodeBytes) beats `toBeat`, only those generated by
// their mirrors (closed seams) whose planes cut no triangle, and at most two of each of the two orders
// that promise most: nothing is tried for a class whose nodes would cost more than a region saves (a
// bolt repeated a thousand times).
std::pair<std::optional<FundamentalRegion>, double> cheapestRegion(
    const Primitive& tile, const std::vector<Eigen::Matrix3d>& group, const Eigen::Vector3d& center, double tolerance,
    int seamGridBits, StorageCosts& costs, double tileBytes, double nodeBytes, double toBeat,
    const std::function<double(const FundamentalRegion&)>& nodes) {
    auto cost = [&](const FundamentalRegion& r) { return costs.asMesh(r.region) + nodes(r); };
    std::optional<FundamentalRegion> best = storableRegion(tile, group, center, tolerance, seamGridBits);
    double bestCost = best ? cost(*best) : std::numeric_limits<double>::infinity();
    auto estimate = [&](std::size_t order) { return tileBytes / double(order) + double(order) * nodeBytes; };
    std::vector<std::vector<std::size_t>> subgroups;
    try {
        subgroups = subgroupsOf(group, 1e-5);
    } catch (const std::invalid_argument&) {
        return {std::move(best), bestCost};  // not closed within the tolerance: the region code refuses it too
    }
    std::map<std::size_t, std::vector<std::vector<Eigen::Matrix3d>>> byOrder;
    for (const auto& h : subgroups) {
        if (h.size() == 1 || h.size() == group.size() || estimate(h.size()) >= std::min(bestCost, toBeat)) continue;
        std::vector<Eigen::Matrix3d> subgroup;
        for (std::size_t e : h) subgroup.push_back(group[e]);
        if (generatedByMirrors(subgroup)) byOrder[h.size()].push_back(std::move(subgroup));
    }
    std::vector<std::size_t> orders;
    for (const auto& entry : byOrder) orders.push_back(entry.first);
    std::sort(orders.begin(), orders.end(), [&](std::size_t a, std::size_t b) { return estimate(a) < estimate(b); });
    for (std::size_t o = 0; o < std::min<std::size_t>(orders.size(), 2); ++o)
        for (std::size_t c = 0; c < std::min<std::size_t>(byOrder[orders[o]].size(), 2); ++c) {
            const std::vector<Eigen::Matrix3d>& subgroup = byOrder[orders[o]][c];
            std::optional<FundamentalRegion> region = storableRegion(tile, subgroup, center, tolerance, seamGridBits);
            // A cut splits triangles and puts new vertices mid-edge (decoders comparing vertices see them
            // as deviations): the whole group may cut, a subgroup is chosen only where it cuts nothing.
            if (region && region->trianglesCut == 0 && cost(*region) < bestCost) bestCost = cost(*region), best = std::move(region);
        }
    return {std::move(best), bestCost};
}

// The name of the input node that draws tile t (empty when it has none): instance nodes keep it.
std::string sourceName(const Scene& input, const SceneAnalysis& analysis, std::size_t t) {
    const Tile& tile = analysis.tiles[t];
    if (tile.sources.empty()) return {};
    const int node = analysis.soup[tile.sources.front().primitive].node;
    return node >= 0 && std::size_t(node) < input.nodes.size() ? input.nodes[std::size_t(node)].name : std::string();
}

void addRootNode(Scene& out, int mesh, const Eigen::Matrix4d& transform, const std::string& name) {
    Node node;
    node.name = name;
    node.mesh = mesh;
    node.transform = transform;
    out.roots.push_back(int(out.nodes.size()));
    out.nodes.push_back(std::move(node));
}

// Which nodes are animated or under an animated node (reached from the roots); `tops` gets the animated
// nodes with no animated ancestor, in increasing order.
std::vector<bool> markAnimatedSubtrees(const Scene& input, std::vector<int>& tops) {
    std::vector<bool> animated(input.nodes.size(), false), inSubtree(input.nodes.size(), false);
    for (const Animation& animation : input.animations)
        for (const AnimationChannel& channel : animation.channels) animated[std::size_t(channel.node)] = true;
    std::vector<std::pair<int, bool>> stack;  // node, whether an ancestor is animated
    for (int root : input.roots) stack.push_back({root, false});
    while (!stack.empty()) {
        const auto [node, under] = stack.back();
        stack.pop_back();
        if (animated[std::size_t(node)] && !under) tops.push_back(node);
        inSubtree[std::size_t(node)] = under || animated[std::size_t(node)];
        for (int child : input.nodes[std::size_t(node)].children) stack.push_back({child, inSubtree[std::size_t(node)]});
    }
    std::sort(tops.begin(), tops.end());
    return inSubtree;
}

// The animated subtrees as they are (SceneAnalysis::animatedSubtrees), each under a root node holding its
// parent's world transform, and the input's animations retargeted to them. Meshes are shared with the
// other kept meshes through `keptMesh` (input mesh -> output mesh).
void keepAnimatedSubtrees(const Scene& input, const SceneAnalysis& analysis, Scene& out, std::map<int, int>& keptMesh,
                          CompressionStats& stats) {
    if (input.animations.empty()) return;
    const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
    std::vector<int> parent(input.nodes.size(), -1);
    for (std::size_t n = 0; n < input.nodes.size(); ++n)
        for (int child : input.nodes[n].children) parent[std::size_t(child)] = int(n);
    std::map<int, int> nodeOf;  // input node -> output node
    auto copy = [&](auto&& self, int node) -> int {
        const Node& from = input.nodes[std::size_t(node)];
        Node to;
        to.name = from.name;
        to.transform = from.transform;
        to.camera = from.camera;
        to.light = from.light;
        if (from.mesh >= 0) {
            auto [entry, added] = keptMesh.emplace(from.mesh, int(out.meshes.size()));
            if (added) out.meshes.push_back(input.meshes[std::size_t(from.mesh)]);
            to.mesh = entry->second;
        }
        const int index = int(out.nodes.size());
        out.nodes.push_back(std::move(to));
        nodeOf[node] = index;
        ++stats.animatedNodesKept;
        for (int child : from.children) {
            const int copied = self(self, child);
            out.nodes[std::size_t(index)].children.push_back(copied);
        }
        return index;
    };
    for (int top : analysis.animatedSubtrees) {
        // The parent's own world transform, not the node's times its inverse: an animated node may have a
        // scale of 0 at rest (hidden until its animation shows it).
        const int above = parent[std::size_t(top)];
        addRootNode(out, -1, above < 0 ? Eigen::Matrix4d::Identity() : world[std::size_t(above)], "");
        const int holder = out.roots.back();
        const int copied = copy(copy, top);
        out.nodes[std::size_t(holder)].children.push_back(copied);
    }
    std::size_t undrawn = 0;  // channels of nodes that no root reaches
    for (Animation animation : input.animations) {
        std::vector<AnimationChannel> kept;
        for (AnimationChannel& channel : animation.channels) {
            const auto copied = nodeOf.find(channel.node);
            if (copied == nodeOf.end()) {
                ++undrawn;
                continue;
            }
            channel.node = copied->second;
            kept.push_back(std::move(channel));
        }
        animation.channels = std::move(kept);
        if (!animation.channels.empty()) out.animations.push_back(std::move(animation));
    }
    if (undrawn)
        out.warnings.push_back(std::to_string(undrawn) + " animation channels of nodes the scene does not draw left out");
}

// Every node with a camera or a light, outside the animated subtrees (which keep theirs), as a root node at
// its world placement: the tiles are rebuilt elsewhere, the viewpoints and lights stay where they were.
void keepCamerasAndLights(const Scene& input, const SceneAnalysis& analysis, Scene& out, CompressionStats& stats) {
    out.cameras = input.cameras;
    out.lights = input.lights;
    const std::vector<int>& animated = analysis.animatedSubtrees;  // their tops, sorted: a subtree is skipped whole
    std::vector<std::pair<int, Eigen::Matrix4d>> stack;  // node, its parent's world transform
    for (auto root = input.roots.rbegin(); root != input.roots.rend(); ++root) stack.push_back({*root, Eigen::Matrix4d::Identity()});
    while (!stack.empty()) {
        const auto [node, parentWorld] = stack.back();
        stack.pop_back();
        const Node& from = input.nodes[std::size_t(node)];
        if (std::binary_search(animated.begin(), animated.end(), node)) continue;
        const Eigen::Matrix4d world = parentWorld * from.transform;
        if (from.camera >= 0 || from.light >= 0) {
            addRootNode(out, -1, world, from.name);
            out.nodes.back().camera = from.camera;
            out.nodes.back().light = from.light;
            ++stats.camerasAndLightsKept;
        }
        for (auto child = from.children.rbegin(); child != from.children.rend(); ++child) stack.push_back({*child, world});
    }
}

// The primitive with its positions only: what `reproduces` compares when attributes are ignored.
Primitive geometryOf(Primitive primitive) {
    primitive.normals.clear();
    primitive.texcoords.clear();
    primitive.colors.clear();
    return primitive;
}

// `reproduces`, on positions and faces only with --geometry-only.
bool reproducesAsAsked(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                       const CompressOptions& options) {
    return options.geometryOnly ? reproduces(geometryOf(prototype), geometryOf(member), j, tolerance)
                                : reproduces(prototype, member, j, tolerance);
}

// The scene's own symmetry: the group G of the whole assembly of tiles (paper 6.3). The tiles of G's free
// orbits (which G moves onto |G| distinct tiles) are stored once, for one fundamental part of the scene,
// as one mesh drawn by a node per element of G: a room of mirrored quadrants costs one quadrant. From each
// orbit the tile nearest a point that no element fixes is taken: the part is the tiles of one Dirichlet
// domain of G, a compact region. Tiles on G's planes and axes are left to the other mechanisms. Returns
// which tiles it draws.
std::vector<bool> planSceneSymmetry(const SceneAnalysis& analysis, const CompressOptions& options, StorageCosts& costs,
                                    Scene& out, CompressionStats& stats) {
    const std::vector<Tile>& tiles = analysis.tiles;
    const TileClassification& classification = analysis.classification;
    std::vector<bool> drawn(tiles.size(), false);
    const SymmetryGroup group = assemblySymmetries(classification, options.tolerance);
    const std::size_t order = group.elements.size();
    if (order < 2) return drawn;
    const std::vector<std::vector<std::size_t>> images = tileImages(classification, group, options.tolerance);
    const Eigen::Vector3d center = group.centroid;
    auto about = [&](std::size_t e) {
        Isometry map;
        map.linear = group.elements[e].linear;
        map.translation = center - map.linear * center;
        return map;
    };
    const double tolerance = options.tolerance * classification.sceneDiagonal;
    auto reproducedBy = [&](std::size_t from, std::size_t to, const Isometry& map) {
        return reproducesAsAsked(tilePrimitive(tiles[from], analysis.soup), tilePrimitive(tiles[to], analysis.soup), map,
                                 tolerance, options);
    };
    const Eigen::Vector3d generic = center + classification.sceneDiagonal * Eigen::Vector3d(0.5377, 0.8314, 0.1403);

    std::vector<bool> seen(tiles.size(), false);
    std::vector<std::size_t> part, orbitTiles;
    double apart = 0;
    for (std::size_t t = 0; t < tiles.size(); ++t) {
        if (seen[t]) continue;
        std::set<std::size_t> orbit;
        for (std::size_t e = 0; e < order; ++e) orbit.insert(images[e][t]);
        for (std::size_t u : orbit)
            if (u < tiles.size()) seen[u] = true;
        if (orbit.size() < order || *orbit.rbegin() >= tiles.size()) continue;  // on a plane or axis of G
        const std::size_t representative = *std::min_element(orbit.begin(), orbit.end(), [&](std::size_t a, std::size_t b) {
            return (classification.shapes[a].moments.centroid - generic).norm() < (classification.shapes[b].moments.centroid - generic).norm();
        });
        bool verified = true;
        for (std::size_t e = 1; e < order && verified; ++e) verified = reproducedBy(representative, images[e][representative], about(e));
        if (!verified) continue;
        part.push_back(representative);
        orbitTiles.insert(orbitTiles.end(), orbit.begin(), orbit.end());
        apart += double(order) * costs.apart(representative);
    }
    // Once with a node per element, against storing every tile apart; a mesh of its own costs extra only
    // when some tiles are left for another mesh.
    auto nodeOf = [&](std::size_t e) {
        Eigen::Matrix4d node = Eigen::Matrix4d::Identity();
        node.topLeftCorner<3, 3>() = group.elements[e].linear;
        node.topRightCorner<3, 1>() = center;
        return node;
    };
    double nodes = 0;
    for (std::size_t e = 0; e < order; ++e) nodes += costs.node(nodeOf(e), "");
    if (part.empty() || costs.meshOf(part, orbitTiles.size() < tiles.size()) + nodes >= apart) return drawn;
    PrimitivesByKind parts;
    for (std::size_t t : part) {
        Primitive local = tilePrimitive(tiles[t], analysis.soup);
        for (auto& p : local.positions) p -= center;
        parts.add(local);
    }
    Mesh mesh;
    mesh.name = "1/" + std::to_string(order) + " of the scene (" + group.name + ")";
    parts.moveInto(mesh);
    out.meshes.push_back(std::move(mesh));
    for (std::size_t e = 0; e < order; ++e) addRootNode(out, int(out.meshes.size()) - 1, nodeOf(e), "");
    for (std::size_t t : orbitTiles) drawn[t] = true;
    stats.sceneGroup = group.name;
    stats.tilesInSceneSymmetry = orbitTiles.size();
    stats.instances += order;
    stats.maxDeviation = std::max(stats.maxDeviation, options.tolerance);  // each copy verified vertex by vertex
    return drawn;
}

// The repeated assemblies worth storing once: each becomes one mesh (its first copy, about its anchor's
// centroid) drawn by a node per copy; an assembly with a tile already `drawn` is left out. Marks the
// tiles they draw in `drawn`.
void planAssemblies(const Scene& input, const SceneAnalysis& analysis, const CompressOptions& options,
                    StorageCosts& costs, Scene& out, CompressionStats& stats, std::vector<bool>& drawn) {
    const std::vector<Tile>& tiles = analysis.tiles;
    const TileClassification& classification = analysis.classification;
    const double tolerance = options.tolerance * classification.sceneDiagonal;
    std::vector<std::optional<Primitive>> primitives(tiles.size());
    auto primitiveOf = [&](std::size_t t) -> const Primitive& {
        if (!primitives[t]) primitives[t] = tilePrimitive(tiles[t], analysis.soup);
        return *primitives[t];
    };
    AssemblyOptions assemblyOptions;
    assemblyOptions.tolerance = options.tolerance;
    assemblyOptions.accept = [&](std::size_t from, std::size_t to, const Isometry& map) {
        return reproducesAsAsked(primitiveOf(from), primitiveOf(to), map, tolerance, options);
    };
    std::vector<double> classDeviation(tiles.size(), 0);
    for (const CongruenceClass& c : classification.classes)
        for (std::size_t i = 0; i < c.members.size(); ++i) classDeviation[c.members[i]] = c.deviations[i];

    for (const RepeatedAssembly& assembly : findRepeatedAssemblies(tiles, classification, assemblyOptions)) {
        if (std::any_of(assembly.copies.begin(), assembly.copies.end(), [&](const std::vector<std::size_t>& copy) {
                return std::any_of(copy.begin(), copy.end(), [&](std::size_t t) { return bool(drawn[t]); });
            }))
            continue;
        // Once with a node per copy, against storing every tile of every copy apart.
        const Eigen::Vector3d center = classification.shapes[assembly.copies[0][0]].moments.centroid;
        Eigen::Matrix4d atCenter = Eigen::Matrix4d::Identity();
        atCenter.topRightCorner<3, 1>() = center;
        double apart = 0, nodes = 0;
        for (std::size_t j = 0; j < assembly.copies.size(); ++j) {
            for (std::size_t t : assembly.copies[j]) apart += costs.apart(t);
            nodes += costs.node(assembly.placements[j].matrix() * atCenter, sourceName(input, analysis, assembly.copies[j][0]));
        }
        if (costs.meshOf(assembly.copies[0]) + nodes >= apart) continue;
        const std::size_t index = stats.assemblies++;
        PrimitivesByKind parts;
        for (std::size_t t : assembly.copies[0]) {
            Primitive local = primitiveOf(t);
            for (auto& p : local.positions) p -= center;
            parts.add(local);
        }
        Mesh mesh;
        mesh.name = "assembly " + std::to_string(index) + " (" + std::to_string(assembly.copies[0].size()) + " tiles)";
        parts.moveInto(mesh);
        out.meshes.push_back(std::move(mesh));
        for (std::size_t j = 0; j < assembly.copies.size(); ++j) {
            addRootNode(out, int(out.meshes.size()) - 1, assembly.placements[j].matrix() * atCenter,
                        sourceName(input, analysis, assembly.copies[j][0]));
            double worst = 0;
            for (std::size_t i = 0; i < assembly.copies[j].size(); ++i) {
                drawn[assembly.copies[j][i]] = true;
                worst = std::max(worst, classDeviation[assembly.copies[0][i]] + classDeviation[assembly.copies[j][i]]);
            }
            // Every tile of every copy was also verified vertex by vertex (assemblyOptions.accept).
            if (j > 0) stats.maxDeviation = std::max(stats.maxDeviation, std::min(assembly.deviation + worst, options.tolerance));
        }
        stats.assemblyCopies += assembly.copies.size();
        stats.instances += assembly.copies.size();
        stats.tilesInAssemblies += assembly.copies.size() * assembly.copies[0].size();
    }
}

double since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void reportProgress(const CompressOptions& options, const char* stage, std::size_t count, const char* unit) {
    if (options.progress) options.progress(stage, count, unit);
}

}  // namespace

SceneAnalysis analyzeScene(const Scene& input, const CompressOptions& options) {
    SceneAnalysis analysis;
    auto start = std::chrono::steady_clock::now();
    analysis.soup = flattenScene(input);
    const std::vector<bool> animated = markAnimatedSubtrees(input, analysis.animatedSubtrees);
    analysis.soup.erase(std::remove_if(analysis.soup.begin(), analysis.soup.end(),
                                       [&](const WorldPrimitive& placed) { return animated[std::size_t(placed.node)]; }),
                        analysis.soup.end());
    if (options.keepInputInstances) {
        // A mesh drawn by two or more nodes, one of them scaling or shearing it, is the author's instancing
        // of copies that are not congruent: kept as it is, and left out of the tiles. (Rigid copies are
        // left to the classes, which may also find more of them baked elsewhere.)
        std::map<int, std::set<int>> nodesOfMesh;
        for (const WorldPrimitive& placed : analysis.soup) nodesOfMesh[placed.mesh].insert(placed.node);
        const std::vector<Eigen::Matrix4d> world = worldTransforms(input);
        auto rigid = [&](int node) {
            const Eigen::Matrix3d linear = world[std::size_t(node)].topLeftCorner<3, 3>();
            return (linear.transpose() * linear - Eigen::Matrix3d::Identity()).norm() < 1e-6;
        };
        std::set<int> kept;
        for (const auto& [mesh, nodes] : nodesOfMesh)
            if (mesh >= 0 && nodes.size() > 1 && !std::all_of(nodes.begin(), nodes.end(), rigid)) {
                kept.insert(mesh);
                for (int node : nodes) analysis.keptInstances.push_back({mesh, world[std::size_t(node)], input.nodes[std::size_t(node)].name});
            }
        analysis.soup.erase(std::remove_if(analysis.soup.begin(), analysis.soup.end(),
                                           [&](const WorldPrimitive& placed) { return kept.count(placed.mesh) > 0; }),
                            analysis.soup.end());
    }
    std::size_t triangles = 0;
    for (const WorldPrimitive& placed : analysis.soup) triangles += placed.primitive.triangles.size();
    reportProgress(options, "splitting into tiles", triangles, "triangles");
    analysis.tiles = splitIntoTiles(analysis.soup);
    analysis.digest = digestOf(worldMesh(input), options.tolerance);
    analysis.secondsTiles = since(start);
    start = std::chrono::steady_clock::now();
    CongruenceOptions congruenceOptions;
    congruenceOptions.tolerance = options.tolerance;
    congruenceOptions.threads = options.threads;
    if (options.instancing) {
        reportProgress(options, "classifying", analysis.tiles.size(), "tiles");
        analysis.classification = classifyTiles(analysis.tiles, congruenceOptions);
    }
    analysis.secondsClasses = since(start);
    return analysis;
}

CompressedScene compressScene(const Scene& input, const CompressOptions& options) {
    return planCompression(input, analyzeScene(input, options), options);
}

CompressedScene planCompression(const Scene& input, const SceneAnalysis& analysis, const CompressOptions& options) {
    CompressedScene result;
    CompressionStats& stats = result.stats;
    const std::vector<WorldPrimitive>& soup = analysis.soup;
    const std::vector<Tile>& tiles = analysis.tiles;
    result.digest = analysis.digest;
    stats.trianglesIn = result.digest.triangles;
    stats.tiles = tiles.size();
    stats.secondsTiles = analysis.secondsTiles;
    stats.secondsClasses = analysis.secondsClasses;
    static const TileClassification noClasses;
    const TileClassification& classification = options.instancing ? analysis.classification : noClasses;

    const auto start = std::chrono::steady_clock::now();
    Scene& out = result.scene;
    out.textures = input.textures;
    out.materials = input.materials;
    out.x3dEnvironment = input.x3dEnvironment;
    out.warnings = input.warnings;
    std::map<int, int> keptMesh;  // input mesh -> output mesh
    PrimitivesByKind unique;        // tiles stored as they are
    std::set<std::string> merged;   // names of the input nodes whose parts are merged into `unique`
    for (const KeptInstance& kept : analysis.keptInstances) {
        if (!options.instancing) {
            // Every copy as it is, as Draco alone stores it: the author's sharing may cost more than it saves
            // (hundreds of small scaled copies), and this plan is the one that stores nothing shared.
            for (const Primitive& primitive : input.meshes[std::size_t(kept.mesh)].primitives)
                unique.add(transformPrimitive(primitive, kept.transform));
            if (!kept.name.empty()) merged.insert(kept.name);
            continue;
        }
        auto [entry, added] = keptMesh.emplace(kept.mesh, int(out.meshes.size()));
        if (added) out.meshes.push_back(input.meshes[std::size_t(kept.mesh)]);
        addRootNode(out, entry->second, kept.transform, kept.name);
        ++stats.inputInstancesKept;
        ++stats.instances;
    }
    keepAnimatedSubtrees(input, analysis, out, keptMesh, stats);
    keepCamerasAndLights(input, analysis, out, stats);
    if (!options.instancing)
        for (const Tile& tile : tiles) unique.add(tilePrimitive(tile, soup));
    std::vector<bool> uniqueTile(tiles.size(), !options.instancing);  // stored as it is
    const double tolerance = options.tolerance * analysis.classification.sceneDiagonal;
    reportProgress(options, "planning", analysis.classification.classes.size(), "classes");
    // Tiles drawn by a shared mesh of the scene's symmetry or of a repeated assembly.
    std::vector<bool> drawn(tiles.size(), false);
    StorageCosts costs(analysis, options);
    if (options.instancing && options.assemblies) {
        drawn = planSceneSymmetry(analysis, options, costs, out, stats);
        planAssemblies(input, analysis, options, costs, out, stats, drawn);
    }
    for (std::size_t k = 0; k < classification.classes.size(); ++k) {
        const CongruenceClass& c = classification.classes[k];
        ++stats.classes;
        if (classification.shapes[c.prototype].symmetry.order() > 1) ++stats.symmetricClasses;
        const Primitive prototype = tilePrimitive(tiles[c.prototype], soup);
        // Indices into c.members drawn from the prototype's mesh (members already drawn are left out).
        std::vector<std::size_t> placed;
        if (!drawn[c.prototype]) placed.push_back(0);
        std::vector<Isometry> placements = c.placements;
        std::vector<Primitive> apart;  // members stored as they are
        const TileShape& shape = classification.shapes[c.prototype];
        for (std::size_t i = 1; i < c.members.size(); ++i) {
            if (drawn[c.members[i]]) continue;
            Primitive member = tilePrimitive(tiles[c.members[i]], soup);
            // Every J g (g in the prototype's group) places the geometry (paper property 4); the
            // attributes and the faces' orientation pick among them.
            bool found = false;
            for (const Symmetry& g : shape.symmetry.elements) {
                Isometry candidate;
                candidate.linear = c.placements[i].linear * g.linear;
                candidate.translation = c.placements[i].linear * (shape.moments.centroid - g.linear * shape.moments.centroid) +
                                        c.placements[i].translation;
                if (reproducesAsAsked(prototype, member, candidate, tolerance, options)) {
                    placements[i] = candidate;
                    found = true;
                    break;
                }
            }
            if (found) {
                placed.push_back(i);
            } else {
                ++stats.attributeMismatches;
                uniqueTile[c.members[i]] = true;
                apart.push_back(std::move(member));
            }
        }
        for (const Primitive& member : apart) unique.add(member);
        if (placed.empty()) continue;

        // The nodes drawing the class's mesh: one per placed member and copy in its tile.
        auto nodesCost = [&](const std::vector<Eigen::Matrix4d>& copiesInTile) {
            double bytes = 0;
            for (std::size_t i : placed)
                for (const Eigen::Matrix4d& copy : copiesInTile)
                    bytes += costs.node(placements[i].matrix() * copy, sourceName(input, analysis, c.members[i]));
            return bytes;
        };
        const Eigen::Vector3d center = shape.moments.centroid;
        Eigen::Matrix4d atCenter = Eigen::Matrix4d::Identity();
        atCenter.topRightCorner<3, 1>() = center;
        // Store whichever costs least: every copy as it is, the tile once with a node per copy, or a
        // fundamental region once with a node per copy and group element.
        // A single copy with no symmetry is stored as it is without measuring (most classes of a big scene).
        constexpr double kNever = std::numeric_limits<double>::infinity();
        const double copies = double(placed.size());
        std::optional<FundamentalRegion> region;
        double regional = kNever;
        double instanced = kNever;
        if (placed.size() > 1 || (options.regions && shape.symmetry.order() > 1))
            instanced = costs.alone(c.prototype) + nodesCost({atCenter});
        // The prototype's symmetries that also carry its attributes onto themselves: the group its
        // fundamental region may use (a textured part is rarely symmetric in its texture coordinates).
        if (options.regions && shape.symmetry.order() > 1) {
            std::vector<Eigen::Matrix3d> group;
            for (const Symmetry& g : shape.symmetry.elements) {
                Isometry about;
                about.linear = g.linear;
                about.translation = center - g.linear * center;
                if (reproducesAsAsked(prototype, prototype, about, tolerance, options)) group.push_back(g.linear);
            }
            auto regionNodes = [&](const FundamentalRegion& r) {
                std::vector<Eigen::Matrix4d> copiesInTile;
                for (std::size_t j = 0; j < r.instances.size(); ++j) copiesInTile.push_back(instanceTransform(r, j));
                return nodesCost(copiesInTile);
            };
            const double alone = costs.alone(c.prototype), perNode = (instanced - alone) / copies;
            if (group.size() > 1)
                std::tie(region, regional) = cheapestRegion(prototype, group, center, tolerance, options.seamGridBits, costs, alone,
                                                            perNode, std::min(instanced, copies * costs.merged(c.prototype)), regionNodes);
        }
        const bool single = placed.size() == 1 && !region;
        if (single || copies * costs.merged(c.prototype) <= std::min(instanced, regional)) {
            if (placed.size() > 1) stats.notWorthInstancing += placed.size();
            for (std::size_t i : placed) {
                uniqueTile[c.members[i]] = true;
                unique.add(i == 0 ? prototype : tilePrimitive(tiles[c.members[i]], soup));
            }
            continue;
        }
        const bool useRegion = regional < instanced;
        // The shared mesh is stored about the prototype's centroid (a small range for quantization); a
        // region in its aligned frame, also about the centroid (see RegionFrame::Aligned).
        Mesh mesh;
        mesh.name = "class " + std::to_string(k) + (useRegion ? " (fundamental region)" : "");
        Primitive local = useRegion ? region->region : prototype;
        if (!useRegion)
            for (auto& p : local.positions) p -= center;
        mesh.primitives.push_back(std::move(local));
        const int meshIndex = int(out.meshes.size());
        out.meshes.push_back(std::move(mesh));
        if (placed.size() > 1) ++stats.instancedClasses;
        if (useRegion) ++stats.regionClasses;
        std::vector<Eigen::Matrix4d> copiesInTile;
        if (useRegion) {
            for (std::size_t j = 0; j < region->instances.size(); ++j) copiesInTile.push_back(instanceTransform(*region, j));
        } else {
            copiesInTile.push_back(atCenter);
        }
        for (std::size_t i : placed) {
            for (std::size_t j = 0; j < copiesInTile.size(); ++j) {
                addRootNode(out, meshIndex, placements[i].matrix() * copiesInTile[j], sourceName(input, analysis, c.members[i]));
                ++stats.instances;
            }
            stats.maxDeviation = std::max(stats.maxDeviation, c.deviations[i]);
        }
    }
    if (!unique.empty()) {
        // One mesh per material for every tile stored as it is, drawn by one node: it takes the name of
        // the node its tiles came from when that is a single one; otherwise the names are lost.
        for (std::size_t t = 0; t < tiles.size(); ++t)
            if (uniqueTile[t])
                if (std::string name = sourceName(input, analysis, t); !name.empty()) merged.insert(name);
        if (merged.size() > 1)
            out.warnings.push_back(std::to_string(merged.size()) + " node names (e.g. '" + *merged.begin() +
                                   "') not kept: their tiles are stored as they are in one mesh per material");
        Mesh mesh;
        unique.moveInto(mesh);
        out.meshes.push_back(std::move(mesh));
        addRootNode(out, int(out.meshes.size()) - 1, Eigen::Matrix4d::Identity(), merged.size() == 1 ? *merged.begin() : "");
    }
    // Triangles with two corners at one point draw nothing; kept, they would cost Draco's edgebreaker
    // (which drops them) a sequential primitive (the subpass scene has 4100 of them).
    std::size_t pointLike = 0;
    for (Mesh& mesh : out.meshes)
        for (Primitive& p : mesh.primitives) {
            const std::size_t before = p.triangles.size();
            p.triangles.erase(std::remove_if(p.triangles.begin(), p.triangles.end(), [&](const Triangle& t) {
                                  return p.positions[t[0]] == p.positions[t[1]] || p.positions[t[1]] == p.positions[t[2]] ||
                                         p.positions[t[0]] == p.positions[t[2]];
                              }),
                              p.triangles.end());
            pointLike += before - p.triangles.size();
            stats.trianglesStored += p.triangles.size();
        }
    if (pointLike)
        out.warnings.push_back(std::to_string(pointLike) +
                               " stored triangles with two corners at one point (zero area, they draw nothing) left out");
    stats.secondsPlan = since(start);
    return result;
}

SurfaceDigest digestOf(const TriangleMesh& surface, double tolerance) {
    SurfaceDigest digest;
    digest.triangles = surface.triangles.size();
    digest.tolerance = tolerance;
    for (const Triangle& t : surface.triangles) {
        const auto &a = surface.positions[t[0]], &b = surface.positions[t[1]], &c = surface.positions[t[2]];
        digest.area += 0.5 * (b - a).cross(c - a).norm();
        digest.bounds.extend(a).extend(b).extend(c);
    }
    return digest;
}

std::string SurfaceDigest::json() const {
    // Nine digits: far below any tolerance the digest is checked with, and half the text of seventeen.
    auto number = [](double x) { return rounded(x, 9); };
    auto vector = [&](const Eigen::Vector3d& v) { return nlohmann::json{number(v.x()), number(v.y()), number(v.z())}; };
    nlohmann::json digest{{"triangles", triangles}, {"area", number(area)}, {"tolerance", number(tolerance)}};
    if (!bounds.isEmpty()) digest["bbox"] = {{"min", vector(bounds.min())}, {"max", vector(bounds.max())}};
    return nlohmann::json{{"symcompress_digest", digest}}.dump();
}

bool SurfaceDigest::fromJson(const std::string& text, SurfaceDigest& digest) {
    const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
    if (root.is_discarded() || !root.is_object() || !root.contains("symcompress_digest")) return false;
    const auto& d = root["symcompress_digest"];
    try {
        digest.triangles = d.at("triangles").get<std::size_t>();
        digest.area = d.at("area").get<double>();
        digest.tolerance = d.at("tolerance").get<double>();
        if (d.contains("bbox")) {
            const auto& lo = d["bbox"].at("min");
            const auto& hi = d["bbox"].at("max");
            digest.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(lo[0], lo[1], lo[2]), Eigen::Vector3d(hi[0], hi[1], hi[2]));
        }
    } catch (const nlohmann::json::exception&) {
        return false;
    }
    return true;
}

}  // namespace symcompress
