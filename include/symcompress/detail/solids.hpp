// Polyhedra with known symmetry groups, for tests, samples and benchmarks.
#pragma once

#include "symcompress/scene.hpp"

#include <cstdint>
#include <vector>

namespace symcompress {

// A polyhedron with planar convex faces, counter-clockwise seen from outside, centred on the origin.
struct Polyhedron {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::vector<std::uint32_t>> faces;
};

// The convex hull of points in convex position (every point a vertex), moved so that the mean of the
// points is at the origin.
Polyhedron makeConvexPolyhedron(std::vector<Eigen::Vector3d> vertices);

Polyhedron makeTetrahedron();   // Td, 24
Polyhedron makeCube();          // Oh, 48
Polyhedron makeOctahedron();    // Oh, 48
Polyhedron makeDodecahedron();  // Ih, 120
Polyhedron makeIcosahedron();   // Ih, 120
Polyhedron makePrism(int n, double height);      // Dnh, 4n (n >= 3; n = 4 with height 2 is the cube)
Polyhedron makeAntiprism(int n, double height);  // Dnd, 4n
Polyhedron makePyramid(int n, double height);    // Cnv, 2n

// Each face fanned from its first vertex (the mesh keeps the face's symmetry only where the fan does).
TriangleMesh triangulateFaces(const Polyhedron& polyhedron);

// Each face fanned from a random interior point (a random convex combination of its vertices), so
// that the triangulation itself has no symmetry while the surface keeps all of it.
TriangleMesh triangulateWithRandomFanPoints(const Polyhedron& polyhedron, std::uint64_t seed);

}  // namespace symcompress
