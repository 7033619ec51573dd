// EXT_mesh_gpu_instancing: batches of plain leaves drawing one mesh, chosen by the bytes they save, and written.
//
// The extension goes in extensionsRequired: a viewer without it would draw one copy per batch where there are
// hundreds, a wrong scene rather than a plainer one (gltfpack -mi marks it required as well). Rotations may be
// normalized SHORT, which the extension allows without KHR_mesh_quantization; translations and scales stay
// FLOAT, the only type it allows for them without that extension (which would also ask for a dequantizing
// node transform that the batch's mesh would inherit). With Draco the values may go through
// EXT_meshopt_compression (gltf_instance_encoding.cpp), which is then required too: its fallback buffer has
// no data.
#include "gltf_gpu_instancing.hpp"

#include "rotation_and_scale.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

const char* const kExtension = "EXT_mesh_gpu_instancing";
const char* const kMeshopt = "EXT_meshopt_compression";
const char* const kTypes[3] = {"VEC3", "VEC4", "VEC3"};  // of TRANSLATION, ROTATION, SCALE
const char* const kNames[3] = {"TRANSLATION", "ROTATION", "SCALE"};

bool mirrors(const Eigen::Matrix4d& transform) { return transform.topLeftCorner<3, 3>().determinant() < 0; }

// The instance's TRS for a node of local transform `local` in a batch whose node mirrors or not; nothing
// where TRS cannot hold it (a shear) or its handedness is not the batch's.
std::optional<InstanceTrs> instanceTrsOf(const Eigen::Matrix4d& local, bool mirrored) {
    Eigen::Matrix4d matrix = local;
    if (mirrored) matrix.row(0) *= -1;  // mirror^-1 * local, the mirror being scale [-1, 1, 1]
    const auto rotationAndScale = asRotationAndScale(matrix.topLeftCorner<3, 3>());
    if (!rotationAndScale || rotationAndScale->second.x() < 0) return std::nullopt;
    InstanceTrs trs;
    trs.translation = matrix.topRightCorner<3, 1>();
    trs.rotation = Eigen::Quaterniond(rotationAndScale->first).normalized();
    if (trs.rotation.w() < 0) trs.rotation.coeffs() *= -1;  // the same rotation; identity as (0, 0, 0, 1)
    trs.scale = rotationAndScale->second;
    return trs;
}

// A node that can be an instance as far as the node itself tells: it draws a mesh and nothing else, holds no
// extras or extensions of its own (kept on the node; only names have a place in the batch) and is TRS.
bool plainLeaf(const Node& node) {
    return node.mesh >= 0 && node.children.empty() && node.camera < 0 && node.light < 0 && node.skin < 0 &&
           node.weights.empty() && node.extrasJson.empty() && node.extensionsJson.empty() &&
           instanceTrsOf(node.transform, mirrors(node.transform));
}

// Which of the three attributes a batch needs: each is left out where it does nothing for every instance.
std::array<bool, 3> attributesOf(const std::vector<InstanceTrs>& instances) {
    std::array<bool, 3> used{false, false, false};
    for (const InstanceTrs& trs : instances) {
        used[0] = used[0] || !trs.translation.unaryExpr(&asFloat32).isZero(0);
        used[1] = used[1] || trs.rotation.coeffs().unaryExpr(&asFloat32) != Eigen::Vector4d(0, 0, 0, 1);
        used[2] = used[2] || trs.scale.unaryExpr(&asFloat32) != Eigen::Vector3d::Ones();
    }
    return used;
}

Json instanceAccessor(int view, std::size_t offset, int componentType, std::size_t count, const char* type) {
    Json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (offset) accessor["byteOffset"] = offset;
    if (componentType == kShort) accessor["normalized"] = true;
    return accessor;
}

// The origin of a batch of `instances` (InstanceBatch::origin, in the instances' own frame, mirrored where the
// batch is), in decimals to a 16th of `allowed`; zero where float32 holds the translations within a quarter of
// `allowed` as they are (it rounds a coordinate by at most 2^-24 of it).
Eigen::Vector3d batchOrigin(const std::vector<InstanceTrs>& instances, double allowed) {
    Eigen::AlignedBox3d box;
    for (const InstanceTrs& trs : instances) box.extend(trs.translation);
    const double farthest = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
    if (box.isEmpty() || !(farthest * std::ldexp(std::sqrt(3.0), -24) > allowed / 4)) return Eigen::Vector3d::Zero();
    Eigen::Vector3d centre = box.center();
    if (allowed > 0) {
        const int decimals = std::clamp(int(-std::floor(std::log10(allowed / 16))), 0, 17);
        for (int c = 0; c < 3; ++c) centre[c] = roundedDecimals(centre[c], decimals);
    }
    return centre;
}

