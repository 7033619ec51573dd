// A channel's node at rest (channel_rest.hpp).
#include "channel_rest.hpp"

#include "io/rotation_and_scale.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

namespace symcompress {
namespace {

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

bool holdsRest(const Scene& scene, const AnimationChannel& channel, const std::function<bool(double, double)>& same) {
    const std::optional<std::vector<double>> rest = restValue(scene, channel);
    const std::size_t width = channel.components();
    if (!rest || width == 0 || channel.values.size() != channel.valuesPerKey() * channel.times.size()) return false;
    const bool cubic = channel.interpolation == AnimationChannel::Interpolation::CubicSpline;
    for (std::size_t at = 0; at < channel.values.size(); at += width) {
        const bool tangent = cubic && (at / width) % 3 != 1;
        bool equal = true, opposite = channel.path == AnimationChannel::Path::Rotation && !tangent;
        for (std::size_t c = 0; c < width; ++c) {
            const double value = channel.values[at + c];
            equal = equal && same(value, tangent ? 0.0 : (*rest)[c]);
            opposite = opposite && same(value, -(*rest)[c]);
        }
        if (!equal && !opposite) return false;
    }
    return true;
}

std::multiset<std::pair<int, AnimationChannel::Path>> keyedPaths(const Scene& scene) {
    std::multiset<std::pair<int, AnimationChannel::Path>> keyed;
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) keyed.insert({channel.node, channel.path});
    return keyed;
}

std::vector<char> channelsKeptWithLength(const Animation& animation, const std::vector<char>& removable) {
    std::vector<char> kept(animation.channels.size(), 1);
    const auto span = timeSpan(animation, kept);
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        if (!removable[c]) continue;
        kept[c] = 0;
        if (std::none_of(kept.begin(), kept.end(), [](char k) { return k != 0; }) || timeSpan(animation, kept) != span)
            kept[c] = 1;
    }
    return kept;
}

}  // namespace symcompress
