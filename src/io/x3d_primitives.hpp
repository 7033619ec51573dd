// Tessellation of X3D's geometric primitives (Box, Sphere, Cylinder, Cone), with normals and texture
// coordinates (glTF convention: v down), centred on the origin as X3D defines them.
#pragma once

#include "symcompress/scene.hpp"

#include <vector>

namespace symcompress::x3d {

Primitive tessellateBox(const Eigen::Vector3d& size);
// As X_ITE draws them (its default options): the sphere of 32 points around and 15 from pole to pole, smoothed as a
// face set with a creaseAngle of pi; the cylinder and cone of 20 sides, their normals those of the smooth surface;
// along y from -height/2 to height/2.
Primitive tessellateSphere(double radius);
Primitive tessellateCylinder(double radius, double height, bool side, bool bottom, bool top);
Primitive tessellateCone(double bottomRadius, double height, bool side, bool bottom);

// X3D's Geometry2D nodes in the z = 0 plane, as X_ITE draws them: the rectangle a quad from (1, 1) round, the disk a
// fan of 40 triangles (a ring of 40 quads' two triangles where innerRadius > 0), its texture across its box; the
// circle and the arc lines of 40 segments to the whole turn (at least 3); a 2D triangle set facing +z, its texture
// across its box's longer side. Lines and points as their Topology.
Primitive tessellateRectangle2D(const Eigen::Vector2d& size);
Primitive tessellateDisk2D(double innerRadius, double outerRadius);
Primitive triangleSet2D(const std::vector<Eigen::Vector2d>& vertices);
Primitive arc2D(double radius, double startAngle, double endAngle);  // a whole circle where the angles are equal
// An arc closed by its chord (a fan from its first point) or as a pie (from the centre), of 40 triangles to the turn.
Primitive tessellateArcClose2D(double radius, double startAngle, double endAngle, bool chord);
Primitive polyline2D(const std::vector<Eigen::Vector2d>& points);
Primitive polypoint2D(const std::vector<Eigen::Vector2d>& points);

}  // namespace symcompress::x3d
