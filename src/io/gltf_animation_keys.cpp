// Key values rounded within the budget, measured in the poses (PoseProbe) with the values as a viewer decodes them
// (meshopt's own decoding filters), against the values as read.
#include "gltf_animation_keys.hpp"

#include "geometry/quaternion_difference.hpp"
#include "gltf_instance_encoding.hpp"
#include "mesh/pose_probe.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace symcompress {
namespace {

// A channel's values rounded: as the file stores them, and as a viewer decodes them.
struct Rounded {
    KeyValues stored;
    std::vector<double> values;
};

std::vector<float> floatsOf(const std::vector<double>& values) { return {values.begin(), values.end()}; }

template <typename T>
std::vector<unsigned char> bytesOf(const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

// Rotations (unit quaternions, x y z w) through meshopt's quaternion filter: normalized SHORTs once decoded, read
// as c / 32767, no lower than -1.
Rounded quaternionRounded(const AnimationChannel& channel, int bits) {
    const std::vector<float> floats = floatsOf(channel.values);
    const std::size_t count = floats.size() / 4;
    std::vector<std::int16_t> encoded(floats.size());
    meshopt_encodeFilterQuat(encoded.data(), count, 8, bits, floats.data());
    std::vector<std::int16_t> decoded = encoded;
    meshopt_decodeFilterQuat(decoded.data(), count, 8);
    Rounded out{{"QUATERNION", kShort, 8, bytesOf(encoded), bits}, {}};
    for (std::int16_t c : decoded) out.values.push_back(std::max(c / 32767.0, -1.0));
    return out;
}

// Whether a rotation decoded gives back one key as read, to half a step of the SHORTs the filter decodes to (either
// of its quaternions).
bool givesBack(const double* decoded, const double* read) {
    constexpr double kHalfShortStep = 0.5 / 32767;
    return quaternionDifference(decoded, read) <= kHalfShortStep;
}

// One key (x y z w) in the quaternion filter's encoding at `bits` with component `largest` left out and rebuilt by
// the decoder (EXT_meshopt_compression: the other three times sqrt(2) as signed normalized `bits`-bit integers, in
// the order that follows it, then the scale's integer with the component's index in its two low bits).
std::array<std::int16_t, 4> quaternionKey(const double* q, int bits, int largest) {
    const double scale = double((1 << (bits - 1)) - 1), sign = q[largest] < 0 ? -1 : 1;
    auto snorm = [&](double v) { return std::int16_t(std::lround(std::clamp(v, -1.0, 1.0) * scale)); };
    std::array<std::int16_t, 4> key{};
    for (int i = 0; i < 3; ++i) key[std::size_t(i)] = snorm(q[(largest + 1 + i) & 3] * std::sqrt(2.0) * sign);
    key[3] = std::int16_t((int(scale) & ~3) | largest);
    return key;
}

// Rotations on the quaternion filter's grid at `bits` already (a file gltfpack or symcompress wrote): each key
// encoded with the component left out that gives it back, where one does. meshopt's encoder leaves out the
// largest, which need not be the one the file left out where two are nearly equal (gltfpack's fox: 0.68688 and
// -0.687063), and then moves the key by up to half a step. Where no component gives a key back, the keys after it
// are left as meshopt's encoder has them: the rotations are not on this grid.
Rounded quaternionOnItsGrid(const AnimationChannel& channel, int bits) {
    Rounded out = quaternionRounded(channel, bits);
    for (std::size_t at = 0; at < channel.values.size(); at += 4) {
        const double* q = &channel.values[at];
        if (givesBack(&out.values[at], q)) continue;
        bool back = false;
        for (int largest = 0; largest < 4 && !back; ++largest) {
            std::array<std::int16_t, 4> key = quaternionKey(q, bits, largest);
            const std::array<std::int16_t, 4> encoded = key;
            meshopt_decodeFilterQuat(key.data(), 1, 8);
            double decoded[4];
            for (int c = 0; c < 4; ++c) decoded[c] = std::max(key[std::size_t(c)] / 32767.0, -1.0);
            back = givesBack(decoded, q);
            if (!back) continue;
            std::memcpy(out.stored.filtered.data() + at * sizeof(std::int16_t), encoded.data(), sizeof encoded);
            std::copy(decoded, decoded + 4, out.values.begin() + std::ptrdiff_t(at));
        }
        if (!back) break;
    }
    return out;
}

// Whether rotations rounded give back every key as read (givesBack).
bool givesBack(const std::vector<double>& rounded, const std::vector<double>& read) {
    if (rounded.size() != read.size()) return false;
    for (std::size_t at = 0; at < read.size(); at += 4)
        if (!givesBack(&rounded[at], &read[at])) return false;
    return true;
}

// Any values through meshopt's exponential filter, a key's value to an element (its components sharing one
// exponent: a weight near 0 then costs no more bits than its key's largest): float32 once decoded. Morph weights
// of more than 64 targets go one to an element (meshopt's elements are 256 bytes at most).
// `liftZeros`: as exponentialFiltered says.
template <bool liftZeros>
Rounded exponentialRounded(const AnimationChannel& channel, int bits) {
    const std::vector<float> floats = floatsOf(channel.values);
    constexpr std::size_t kMostComponents = 64;
    const std::size_t components = channel.components() > kMostComponents ? 1 : channel.components();
    const std::vector<std::uint32_t> encoded = exponentialFiltered(floats, components, bits, liftZeros);
    const std::vector<float> back = exponentialDecoded(encoded, components);
    return {{"EXPONENTIAL", kFloat, components * 4, bytesOf(encoded), bits}, {back.begin(), back.end()}};
}

// The bytes meshopt codes the channels' rounded values into, in one stream as the file stores them.
std::size_t codedBytes(const std::vector<Rounded>& rounded) {
    std::vector<unsigned char> stream;
    for (const Rounded& r : rounded) stream.insert(stream.end(), r.stored.filtered.begin(), r.stored.filtered.end());
    return rounded.empty() ? 0 : meshoptEncoded(stream, rounded.front().stored.elementBytes).size();
}

}  // namespace

std::vector<KeyValues> roundedKeyValues(const Scene& scene, const Animation& animation, double allowed) {
    std::vector<KeyValues> out(animation.channels.size());
    if (!(allowed > 0)) return out;
    const std::vector<char> measured = measuredNodes(scene);
    std::vector<std::size_t> rotations, others;  // the channels to round
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const AnimationChannel& channel = animation.channels[c];
        if (channel.node < 0 || std::size_t(channel.node) >= measured.size() || !measured[std::size_t(channel.node)])
            continue;
        // A cubic spline's tangents are no unit quaternions: its rotations take the exponential filter.
        const bool unitQuaternions = channel.path == AnimationChannel::Path::Rotation &&
                                     channel.interpolation != AnimationChannel::Interpolation::CubicSpline;
        (unitQuaternions ? rotations : others).push_back(c);
    }
    if (rotations.empty() && others.empty()) return out;
    const PoseProbe probe(scene, animation);
    if (!probe.measurable()) return out;

