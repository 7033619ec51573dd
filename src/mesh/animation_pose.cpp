// Scenes at a time of one of their animations (glTF 2.0, sections 3.7.2 "Skins" and 3.11 "Animations", Appendix C
// "Interpolation"): what the decoder draws to compare poses, and what bounds the rounding of a skin's weights.
#include "symcompress/scene_ops.hpp"

#include "io/rotation_and_scale.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace symcompress {

std::vector<double> sampleChannel(const AnimationChannel& channel, double time) {
    const std::size_t width = channel.components(), keys = channel.times.size();
    const bool cubic = channel.interpolation == AnimationChannel::Interpolation::CubicSpline;
    // Key k's value (a cubic spline stores in-tangent, value, out-tangent) and, for splines, its tangents.
    auto part = [&](std::size_t k, std::size_t which) {
        const std::size_t at = (cubic ? 3 * k + which : k) * width;
        return std::vector<double>(channel.values.begin() + std::ptrdiff_t(at),
                                   channel.values.begin() + std::ptrdiff_t(at + width));
    };
    const std::size_t valueAt = cubic ? 1 : 0;
    const auto after = std::upper_bound(channel.times.begin(), channel.times.end(), time);
    if (after == channel.times.begin()) return part(0, valueAt);
    if (after == channel.times.end()) return part(keys - 1, valueAt);
    const std::size_t k = std::size_t(after - channel.times.begin()) - 1;
    const double span = channel.times[k + 1] - channel.times[k], u = (time - channel.times[k]) / span;
    const bool rotation = channel.path == AnimationChannel::Path::Rotation;
    std::vector<double> out(width);
    switch (channel.interpolation) {
    case AnimationChannel::Interpolation::Step: return part(k, 0);
    case AnimationChannel::Interpolation::Linear:
        if (rotation) {
            const std::vector<double> a = part(k, 0), b = part(k + 1, 0);
            const Eigen::Quaterniond q = Eigen::Quaterniond(a[3], a[0], a[1], a[2])
                                             .normalized()
                                             .slerp(u, Eigen::Quaterniond(b[3], b[0], b[1], b[2]).normalized());
            return {q.x(), q.y(), q.z(), q.w()};
        }
        for (std::size_t c = 0; c < width; ++c) out[c] = (1 - u) * part(k, 0)[c] + u * part(k + 1, 0)[c];
        break;
    case AnimationChannel::Interpolation::CubicSpline: {
        const double u2 = u * u, u3 = u2 * u;
        const std::vector<double> v0 = part(k, 1), b0 = part(k, 2), a1 = part(k + 1, 0), v1 = part(k + 1, 1);
        for (std::size_t c = 0; c < width; ++c)
            out[c] = (2 * u3 - 3 * u2 + 1) * v0[c] + (u3 - 2 * u2 + u) * span * b0[c] + (-2 * u3 + 3 * u2) * v1[c] +
                     (u3 - u2) * span * a1[c];
        break;
    }
    }
    if (rotation) {
        const double length = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
        if (length > 0)
            for (double& x : out) x /= length;
    }
    return out;
}

namespace {

// The node's local transform with the animated parts of its TRS replaced. glTF allows no matrix on an animated
// node, so its transform is a rotation and a scale (asRotationAndScale); one that shears keeps its transform.
Eigen::Matrix4d animatedTransform(const Eigen::Matrix4d& rest, const std::vector<const AnimationChannel*>& channels,
                                  double time) {
    const auto trs = asRotationAndScale(rest.topLeftCorner<3, 3>());
    if (!trs) return rest;
    Eigen::Vector3d translation = rest.topRightCorner<3, 1>(), scale = trs->second;
    Eigen::Quaterniond rotation(trs->first);
    for (const AnimationChannel* channel : channels) {
        const std::vector<double> value = sampleChannel(*channel, time);
        switch (channel->path) {
        case AnimationChannel::Path::Translation: translation = {value[0], value[1], value[2]}; break;
        case AnimationChannel::Path::Rotation:
            rotation = Eigen::Quaterniond(value[3], value[0], value[1], value[2]);
            break;
        case AnimationChannel::Path::Scale: scale = {value[0], value[1], value[2]}; break;
        case AnimationChannel::Path::Weights: break;
        }
    }
    Eigen::Matrix4d out = Eigen::Matrix4d::Identity();
    out.topLeftCorner<3, 3>() = rotation.toRotationMatrix() * scale.asDiagonal();
    out.topRightCorner<3, 1>() = translation;
    return out;
}

const VertexAttribute* attributeNamed(const Primitive& primitive, const std::string& name) {
    for (const VertexAttribute& attribute : primitive.attributes)
        if (attribute.name == name) return &attribute;
    return nullptr;
}

}  // namespace

