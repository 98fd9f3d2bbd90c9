#pragma once
// Building blocks for hand-made test faces.
#include <vector>

#include "boundary/face_model.hpp"

namespace mm::test {

inline BoundaryEdge line(Vec2 a, Vec2 b) {
  const double length = distance(a, b);
  return BoundaryEdge{LineCurve{a, (b - a) / length}, 0.0, length, 0, {}, {}};
}

// Closed polygon through the points, in their order.
inline std::vector<BoundaryEdge> polygon(const std::vector<Vec2>& pts) {
  std::vector<BoundaryEdge> edges;
  for (std::size_t i = 0; i < pts.size(); ++i) edges.push_back(line(pts[i], pts[(i + 1) % pts.size()]));
  return edges;
}

// Full circle; sense +1 counter-clockwise (an outer loop), -1 clockwise (a hole).
inline BoundaryEdge full_circle(Vec2 center, double radius, int sense) {
  return BoundaryEdge{CircleCurve{center, radius, 0.0, sense}, 0.0, 2 * kPi, 0, {}, {}};
}

}  // namespace mm::test
