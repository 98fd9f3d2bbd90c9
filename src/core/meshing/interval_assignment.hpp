#pragma once
// Interval assignment (the paper's section 4, after Mitchell's integer
// program): one interval count per segment for the whole face at once, so
// that every block's template can be built and shared segments conform.
#include <string>
#include <vector>

#include "meshing/block_shape.hpp"

namespace mm {

struct IntervalSegment {
  double goal = 1.0;  // wanted intervals: length / target size
  int min_count = 1;  // small features stay resolved (curved edges: <= 45 degrees an interval)
};

struct IntervalProblem {
  std::vector<IntervalSegment> segments;
  std::vector<BlockShape> blocks;
};

struct IntervalAssignment {
  std::vector<int> counts;               // per segment
  std::vector<std::vector<int>> params;  // per block, see block_shape.hpp
  bool relaxed = false;                  // some goal or lower bound had to give way
  std::vector<std::string> notes;
};

// Least weighted relative deviation from the goals subject to every block's
// conditions. Never fails on a problem some counts satisfy; throws
// std::runtime_error naming the block when none can.
IntervalAssignment assign_intervals(const IntervalProblem& problem);

}  // namespace mm
