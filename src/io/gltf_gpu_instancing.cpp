// EXT_mesh_gpu_instancing: batches of plain leaves drawing one mesh, chosen by the bytes they save, and written.
//
// The extension goes in extensionsRequired: a viewer without it would draw one copy per batch where there are
// hundreds, a wrong scene rather than a plainer one (gltfpack -mi marks it required as well). Rotations are
// normalized SHORT, which the extension allows without KHR_mesh_quantization; translations and scales stay
// FLOAT, the only type it allows for them without that extension (which would also ask for a dequantizing
// node transform that the batch's mesh would inherit).
#include "gltf_gpu_instancing.hpp"

#include "rotation_and_scale.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <tuple>

namespace symcompress {
namespace {

constexpr int kShort = 5122;
const char* const kExtension = "EXT_mesh_gpu_instancing";

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
// extras of its own (kept on the node; only names have a place in the batch) and is TRS.
bool plainLeaf(const Node& node) {
    return node.mesh >= 0 && node.children.empty() && node.camera < 0 && node.light < 0 && node.skin < 0 &&
           node.weights.empty() && node.extrasJson.empty() && instanceTrsOf(node.transform, mirrors(node.transform));
}

std::int16_t asNormalizedShort(double value) {
    return std::int16_t(std::clamp(std::lround(value * 32767.0), -32767L, 32767L));
}

// The rotation as the reader gets it back from normalized SHORTs (each component at most 1/32767 off).
Eigen::Quaterniond shortRotation(const Eigen::Quaterniond& rotation) {
    const Eigen::Vector4d q = rotation.coeffs().unaryExpr([](double c) { return asNormalizedShort(c) / 32767.0; });
    return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized();
}

// Which of the three attributes a batch needs: each is left out where it does nothing for every instance.
struct BatchAttributes {
    bool translation = false, rotation = false, scale = false;
};

BatchAttributes attributesOf(const std::vector<InstanceTrs>& instances) {
    BatchAttributes used;
    for (const InstanceTrs& trs : instances) {
        used.translation |= !trs.translation.unaryExpr(&asFloat32).isZero(0);
        used.rotation |= trs.rotation.coeffs().unaryExpr(&asFloat32) != Eigen::Vector4d(0, 0, 0, 1);
        used.scale |= trs.scale.unaryExpr(&asFloat32) != Eigen::Vector3d::Ones();
    }
    return used;
}

Json instanceAccessor(int view, std::size_t offset, int componentType, std::size_t count, const char* type) {
    Json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
    if (offset) accessor["byteOffset"] = offset;
    if (componentType == kShort) accessor["normalized"] = true;
    return accessor;
}

Json batchNode(int mesh, const Json& attributes, bool mirrored, const std::vector<std::string>& names) {
    Json node = {{"mesh", mesh}, {"extensions", {{kExtension, {{"attributes", attributes}}}}}};
    if (mirrored) node["scale"] = {-1, 1, 1};
    if (std::any_of(names.begin(), names.end(), [](const std::string& name) { return !name.empty(); }))
        node["extras"]["instanceNames"] = names;  // parallel to the instances; the reader gives them back
    return node;
}

// What a batch adds to the file: its node (with its index in its parent's list), its accessors (indices and
// offsets of a typical size) and its binary data; the buffer views, shared by every batch, not counted.
double batchBytes(const std::vector<InstanceTrs>& instances, const std::vector<std::string>& names, bool mirrored,
                  bool shortRotation) {
    const BatchAttributes used = attributesOf(instances);
    const std::size_t count = instances.size();
    Json attributes = Json::object();
    double bytes = 0;
    auto add = [&](const char* name, int componentType, const char* type, std::size_t elementBytes) {
        attributes[name] = 100;
        bytes += double(jsonText(instanceAccessor(1, 10000, componentType, count, type)).size() + 1);
        bytes += double(count * elementBytes);
    };
    if (used.translation) add("TRANSLATION", kFloat, "VEC3", 12);
    if (used.rotation) add("ROTATION", shortRotation ? kShort : kFloat, "VEC4", shortRotation ? 8 : 16);
    if (used.scale) add("SCALE", kFloat, "VEC3", 12);
    return bytes + double(jsonText(batchNode(10, attributes, mirrored, names)).size() + 1 + 3);
}

// What the first batch adds once: the extension's name in extensionsUsed and extensionsRequired, and a shared
// buffer view per attribute.
double fileBytesOfFirstBatch() {
    const Json view = {{"buffer", 0}, {"byteLength", 10000}, {"byteOffset", 1000000}};
    return 2.0 * double(std::string(kExtension).size() + 3) + 3.0 * double(jsonText(view).size() + 1);
}

// Whether normalized SHORT rotations move no vertex of the mesh farther than `allowed`.
bool shortRotationsHold(const std::vector<InstanceTrs>& instances, double meshRadius, double allowed) {
    for (const InstanceTrs& trs : instances) {
        const double angle = trs.rotation.angularDistance(shortRotation(trs.rotation));
        if (angle * meshRadius * trs.scale.cwiseAbs().maxCoeff() > allowed) return false;
    }
    return true;
}

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
    std::vector<bool> fixed(scene.nodes.size(), false);
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) fixed[std::size_t(channel.node)] = true;
    for (const Skin& skin : scene.skins) {
        for (int joint : skin.joints) fixed[std::size_t(joint)] = true;
        if (skin.skeleton >= 0) fixed[std::size_t(skin.skeleton)] = true;
    }
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
        return !fixed[std::size_t(n)] && plainLeaf(node) && meshIndex[std::size_t(node.mesh)] >= 0 &&
               morphTargetCount(scene.meshes[std::size_t(node.mesh)]) == 0;
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
            if (isNew) groups.push_back({parent, node.mesh, std::get<2>(key), true, {}, {}});
            groups[at->second].nodes.push_back(n);
        }
    };
    collect(-1, scene.roots);
    for (std::size_t p = 0; p < scene.nodes.size(); ++p) collect(int(p), scene.nodes[p].children);

    const double allowed = options.instanceRotationDeviation * sceneDiagonal(scene);
    std::vector<double> radius(scene.meshes.size(), -1);
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
        batch.shortRotation = options.draco && shortRotationsHold(batch.instances, r, allowed);
        const double batched =
            batchBytes(batch.instances, namesOf(scene, batch.nodes), batch.mirrored, batch.shortRotation) +
            (plan.batches.empty() ? fileBytesOfFirstBatch() : 0);
        if (batched >= separate) continue;
        for (int n : batch.nodes) plan.batchOf[std::size_t(n)] = int(plan.batches.size());
        plan.batches.push_back(std::move(batch));
    }
    return plan;
}

