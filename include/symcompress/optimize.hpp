// What every peer does before it compresses, on the scene before it is split into tiles: what nothing
// draws or reads is pruned, what is equal by content is stored once. None of it changes what a viewer
// draws. docs/optimizations.md.
#pragma once

#include "symcompress/scene.hpp"

#include <string>
#include <vector>

namespace symcompress {

struct OptimizeOptions {
    bool pruneAttributes = true;  // texture coordinates that no texture reads
    bool prune = true;            // materials no primitive uses, textures no material uses
    bool dedup = true;            // materials equal but for their names, textures equal by content
};

// What the optimizations removed or merged, counted.
struct OptimizeReport {
    std::size_t texcoordsDropped = 0;  // primitives whose texture coordinates no texture reads
    std::size_t materialsMerged = 0, texturesMerged = 0;
    std::size_t materialsRemoved = 0, texturesRemoved = 0;
    // One line for each optimization that did something, for the warnings a user reads.
    std::vector<std::string> lines() const;
};

// Dedup first (textures, then the materials that become equal through them), then pruning (which also
// removes what dedup left unused). The scene stays valid (validateScene): every index is remapped.
OptimizeReport optimizeScene(Scene& scene, const OptimizeOptions& options = {});

// The texture coordinates of primitives whose material reads no texture (no material, or one that names
// no texture) dropped; returns how many primitives lost theirs. A texture whose image could not be read
// still reads them: its reference is written, and the image may be put beside the file.
std::size_t dropUnreadTexcoords(Scene& scene);

// Materials equal in every field but their names drawn by the first of them (its name kept); textures
// with the same image (bytes and type, or the same URI where the image could not be read) by the first.
// Returns {materials merged, textures merged}; the merged ones are left unused for pruneUnused.
std::pair<std::size_t, std::size_t> mergeDuplicateMaterialsAndTextures(Scene& scene);

// Materials that no primitive uses and textures that no material uses, removed. Returns {materials,
// textures} removed.
std::pair<std::size_t, std::size_t> pruneUnused(Scene& scene);

}  // namespace symcompress
