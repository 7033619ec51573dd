#include "plan/primitives_by_kind.hpp"

namespace symcompress {

void PrimitivesByKind::add(const Primitive& part) {
    append(parts_[{part.material, !part.normals.empty(), !part.texcoords.empty(), !part.colors.empty()}], part);
}

void PrimitivesByKind::append(Primitive& into, const Primitive& part) {
    const auto offset = static_cast<std::uint32_t>(into.positions.size());
    into.material = part.material;
    into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
    into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
    into.texcoords.insert(into.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
    into.colors.insert(into.colors.end(), part.colors.begin(), part.colors.end());
    for (const Triangle& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

void PrimitivesByKind::moveInto(Mesh& mesh) {
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
    one.triangles = {{0, 1, 2}};
    return one;
}

}  // namespace symcompress
