// Congruence classes of tiles (paper 6.2 and 6.3.3, docs/congruence.md): tiles that are the same shape up
// to a rotation or a reflection, found by descriptor, symmetry group and a geometric check, with the
// isometry that places the class prototype onto each member.
#pragma once

#include "symcompress/detail/congruence_descriptor.hpp"
#include "symcompress/symmetry.hpp"
#include "symcompress/tiles.hpp"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace symcompress {

// x -> linear x + translation, linear orthogonal.
struct Isometry {
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    bool mirrors() const { return linear.determinant() < 0; }
    Eigen::Matrix4d matrix() const;
    Isometry inverse() const;                         // linear orthogonal: its transpose
    Isometry operator*(const Isometry& first) const;  // `first`, then this
};

// What the classification needs of one tile.
struct TileShape {
    int material = -1;
    std::size_t triangles = 0;
    double diagonal = 0;  // of the tile's bounding box
    MomentCoefficients moments;
    CongruenceDescriptor descriptor;
    Eigen::Matrix3d secondMoments = Eigen::Matrix3d::Zero();  // integral of s s^T about the centroid
    Eigen::Vector3d principalMoments = Eigen::Vector3d::Zero();  // its eigenvalues, ascending
    SymmetryGroup symmetry;  // detected on class prototypes; a member's is its prototype's, carried over by J
    bool symmetrySkipped = false;  // not detected: no use could be made of it (CongruenceOptions::groupUsable)
};

// Invariant: members[0] == prototype; placements[i] takes the prototype onto members[i] (identity for
// the prototype itself) within the tolerance; every member has the prototype's material (and, being
// congruent, a conjugate group).
struct CongruenceClass {
    std::size_t prototype = 0;
    std::vector<std::size_t> members;
    std::vector<Isometry> placements;
    std::vector<double> deviations;  // d_A of each placement, relative to the scene's diagonal
    // Classes of other materials whose prototypes are congruent to this one's make a family: one stored mesh can
    // draw all their members, each in its own material. `family` is the family's first class (this class's own
    // index when it leads one or stands alone); fromFamily takes that class's prototype onto this one's, within
    // the tolerance, at familyDeviation (relative to the scene's diagonal).
    std::size_t family = 0;
    Isometry fromFamily;
    double familyDeviation = 0;
};

struct CongruenceOptions {
    double tolerance = 1e-5;  // relative to the scene's bounding-box diagonal (d_A of placements and symmetries)
    double absoluteTolerance = 0;  // when > 0, the tolerance as a distance, in place of `tolerance`
    int maxOrder = 8;         // moment orders in the descriptor
    bool symmetries = true;   // find each class's symmetry group
    bool elementDeviations = true;  // and measure each of its elements (SymmetryOptions::elementDeviations)
    int threads = 0;
    // When set: whether the group of a class of this one tile could be used (called from one thread). The
    // groups it cannot use are not detected, unless the symmetry of the whole assembly of tiles might need
    // them: that is the identity alone as soon as one class of one tile has no symmetry.
    std::function<bool(std::size_t tile)> groupUsable;
};

struct TileClassification {
    std::vector<TileShape> shapes;  // one per tile
    std::vector<CongruenceClass> classes;
    double sceneDiagonal = 0;
    // The tolerance the classification was made with, as a distance and relative to sceneDiagonal: what the
    // stages built on it (assemblies, the plan) use too.
    double absoluteTolerance = 0, tolerance = 0;
    std::size_t descriptorMatches = 0;  // pairs that passed descriptor and group and went to the geometric check
    std::size_t verifiedMatches = 0;    // of those, the congruent ones
    std::size_t groupsSkipped = 0;      // classes whose group was not detected (CongruenceOptions::groupUsable)
};


// Every tile in exactly one class. Tiles are grouped by area (a sorted index, never all pairs), then
// material and descriptor, then checked geometrically (which also keeps tiles of different groups apart).
TileClassification classifyTiles(const std::vector<Tile>& tiles, const CongruenceOptions& options = {});

}  // namespace symcompress
