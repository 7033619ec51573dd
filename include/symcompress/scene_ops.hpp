// Operations on a whole scene: checking it, measuring it, flattening it to world space.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace symcompress {

// A scene drawing one mesh of one primitive once, at the identity, by a node named `name` (materials are the
// caller's).
Scene sceneOfOneMesh(const std::string& name, Primitive primitive);

// Throws std::invalid_argument naming the first broken invariant of scene.hpp.
void validateScene(const Scene& scene);

// The number of morph targets of a mesh (each of its primitives has as many).
std::size_t morphTargetCount(const Mesh& mesh);

// What breaks scene.hpp's invariants in an animation channel of a scene of `nodes` nodes, or "" when
// nothing does (validateScene throws it; readers leave such a channel out with it as a warning).
std::string animationChannelProblem(const AnimationChannel& channel, std::size_t nodes);
// The same for a camera and a light.
std::string cameraProblem(const Camera& camera);
std::string lightProblem(const Light& light);

// The channel's value at `time`: the first key's before it, the last key's after it (glTF clamps), else
// interpolated as its sampler says (step, linear with slerp for rotations, cubic spline), a rotation normalized.
std::vector<double> sampleChannel(const AnimationChannel& channel, double time);

// The times of an animation's keys, every channel's, in order, each once.
std::vector<double> keyTimes(const Animation& animation);

// Every node's world transform at `time` of `animation` (null: at rest), its keyed translation, rotation and
// scale replacing its own (glTF allows no matrix on an animated node). The animation names the scene's nodes.
std::vector<Eigen::Matrix4d> posedWorldTransforms(const Scene& scene, const Animation* animation, double time);

// Which nodes lie under `seeds` (node indices), the seeds included.
std::vector<char> nodesUnder(const Scene& scene, std::vector<int> seeds);

// The parts of the scene that `animation` moves (the nodes it targets and all under them, the meshes their joints
// skin), drawn at `time` as a viewer draws them: keyed translations, rotations and scales interpolated as their
// samplers say, morph targets at their weights, skinned vertices by their joints. The same scene and channel
// targets give the same vertices in the same order, whatever the keys.
TriangleMesh posedMesh(const Scene& scene, const Animation& animation, double time);

// A skin's joint matrices in a pose: each joint's world transform times its inverse bind matrix.
std::vector<Eigen::Matrix4d> jointMatrices(const Skin& skin, const std::vector<Eigen::Matrix4d>& world);

// A primitive's JOINTS_n and WEIGHTS_n, set by set, as long as both are there.
struct SkinAttributes {
    std::vector<const VertexAttribute*> joints, weights;
};
SkinAttributes skinAttributesOf(const Primitive& primitive);

// Vertex v of a skinned primitive (its `skin` attributes) at `position` (its morph targets applied) drawn by
// `joints`: the sum of its joints' matrices weighted by WEIGHTS_n, the weights scaled to sum to 1 as viewers do
// (glTF asks that they do; three.js scales those that do not); by `otherwise` where it has no joints or weights.
Eigen::Vector3d skinnedPosition(const SkinAttributes& skin, std::size_t v, const Eigen::Vector3d& position,
                                const std::vector<Eigen::Matrix4d>& joints, const Eigen::Matrix4d& otherwise);

// How far rounding the skinned primitive's weights can move its vertices, per unit of rounding: the largest, over
// its vertices (of weights summing to s > 0) at rest and at every key time of every animation, of the distance
// from where one of its joints alone would carry it to where all of them do, over s. Rounding each of a vertex's
// k weights by at most d moves it by at most k d times this, over 1 - k d / s (the scaling to a sum of 1).
double skinWeightSensitivity(const Scene& scene, const Primitive& primitive, const Skin& skin);

// A primitive placed in world space: attributes transformed (normals by the inverse transpose and
// renormalized), winding flipped where the world transform has a negative determinant.
struct WorldPrimitive {
    Primitive primitive;
    int node = -1;  // the node that draws it
    int mesh = -1;
};

