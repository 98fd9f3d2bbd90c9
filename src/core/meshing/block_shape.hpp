#pragma once
// What interval assignment and the block templates agree on: a block as its
// logical sides (each a chain of segments, a segment being one piece of
// boundary edge or one split, shared by every block that uses it), and the
// meaning of each template's integer parameters.
#include <utility>
#include <vector>

namespace mm {

enum class BlockTemplate {
  Submap,    // submapping (4-sided mapping included): sides by direction
  Disc,      // 0 sides (k = -4): O-grid, an inner a x b rectangle and a ring
  OneSided,  // 1 side (k = -3): a quad at the corner, then a TwoSided block
  TwoSided,  // 2 sides (k = -2): a quad at corner 0, then a Midpoint block of 3
  Midpoint,  // 3, 5 or 6 sides (k = -1, +1, +2): midpoint subdivision
};

// A block as interval assignment sees it. Corner i starts side i; corners run
// counter-clockwise. corner_types[i] is the number of elements at corner i
// (1 convex, 0 cusp, 3 and 4 reflex); the outline turns left by
// (2 - type) quarter turns there. A Disc block has no corner and one side.
struct BlockShape {
  BlockTemplate kind = BlockTemplate::Submap;
  std::vector<int> corner_types;
  std::vector<std::vector<int>> side_segments;  // segment ids along each side
  // Submap: side pairs (s, t) facing each other across the block, and
  // across something outside it; interval assignment keeps t at least one
  // interval from s along s's inward (outward) normal (a soft condition: the
  // lattice outline must not fold onto itself).
  std::vector<std::pair<int, int>> facing, facing_outside;
  // Submap: per pair of `facing`, the intervals across wanted (the narrowest
  // distance between the two sides over the target size); empty for none.
  // Far more lattice lines across than that crowd into the narrows.
  std::vector<double> facing_goals;
  // Midpoint: per side, the intervals the line from the block's centre to
  // that side wants at least (its length over the target size); empty for
  // none. Without it a side nearly as long as the others together leaves
  // that line one interval: elements many times longer than the target.
  std::vector<double> spoke_goals;
};

// Template parameters (BlockIntervals::params), n_i the intervals of side i:
//  Midpoint, m sides: c_0 .. c_{m-1} >= 1 with n_i = c_{i-1} + c_{i+1}
//    (indices mod m); side i is cut c_{i-1} intervals from corner i, and the
//    cut point joins the centre by a line of c_i intervals.
//  TwoSided: u, v, c_0, c_1, c_2 (all >= 1). A mapped u x v quad sits at corner
//    0: u intervals along side 0 from corner 0, v along the end of side 1; its
//    inner node has valence 3. The rest is a Midpoint block of 3 sides:
//    L_0 = n_0 - u (cut point to corner 1), L_1 = n_1 - v (corner 1 to the
//    cut point on side 1), L_2 = u + v (back past the inner node), with
//    L_i = c_{i-1} + c_{i+1}.
//  OneSided: u, v, then the five TwoSided parameters of the rest. A u x v quad
//    at the corner (u along the side from the corner, v along its end); the
//    rest is a TwoSided block whose side 0 is the boundary, n_0 - u - v
//    intervals, and whose side 1 runs back past the quad's inner node, u + v.
//  Disc: a, b >= 1 with n_0 = 2a + 2b; the template picks where on the loop
//    the four ring corners go.
//  Submap: none. Sides are given directions by the turning at the corners;
//    for each direction the sum of counts equals that of the opposite one.

}  // namespace mm
