// Animation keys that interpolation gives back, dropped (glTF-Transform's `resample` does the same): exporters
// sample every frame, where a linear track needs only its turning points (the milk truck's wheels: 31 keys of one
// steady turn). Within a share of the budget, measured in the poses as the rounding of the keys is (PoseProbe).
// A channel that stays that close to its node's rest value goes altogether (Cesium Man's scales, 1 to a millionth,
// and translations).
#include "channel_rest.hpp"
#include "geometry/quaternion_difference.hpp"
#include "mesh/pose_probe.hpp"
#include "symcompress/optimize.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>

namespace symcompress {
namespace {

// The most keys one kept pair may stand for: each span is checked key by key as it grows, so a key costs up to this
// many checks (of each channel sharing its times); a steady track then keeps one key in 64.
constexpr std::size_t kLongestSpan = 64;
// The tolerances tried, relative (a quaternion's components; a translation's or scale's over its largest value),
// coarsest first: the coarsest whose poses stay within the allowance is kept.
constexpr double kTolerances[] = {3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6};

bool reducible(const AnimationChannel& channel, const std::vector<char>& measured) {
    return channel.interpolation != AnimationChannel::Interpolation::CubicSpline && channel.times.size() > 2 &&
           channel.node >= 0 && std::size_t(channel.node) < measured.size() && measured[std::size_t(channel.node)] &&
           channel.components() > 0 && channel.values.size() == channel.times.size() * channel.components();
}

// What a tolerance is relative to: 1 for rotations (unit quaternions) and weights, else the largest value's size.
double unitOf(const AnimationChannel& channel) {
    if (channel.path == AnimationChannel::Path::Rotation || channel.path == AnimationChannel::Path::Weights) return 1;
    double largest = 0;
    for (double value : channel.values) largest = std::max(largest, std::abs(value));
    return largest;
}

// Slerp from one unit quaternion to another, their angle found once for every key between them (Eigen's slerp, whose
// arithmetic this repeats, finds it at each: its acos and sine were a third of the time on densely keyed tracks).
class SpanSlerp {
public:
    SpanSlerp(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) : a_(a), b_(b) {
        const double d = a.dot(b), absD = std::abs(d);
        linear_ = absD >= 1 - std::numeric_limits<double>::epsilon();
        if (!linear_) theta_ = std::acos(absD), sinTheta_ = std::sin(theta_);
        sign_ = d < 0 ? -1 : 1;
    }
    Eigen::Quaterniond at(double t) const {
        const double scale0 = linear_ ? 1 - t : std::sin((1 - t) * theta_) / sinTheta_;
        const double scale1 = sign_ * (linear_ ? t : std::sin(t * theta_) / sinTheta_);
        return Eigen::Quaterniond(scale0 * a_.coeffs() + scale1 * b_.coeffs());
    }

private:
    Eigen::Quaterniond a_, b_;
    bool linear_ = true;
    double theta_ = 0, sinTheta_ = 1, sign_ = 1;
};

// Whether interpolating keys a and b alone gives every key between them within `tolerance` (each component; a
// rotation as either of its quaternions), as the sampler interpolates: held for STEP, slerp for rotations.
bool spanHolds(const AnimationChannel& channel, std::size_t a, std::size_t b, double tolerance) {
    const std::size_t width = channel.components();
    const double* va = &channel.values[a * width];
    const double* vb = &channel.values[b * width];
    const bool step = channel.interpolation == AnimationChannel::Interpolation::Step,
               slerped = channel.path == AnimationChannel::Path::Rotation && !step;
    // The span's ends as unit quaternions, once (a rotation's key has four values; others' none of this).
    const SpanSlerp slerp = slerped ? SpanSlerp(Eigen::Quaterniond(va[3], va[0], va[1], va[2]).normalized(),
                                                Eigen::Quaterniond(vb[3], vb[0], vb[1], vb[2]).normalized())
                                    : SpanSlerp(Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity());
    for (std::size_t k = a + 1; k < b; ++k) {
        const double u = (channel.times[k] - channel.times[a]) / (channel.times[b] - channel.times[a]);
        const double* vk = &channel.values[k * width];
        if (slerped) {
            const Eigen::Quaterniond q = slerp.at(u);
            const double expected[] = {q.x(), q.y(), q.z(), q.w()};
            if (quaternionDifference(vk, expected) > tolerance) return false;
            continue;
        }
        for (std::size_t c = 0; c < width; ++c) {
            const double expected = step ? va[c] : (1 - u) * va[c] + u * vb[c];
            if (!(std::abs(vk[c] - expected) <= tolerance)) return false;
        }
    }
    return true;
}

// The keys kept at `tolerance` of channels keyed at the same times: the first and the last (the length), and each
// key after which the span from the key kept before it no longer holds for one of them.
std::vector<std::size_t> keysKept(const Animation& animation, const std::vector<std::size_t>& channels,
                                  double tolerance) {
    std::vector<double> tolerances;
    for (std::size_t c : channels) tolerances.push_back(tolerance * unitOf(animation.channels[c]));
    auto holds = [&](std::size_t a, std::size_t b) {
        for (std::size_t i = 0; i < channels.size(); ++i)
            if (!spanHolds(animation.channels[channels[i]], a, b, tolerances[i])) return false;
        return true;
    };
    const std::size_t count = animation.channels[channels.front()].times.size();
    std::vector<std::size_t> kept{0};
    for (std::size_t b = 2; b < count; ++b)
        if (b - kept.back() > kLongestSpan || !holds(kept.back(), b)) kept.push_back(b - 1);
    kept.push_back(count - 1);
    return kept;
}

void keepOnly(AnimationChannel& channel, const std::vector<std::size_t>& keys) {
    const std::size_t width = channel.components();
    std::vector<double> times, values;
    for (std::size_t k : keys) {
        times.push_back(channel.times[k]);
        values.insert(values.end(), channel.values.begin() + std::ptrdiff_t(k * width),
                      channel.values.begin() + std::ptrdiff_t((k + 1) * width));
    }
    channel.times = std::move(times);
    channel.values = std::move(values);
}

// `animation` with the keys that interpolation gives back within `tolerance` dropped from its `reducible`
// channels, and those of them `removable` that stay within it of their node's rest value removed (where the
// animation keeps its length). Channels keyed at the same times share one accessor of them in the file and keep
// the same keys: each its own took the fox 61564 -> 64824 bytes, Cesium Man 265528 -> 265532 (times code poorly,
// and meshopt codes the values of a channel that hardly moves in a few bytes however many keys it has); even
// channels that hold one value throughout, cut to their first and last keys, saved Cesium Man 48 bytes and cost
// the fox 48 (an accessor of two times).
Animation reduced(const Scene& scene, const Animation& animation, const std::vector<char>& reducible,
                  const std::vector<char>& removable, double tolerance) {
    std::vector<char> still(animation.channels.size(), 0);
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const double within = tolerance * unitOf(animation.channels[c]);
        still[c] = reducible[c] && removable[c] && holdsRest(scene, animation.channels[c], [&](double a, double b) {
                       return std::abs(a - b) <= within;
                   });
    }
    const std::vector<char> kept = channelsKeptWithLength(animation, still);
    Animation out = animation;
    std::map<std::vector<double>, std::vector<std::size_t>> byTimes;
    for (std::size_t c = 0; c < animation.channels.size(); ++c)
        if (reducible[c] && kept[c]) byTimes[animation.channels[c].times].push_back(c);
    for (const auto& [times, channels] : byTimes) {
        const std::vector<std::size_t> keys = keysKept(animation, channels, tolerance);
        for (std::size_t c : channels) keepOnly(out.channels[c], keys);
    }
    std::vector<AnimationChannel> channels;
    for (std::size_t c = 0; c < animation.channels.size(); ++c)
        if (kept[c]) channels.push_back(std::move(out.channels[c]));
    out.channels = std::move(channels);
    return out;
}

std::size_t keyCount(const Animation& animation) {
    std::size_t keys = 0;
    for (const AnimationChannel& channel : animation.channels) keys += channel.times.size();
    return keys;
}

}  // namespace

