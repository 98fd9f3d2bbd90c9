#pragma once
// Point tests against a segment and against a closed polygon given as its
// corners (the last joins the first), used by the decomposition's self-check
// and its pictures and by the medial axis's nearest boundary search.
#include <algorithm>
#include <limits>
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// Even-odd rule: whether p lies inside the polygon (a point on it may go
// either way).
inline bool inside_polygon(const std::vector<Vec2>& polygon, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2 a = polygon[i], b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
  }
  return in;
}

// The signed area of a closed polygon (positive counter-clockwise).
inline double polygon_area(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) twice += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  return 0.5 * twice;
}

// Whether segments ab and cd cross at a point inside both (not at an end):
// each pair of ends strictly on either side of the other segment, by more
// than tol times its length.
inline bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d, double tol = 0.0) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  const double ab = norm(b - a), cd = norm(d - c);
  return ((d1 > tol * ab && d2 < -tol * ab) || (d1 < -tol * ab && d2 > tol * ab)) &&
         ((d3 > tol * cd && d4 < -tol * cd) || (d3 < -tol * cd && d4 > tol * cd));
}

// The distance from p to the segment from a to b.
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double len2 = dot(d, d);
  const double f = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return distance(a + f * d, p);
}

// The distance from p to an open polyline (infinite if it has no segment).
inline double distance_to_polyline(const std::vector<Vec2>& line, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < line.size(); ++k) best = std::min(best, distance_to_segment(p, line[k], line[k + 1]));
  return best;
}

// The distance from p to the polygon's outline.
inline double distance_to_polygon(const std::vector<Vec2>& polygon, Vec2 p) {
  double best = 1e300;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    best = std::min(best, distance_to_segment(p, polygon[j], polygon[i]));
  return best;
}

}  // namespace mm
