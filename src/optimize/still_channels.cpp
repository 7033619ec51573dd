// Animation channels that hold their node where it rests: a track whose every key is the node's own translation,
// rotation, scale or morph weights draws what the node draws without it, and costs a sampler, a channel, an
// accessor and its keys (Cesium Man: 10 of its 19 translation tracks).
#include "io/rotation_and_scale.hpp"
#include "symcompress/optimize.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>

namespace symcompress {
namespace {

// Equal as float32 values, which is how the file holds both: within a few units in the last place (the rest
// value went through a matrix and back).
bool sameAsFloat(double a, double b) { return std::abs(a - b) <= std::ldexp(std::max(std::abs(a), std::abs(b)), -21); }

// The node's own value of what the channel keys, from its rest transform (and its or its mesh's morph weights);
// nothing where the transform shears (no TRS holds it).
std::optional<std::vector<double>> restValue(const Scene& scene, const AnimationChannel& channel) {
    const Node& node = scene.nodes[std::size_t(channel.node)];
    switch (channel.path) {
    case AnimationChannel::Path::Translation: {
        const Eigen::Vector3d t = node.transform.topRightCorner<3, 1>();
        return std::vector<double>{t.x(), t.y(), t.z()};
    }
    case AnimationChannel::Path::Rotation:
    case AnimationChannel::Path::Scale: {
        const auto trs = asRotationAndScale(node.transform.topLeftCorner<3, 3>());
        if (!trs) return std::nullopt;
        if (channel.path == AnimationChannel::Path::Scale)
            return std::vector<double>{trs->second.x(), trs->second.y(), trs->second.z()};
        const Eigen::Quaterniond q(trs->first);
        return std::vector<double>{q.x(), q.y(), q.z(), q.w()};
    }
    case AnimationChannel::Path::Weights: {
        std::vector<double> weights = node.weights;
        if (weights.empty() && node.mesh >= 0) weights = scene.meshes[std::size_t(node.mesh)].weights;
        weights.resize(channel.components(), 0.0);
        return weights;
    }
    }
    return std::nullopt;
}

// Whether every key of the channel is its node's rest value (a rotation as either of its quaternions), and a
// cubic spline's tangents are all 0.
bool holdsRest(const Scene& scene, const AnimationChannel& channel) {
    const std::optional<std::vector<double>> rest = restValue(scene, channel);
    const std::size_t width = channel.components();
    if (!rest || width == 0 || channel.values.size() != channel.valuesPerKey() * channel.times.size()) return false;
    const bool cubic = channel.interpolation == AnimationChannel::Interpolation::CubicSpline;
    for (std::size_t at = 0; at < channel.values.size(); at += width) {
        const bool tangent = cubic && (at / width) % 3 != 1;
        bool same = true, opposite = channel.path == AnimationChannel::Path::Rotation && !tangent;
        for (std::size_t c = 0; c < width; ++c) {
            const double value = channel.values[at + c];
            same = same && sameAsFloat(value, tangent ? 0.0 : (*rest)[c]);
            opposite = opposite && sameAsFloat(value, -(*rest)[c]);
        }
        if (!same && !opposite) return false;
    }
    return true;
}

// The first and last key times of the channels, over those `kept`.
std::pair<double, double> timeSpan(const Animation& animation, const std::vector<char>& kept) {
    double first = std::numeric_limits<double>::infinity(), last = -first;
    for (std::size_t c = 0; c < animation.channels.size(); ++c)
        if (kept[c] && !animation.channels[c].times.empty()) {
            first = std::min(first, animation.channels[c].times.front());
            last = std::max(last, animation.channels[c].times.back());
        }
    return {first, last};
}

}  // namespace

std::size_t removeStillChannels(Scene& scene) {
    // A node's path keyed by two animations stays: played together, a viewer blends them, and the still one
    // holds the node back.
    std::multiset<std::pair<int, AnimationChannel::Path>> keyed;
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) keyed.insert({channel.node, channel.path});
    std::size_t removed = 0;
    for (Animation& animation : scene.animations) {
        std::vector<char> kept(animation.channels.size(), 1);
        const auto span = timeSpan(animation, kept);
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const AnimationChannel& channel = animation.channels[c];
            if (keyed.count({channel.node, channel.path}) > 1 || !holdsRest(scene, channel)) continue;
            kept[c] = 0;
            // An animation keeps a channel (glTF asks for one) and its length (a viewer loops over it).
            if (std::none_of(kept.begin(), kept.end(), [](char k) { return k != 0; }) ||
                timeSpan(animation, kept) != span)
                kept[c] = 1;
        }
        std::vector<AnimationChannel> channels;
        for (std::size_t c = 0; c < animation.channels.size(); ++c)
            if (kept[c]) channels.push_back(std::move(animation.channels[c]));
        removed += animation.channels.size() - channels.size();
        animation.channels = std::move(channels);
    }
    return removed;
}

}  // namespace symcompress
