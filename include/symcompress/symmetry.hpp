// Symmetries of a single shape (paper section 5, ALGORITHM.md 3-5): candidate axes from the critical
// points of the moment functions, the parameters each axis allows, verification on the shape with the
// measure d_A, refinement, and the point group they form.
#pragma once

#include "symcompress/moments.hpp"
#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace symcompress {

// An orthogonal map x -> centroid + linear (x - centroid) that maps the shape onto itself.
struct Symmetry {
    enum class Kind { Identity, Rotation, Mirror, Rotoreflection, Inversion };
    Kind kind = Kind::Identity;
    Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();
    Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // rotation axis, or mirror normal (unit; zero for inversion)
    double angle = 0;                                // radians in (0, pi] (rotations and rotoreflections)
    int fold = 0;                                    // rotations: the order of the axis in the group
    double deviation = 0;                            // d_A relative to the bounding-box diagonal
};

const char* kindName(Symmetry::Kind kind);  // "identity", "rotation", "mirror", "rotoreflection", "inversion"

// Classifies an orthogonal matrix: kind, axis, angle (fold and deviation left 0).
Symmetry describeOrthogonal(const Eigen::Matrix3d& linear);

struct SymmetryOptions {
    // Largest d_A accepted, relative to the shape's bounding-box diagonal. The default accepts the exact
    // symmetries of models stored in float32; scans need a looser value.
    double tolerance = 1e-5;
    int maxOrder = 10;    // highest moment order used for the candidate axes (raised to 16 when needed)
    int maxFold = 360;    // largest n tried for axes whose moments are invariant under every rotation
    int threads = 0;      // 0: all cores
};

struct SymmetryGroup {
    std::string name = "C1";  // Schoenflies symbol: C1, Cs, Ci, Cn, Cnv, Cnh, Dn, Dnh, Dnd, S2n, T, Td, Th, O, Oh, I, Ih
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    double diagonal = 0;                // of the bounding box, the unit of the tolerance and deviations
    std::vector<Symmetry> elements;     // the whole group, identity first
    std::vector<std::string> warnings;  // e.g. a shape with no area
    struct {
        double moments = 0;       // the moment coefficients
        double axes = 0;          // critical points of the moment functions
        double verification = 0;  // per-axis moment tests, shape tests, refinement, the group's deviations
    } seconds;
    int order() const { return int(elements.size()); }
};

// The symmetry group of the surface, as verified on the surface itself.
SymmetryGroup detectSymmetries(const TriangleMesh& mesh, const SymmetryOptions& options = {});

// The Schoenflies name of a finite group of orthogonal matrices (given whole, identity included).
std::string pointGroupName(const std::vector<Eigen::Matrix3d>& group);

// Every subgroup of a finite group of orthogonal matrices (given whole, identity first), the trivial
// group and the group itself included, each as the sorted indices of its elements, in order of discovery
// (the trivial group first). Products are matched to elements within `tolerance` on every entry; throws
// std::invalid_argument when the identity is not first or a product matches no element.
std::vector<std::vector<std::size_t>> subgroupsOf(const std::vector<Eigen::Matrix3d>& group, double tolerance = 1e-6);

}  // namespace symcompress
