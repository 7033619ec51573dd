// An animation channel against its node at rest: the value the channel's path takes there, whether every key
// holds it, and which channels an animation may go without (removeStillChannels, dropRedundantKeys).
#pragma once

#include "symcompress/scene.hpp"

#include <functional>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace symcompress {

// The node's own value of what the channel keys, from its rest transform (and its or its mesh's morph weights);
// nothing where the transform shears (no TRS holds it).
std::optional<std::vector<double>> restValue(const Scene& scene, const AnimationChannel& channel);

// Whether every key of the channel is its node's rest value, each component compared by `same(value, rest)`: a
// rotation as either of its quaternions, a cubic spline's tangents against 0.
bool holdsRest(const Scene& scene, const AnimationChannel& channel, const std::function<bool(double, double)>& same);

// The node paths the scene's animations key, once for each channel. A path keyed by two animations must not be
// left to rest by either: a viewer playing both blends them, and the other holds the node back.
std::multiset<std::pair<int, AnimationChannel::Path>> keyedPaths(const Scene& scene);

// Which channels of `animation` stay when those `removable` go, in order, each only where the animation keeps a
// channel (glTF asks for one) and its first and last key times (its length, over which a viewer loops).
std::vector<char> channelsKeptWithLength(const Animation& animation, const std::vector<char>& removable);

}  // namespace symcompress
