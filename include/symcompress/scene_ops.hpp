// Operations on a whole scene: checking it, measuring it, flattening it to world space.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace symcompress {

// A scene drawing one mesh of one primitive once, at the identity (materials are the caller's).
Scene sceneOfOneMesh(const std::string& name, Primitive primitive);

// Throws std::invalid_argument naming the first broken invariant of scene.hpp.
void validateScene(const Scene& scene);

// What breaks scene.hpp's invariants in an animation channel of a scene of `nodes` nodes, or "" when
// nothing does (validateScene throws it; readers leave such a channel out with it as a warning).
std::string animationChannelProblem(const AnimationChannel& channel, std::size_t nodes);
// The same for a camera and a light.
std::string cameraProblem(const Camera& camera);
std::string lightProblem(const Light& light);

// A primitive placed in world space: attributes transformed (normals by the inverse transpose and
// renormalized), winding flipped where the world transform has a negative determinant.
struct WorldPrimitive {
    Primitive primitive;
    int node = -1;  // the node that draws it
    int mesh = -1;
};

// `local` placed by `world` as WorldPrimitive says.
Primitive transformPrimitive(const Primitive& local, const Eigen::Matrix4d& world);

// Brings every normal to unit length; a normal of zero length (or not finite) is replaced by the
// area-weighted normal of the vertex's triangles. Returns how many were replaced, for a warning.
std::size_t repairNormals(Scene& scene);

// Every drawn primitive in world space, in traversal order of Scene::roots.
std::vector<WorldPrimitive> flattenScene(const Scene& scene);

// Every drawn triangle in world space as one mesh (positions not welded, attributes dropped): the whole
// scene taken as one shape.
TriangleMesh worldMesh(const Scene& scene);

// The same drawing as one mesh under one root node with the identity transform: every instance
// expanded, materials and textures kept, cameras and lights kept on root nodes at their world
// placement, animations left out (a warning says so).
Scene expandInstances(const Scene& scene);

// The texture coordinate of `primitive`'s vertex `v` as its base colour texture reads it: through the
// texture's KHR_texture_transform, for writers of formats without one (X3D, OBJ, PLY).
Eigen::Vector2d baseColorTexcoord(const Scene& scene, const Primitive& primitive, std::size_t v);

// Every material's texture uses renumbered: texture t becomes newIndex[t] (-1: the use is dropped).
void renumberTextures(Scene& scene, const std::vector<int>& newIndex);

// For each texture, the first one with the same image bytes and type: an image that several materials
// (or an X3D file's several ImageTextures of one URL) use is written once.
std::vector<int> firstTextureOfSameImage(const std::vector<Texture>& textures);

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
