// Candidate symmetry axes (paper 5.1, ALGORITHM.md 3): the critical points of the moment functions on
// the sphere, which contain every rotation axis and mirror normal (paper Theorem 1).
#pragma once

#include "symcompress/moments.hpp"

#include <vector>

namespace symcompress {

// Critical points of each function, from Newton's method on the tangential gradient started at points
// spread over a hemisphere; one direction per axis (w and -w are the same), merged across functions
// when closer than mergeAngle (radians).
std::vector<Eigen::Vector3d> findCandidateAxes(const std::vector<MomentFunction>& functions, double mergeAngle);

}  // namespace symcompress
