// The vertices of a primitive that Draco cannot hold (a morphed one: its reordering of the vertices would no
// longer match the targets' displacements; lines and points), rounded by EXT_meshopt_compression's exponential
// filter instead of stored as float32: each attribute to the fewest bits that keep it within what Draco's quantization
// allows the same attribute of a primitive it holds, the targets' displacements within that share over the weights they
// are drawn with.
#pragma once

#include "symcompress/io.hpp"
#include "symcompress/scene.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace symcompress {

// One accessor's values through the filter: as the file stores them, and as a viewer decodes them.
struct RoundedAttribute {
    std::vector<unsigned char> filtered;  // the filter's elements, one a vertex
    std::size_t elementBytes = 0;         // of one element (meshopt's byteStride)
    std::vector<float> decoded;
    int bits = 0;
};

// By target (-1: the primitive's own attributes) and attribute name (POSITION, NORMAL, TEXCOORD_0, COLOR_0, or
// one of Primitive::attributes); what is missing stays as read.
using RoundedVertices = std::map<std::pair<int, std::string>, RoundedAttribute>;

// The rounding of `primitive`'s vertices and displacements: POSITION within its error bound (positionErrorBound;
// half of it where morph targets take the other half), the displacements that half over the sum of `largestWeights` (of
// each target, the largest magnitude it is drawn with); NORMAL and TANGENT within the angle of Draco's normal
// quantization, texture coordinates, colours and weights within half a step of its quantization over their span, their
// displacements alike. Joints and an application's attributes stay as read, and everything does where the
// primitive has no error bound.
RoundedVertices roundedPlainVertices(const Primitive& primitive, const WriteOptions& options,
                                     const std::vector<double>& largestWeights);

// A point primitive's vertices in meshoptimizer's spatial order (meshopt_spatialSortRemap): neighbours side by
// side, which meshopt's codec codes smaller (a scan's points as its scanner gave them, or in any order). The order
// in which points are drawn draws nothing.
Primitive spatiallySortedPoints(const Primitive& points);

// Of each morph target of scene.meshes[mesh], the largest magnitude of a weight it is drawn with: its default,
// a node's, and an animation's keys (cubic splines: with what their tangents can add between keys).
std::vector<double> largestMorphWeights(const Scene& scene, std::size_t mesh);

}  // namespace symcompress
