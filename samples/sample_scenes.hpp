// Scenes whose repetition and symmetry are known by construction: the bundled samples, and test input
// with known answers. Every function is deterministic.
#pragma once

#include "symcompress/scene.hpp"

namespace symcompress::samples {

// 24 copies of a C6v bolt baked into one mesh at random placements, every third one mirrored.
// Expected: 24 tiles, 1 congruence class (8 members mirrored), tile group C6v (order 12).
Scene makeBoltsScene();

}  // namespace symcompress::samples
