// The member check: whether a stored part, placed by an isometry, may stand for a tile. The classes are
// congruent as surfaces; a node may draw a member only where the prototype reproduces it vertex for vertex,
// attributes included, facing the same way (docs/compression-plan.md, "The member check").
#pragma once

#include "symcompress/congruence.hpp"
#include "symcompress/scene.hpp"

namespace symcompress {

// Whether `prototype` placed by j reproduces `member` one vertex to one vertex within `tolerance` (a
// distance), facing the same way; with `geometryOnly`, positions and faces only, else normals, texture
// coordinates and colours too.
bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly);

}  // namespace symcompress