// `instances` made relative to their batchOrigin; the batch node's translation (in its parent's frame).
Eigen::Vector3d moveToOrigin(std::vector<InstanceTrs>& instances, bool mirrored, double allowed) {
    const Eigen::Vector3d origin = batchOrigin(instances, allowed);
    for (InstanceTrs& trs : instances) trs.translation -= origin;
    return mirrored ? Eigen::Vector3d(-origin.x(), origin.y(), origin.z()) : origin;  // the mirror's own frame
}

Json batchNode(int mesh, const Json& attributes, bool mirrored, const Eigen::Vector3d& origin,
               const std::vector<std::string>& names) {
    Json node = {{"mesh", mesh}, {"extensions", {{kExtension, {{"attributes", attributes}}}}}};
    if (!origin.isZero(0)) node["translation"] = {origin.x(), origin.y(), origin.z()};
    if (mirrored) node["scale"] = {-1, 1, 1};
    // Parallel to the instances, or one name for all of them (a lathe's 256 sectors, each named after its
    // node); the reader gives them back.
    if (std::all_of(names.begin(), names.end(), [&](const std::string& name) { return name == names.front(); })) {
        if (!names.empty() && !names.front().empty()) node["extras"]["instanceNames"] = names.front();
    } else {
        node["extras"]["instanceNames"] = names;
    }
    return node;
}

// A buffer view of instance values: per attribute and encoding (its filter, its component type), shared by
// every batch that stores that attribute so.
using Stream = std::tuple<int, std::string, int>;

Stream streamOf(int attribute, const InstanceEncoding& encoding) {
    return {attribute, encoding.filter, encoding.componentType};
}

// What the first batch of a stream adds once: its buffer view; and the first of meshopt's, the extension's
// name in extensionsUsed and extensionsRequired and the fallback buffer.
double streamBytes(const InstanceEncoding& encoding, bool firstOfMeshopt) {
    if (!encoding.meshopt()) {
        const Json view = {{"buffer", 0}, {"byteLength", 10000}, {"byteOffset", 1000000}};
        return double(jsonText(view).size() + 1);
    }
    const Json compressed = {{"buffer", 0},     {"byteLength", 10000},   {"byteOffset", 100000}, {"byteStride", 12},
                             {"count", 1000},   {"mode", "ATTRIBUTES"}, {"filter", encoding.filter}};
    const Json view = {{"buffer", 1}, {"byteLength", 10000}, {"byteOffset", 100000},
                       {"extensions", {{kMeshopt, compressed}}}};
    double bytes = double(jsonText(view).size() + 1);
    if (firstOfMeshopt) {
        const Json fallback = {{"byteLength", 100000}, {"extensions", {{kMeshopt, {{"fallback", true}}}}}};
        bytes += double(jsonText(fallback).size() + 1) + 2.0 * double(std::string(kMeshopt).size() + 3);
    }
    return bytes;
}

// What the batches' streams so far are.
struct StreamsInUse {
    std::set<Stream> streams;
    bool meshopt = false;
};

// What an attribute of `count` instances stored as `encoding` adds: its accessor, its data and, where no batch
// has used its stream yet, the stream.
double attributeBytes(int attribute, const InstanceEncoding& encoding, std::size_t count, const StreamsInUse& inUse) {
    double bytes = double(jsonText(instanceAccessor(1, 10000, encoding.componentType, count, kTypes[attribute])).size() + 1);
    bytes += double(encoding.storedBytes);
    if (!inUse.streams.count(streamOf(attribute, encoding)))
        bytes += streamBytes(encoding, encoding.meshopt() && !inUse.meshopt);
    return bytes;
}

// What the rounding of one batch may cost. The mesh is not always known (the plan's estimate): then rotations
// are held to a precision, not a distance (lever 1), and scales kept exact.
struct BatchAllowance {
    bool compress = false;               // with Draco: SHORT rotations and meshopt among the candidates
    double translation = 0;              // what translations and scales, together, may move a vertex by
    double rotation = 0;                 // what rotations may
    double meshRadius = 0;               // 0: unknown
    std::vector<double> rotationLever;   // per instance: its farthest vertex from the mesh's origin, scaled
};

