// The classification's tolerance formulas: how the scene's absolute tolerance becomes the descriptor's and
// a tile's own (docs/congruence.md, "Tolerances").
#pragma once

namespace symcompress {

// The largest descriptorDifference between tiles that go on to the geometric check, for a tile of this
// bounding-box diagonal and the classification's absolute tolerance.
double descriptorTolerance(double tileDiagonal, double absoluteTolerance);
// The relative tolerance of a tile's own symmetry group: the classification's absolute tolerance relative
// to the tile, at least `relativeTolerance` and at most 1e-3 (a small tile is not allowed everything).
double tileSymmetryTolerance(double tileDiagonal, double absoluteTolerance, double relativeTolerance);

}  // namespace symcompress