    Animation trial = animation;
    // The channels `which` rounded by `round` at `bits` in `trial`; their roundings.
    auto roundIn = [&](const std::vector<std::size_t>& which, Rounded (*round)(const AnimationChannel&, int),
                       int bits) {
        std::vector<Rounded> rounded;
        for (std::size_t c : which) {
            rounded.push_back(round(animation.channels[c], bits));
            trial.channels[c].values = rounded.back().values;
        }
        return rounded;
    };
    auto restore = [&](const std::vector<std::size_t>& which) {
        for (std::size_t c : which) trial.channels[c].values = animation.channels[c].values;
    };
    // The fewest bits of `round` in [low, high] that keep the poses within `share` with `which` rounded (the
    // channels rounded before as they were left), and their roundings; none where even `high` does not. The same
    // bits for every channel: fewer for the channels that move the vertices less (a toe's joint against the
    // hip's) saved nothing on the fox or Cesium Man, as meshopt codes the filters' output.
    auto fewest = [&](const std::vector<std::size_t>& which, Rounded (*round)(const AnimationChannel&, int), int low,
                      int high, double share) {
        const int bits = which.empty() ? 0 : fewestBits(low, high, [&](int b) {
            roundIn(which, round, b);
            return probe.within(trial, share);
        });
        restore(which);
        return bits ? roundIn(which, round, bits) : std::vector<Rounded>();
    };

    // Of the roundings of the channels `which` by each filter, the one meshopt codes smallest (none where none
    // holds), left in `trial` and `out`.
    auto keepSmallest = [&](const std::vector<std::size_t>& which, std::vector<std::vector<Rounded>> candidates) {
        const std::vector<Rounded>* kept = nullptr;
        for (const std::vector<Rounded>& candidate : candidates)
            if (!candidate.empty() && (!kept || codedBytes(candidate) < codedBytes(*kept))) kept = &candidate;
        for (std::size_t i = 0; kept && i < kept->size(); ++i) {
            out[which[i]] = (*kept)[i].stored;
            trial.channels[which[i]].values = (*kept)[i].values;
        }
    };
    // Rotations with three quarters of the allowance (they are most of the data), by the filter that codes them
    // smaller: at the default budget the quaternion filter's 16 bits move the fox's paws 1.2 to 2.3 times too far.
    // Rotations that a file rounded by the quaternion filter already (gltfpack's, symcompress's) come back as read at
    // the file's bits, which no search finds: the filter's grids (2^(b-1) - 1 steps) do not refine one another, so
    // gltfpack's fox, at 12 bits, moves by 7 times the allowance at 14 bits and by 1.7 times at 16.
    auto asReadOnItsGrid = [&](const std::vector<std::size_t>& which, double share) {
        for (int bits = 4; bits <= 16 && !which.empty(); ++bits) {
            std::vector<Rounded> rounded = roundIn(which, quaternionOnItsGrid, bits);
            bool back = true;
            for (std::size_t i = 0; back && i < which.size(); ++i)
                back = givesBack(rounded[i].values, animation.channels[which[i]].values);
            if (back && probe.within(trial, share)) return rounded;
            restore(which);
        }
        return std::vector<Rounded>();
    };
    std::vector<std::vector<Rounded>> rotationCandidates;
    rotationCandidates.push_back(fewest(rotations, quaternionRounded, 4, 16, allowed * 3 / 4));
    restore(rotations);
    rotationCandidates.push_back(asReadOnItsGrid(rotations, allowed * 3 / 4));
    restore(rotations);
    rotationCandidates.push_back(
        fewest(rotations, exponentialRounded<false>, 1, kMostExponentialBits, allowed * 3 / 4));
    restore(rotations);
    rotationCandidates.push_back(fewest(rotations, exponentialRounded<true>, 1, kMostExponentialBits, allowed * 3 / 4));
    restore(rotations);
    keepSmallest(rotations, std::move(rotationCandidates));
    // The others with what the rotations left.
    std::vector<std::vector<Rounded>> otherCandidates;
    otherCandidates.push_back(fewest(others, exponentialRounded<false>, 1, kMostExponentialBits, allowed));
    restore(others);
    otherCandidates.push_back(fewest(others, exponentialRounded<true>, 1, kMostExponentialBits, allowed));
    restore(others);
    keepSmallest(others, std::move(otherCandidates));
    return out;
}

}  // namespace symcompress