// The smallest encoding of each attribute the batch needs, and what they add to the file with `inUse`, which
// then holds their streams too.
std::pair<std::array<std::optional<InstanceEncoding>, 3>, double> chosenEncodings(
    const std::vector<InstanceTrs>& instances, const BatchAllowance& allowance, StreamsInUse& inUse) {
    const std::array<bool, 3> used = attributesOf(instances);
    std::vector<Eigen::Vector3d> translations, scales;
    std::vector<Eigen::Quaterniond> rotations;
    for (const InstanceTrs& trs : instances) {
        translations.push_back(trs.translation);
        rotations.push_back(trs.rotation);
        scales.push_back(trs.scale);
    }
    // Translations and scales share their allowance, half each where both are stored.
    const double vectorShare = allowance.translation * (used[0] && used[2] ? 0.5 : 1.0);
    std::array<std::vector<InstanceEncoding>, 3> candidates;
    if (used[0]) candidates[0] = vectorEncodings(translations, 1, vectorShare, allowance.compress);
    if (used[1]) candidates[1] = rotationEncodings(rotations, allowance.rotationLever, allowance.rotation, allowance.compress);
    if (used[2])
        candidates[2] = vectorEncodings(scales, std::max(allowance.meshRadius, 1e-300),
                                        allowance.meshRadius > 0 ? vectorShare : 0, allowance.compress);
    std::array<std::optional<InstanceEncoding>, 3> chosen;
    double bytes = 0;
    for (int a = 0; a < 3; ++a) {
        if (candidates[std::size_t(a)].empty()) continue;
        double best = 0;
        for (InstanceEncoding& candidate : candidates[std::size_t(a)]) {
            const double candidateBytes = attributeBytes(a, candidate, instances.size(), inUse);
            if (!chosen[std::size_t(a)] || candidateBytes < best) chosen[std::size_t(a)] = std::move(candidate), best = candidateBytes;
        }
        bytes += best;
        inUse.streams.insert(streamOf(a, *chosen[std::size_t(a)]));
        inUse.meshopt = inUse.meshopt || chosen[std::size_t(a)]->meshopt();
    }
    return {std::move(chosen), bytes};
}

// What a batch adds to the file: its node (with its index in its parent's list), its accessors (indices and
// offsets of a typical size) and its binary data, and the streams `inUse` did not hold yet.
double batchBytes(const std::vector<InstanceTrs>& instances, const std::vector<std::string>& names, bool mirrored,
                  const Eigen::Vector3d& origin, double encodedBytes) {
    Json attributes = Json::object();
    const std::array<bool, 3> used = attributesOf(instances);
    for (int a = 0; a < 3; ++a)
        if (used[std::size_t(a)]) attributes[kNames[a]] = 100;
    return encodedBytes + double(jsonText(batchNode(10, attributes, mirrored, origin, names)).size() + 1 + 3);
}

// What the first batch adds once: the extension's name in extensionsUsed and extensionsRequired.
double fileBytesOfFirstBatch() { return 2.0 * double(std::string(kExtension).size() + 3); }

double meshRadius(const Mesh& mesh) {
    double radius = 0;
    for (const Primitive& primitive : mesh.primitives)
        for (const Eigen::Vector3d& p : primitive.positions) radius = std::max(radius, p.norm());
    return radius;
}

// The diagonal of the box of everything the scene draws.
double sceneDiagonal(const Scene& scene) {
    std::vector<Eigen::AlignedBox3d> meshBox(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& primitive : scene.meshes[m].primitives)
            for (const Eigen::Vector3d& p : primitive.positions) meshBox[m].extend(p);
    const std::vector<Eigen::Matrix4d> world = worldTransforms(scene);
    Eigen::AlignedBox3d box;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const int mesh = scene.nodes[n].mesh;
        if (mesh < 0 || meshBox[std::size_t(mesh)].isEmpty()) continue;
        for (int corner = 0; corner < 8; ++corner) {
            const Eigen::Vector3d p = meshBox[std::size_t(mesh)].corner(Eigen::AlignedBox3d::CornerType(corner));
            box.extend((world[n] * p.homogeneous()).head<3>());
        }
    }
    return box.isEmpty() ? 0 : box.diagonal().norm();
}

// Nodes that must stay nodes whatever they hold: what an animation moves and everything under it, a skin's
// joints and skeleton.
std::vector<bool> fixedNodes(const Scene& scene) {
    std::vector<bool> fixed = nodesAnimationsAndSkinsMove(scene);
    for (const Skin& skin : scene.skins)
        if (skin.skeleton >= 0) fixed[std::size_t(skin.skeleton)] = true;
    // Down the hierarchy, from every animated node: the scene is a forest (validateScene).
    std::vector<int> stack;
    for (std::size_t n = 0; n < fixed.size(); ++n)
        if (fixed[n]) stack.push_back(int(n));
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        for (int child : scene.nodes[std::size_t(n)].children)
            if (!fixed[std::size_t(child)]) fixed[std::size_t(child)] = true, stack.push_back(child);
    }
    return fixed;
}

