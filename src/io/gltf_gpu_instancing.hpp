// EXT_mesh_gpu_instancing in the glTF writer: leaves that draw one mesh under one parent written as one node
// with a translation, rotation and scale per instance, where that is smaller than a node each.
#pragma once

#include "gltf_builder.hpp"
#include "gltf_instance_encoding.hpp"
#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

#include <array>
#include <optional>
#include <vector>

namespace symcompress {

// One instance as the extension stores it: T * R * S, the scale positive (a mirror is the batch node's).
struct InstanceTrs {
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

// Leaves of one parent drawing one mesh, all mirrored or none, written as one node. three.js picks the
// winding per object, not per instance: mirrored instances get a batch of their own, whose node mirrors
// (scale [-1, 1, 1]), each instance's TRS then mirror^-1 * its matrix, with a positive determinant.
struct InstanceBatch {
    int parent = -1;  // the scene node whose children they are, -1 for roots
    int mesh = -1;    // into Scene::meshes
    bool mirrored = false;
    std::vector<int> nodes;              // the scene nodes, in the order their parent lists them
    std::vector<InstanceTrs> instances;  // one per node, relative to `origin`
    // The batch node's translation, in its parent's frame: where the batch lies far from the parent's origin (a
    // scene placed 1e5 units away), the centre of the instances' box, so that float32 holds their translations
    // from it within their allowance; else zero.
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    // How TRANSLATION, ROTATION and SCALE are stored, in that order; none where no instance needs it.
    std::array<std::optional<InstanceEncoding>, 3> attributes;
};

struct GpuInstancingPlan {
    std::vector<InstanceBatch> batches;
    std::vector<int> batchOf;  // per scene node: the batch it is written in, -1 for a node of its own
};

// The batches worth writing: every group of plain leaves (a mesh that is written, has no morph targets and draws
// nothing blended; no children, camera, light, skin, weights or extras; not animated, under nothing animated, no joint;
// a transform that TRS holds) whose batch is smaller than its nodes, by the writer's bytes. Each attribute is stored
// the smallest way that keeps every vertex within options.instanceRotationDeviation (rotations) and
// options.instanceTranslationDeviation (translations and scales) of the scene's diagonal: with Draco, normalized
// SHORT rotations and EXT_meshopt_compression streams are among the candidates; without, the file is float
// throughout. `meshIndex` is the glTF mesh of each scene mesh (-1: not written). Empty when
// options.gpuInstancing is off.
GpuInstancingPlan planGpuInstancing(const Scene& scene, const std::vector<int>& meshIndex, const WriteOptions& options);

// What a batch of `nodes` (local transforms relative to one parent, one mesh) adds to the file, by its JSON and
// binary data (meshopt's views and extension included where it takes them), and whether it is possible at all
// (no shear, one handedness): -1 when it is not. The mesh and the scene are not known here: rotations are held
// to the precision of normalized SHORTs, translations to options.instanceTranslationDeviation of their own
// extent, scales kept exact.
double gpuBatchBytes(const std::vector<Node>& nodes, const WriteOptions& options);

// Writes the plan's batch nodes (appended to root["nodes"] in batch order) with their accessors, the
// instances' data in one buffer view per attribute and encoding, shared by every batch (meshopt's views in the
// fallback buffer, GltfBuilder::addMeshoptBufferView).
void writeGpuBatches(const GpuInstancingPlan& plan, const Scene& scene, const std::vector<int>& meshIndex,
                     GltfBuilder& builder, Json& root);

}  // namespace symcompress
