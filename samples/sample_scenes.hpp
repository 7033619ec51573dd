// Scenes whose repetition and symmetry are known by construction: the bundled samples, and test input
// with known answers. Every function is deterministic.
#pragma once

#include "symcompress/scene.hpp"

#include <string>

namespace symcompress::samples {

// One mesh of one primitive, drawn once, with one material of the given base colour.
Scene singleMeshScene(const std::string& name, Primitive primitive, const Eigen::Vector4d& colour);

// 12 copies of a bolt baked into one mesh at random placements, every third one mirrored.
// Expected: 12 tiles, 1 congruence class (4 members mirrored), tile group C6 (order 6).
Scene makeBoltsScene();

// Paper Fig. 8: three equal UV spheres (12 segments) on a circle, each turned to face the centre.
// Expected: 3 tiles in 1 class; assembly group D3h (order 12).
Scene makeThreeSpheresScene();

// Paper Fig. 11: a lamp of 7 equal arms (each with one mirror plane) around a heptagonal pyramid.
// Expected: 8 tiles in 2 classes; assembly group C7v (order 14).
Scene makeLampScene();

}  // namespace symcompress::samples