std::vector<std::string> namesOf(const Scene& scene, const std::vector<int>& nodes) {
    std::vector<std::string> names;
    for (int n : nodes) names.push_back(scene.nodes[std::size_t(n)].name);
    return names;
}

}  // namespace

GpuInstancingPlan planGpuInstancing(const Scene& scene, const std::vector<int>& meshIndex,
                                    const WriteOptions& options) {
    GpuInstancingPlan plan;
    plan.batchOf.assign(scene.nodes.size(), -1);
    if (!options.gpuInstancing) return plan;
    const std::vector<bool> fixed = fixedNodes(scene);
    auto eligible = [&](int n) {
        const Node& node = scene.nodes[std::size_t(n)];
        if (fixed[std::size_t(n)] || !plainLeaf(node) || meshIndex[std::size_t(node.mesh)] < 0) return false;
        const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
        // three.js instances no lines or points (its loader draws such a node once), and sorts no instances:
        // blended ones would be drawn in the batch's order, not back to front as nodes of their own are.
        return morphTargetCount(mesh) == 0 &&
               std::all_of(mesh.primitives.begin(), mesh.primitives.end(), [&](const Primitive& p) {
                   return p.topology == Topology::Triangles && !drawnBlended(scene, p.material);
               });
    };
    // Groups by parent, mesh and handedness, in the order of their first node.
    std::map<std::tuple<int, int, bool>, std::size_t> groupOf;
    std::vector<InstanceBatch> groups;
    auto collect = [&](int parent, const std::vector<int>& list) {
        for (int n : list) {
            if (!eligible(n)) continue;
            const Node& node = scene.nodes[std::size_t(n)];
            const auto key = std::make_tuple(parent, node.mesh, mirrors(node.transform));
            const auto [at, isNew] = groupOf.emplace(key, groups.size());
            if (isNew) groups.push_back({parent, node.mesh, std::get<2>(key), {}, {}, {}, {}});
            groups[at->second].nodes.push_back(n);
        }
    };
    collect(-1, scene.roots);
    for (std::size_t p = 0; p < scene.nodes.size(); ++p) collect(int(p), scene.nodes[p].children);

    const double diagonal = sceneDiagonal(scene);
    std::vector<double> radius(scene.meshes.size(), -1);
    StreamsInUse inUse;
    for (InstanceBatch& batch : groups) {
        if (batch.nodes.size() < 2) continue;
        double separate = 0;
        for (int n : batch.nodes) {
            separate += double(gltfNodeBytes(scene.nodes[std::size_t(n)]));
            batch.instances.push_back(*instanceTrsOf(scene.nodes[std::size_t(n)].transform, batch.mirrored));
        }
        double& r = radius[std::size_t(batch.mesh)];
        if (r < 0) r = meshRadius(scene.meshes[std::size_t(batch.mesh)]);
        // Without Draco the file is float throughout, as exact as its reader: the rotations too.
        BatchAllowance allowance{options.draco, options.instanceTranslationDeviation * diagonal,
                                 options.instanceRotationDeviation * diagonal, r, {}};
        batch.origin = moveToOrigin(batch.instances, batch.mirrored, allowance.translation);
        for (const InstanceTrs& trs : batch.instances) allowance.rotationLever.push_back(r * trs.scale.maxCoeff());
        StreamsInUse withBatch = inUse;
        auto [attributes, encodedBytes] = chosenEncodings(batch.instances, allowance, withBatch);
        const double batched =
            batchBytes(batch.instances, namesOf(scene, batch.nodes), batch.mirrored, batch.origin, encodedBytes) +
            (plan.batches.empty() ? fileBytesOfFirstBatch() : 0);
        if (batched >= separate) continue;
        inUse = std::move(withBatch);
        batch.attributes = std::move(attributes);
        for (int n : batch.nodes) plan.batchOf[std::size_t(n)] = int(plan.batches.size());
        plan.batches.push_back(std::move(batch));
    }
    return plan;
}