RedundantKeys dropRedundantKeys(Scene& scene, double allowed) {
    RedundantKeys out;
    if (!(allowed > 0)) return out;
    const std::vector<char> measured = measuredNodes(scene);
    const auto keyed = keyedPaths(scene);
    for (Animation& animation : scene.animations) {
        std::vector<char> reducibleChannels(animation.channels.size()), removable(animation.channels.size());
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const AnimationChannel& channel = animation.channels[c];
            reducibleChannels[c] = reducible(channel, measured);
            removable[c] = keyed.count({channel.node, channel.path}) == 1;
        }
        auto reducedAt = [&](double tolerance) {
            return reduced(scene, animation, reducibleChannels, removable, tolerance);
        };
        if (std::none_of(reducibleChannels.begin(), reducibleChannels.end(), [](char r) { return r != 0; }) ||
            keyCount(reducedAt(kTolerances[0])) == keyCount(animation))
            continue;
        const PoseProbe probe(scene, animation);
        if (!probe.measurable()) continue;
        // The coarsest tolerance within the allowance, by bisection (the poses' error grows with it).
        // kTolerances[high] holds (none tried yet: high is past the end), [low, high) are not known to.
        std::size_t low = 0, high = std::size(kTolerances);
        std::optional<Animation> kept;
        while (low < high) {
            const std::size_t middle = (low + high) / 2;
            Animation trial = reducedAt(kTolerances[middle]);
            if (probe.within(trial, allowed)) {
                high = middle;
                kept = std::move(trial);
            } else {
                low = middle + 1;
            }
        }
        if (!kept || keyCount(*kept) == keyCount(animation)) continue;
        out.deviation = std::max(out.deviation, probe.deviation(*kept));
        out.keysDropped += keyCount(animation) - keyCount(*kept);
        out.channelsRemoved += animation.channels.size() - kept->channels.size();
        animation = std::move(*kept);
    }
    return out;
}

}  // namespace symcompress
