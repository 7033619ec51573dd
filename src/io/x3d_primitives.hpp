// Tessellation of X3D's geometric primitives (Box, Sphere, Cylinder, Cone), with normals and texture
// coordinates (glTF convention: v down), centred on the origin as X3D defines them.
#pragma once

#include "symcompress/scene.hpp"

namespace symcompress::x3d {

Primitive tessellateBox(const Eigen::Vector3d& size);
Primitive tessellateSphere(double radius, int slices = 32, int stacks = 16);
// Along y from -height/2 to height/2. A cone is a cylinder whose top radius is 0.
Primitive tessellateCylinder(double bottomRadius, double topRadius, double height, bool side, bool bottom, bool top,
                             int slices = 32);

}  // namespace symcompress::x3d