double gpuBatchBytes(const std::vector<Node>& nodes, const WriteOptions& options) {
    if (nodes.empty()) return -1;
    const bool mirrored = mirrors(nodes.front().transform);
    std::vector<InstanceTrs> instances;
    std::vector<std::string> names;
    std::vector<Eigen::Quaterniond> rotations;
    Eigen::AlignedBox3d extent;
    for (const Node& node : nodes) {
        if (!plainLeaf(node) || mirrors(node.transform) != mirrored) return -1;
        instances.push_back(*instanceTrsOf(node.transform, mirrored));
        names.push_back(node.name);
        rotations.push_back(instances.back().rotation);
        extent.extend(instances.back().translation);
    }
    // The plan cannot tell the mesh yet: rotations as precise as normalized SHORTs, which nearly every batch
    // has; translations within the allowance of their own extent, no larger than the scene's.
    BatchAllowance allowance{options.draco, options.instanceTranslationDeviation * extent.diagonal().norm(),
                             shortRotationError(rotations), 0, std::vector<double>(nodes.size(), 1.0)};
    const Eigen::Vector3d origin = moveToOrigin(instances, mirrored, allowance.translation);
    // Priced as the file's only batch, with every view and extension name its own: the plan weighs one mesh's
    // nodes at a time, and a small scene's batch pays for them all.
    StreamsInUse inUse;
    const double encodedBytes = chosenEncodings(instances, allowance, inUse).second;
    return batchBytes(instances, names, mirrored, origin, encodedBytes) + fileBytesOfFirstBatch();
}

void writeGpuBatches(const GpuInstancingPlan& plan, const Scene& scene, const std::vector<int>& meshIndex,
                     GltfBuilder& builder, Json& root) {
    if (plan.batches.empty()) return;
    // Every batch's values, one stream of each kind, and where each batch's start in it.
    struct StreamData {
        std::size_t elementBytes = 0;
        std::vector<unsigned char> values;
        int view = -1;
    };
    std::map<Stream, StreamData> streams;
    std::vector<std::array<std::size_t, 3>> offsets;
    for (const InstanceBatch& batch : plan.batches) {
        std::array<std::size_t, 3> at{0, 0, 0};
        for (int a = 0; a < 3; ++a) {
            const std::optional<InstanceEncoding>& encoding = batch.attributes[std::size_t(a)];
            if (!encoding) continue;
            StreamData& stream = streams[streamOf(a, *encoding)];
            stream.elementBytes = encoding->elementBytes;
            at[std::size_t(a)] = stream.values.size();
            stream.values.insert(stream.values.end(), encoding->values.begin(), encoding->values.end());
        }
        offsets.push_back(at);
    }
    for (auto& [key, stream] : streams) {
        const std::string& filter = std::get<1>(key);
        stream.view = filter.empty()
                          ? builder.addBufferView(stream.values.data(), stream.values.size())
                          : builder.addMeshoptBufferView(meshoptEncoded(stream.values, stream.elementBytes),
                                                         stream.values.size() / stream.elementBytes,
                                                         stream.elementBytes, filter);
    }
    for (std::size_t b = 0; b < plan.batches.size(); ++b) {
        const InstanceBatch& batch = plan.batches[b];
        const std::size_t count = batch.instances.size();
        Json attributes = Json::object();
        for (int a = 0; a < 3; ++a) {
            const std::optional<InstanceEncoding>& encoding = batch.attributes[std::size_t(a)];
            if (!encoding) continue;
            const int view = streams.at(streamOf(a, *encoding)).view;
            attributes[kNames[a]] = builder.addAccessor(
                instanceAccessor(view, offsets[b][std::size_t(a)], encoding->componentType, count, kTypes[a]));
        }
        root["nodes"].push_back(batchNode(meshIndex[std::size_t(batch.mesh)], attributes, batch.mirrored, batch.origin,
                                          namesOf(scene, batch.nodes)));
    }
}

double gltfNodesBytes(const std::vector<Node>& nodes, const WriteOptions& options) {
    double bytes = 0;
    std::vector<Node> byHandedness[2];
    for (const Node& node : nodes) {
        if (options.gpuInstancing && plainLeaf(node))
            byHandedness[mirrors(node.transform)].push_back(node);
        else
            bytes += double(gltfNodeBytes(node));
    }
    for (const std::vector<Node>& group : byHandedness) {
        double separate = 0;
        for (const Node& node : group) separate += double(gltfNodeBytes(node));
        bytes += group.size() < 2 ? separate : std::min(separate, gpuBatchBytes(group, options));
    }
    return bytes;
}

GpuInstancingCount gltfGpuInstancing(const Scene& scene, const WriteOptions& options) {
    std::vector<int> meshIndex(scene.meshes.size(), -1);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& primitive : scene.meshes[m].primitives)
            if (!primitive.drawsNothing()) meshIndex[m] = int(m);
    GpuInstancingCount count;
    for (const InstanceBatch& batch : planGpuInstancing(scene, meshIndex, options).batches) {
        ++count.batches;
        count.instances += batch.nodes.size();
    }
    return count;
}

}  // namespace symcompress
