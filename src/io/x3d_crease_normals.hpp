// The normals an X3D browser makes for a face set without a Normal node, from its creaseAngle: what the
// reader gives a face set, and what lets the writer leave the normals out where the browser makes them.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <utility>
#include <vector>

namespace symcompress {

// The unit normals of the faces at each of a number of points, each distinct one once with the number of faces that
// have it, in one array for all points. A corner's creased normal at a point depends on its face's normal alone,
// so a point where many faces lie in one plane (a fan, a grid) is summed once per plane rather than once per face.
class NormalsAtPoints {
public:
    // From (point, unit normal) pairs, one for each face at each point.
    NormalsAtPoints(std::size_t pointCount, const std::vector<std::pair<std::uint32_t, Eigen::Vector3d>>& incidences);

    // The sum of the normals at `point` that turn by less than the crease angle from `own` (its cosine), `own`
    // among them: the browser's normal of a corner there whose face has normal `own`, before normalization.
    Eigen::Vector3d smoothed(std::size_t point, const Eigen::Vector3d& own, double cosCrease) const;

private:
    std::vector<std::size_t> begin_, end_;  // each point's distinct normals: [begin_[p], end_[p])
    std::vector<Eigen::Vector3d> normals_;
    std::vector<int> counts_;  // how many faces have each
};

// The normals of every corner (X3D 3.3, 13.3.6 and 11.2.3): at a point, the average of the unit normals of
// the faces around it whose normal turns by less than `creaseAngle` from that of the corner's own face
// (unweighted, as X_ITE averages them). Returns the distinct normals (flat) and, for each corner in face
// order, the index of its normal. Points out of range are left to the caller.
std::pair<std::vector<double>, std::vector<std::int64_t>> creasedNormals(
    const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points, double creaseAngle,
    bool ccw);

// How far a browser's normal may lie from the one a corner has and still be its normal: about what Draco's 10-bit
// normals move a normal by in GLB output (0.2 degrees).
constexpr double kCreasedNormalMatch = 3.5e-3;

// Whether creasedNormals at `creaseAngle` gives every corner the normal it has (`cornerNormals`, one per
// corner in face order, ccw faces), within kCreasedNormalMatch.
bool creasedNormalsMatch(const std::vector<std::vector<std::int64_t>>& faces, const std::vector<double>& points,
                         const std::vector<Eigen::Vector3d>& cornerNormals, double creaseAngle);

}  // namespace symcompress
