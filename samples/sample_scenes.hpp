// Scenes whose repetition and symmetry are known by construction: the bundled samples, and test input
// with known answers. Every function is deterministic.
#pragma once

#include "symcompress/scene.hpp"
#include "symcompress/tiles.hpp"

#include <random>
#include <string>
#include <vector>

namespace symcompress::samples {

// A vector or a quaternion drawn coordinate by coordinate from `draw()`, in one order whatever the compiler: a
// function's arguments are evaluated in an unspecified order (GCC, which made the committed samples, right to left;
// Clang left to right), so that Eigen::Vector3d(d(r), d(r), d(r)) differs between them. The last is drawn first.
template <typename Draw>
Eigen::Vector3d drawnVector(Draw draw) {
    const double z = draw(), y = draw(), x = draw();
    return {x, y, z};
}
template <typename Draw>
Eigen::Vector4d drawnVector4(Draw draw) {
    const double w = draw(), z = draw(), y = draw(), x = draw();
    return {x, y, z, w};
}
template <typename Draw>
Eigen::Quaterniond drawnQuaternion(Draw draw) {
    const Eigen::Vector4d wxyz = drawnVector4(draw);
    return {wxyz[0], wxyz[1], wxyz[2], wxyz[3]};
}

// Building blocks (sample_geometry.cpp).
void appendMesh(Primitive& out, const TriangleMesh& part);
TriangleMesh boxMesh(const Eigen::Vector3d& centre, const Eigen::Vector3d& size);  // axis-aligned, 12 triangles
// A closed surface of revolution about the z axis through `base`: profile points (radius, z), the first
// and last on the axis; `segments` equal sectors, so group C_nv with n = segments.
TriangleMesh latheMesh(const std::vector<Eigen::Vector2d>& profile, int segments, const Eigen::Vector3d& base);
// An ellipsoid of revolution (radius 0.5, height 2) on 24 rings of `azimuths`, every vertex slid along the
// surface by up to a fifth of its spacing and each quad split along a random diagonal, randomly turned and
// rounded to float32: within a loose tolerance of round, with no symmetry of its tessellation (a roller a
// modeller tessellated on its own).
TriangleMesh unevenEllipsoid(int azimuths, std::uint64_t seed);
// A convex part of 16 random points on an ellipsoid of random axes (0.4 to 1.2), about 28 triangles: no
// symmetry. Draws from `random`, so that a caller's sequence of parts is its own.
TriangleMesh randomConvexPart(std::mt19937_64& random);
// A rotation uniformly distributed over SO(3) (a normalized Gaussian quaternion), drawn from `random`.
Eigen::Matrix3d randomRotation(std::mt19937_64& random);
// x -> linear x + translation; a mirroring map also reverses the triangles, keeping them outward.
TriangleMesh transformed(TriangleMesh mesh, const Eigen::Matrix3d& linear, const Eigen::Vector3d& translation);

// A scene of one mesh drawn once, one primitive per material, filled part by part.
class OneMeshBuilder {
public:
    explicit OneMeshBuilder(std::string name);
    int addMaterial(const std::string& name, const Eigen::Vector4d& colour);  // returns the material's index
    void add(int material, const TriangleMesh& part);
    Scene build() &&;

private:
    std::string name_;
    std::vector<Material> materials_;
    std::vector<Primitive> primitives_;  // primitives_[k] has material k
};

// One mesh of one primitive, drawn once, with one material of the given base colour.
Scene singleMeshScene(const std::string& name, Primitive primitive, const Eigen::Vector4d& colour);

// The bolt of bolts.glb: one closed surface of 1248 flat-shaded triangles, group C6.
Primitive makeBolt();

// 12 copies of a bolt baked into one mesh at random placements, every third one mirrored.
// Expected: 12 tiles, 1 congruence class (4 members mirrored), tile group C6 (order 6).
Scene makeBoltsScene();

// Paper Fig. 8: three equal UV spheres (12 segments) on a circle, each turned to face the centre.
// Expected: 3 tiles in 1 class; assembly group D3h (order 12).
Scene makeThreeSpheresScene();

// Paper Fig. 11: a lamp of 7 equal arms (each with one mirror plane) around a heptagonal pyramid.
// Expected: 8 tiles in 2 classes; assembly group C7v (order 14).
Scene makeLampScene();

// Paper 6.4: pliers of two congruent handles (each with one mirror plane), crossed.
// Expected: 2 tiles in 1 class (group Cs); assembly group C2 (order 2).
Scene makePliersScene();

// Paper Fig. 11: a chess board of 64 squares (two materials) with 4 pawns and 2 rooks (12-sided lathes)
// moved so that one 2-fold axis is left. Expected: 70 tiles in 4 classes; assembly group C2 (order 2).
Scene makeChessScene();

// Paper Fig. 10: 60 oblique 16-sided cones (each with one mirror plane, nearly of revolution) placed by
// the 60 rotations of the icosahedron on a sphere. Expected: 60 tiles in 1 class; assembly group Ih (120).
Scene makeIcosahedralScene();

// In the spirit of the paper's Room: floor, walls, 4 tables with 4 chairs each, 4 bookshelves of
// books of 3 sizes (two colours), all axis-aligned boxes in 5 materials, laid out with two mirror planes.
// Expected: kRoomTiles tiles in kRoomClasses classes; assembly group C2v (order 4).
Scene makeRoomScene();
constexpr std::size_t kRoomTiles = 5 + 4 * (5 + 4 * 6) + 4 * (2 + 6 + 5 * 36);
constexpr std::size_t kRoomClasses = 3 + 2 + 3 + 2 + 3;  // room, table, chair, shelf, books

// Tiles whose congruence is known by construction (labelled_tiles.cpp): each base shape `copies` times at
// random rotations (every second copy mirrored), and, when `perturbation` > 0, once more with one vertex
// pushed out by that fraction of the largest base's diagonal (a distance the same for every tile, as the
// classification's tolerance is), under a label of its own. Tiles of one label are congruent; tiles of
// different labels are not, provided the bases are pairwise non-congruent. Material 0, apart on a grid.
struct LabelledTiles {
    std::vector<Tile> tiles;
    std::vector<std::size_t> labels;
};
LabelledTiles labelledCopies(const std::vector<TriangleMesh>& bases, int copies, double perturbation, std::uint64_t seed);

}  // namespace symcompress::samples
