// Primitives gathered by material and by which attributes they carry, so that merging never drops an
// attribute some of them have (a tile without normals next to tiles with them gets a primitive of its own).
#pragma once

#include "symcompress/scene.hpp"

#include <map>
#include <string>
#include <tuple>

namespace symcompress {

class PrimitivesByKind {
public:
    void add(const Primitive& part);
    bool empty() const { return parts_.empty(); }
    // One primitive per kind, in the order of (material, normals, texture coordinates, colours); a small part
    // without normals joins the part with normals of its material, each corner given its triangle's normal.
    void moveInto(Mesh& mesh);

private:
    // Material, normals, texture coordinates, colours, and the other attributes' names and sizes.
    std::map<std::tuple<int, bool, bool, bool, std::string>, Primitive> parts_;
};

// Triangle t of the part on its own: its three vertices with their attributes (writers store every vertex
// a primitive lists, used or not).
Primitive triangleOf(const Primitive& part, std::size_t t);

}  // namespace symcompress
