#pragma once
// What a user would check of a decomposition, from its output alone: the
// blocks tile the face, every block is simple, splits lie inside the face
// and end on the boundary or on other splits, polygon blocks are convex
// with 0 to 6 sides and hold their one singularity, and every block's
// corner types close up.
#include <string>
#include <vector>

#include "decomposition/decomposition.hpp"

namespace mm::test {

// The problems found, empty when the decomposition is right.
std::vector<std::string> decomposition_problems(const FaceModel& face, const MeshFlow& flow, const Decomposition& d);

// The decomposition of a face with the given merge factor (0: no merging).
Decomposition decompose_face(const FaceModel& face, double merge_factor);

}  // namespace mm::test