// An attribute moved with its primitive by `linear` (normalMatrix: its inverse transpose): a TANGENT's direction
// turned (its handedness w kept: a viewer builds the bitangent from the placed normal and tangent, so a mirrored
// placement and its baked copy draw alike), a NORMAL or TANGENT of a morph target (`displacement`) turned, and
// its POSITION too; the others stay as they are.
void transformAttribute(VertexAttribute& attribute, const Eigen::Matrix3d& linear, const Eigen::Matrix3d& normalMatrix,
                        bool displacement);

// `local` placed by `world` as WorldPrimitive says (a primitive passed as an rvalue is placed in its own arrays).
Primitive transformPrimitive(Primitive local, const Eigen::Matrix4d& world);

// Each mesh that draws triangles and also lines or points (a CAD part with its edges) split in two, the lines
// and points moved to a mesh of their own that a new child of each node drawing the mesh draws (at the identity),
// so that the triangles can still be tiled while the lines and points are kept as they are. The order of a mesh's
// primitives changes (triangles first); a morphed or skinned mesh stays whole. Returns the child nodes added.
std::size_t splitLinesAndPoints(Scene& scene);

// The primitive's vertices `kept` (indices into its arrays, in their new order; one may come twice), every
// attribute and morph target with them. Triangles and lines are left to the caller to renumber.
void keepVertices(Primitive& primitive, const std::vector<std::uint32_t>& kept);

// Whether triangle t has two corners at one point: zero area, it draws nothing, but viewers count it, and Draco's
// edgebreaker cannot hold it.
inline bool hasTwoCornersAtOnePoint(const std::vector<Eigen::Vector3d>& positions, const Triangle& t) {
    return positions[t[0]] == positions[t[1]] || positions[t[1]] == positions[t[2]] ||
           positions[t[0]] == positions[t[2]];
}

// A primitive's triangles of zero area: how many, and the first corner of the first of them, at which the writers
// keep them all.
struct ZeroAreaTriangles {
    std::size_t count = 0;
    std::uint32_t vertex = 0;
};
// Them; nothing where the primitive has none.
std::optional<ZeroAreaTriangles> zeroAreaTrianglesOf(const Primitive& primitive);
// The primitive without them (its vertices that only they used left out too), and them; nothing where it has none.
std::optional<std::pair<Primitive, ZeroAreaTriangles>> withoutZeroAreaTriangles(const Primitive& primitive);

// `part`'s vertices and triangles appended to `into` (its material taken), which carries the same attributes or
// nothing yet.
void appendPrimitive(Primitive& into, const Primitive& part);

// A hash of the positions of the triangles' corners, triangle by triangle: the same whatever the vertices' order
// or their other attributes (a weld, pruned attributes), another where a triangle moved (X3dGeometrySource).
std::uint64_t trianglePositionsHash(const Primitive& primitive);

// The names and sizes of the primitive's other attributes (Primitive::attributes), as one key ("TANGENT:4;"):
// primitives or tiles with different keys are never merged into one.
std::string attributeSignature(const Primitive& primitive);

// Brings every normal to unit length; a normal of zero length (or not finite) is replaced by the
// area-weighted normal of the vertex's triangles. Returns how many were replaced, for a warning.
std::size_t repairNormals(Scene& scene);

// Every drawn primitive in world space, in traversal order of Scene::roots.
std::vector<WorldPrimitive> flattenScene(const Scene& scene);

// The same, for a caller that needs the geometry of the meshes m with takeMesh[m] no more: the last node to
// draw such a mesh gets its arrays moved into the soup instead of copied, and each such mesh is left with its
// primitives' materials only. The job's way to keep one copy of the scene's geometry, not two.
std::vector<WorldPrimitive> flattenSceneTaking(Scene& scene, const std::vector<char>& takeMesh);

// Every drawn triangle in world space as one mesh (positions not welded, attributes dropped): the whole
// scene taken as one shape.
TriangleMesh worldMesh(const Scene& scene);

// What the scene draws as points and as the ends of line segments (two a segment), in world space: each vertex a
// triangle of three equal corners, so that the surfaces' measures take the distances between them.
struct DrawnVertices {
    TriangleMesh points, lineEnds;
};
DrawnVertices worldPointsAndLineEnds(const Scene& scene);

