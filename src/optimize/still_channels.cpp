// Animation channels that hold their node where it rests: a track whose every key is the node's own translation,
// rotation, scale or morph weights draws what the node draws without it, and costs a sampler, a channel, an
// accessor and its keys (Cesium Man: 10 of its 19 translation tracks).
#include "channel_rest.hpp"
#include "symcompress/optimize.hpp"

#include <algorithm>
#include <cmath>

namespace symcompress {
namespace {

// Equal as float32 values, which is how the file holds both: within a few units in the last place (the rest
// value went through a matrix and back).
bool sameAsFloat(double a, double b) { return std::abs(a - b) <= std::ldexp(std::max(std::abs(a), std::abs(b)), -21); }

}  // namespace

std::size_t removeStillChannels(Scene& scene) {
    const auto keyed = keyedPaths(scene);
    std::size_t removed = 0;
    for (Animation& animation : scene.animations) {
        std::vector<char> still(animation.channels.size(), 0);
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const AnimationChannel& channel = animation.channels[c];
            still[c] = keyed.count({channel.node, channel.path}) == 1 && holdsRest(scene, channel, sameAsFloat);
        }
        const std::vector<char> kept = channelsKeptWithLength(animation, still);
        std::vector<AnimationChannel> channels;
        for (std::size_t c = 0; c < animation.channels.size(); ++c)
            if (kept[c]) channels.push_back(std::move(animation.channels[c]));
        removed += animation.channels.size() - channels.size();
        animation.channels = std::move(channels);
    }
    return removed;
}

}  // namespace symcompress
