// Tessellation of X3D's geometric primitives (Box, Sphere, Cylinder, Cone), with normals and texture
// coordinates (glTF convention: v down), centred on the origin as X3D defines them.
#pragma once

#include "symcompress/scene.hpp"

namespace symcompress::x3d {

Primitive tessellateBox(const Eigen::Vector3d& size);
// As X_ITE draws them (its default options): the sphere of 32 points around and 15 from pole to pole, smoothed as a
// face set with a creaseAngle of pi; the cylinder and cone of 20 sides, their normals those of the smooth surface;
// along y from -height/2 to height/2.
Primitive tessellateSphere(double radius);
Primitive tessellateCylinder(double radius, double height, bool side, bool bottom, bool top);
Primitive tessellateCone(double bottomRadius, double height, bool side, bool bottom);

}  // namespace symcompress::x3d
