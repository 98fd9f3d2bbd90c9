#pragma once
// Interval assignment (the paper's section 4, after Mitchell's integer
// program): one interval count per segment for the whole face at once, so
// that every block's template can be built and shared segments conform.
#include <stdexcept>
#include <string>
#include <vector>

#include "meshing/block_shape.hpp"

namespace mm {

struct IntervalSegment {
  double goal = 1.0;  // wanted intervals: length / target size
  int min_count = 1;  // small features stay resolved (curved edges: <= 45 degrees an interval)
};

// Two chains of segments that must get the same total: a piece of boundary
// several faces share, cut differently by each face's splits.
struct EqualSums {
  std::vector<int> first;
  std::vector<int> second;
};

struct IntervalProblem {
  std::vector<IntervalSegment> segments;
  std::vector<BlockShape> blocks;
  std::vector<EqualSums> equal_sums;
};

struct IntervalAssignment {
  std::vector<int> counts;               // per segment
  std::vector<std::vector<int>> params;  // per block, see block_shape.hpp
  // Every block condition is a homogeneous linear equation, so scaling any
  // answer up meets any lower bounds; only the goals give way. No answer at
  // all means the equations force some count to 0 (IntervalsInfeasible): the
  // block structure, not the goals, must change (mesh_blocks does).
  std::vector<std::string> notes;
  // The facing pairs (block, index into its `facing`) given crowding rows.
  std::vector<std::pair<std::size_t, std::size_t>> crowded;
};

// No counts satisfy the blocks' conditions, whatever the goals: the block
// structure itself contradicts (the caller may change a template and retry).
struct IntervalsInfeasible : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Least deviation from the goals, summed over segments: |n_s - g_s| / g_s
// above the goal and within one interval below it (g_s = max(goal_s, 1)),
// growing as g_s / n_s further below (how many times too large the elements
// are; linear beyond 8 times too large), so that a goal alone rounds to the
// nearest count and goals forced equal meet near their geometric mean (where
// the LP optimum of that is fractional, the answer of least |n - g| / g all
// the way down is kept when it is among the cheapest); subject to every
// block's conditions (block_shape.hpp), n_s >= min_count, and every
// equal_sums pair summing alike. Template parameters
// the equations leave free (Disc a, b; TwoSided and OneSided u, v) are chosen
// by a tie-break far below one interval of deviation: a ~ b, the midpoint
// triangle's sides alike, OneSided u ~ v with its two rest sides alike; among
// equal deviations the fewest intervals. A midpoint block's c_i below its
// spoke goal costs as a count below its goal; a submapped block's facing
// pair with far more lattice lines across than its facing goal (see
// BlockShape) gets a row costing the excess, and the counts are solved
// again (only for pairs the answer crowds). Solved by Clp's LP relaxation when
// that is integral, else by CBC (10 s limit, best integer answer then). Bad
// input (ids out of range, wrong side or corner counts, a submap outline not
// turning +4) throws std::invalid_argument; a problem no counts satisfy throws
// IntervalsInfeasible naming the first block whose conditions cannot hold with
// those before it.
// `crowded`: facing pairs to give crowding rows from the start (a previous
// answer's, for the same blocks with more facing pairs appended), sparing
// the solves that would find them again.
IntervalAssignment assign_intervals(const IntervalProblem& problem,
                                    const std::vector<std::pair<std::size_t, std::size_t>>& crowded = {});

// Where a submapped block's lattice outline meets itself for the given
// counts (per segment; no mesh then), the facing pairs for BlockShape that
// would keep it apart, best first: the two sides that meet if they run
// opposite ways, else those beside them that run opposite to the other. A
// pair lies across the block (outside = false) when the outline turns left
// round from s to t, across something outside it when it turns right. The
// decomposition's facing pairs are only the sides straight across from each
// other; a winding block may fold elsewhere. Empty when the outline is simple.
struct FoldedSides {
  int s = -1, t = -1;
  bool outside = false;
};
std::vector<FoldedSides> folded_sides(const BlockShape& block, const std::vector<int>& counts);

}  // namespace mm
