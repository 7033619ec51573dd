// icosahedral assembly (paper Fig. 10): 60 congruent cones, each with a single mirror plane, placed by the
// rotation group of the icosahedron so that the assembly has all 120 symmetries of Ih.
#include "sample_scenes.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress::samples {
namespace {

// The 60 rotations of the icosahedron with vertices (0, +-1, +-phi) and their cyclic permutations: the
// closure of a 5-fold turn about a vertex and the half-turn about z.
std::vector<Eigen::Matrix3d> icosahedralRotations() {
    const double phi = (1 + std::sqrt(5.0)) / 2;
    const std::vector<Eigen::Matrix3d> generators{
        Eigen::AngleAxisd(2 * M_PI / 5, Eigen::Vector3d(0, 1, phi).normalized()).toRotationMatrix(),
        Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix()};
    std::vector<Eigen::Matrix3d> group{Eigen::Matrix3d::Identity()};
    for (std::size_t next = 0; next < group.size(); ++next)
        for (const Eigen::Matrix3d& g : generators) {
            const Eigen::Matrix3d product = g * group[next];
            bool known = false;
            for (const Eigen::Matrix3d& h : group) known = known || (h - product).norm() < 1e-9;
            if (!known) group.push_back(product);
        }
    return group;
}

}  // namespace

Scene makeIcosahedralScene() {
    // The cone sits at a generic point of the mirror plane z = 0 (a mirror plane of the icosahedron in
    // these coordinates), pointing outward; its apex leans along `lean`, inside that plane, so that
    // z -> -z is its only symmetry and the point's stabiliser in Ih is that mirror: 120 / 2 = 60 cones.
    const double angle = 0.3;
    const Eigen::Vector3d out(std::cos(angle), std::sin(angle), 0), lean(-std::sin(angle), std::cos(angle), 0);
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d centre = 3.0 * out;
    constexpr int kSegments = 16;
    TriangleMesh cone;
    cone.positions.push_back(centre);
    for (int k = 0; k < kSegments; ++k) {
        const double t = 2 * M_PI * k / kSegments;
        cone.positions.push_back(centre + 0.25 * (std::cos(t) * lean + std::sin(t) * up));
    }
    cone.positions.push_back(centre + 0.6 * out + 0.08 * lean);
    const auto apex = std::uint32_t(kSegments + 1);
    for (int k = 0; k < kSegments; ++k) {
        const auto a = std::uint32_t(1 + k), b = std::uint32_t(1 + (k + 1) % kSegments);
        cone.triangles.push_back({0, b, a});     // base, facing the sphere's centre
        cone.triangles.push_back({a, b, apex});  // side
    }
    // lean x up = out: the ring turns counter-clockwise about `out`, so (a, b, apex) faces outward.
    Primitive baked;
    for (const Eigen::Matrix3d& rotation : icosahedralRotations()) appendMesh(baked, transformed(cone, rotation, Eigen::Vector3d::Zero()));
    return singleMeshScene("icosahedral", std::move(baked), {0.5, 0.7, 0.9, 1});
}

}  // namespace symcompress::samples
