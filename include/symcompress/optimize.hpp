// What every peer does before it compresses, on the scene before it is split into tiles: what nothing
// draws or reads is pruned, what is equal by content is stored once. None of it changes what a viewer
// draws. docs/optimizations.md.
#pragma once

#include "symcompress/scene.hpp"

#include <functional>
#include <string>
#include <vector>

namespace symcompress {

struct OptimizeOptions {
    bool pruneAttributes = true;  // texture coordinates that no texture reads, tangents no normal map reads
    bool prune =
        true;  // materials no primitive uses, textures no material uses, animation channels that change nothing
    bool dedup = true;            // materials equal but for their names, textures equal by content
    bool dropFlatNormals = true;  // normals equal to their triangles' own (the viewer's flat shading)
    // Animation keys that interpolation gives back within the budget (compressFile, which has the budget:
    // dropRedundantKeys).
    bool dropKeys = true;
    // Primitives of one mesh in materials that differ only in base colour drawn as one, the colour per vertex
    // (compressFile, once the plan has made its meshes, for glTF with Draco: joinByBaseColor).
    bool joinByBaseColor = true;
};

// What the optimizations removed or merged, counted.
struct OptimizeReport {
    std::size_t unreadAttributesDropped = 0;  // primitives that lost attributes no material reads
    std::size_t flatNormalsDropped = 0;       // primitives whose normals were their triangles' own
    std::size_t materialsMerged = 0, texturesMerged = 0;
    std::size_t materialsRemoved = 0, texturesRemoved = 0;
    std::size_t stillChannelsRemoved = 0;  // animation channels that hold their node where it rests
    std::size_t animationKeysDropped = 0;  // keys that interpolation gives back (dropRedundantKeys)
    std::size_t animationChannelsRemoved = 0;  // channels near their node's rest, within the budget (the same)
    // Primitives joined by their base colour and the primitives they became (joinByBaseColor, on the plan kept).
    std::size_t primitivesJoinedByColor = 0, joinedPrimitives = 0;
    // One line for each optimization that did something, for the warnings a user reads.
    std::vector<std::string> lines() const;
};

// Dedup first (textures, then the materials that become equal through them), then pruning (which also
// removes what dedup left unused). The scene stays valid (validateScene): every index is remapped.
OptimizeReport optimizeScene(Scene& scene, const OptimizeOptions& options = {});

// The attributes no viewer reads dropped: a TEXCOORD_n set that no texture of the primitive's material reads
// (no material, or none of its textures on that set), TANGENT where the material has no normal map (core,
// clear-coat) and no anisotropy. Returns how many primitives lost some. A texture whose image could not be
// read still reads its set: its reference is written, and the image may be put beside the file. A primitive
// with morph targets keeps everything (its targets may displace what it has).
std::size_t dropUnreadAttributes(Scene& scene);

// Normals that say nothing dropped: where every corner's normal is its triangle's geometric normal (STL facet
// normals, CAD exports split by face), glTF viewers shade flat without them, and the X3D writer asks for
// normals per face. The vertices they had split are merged. Kept where morph targets, tangents or a normal map
// (which reads tangents) need them. Returns how many primitives lost theirs. Not for OBJ or PLY output, whose
// viewers smooth a mesh without normals.
std::size_t dropFlatNormals(Scene& scene);

// Materials equal in every field but their names drawn by the first of them (its name kept); textures
// with the same image (bytes and type, or the same URI where the image could not be read) by the first.
// Returns {materials merged, textures merged}; the merged ones are left unused for pruneUnused.
std::pair<std::size_t, std::size_t> mergeDuplicateMaterialsAndTextures(Scene& scene);

// Materials that no primitive uses and textures that no material uses, removed. Returns {materials,
// textures} removed.
std::pair<std::size_t, std::size_t> pruneUnused(Scene& scene);

// Animation channels that hold their node where it rests removed: every key its own translation, rotation
// (either quaternion), scale or morph weights to float32's precision (a cubic spline's tangents 0), where no other
// animation keys the same node and path (a viewer playing both would blend them), the animation keeps a channel
// and the same first and last key times (its length, over which a viewer loops). Returns how many.
std::size_t removeStillChannels(Scene& scene);

// What dropRedundantKeys dropped, and how far that moves a vertex in the poses.
struct RedundantKeys {
    std::size_t keysDropped = 0;      // the channels' removed among them
    std::size_t channelsRemoved = 0;  // channels within the allowance of their node's rest value
    double deviation = 0;  // a distance, at most the allowance
};
// Animation keys that interpolation of the keys kept gives back dropped, where every vertex the animation moves
// stays within `allowed` (a distance) of where it lies as read, at each key time and halfway between (PoseProbe):
// in linear and step channels of nodes that draw something (a camera's or a light's motion is not measured), each
// channel's first and last keys kept (its length). Channels keyed at the same times keep them shared (one accessor in
// the file). A channel that stays within the allowance of its node's rest value is removed, as
// removeStillChannels removes those that hold it exactly, where no other animation keys the node's path and the
// animation keeps its length. Nothing where the poses are too many to measure.
RedundantKeys dropRedundantKeys(Scene& scene, double allowed);

// What joinByBaseColor joined: primitives, the primitives they became, and the materials left unused and removed.
struct BaseColorJoins {
    std::size_t primitivesJoined = 0, joinedPrimitives = 0, materialsRemoved = 0;
    std::vector<std::string> namesLost;  // of the materials removed (the joined material has none)
};

// For each material, the first it may be joined with by base colour (joinByBaseColor): equal in everything glTF
// writes but the red, green and blue of its base colour (and its name, and X3D's Phong fields); itself where none is
// earlier, where a material variant swaps it for another, or where it is specular-glossiness (whose diffuse factor,
// not the base colour, COLOR_0 multiplies).
std::vector<int> baseColorJoinGroups(const std::vector<Material>& materials);

// Primitives of one mesh whose materials differ in nothing glTF writes but the red, green and blue of their base
// colour (baseColorJoinGroups) drawn as one primitive: each vertex carries its material's colour in COLOR_0
// (multiplied into its own colours), which glTF multiplies into the base colour, under one material of base colour
// white (nameless; X3D's Phong fields dropped: for glTF output only). Triangles without morph targets, with the same
// attributes otherwise, of at least two materials; joined where `bytes` (the writer's measure of a primitive) says
// the joined one, and `materialBytes` for a new material, is smaller than its members apart. Each joined primitive
// asks for the COLOR_0 bits (Primitive::colorBits) that keep its colours within a quarter of an 8-bit step of sRGB
// output, and keeps every member's position bounds: the least error bound, and the close-up bound of its smallest
// member (members are joined in runs of similar size). The materials it leaves unused are removed.
BaseColorJoins joinByBaseColor(Scene& scene, const std::function<double(const Primitive&)>& bytes,
                               double materialBytes);

}  // namespace symcompress
