// The normals an X3D browser makes for a face set without a Normal node, from its creaseAngle: what the
// reader gives a face set, and what lets the writer leave the normals out where the browser makes them.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace symcompress {

// The normals of every corner (X3D 3.3, 13.3.6 and 11.2.3): at a point, the average of the unit normals of
// the faces around it whose normal turns by less than `creaseAngle` from that of the corner's own face
// (unweighted, as X_ITE averages them). Returns the distinct normals (flat) and, for each corner in face
// order, the index of its normal. Points out of range are left to the caller.
std::pair<std::vector<double>, std::vector<std::int64_t>> creasedNormals(
    const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points, double creaseAngle,
    bool ccw);

// Whether creasedNormals at `creaseAngle` gives every corner the normal it has (`cornerNormals`, one per
// corner in face order, ccw faces), within 3.5e-3: about what Draco's 10-bit normals move a normal by in GLB
// output (0.2 degrees).
bool creasedNormalsMatch(const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points,
                         const std::vector<Eigen::Vector3d>& cornerNormals, double creaseAngle);

}  // namespace symcompress
