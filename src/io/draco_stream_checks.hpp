// Checks of a Draco mesh stream's counts before and during libdraco's decoding: libdraco sizes its tables and
// runs its loops by the counts a stream claims, so that a corrupt count costs seconds and gigabytes before it
// gives up.
#pragma once

#include <cstddef>
#include <string>

namespace symcompress {

// What is wrong with the counts at the head of a Draco mesh stream, given the points its primitive's POSITION
// accessor declares; empty when nothing is (or when the stream is not one whose counts this knows: libdraco
// then decides alone). Linking this file also bounds, inside libdraco, the count of texture-coordinate
// orientations by the values they predict (see draco_stream_checks.cpp).
std::string dracoStreamProblem(const char* stream, std::size_t size, std::size_t declaredPoints);

}  // namespace symcompress
