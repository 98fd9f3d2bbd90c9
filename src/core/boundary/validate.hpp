#pragma once
#include <string>
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// Checks that closed polylines (outer counter-clockwise first, then holes
// clockwise) bound a valid region: no self-intersection, holes inside the
// outer loop and apart from each other. Returns the problem, or "" if none.
std::string find_region_problem(const std::vector<std::vector<Vec2>>& loops);

}  // namespace mm