double gpuBatchBytes(const std::vector<Node>& nodes, bool shortRotation) {
    if (nodes.empty()) return -1;
    const bool mirrored = mirrors(nodes.front().transform);
    std::vector<InstanceTrs> instances;
    std::vector<std::string> names;
    for (const Node& node : nodes) {
        if (!plainLeaf(node) || mirrors(node.transform) != mirrored) return -1;
        instances.push_back(*instanceTrsOf(node.transform, mirrored));
        names.push_back(node.name);
    }
    return batchBytes(instances, names, mirrored, shortRotation);
}

void writeGpuBatches(const GpuInstancingPlan& plan, const Scene& scene, const std::vector<int>& meshIndex,
                     GltfBuilder& builder, Json& root) {
    if (plan.batches.empty()) return;
    // Every batch's values, one buffer of each kind, and where each batch's start.
    std::vector<float> translations, rotations, scales;
    std::vector<std::int16_t> shortRotations;
    struct Offsets {
        std::size_t translation = 0, rotation = 0, scale = 0;
        BatchAttributes used;
    };
    std::vector<Offsets> offsets;
    for (const InstanceBatch& batch : plan.batches) {
        Offsets at{translations.size() * 4, (batch.shortRotation ? shortRotations.size() * 2 : rotations.size() * 4),
                   scales.size() * 4, attributesOf(batch.instances)};
        for (const InstanceTrs& trs : batch.instances) {
            if (at.used.translation)
                for (int c = 0; c < 3; ++c) translations.push_back(float(trs.translation[c]));
            if (at.used.rotation)
                for (int c = 0; c < 4; ++c) {
                    if (batch.shortRotation)
                        shortRotations.push_back(asNormalizedShort(trs.rotation.coeffs()[c]));
                    else
                        rotations.push_back(float(trs.rotation.coeffs()[c]));
                }
            if (at.used.scale)
                for (int c = 0; c < 3; ++c) scales.push_back(float(trs.scale[c]));
        }
        offsets.push_back(at);
    }
    auto viewOf = [&](const auto& values) {
        return values.empty() ? -1 : builder.addBufferView(values.data(), values.size() * sizeof(values[0]));
    };
    const int translationView = viewOf(translations), rotationView = viewOf(rotations),
              shortRotationView = viewOf(shortRotations), scaleView = viewOf(scales);
    for (std::size_t b = 0; b < plan.batches.size(); ++b) {
        const InstanceBatch& batch = plan.batches[b];
        const Offsets& at = offsets[b];
        const std::size_t count = batch.instances.size();
        Json attributes = Json::object();
        if (at.used.translation)
            attributes["TRANSLATION"] =
                builder.addAccessor(instanceAccessor(translationView, at.translation, kFloat, count, "VEC3"));
        if (at.used.rotation)
            attributes["ROTATION"] = builder.addAccessor(
                batch.shortRotation ? instanceAccessor(shortRotationView, at.rotation, kShort, count, "VEC4")
                                    : instanceAccessor(rotationView, at.rotation, kFloat, count, "VEC4"));
        if (at.used.scale)
            attributes["SCALE"] = builder.addAccessor(instanceAccessor(scaleView, at.scale, kFloat, count, "VEC3"));
        root["nodes"].push_back(
            batchNode(meshIndex[std::size_t(batch.mesh)], attributes, batch.mirrored, namesOf(scene, batch.nodes)));
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
        // The plan cannot tell the mesh's radius yet: SHORT rotations, as nearly every batch has them.
        bytes += group.size() < 2 ? separate : std::min(separate, gpuBatchBytes(group, true));
    }
    return bytes;
}

GpuInstancingCount gltfGpuInstancing(const Scene& scene, const WriteOptions& options) {
    std::vector<int> meshIndex(scene.meshes.size(), -1);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& primitive : scene.meshes[m].primitives)
            if (!primitive.triangles.empty()) meshIndex[m] = int(m);
    GpuInstancingCount count;
    for (const InstanceBatch& batch : planGpuInstancing(scene, meshIndex, options).batches) {
        ++count.batches;
        count.instances += batch.nodes.size();
    }
    return count;
}

}  // namespace symcompress