std::vector<double> keyTimes(const Animation& animation) {
    std::vector<double> times;
    for (const AnimationChannel& channel : animation.channels)
        times.insert(times.end(), channel.times.begin(), channel.times.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    return times;
}

std::vector<Eigen::Matrix4d> posedWorldTransforms(const Scene& scene, const Animation* animation, double time) {
    const std::size_t count = scene.nodes.size();
    std::vector<std::vector<const AnimationChannel*>> channelsOf(count);
    if (animation)
        for (const AnimationChannel& channel : animation->channels)
            channelsOf[std::size_t(channel.node)].push_back(&channel);
    std::vector<int> parent(count, -1);
    for (std::size_t n = 0; n < count; ++n)
        for (int child : scene.nodes[n].children) parent[std::size_t(child)] = int(n);
    std::vector<Eigen::Matrix4d> world(count);
    std::vector<char> done(count, 0);
    const std::function<void(std::size_t)> place = [&](std::size_t n) {
        if (done[n]) return;
        const int up = parent[n];
        if (up >= 0) place(std::size_t(up));
        const Eigen::Matrix4d local = channelsOf[n].empty()
                                          ? scene.nodes[n].transform
                                          : animatedTransform(scene.nodes[n].transform, channelsOf[n], time);
        world[n] = up >= 0 ? Eigen::Matrix4d(world[std::size_t(up)] * local) : local;
        done[n] = 1;
    };
    for (std::size_t n = 0; n < count; ++n) place(n);
    return world;
}

std::vector<Eigen::Matrix4d> jointMatrices(const Skin& skin, const std::vector<Eigen::Matrix4d>& world) {
    std::vector<Eigen::Matrix4d> out;
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
        out.push_back(world[std::size_t(skin.joints[j])] *
                      (skin.inverseBindMatrices.empty() ? Eigen::Matrix4d::Identity() : skin.inverseBindMatrices[j]));
    return out;
}

SkinAttributes skinAttributesOf(const Primitive& primitive) {
    SkinAttributes out;
    for (int set = 0; set < 4; ++set) {
        const VertexAttribute* ids = attributeNamed(primitive, "JOINTS_" + std::to_string(set));
        const VertexAttribute* amounts = attributeNamed(primitive, "WEIGHTS_" + std::to_string(set));
        if (!ids || !amounts) break;
        out.joints.push_back(ids);
        out.weights.push_back(amounts);
    }
    return out;
}

Eigen::Vector3d skinnedPosition(const SkinAttributes& skin, std::size_t v, const Eigen::Vector3d& position,
                                const std::vector<Eigen::Matrix4d>& joints, const Eigen::Matrix4d& otherwise) {
    const Eigen::Vector4d h(position.x(), position.y(), position.z(), 1);
    Eigen::Vector4d placed = Eigen::Vector4d::Zero();
    double total = 0;
    std::size_t firstJoint = joints.size();
    for (std::size_t set = 0; !joints.empty() && set < skin.joints.size(); ++set) {
        const VertexAttribute& ids = *skin.joints[set];
        const VertexAttribute& amounts = *skin.weights[set];
        for (int c = 0; c < std::min(ids.components, amounts.components); ++c) {
            const auto joint = std::size_t(ids.vertex(v)[c]);
            if (joint >= joints.size()) continue;
            if (firstJoint == joints.size()) firstJoint = joint;
            placed += amounts.vertex(v)[c] * (joints[joint] * h);
            total += amounts.vertex(v)[c];
        }
    }
    if (firstJoint == joints.size()) return (otherwise * h).head<3>();
    // Weights that do not sum to 1 are scaled to, as three.js does (normalizeSkinWeights); none: the first joint.
    if (!(total > 0)) return (joints[firstJoint] * h).head<3>();
    return placed.head<3>() / total;
}

double skinWeightSensitivity(const Scene& scene, const Primitive& primitive, const Skin& skin) {
    const SkinAttributes attributes = skinAttributesOf(primitive);
    const std::vector<const VertexAttribute*>&ids = attributes.joints, &amounts = attributes.weights;
    double sensitivity = 0;
    auto measure = [&](const std::vector<Eigen::Matrix4d>& world) {
        const std::vector<Eigen::Matrix4d> joints = jointMatrices(skin, world);
        for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
            double sum = 0;
            for (const VertexAttribute* a : amounts)
                for (int c = 0; c < a->components; ++c) sum += a->vertex(v)[c];
            if (!(sum > 0)) continue;
            const Eigen::Vector3d posed = skinnedPosition(attributes, v, primitive.positions[v], joints, world[0]);
            const Eigen::Vector4d h(primitive.positions[v].x(), primitive.positions[v].y(), primitive.positions[v].z(),
                                    1);
            for (std::size_t set = 0; set < ids.size(); ++set)
                for (int c = 0; c < std::min(ids[set]->components, amounts[set]->components); ++c)
                    if (const auto joint = std::size_t(ids[set]->vertex(v)[c]); joint < joints.size())
                        sensitivity = std::max(sensitivity, ((joints[joint] * h).head<3>() - posed).norm() / sum);
        }
    };
    measure(posedWorldTransforms(scene, nullptr, 0));  // at rest
    for (const Animation& animation : scene.animations)
        for (double time : keyTimes(animation)) measure(posedWorldTransforms(scene, &animation, time));
    return sensitivity;
}

}  // namespace symcompress
