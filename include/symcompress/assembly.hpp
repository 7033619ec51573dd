// Symmetries of an assembly of tiles (paper 6.3, ALGORITHM.md 7), built from the tiles' congruence
// classes and groups instead of from the whole surface.
#pragma once

#include "symcompress/congruence.hpp"
#include "symcompress/symmetry.hpp"

namespace symcompress {

// The isometries about the assembly's centroid that map every tile onto a congruent tile. The tile with
// the fewest candidates (members of its class times its group's order) fixes each candidate map: onto
// tile t1 by J_t1 g J_t0^-1 for g in its group (paper property 4); a candidate is kept when every other
// tile's centroid lands on a tile of its class and the map, seen from the two tiles' placements, is a
// symmetry of their prototype. `tolerance` is relative to the scene's diagonal, as for the classes.
SymmetryGroup assemblySymmetries(const TileClassification& classification, double tolerance);

}  // namespace symcompress
