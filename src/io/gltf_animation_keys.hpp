// How a compressed glTF stores an animation's key values: as read (float32, coded by meshopt without loss where
// that is smaller), or rounded by EXT_meshopt_compression's filters (quaternion for rotations, exponential for
// the rest) with the fewest bits that keep every vertex the animation moves within an allowance in every pose.
#pragma once

#include "gltf_builder.hpp"

#include "symcompress/scene.hpp"

#include <string>
#include <vector>

namespace symcompress {

// One channel's output as the file stores it.
struct KeyValues {
    std::string filter;            // meshopt's filter (QUATERNION, EXPONENTIAL); empty: the values as read, float32
    int componentType = kFloat;    // of the accessor: FLOAT, or normalized SHORT (quaternion filter)
    std::size_t elementBytes = 0;  // of one filtered element (meshopt's byteStride)
    std::vector<unsigned char> filtered;  // the filter's encoding of the values
    int bits = 0;                         // the filter's bits
};

// For each channel of `animation` (which names the scene's nodes), how its values are stored: rounded where
// every vertex the animation moves stays within `allowed` (a distance) of where the values as read put it, at
// each key time and halfway between (a cubic spline's tangents act only there). Rotations take the quaternion
// or exponential filter, whichever codes smaller, with three quarters of the allowance; the other channels then the
// exponential filter with the rest. Values stay as read where `allowed` is 0, where a channel moves a camera or
// a light (what they do is not measured), or where the poses to measure are too many (key times times vertices).
std::vector<KeyValues> roundedKeyValues(const Scene& scene, const Animation& animation, double allowed);

}  // namespace symcompress