// The same drawing as one mesh under one root node with the identity transform: every instance
// expanded, materials and textures kept, cameras and lights kept on root nodes at their world
// placement; the animated subtrees (markAnimatedSubtrees) kept as they are, with their animations.
Scene expandInstances(const Scene& scene);

// The texture coordinate of `primitive`'s vertex `v` as its base colour texture reads it: through the
// texture's KHR_texture_transform, for writers of formats without one (X3D, OBJ, PLY).
Eigen::Vector2d baseColorTexcoord(const Scene& scene, const Primitive& primitive, std::size_t v);

// The materials a primitive of material `m` draws with: m itself, then each other one a variant of it draws
// (Material::variants), each once; none for -1 (the default material).
std::vector<const Material*> materialsDrawnWith(const Scene& scene, int m);

// Whether a primitive of material `m` is drawn blended, under some variant: viewers sort blended objects back to
// front, each as a whole, and draw an object's triangles in their order without writing depth (three.js, X_ITE),
// so such a primitive must stay one object as the input drew it: one tile, merged with no other, never batched.
bool drawnBlended(const Scene& scene, int m);

// What an input node says about itself (its name, extras and the extensions passed through), given to a node of the
// output that draws what it drew.
void copyNodeNotes(const Node& from, Node& to);
inline bool hasNodeNotes(const Node& node) {
    return !node.name.empty() || !node.extrasJson.empty() || !node.extensionsJson.empty();
}

// What the file of `from` says about itself (its extras, copyright, the scene's name and extras, the extensions
// passed through on them), given to `to`.
void copyFileMetadata(const Scene& from, Scene& to);

// Every material's variant tables renumbered: material m becomes newIndex[m].
void renumberVariantMaterials(Scene& scene, const std::vector<int>& newIndex);

// The materials not marked in `keep` removed, every primitive's and variant table's index renumbered (a primitive
// of a removed material draws the default one). Returns how many.
std::size_t removeMaterials(Scene& scene, const std::vector<bool>& keep);

// Every material's texture uses renumbered: texture t becomes newIndex[t] (-1: the use is dropped).
void renumberTextures(Scene& scene, const std::vector<int>& newIndex);

// For each texture, the first one with the same image bytes and type (and the same fallback): an image that several
// materials (or an X3D file's several ImageTextures of one URL) use is written once.
std::vector<int> firstTextureOfSameImage(const std::vector<Texture>& textures);

// Of each node, whether an animation's channel targets it or a skin takes it for a joint: what moves its transform,
// or reads it beyond what the node draws.
std::vector<bool> nodesAnimationsAndSkinsMove(const Scene& scene);

// Which nodes are animated or under an animated node (reached from the roots); `tops` gets the animated nodes
// with no animated ancestor, in increasing order. Animated: the target of an animation channel, a skin's
// joint, a node drawing a skinned mesh or one with morph targets: what they draw moves, and is kept as it is.
std::vector<bool> markAnimatedSubtrees(const Scene& scene, std::vector<int>& tops);

// The subtrees at `tops` (markAnimatedSubtrees) copied into `out` as they are, each under a new root node
// holding its parent's world transform, with the skins of their joints and the input's animations retargeted
// to them (a channel of a node no root reaches is left out with a warning). Meshes are shared with the other
// kept meshes through `keptMesh` (input mesh -> output mesh). Returns the number of nodes copied.
std::size_t keepAnimatedSubtrees(const Scene& input, const std::vector<int>& tops, Scene& out,
                                 std::map<int, int>& keptMesh);

// The world transform of every node (identity for nodes that are not reachable from the roots).
std::vector<Eigen::Matrix4d> worldTransforms(const Scene& scene);

struct SceneStatistics {
    std::size_t nodes = 0;
    std::size_t meshes = 0;
    std::size_t materials = 0;
    std::size_t trianglesStored = 0;  // in Scene::meshes
    std::size_t trianglesDrawn = 0;   // instances expanded
    Eigen::AlignedBox3d bounds;       // world space, of what is drawn (empty when nothing is)
};

SceneStatistics sceneStatistics(const Scene& scene);

}  // namespace symcompress
