// Symmetries of an assembly of tiles (paper 6.3, docs/assembly.md), built from the tiles' congruence
// classes and groups instead of from the whole surface.
#pragma once

#include "symcompress/congruence.hpp"
#include "symcompress/symmetry.hpp"
#include "symcompress/tiles.hpp"

#include <functional>

namespace symcompress {

// The isometries about the assembly's centroid that map every tile onto a congruent tile. The tile with
// the fewest candidates (members of its class times its group's order) fixes each candidate map: onto
// tile t1 by J_t1 g J_t0^-1 for g in its group (paper property 4); a candidate is kept when every other
// tile's centroid lands on a tile of its class and the map, seen from the two tiles' placements, is a
// symmetry of their prototype, within the classification's tolerance.
SymmetryGroup assemblySymmetries(const TileClassification& classification);
// The same for an assembly of some of the classification's tiles (a copy of a repeated assembly), about its own
// centroid.
SymmetryGroup assemblySymmetries(const TileClassification& classification, const std::vector<std::size_t>& assembly);

// For each element e of an assembly's group (assemblySymmetries), images[e][t] is the tile that e (about
// the group's centroid) maps tile t onto: one of t's class, where the map is a symmetry of their
// prototype seen from their placements; the number of tiles when there is none.
std::vector<std::vector<std::size_t>> tileImages(const TileClassification& classification, const SymmetryGroup& group);
// The same for the tiles of an assembly (those of assemblySymmetries(classification, assembly)); the other tiles'
// images are none.
std::vector<std::vector<std::size_t>> tileImages(const TileClassification& classification, const SymmetryGroup& group,
                                                 const std::vector<std::size_t>& assembly);

// Tiles that recur together in one relative placement: the parts of a chair, a table with its legs, a
// whole copied object. Copy 0 is the assembly as stored; copy j is placement j of it.
// Invariant: copies[j][i] is the tile that placement j puts tile copies[0][i] onto (a tile of the same
// class); no tile is in two copies, or in two assemblies.
struct RepeatedAssembly {
    std::vector<std::vector<std::size_t>> copies;
    std::vector<Isometry> placements;  // identity for copy 0
    double deviation = 0;              // bound on any rebuilt tile's distance from its original, relative to the diagonal
};

// Copies are found within the classification's tolerance.
struct AssemblyOptions {
    // Optional: whether tile `from`, placed by the isometry, may stand for tile `to` (e.g. attributes agree).
    // Called from several threads at once.
    std::function<bool(std::size_t from, std::size_t to, const Isometry&)> accept;
};

// Grows assemblies from anchors: for a class with several members, the isometries that take one member
// onto another (J_b g J_a^-1, g in the class's group), then, through tiles whose bounding boxes touch,
// every tile that each of those isometries takes onto a free tile of its own class. A tile that a
// placement takes onto itself (a floor under a mirrored room) or onto nothing stops the growth. Only
// assemblies of two or more tiles are returned.
std::vector<RepeatedAssembly> findRepeatedAssemblies(const std::vector<Tile>& tiles, const TileClassification& classification,
                                                     const AssemblyOptions& options = {});

}  // namespace symcompress
