#include "plan/primitives_by_kind.hpp"

#include "symcompress/scene_ops.hpp"

#include <Eigen/Geometry>

namespace symcompress {
namespace {

// The most triangles of a part without normals (flat) that join the part of their material with normals, each
// corner given its triangle's normal: a primitive of its own costs some 360 bytes (accessors and Draco's
// header), a triangle's three corners with a normal each about 15 (the cat's 8 flat triangles: 15728 -> 15296
// bytes).
constexpr std::size_t kSmallFlatPart = 24;

// `part` with a vertex of its own for each corner, and its triangle's normal there: how a viewer shades it
// without normals.
Primitive withFaceNormals(const Primitive& part) {
    Primitive split;
    split.material = part.material;
    for (std::size_t t = 0; t < part.triangles.size(); ++t) {
        Primitive corner = triangleOf(part, t);
        const Eigen::Vector3d cross =
            (corner.positions[1] - corner.positions[0]).cross(corner.positions[2] - corner.positions[0]);
        // A triangle without area draws nothing; its normal need only be a unit vector.
        corner.normals.assign(3, cross.norm() > 0 ? Eigen::Vector3d(cross.normalized()) : Eigen::Vector3d::UnitZ());
        appendPrimitive(split, corner);
    }
    return split;
}

}  // namespace

void PrimitivesByKind::add(const Primitive& part) {
    appendPrimitive(parts_[{part.material, !part.normals.empty(), !part.texcoords.empty(), !part.colors.empty(),
                            attributeSignature(part)}],
                    part);
}

void PrimitivesByKind::moveInto(Mesh& mesh) {
    // A small flat part beside its material's smooth one is drawn by it, shaded as before.
    for (auto part = parts_.begin(); part != parts_.end();) {
        const auto [material, normals, texcoords, colors, attributes] = part->first;
        // (withFaceNormals keeps no other attribute.)
        const auto smooth = normals || !attributes.empty()
                                ? parts_.end()
                                : parts_.find({material, true, texcoords, colors, attributes});
        if (smooth == parts_.end() || part->second.triangles.size() > kSmallFlatPart) {
            ++part;
            continue;
        }
        appendPrimitive(smooth->second, withFaceNormals(part->second));
        part = parts_.erase(part);
    }
    for (auto& [kind, primitive] : parts_) mesh.primitives.push_back(std::move(primitive));
    parts_.clear();
}

Primitive triangleOf(const Primitive& part, std::size_t t) {
    Primitive one;
    one.material = part.material;
    for (std::uint32_t v : part.triangles[t]) {
        one.positions.push_back(part.positions[v]);
        if (!part.normals.empty()) one.normals.push_back(part.normals[v]);
        if (!part.texcoords.empty()) one.texcoords.push_back(part.texcoords[v]);
        if (!part.colors.empty()) one.colors.push_back(part.colors[v]);
    }
    for (const VertexAttribute& attribute : part.attributes) {
        VertexAttribute& corners = one.attributes.emplace_back(attribute.withoutValues());
        for (std::uint32_t v : part.triangles[t]) corners.appendVertex(attribute, v);
    }
    one.triangles = {{0, 1, 2}};
    return one;
}

}  // namespace symcompress
