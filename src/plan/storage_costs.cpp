#include "plan/storage_costs.hpp"

#include "plan/primitives_by_kind.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>

namespace symcompress {

StorageCosts::StorageCosts(const SceneAnalysis& analysis, const StorageCostModel& model,
                           const std::vector<int>& joinGroups)
    : analysis_(analysis), model_(model), classOf_(analysis.tiles.size(), kNone), memberOf_(analysis.tiles.size(), 0) {
    const auto& classes = analysis.classification.classes;
    for (std::size_t k = 0; k < classes.size(); ++k)
        for (std::size_t i = 0; i < classes[k].members.size(); ++i) {
            classOf_[classes[k].members[i]] = k;
            memberOf_[classes[k].members[i]] = i;
        }
    classMesh_.assign(classes.size(), -1);
    // Tiles of one input primitive share material and attributes: its signature built once.
    std::map<std::pair<int, Attributes>, std::size_t> primitives;
    std::map<std::uint32_t, std::size_t> ofSource;
    for (std::size_t t = 0; t < analysis.tiles.size(); ++t) {
        const std::uint32_t source = analysis.tiles[t].sources.front().primitive;
        auto [at, added] = ofSource.try_emplace(source, 0);
        const int material = analysis.tiles[t].material;
        const int drawnWith =
            material >= 0 && std::size_t(material) < joinGroups.size() ? joinGroups[std::size_t(material)] : material;
        if (added) at->second = primitives.try_emplace({drawnWith, attributesOf(t)}, primitives.size()).first->second;
        primitiveOf_.push_back(at->second);
    }
    primitiveCount_ = primitives.size();
    // Where a family's classes are planned as one (StorageCostModel::materialVariantBytes), their mesh is shared by
    // all its members.
    for (std::size_t k = 0; k < classes.size(); ++k) sharers_.push_back(double(classes[k].members.size()));
    if (model.materialVariantBytes)
        for (std::size_t k = 0; k < classes.size(); ++k)
            if (classes[k].family != k) sharers_[classes[k].family] += double(classes[k].members.size());
    for (std::size_t k = 0; k < classes.size(); ++k)
        if (model.materialVariantBytes) sharers_[k] = sharers_[classes[k].family];
}

double StorageCosts::asMesh(const Primitive& part) const {
    if (model_.meshBytes) return model_.meshBytes(part);
    return double(part.triangles.size()) * model_.bytesPerTriangle + model_.bytesPerMesh;
}

double StorageCosts::asMeshQuickly(const Primitive& part) const {
    return model_.quickMeshBytes ? model_.quickMeshBytes(part) : asMesh(part);
}

double StorageCosts::meshBytesQuickly(const Mesh& mesh) const {
    double bytes = 0;
    for (const Primitive& primitive : mesh.primitives) bytes += asMeshQuickly(primitive);
    return bytes;
}

double StorageCosts::node(const Node& node) const {
    return model_.nodeBytes ? model_.nodeBytes(node) : model_.bytesPerInstance;
}

double StorageCosts::node(const Eigen::Matrix4d& transform, const Node* source) const {
    Node drawing;
    drawing.transform = transform;
    if (source) copyNodeNotes(*source, drawing);
    return node(drawing);
}

double StorageCosts::nodes(const std::vector<PlacedCopy>& copies) const {
    // The copies in one material draw one mesh (a node that draws none cannot be an instance); a family's other
    // materials draw meshes of their own, batched apart.
    std::map<std::optional<int>, std::vector<Node>> byMaterial;
    for (const PlacedCopy& copy : copies) {
        Node& drawing = byMaterial[copy.material].emplace_back();
        drawing.mesh = 0;
        drawing.transform = copy.transform;
        if (copy.source) copyNodeNotes(*copy.source, drawing);
    }
    double bytes = 0;
    for (const auto& [material, drawing] : byMaterial) {
        if (model_.nodesBytes && !(material && analysis_.blended(*material))) {
            bytes += model_.nodesBytes(drawing);
            continue;
        }
        for (const Node& one : drawing) bytes += node(one);
    }
    return bytes;
}

double StorageCosts::merged(std::size_t t) {
    if (analysis_.drawnAlone(t)) return alone(t) + node(Eigen::Matrix4d::Identity(), nullptr);
    return double(analysis_.tiles[t].mesh.triangles.size()) * kindOf(t).perTriangle;
}

double StorageCosts::alone(std::size_t t) {
    const std::size_t k = classOf_[t];
    if (k == kNone) return asMesh(tilePrimitive(analysis_.tiles[t], analysis_.soup));
    if (classMesh_[k] < 0) {
        const std::size_t prototype = analysis_.classification.classes[k].prototype;
        classMesh_[k] = asMesh(tilePrimitive(analysis_.tiles[prototype], analysis_.soup));
    }
    return classMesh_[k];
}

double StorageCosts::apart(std::size_t t) {
    if (classOf_[t] == kNone) return std::min(merged(t), model_.bytesPerInstance + alone(t));
    const CongruenceClass& c = analysis_.classification.classes[classOf_[t]];
    return std::min(merged(t), node(c.placements[memberOf_[t]].matrix(), nullptr) + alone(t) / sharers_[classOf_[t]]);
}

bool StorageCosts::regionMayPay(std::size_t t) {
    if (analysis_.drawnAlone(t)) return false;  // drawn whole
    constexpr double kMeshFloor = 0.5;  // of a one-triangle mesh's measure
    const double twoNodes = nodes({PlacedCopy{}, PlacedCopy{}});
    return merged(t) > kMeshFloor * kindOf(t).overhead + twoNodes;
}

double StorageCosts::meshOf(const std::vector<std::size_t>& tiles, bool overhead) {
    double bytes = 0;
    std::set<std::pair<int, Attributes>> primitives;
    for (std::size_t t : tiles) {
        bytes += merged(t);
        if (overhead && primitives.insert({analysis_.tiles[t].material, attributesOf(t)}).second)
            bytes += kindOf(t).overhead;
    }
    return bytes;
}

void StorageCosts::measureKinds() {
    std::set<Attributes> seen;
    for (std::size_t t = 0; t < analysis_.tiles.size(); ++t)
        if (seen.insert(attributesOf(t)).second) kindOf(t);
}

StorageCosts::Attributes StorageCosts::attributesOf(std::size_t t) const {
    const WorldPrimitive& from = analysis_.soup[analysis_.tiles[t].sources.front().primitive];
    return {!from.primitive.normals.empty(), !from.primitive.texcoords.empty(), !from.primitive.colors.empty(),
            attributeSignature(from.primitive)};
}

const StorageCosts::KindCosts& StorageCosts::kindOf(std::size_t t) {
    const Attributes attributes = attributesOf(t);
    const std::lock_guard<std::mutex> lock(kindsMutex_);  // std::map keeps its entries where they are
    if (const auto known = kinds_.find(attributes); known != kinds_.end()) return known->second;
    std::vector<std::size_t> same;
    std::size_t triangles = 0;
    for (std::size_t u = 0; u < analysis_.tiles.size(); ++u)
        if (attributesOf(u) == attributes) {
            same.push_back(u);
            triangles += analysis_.tiles[u].mesh.triangles.size();
        }
    const std::size_t step = std::max<std::size_t>(1, triangles / kSampleTriangles);
    Primitive sample;
    for (std::size_t i = 0; i < same.size(); i += step) {
        Primitive part = tilePrimitive(analysis_.tiles[same[i]], analysis_.soup);
        part.material = -1;
        appendPrimitive(sample, part);
    }
    const Primitive one = triangleOf(sample, 0);
    KindCosts costs;
    costs.overhead = asMesh(one);
    costs.perTriangle = sample.triangles.size() > 1
                            ? std::max(0.0, (asMesh(sample) - costs.overhead) / double(sample.triangles.size() - 1))
                            : costs.overhead;
    return kinds_[attributes] = costs;
}

}  // namespace symcompress
