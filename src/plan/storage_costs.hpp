// The plan's measure of what storing parts costs, in bytes of output (StorageCostModel: the writer's own
// measure where it gives one). A part's triangles merged into a mesh with other parts cost what the scene's
// parts with the same attributes cost a triangle (measured on a sample of them together, as Draco codes
// them: a box among boxes in far fewer bytes than alone); a part as a mesh of its own costs what the writer
// measures for it, its class's prototype measured once.
#pragma once

#include "symcompress/detail/compression_plan.hpp"

#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace symcompress {

class StorageCosts {
public:
    // `joinGroups`: for each material, the one whose primitive its tiles stored as they are join (the writer's
    // joinByBaseColor: baseColorJoinGroups); empty: each its own.
    StorageCosts(const SceneAnalysis& analysis, const StorageCostModel& model, const std::vector<int>& joinGroups = {});

    double asMesh(const Primitive& part) const;
    // asMesh without the writer's trials of settings (StorageCostModel::quickMeshBytes).
    double asMeshQuickly(const Primitive& part) const;
    // Every primitive of the mesh, asMeshQuickly: two ways of storing one mesh (in two frames) measured alike.
    double meshBytesQuickly(const Mesh& mesh) const;
    // A node drawing a shared mesh with this transform and the name and extras of `source` (if any), as the
    // writer measures it.
    double node(const Eigen::Matrix4d& transform, const Node* source) const;
    double node(const Node& node) const;
    // The nodes drawing one shared mesh, together: a batch of instances costs less than its nodes apart (those
    // drawing a blended material, which no batch holds, apart).
    double nodes(const std::vector<PlacedCopy>& copies) const;
    // Tile t's triangles in a mesh with other parts; a tile drawn alone (SceneAnalysis::drawnAlone), a mesh and
    // node of its own.
    double merged(std::size_t t);
    // What a primitive of tile t's kind costs before its triangles (the tiles stored as they are in another
    // material need one of their own).
    double primitiveOverhead(std::size_t t) { return kindOf(t).overhead; }
    // The primitive tile t is stored in when stored as it is (one per material and attributes), numbered from 0
    // to primitives() - 1.
    std::size_t primitiveOf(std::size_t t) const { return primitiveOf_[t]; }
    std::size_t primitives() const { return primitiveCount_; }
    // Tile t as a mesh of its own (its class's prototype).
    double alone(std::size_t t);
    // The cheaper way of storing tile t apart from a group of tiles: as it is, or drawn by its class's mesh
    // (a node placing it, and its share of the mesh).
    double apart(std::size_t t);
    // Whether a fundamental region of tile t, stored for it alone, could cost less than its triangles merged
    // with others: a region is a mesh of its own, at least about what one triangle with t's attributes costs
    // as a mesh (half of it, for what a region's grid and frame may spare), and at least two nodes.
    bool regionMayPay(std::size_t t);
    // A mesh of these tiles: their triangles, and with `overhead` that of a primitive per material and
    // attributes.
    double meshOf(const std::vector<std::size_t>& tiles, bool overhead = true);
    // Whether the writer stores positions on a quantization grid (Draco): a frame that keeps the world's axes
    // then spares nothing, where in printed coordinates (X3D) its translation and scale may spare digits.
    bool positionsOnGrid() const { return model_.seamGridBits > 0; }
    // Measures every kind of tile (its attributes) now, which `merged` and `regionMayPay` would measure when
    // first asked: run beside other work, so that the first question does not wait for the writer.
    void measureKinds();

private:
    static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    static constexpr std::size_t kSampleTriangles = 20000;
    // Normals, texture coordinates, colours, the other attributes' names (attributeSignature).
    using Attributes = std::tuple<bool, bool, bool, std::string>;
    struct KindCosts {
        double perTriangle = 0, overhead = 0;
    };

    Attributes attributesOf(std::size_t t) const;
    // Measured on tiles spread over the scene, up to kSampleTriangles, merged as the writer would.
    const KindCosts& kindOf(std::size_t t);

    const SceneAnalysis& analysis_;
    const StorageCostModel& model_;
    std::vector<std::size_t> classOf_, memberOf_;  // a tile's class, and its index among the class's members
    std::vector<std::size_t> primitiveOf_;
    std::size_t primitiveCount_ = 0;
    std::vector<double> classMesh_;                // < 0: not measured yet
    std::vector<double> sharers_;                  // by class: the members its mesh draws (its family's, or its own)
    std::mutex kindsMutex_;  // the classes are planned in parallel: kinds_ is measured under it
    std::map<Attributes, KindCosts> kinds_;
};

}  // namespace symcompress
