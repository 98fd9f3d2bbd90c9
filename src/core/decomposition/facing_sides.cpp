#include "decomposition/facing_sides.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace mm {

namespace {

// How far along the ray from `from` in direction `ray` it enters the box
// (0 if it starts inside), infinity if it misses it (slab test; a box of
// no width in a direction is entered where the ray is within it).
double ray_box_entry(Vec2 from, Vec2 ray, const Box& box) {
  double enter = 0.0, leave = std::numeric_limits<double>::infinity();
  const double origin[2] = {from.x, from.y}, direction[2] = {ray.x, ray.y};
  const double lo[2] = {box.min.x, box.min.y}, hi[2] = {box.max.x, box.max.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (direction[axis] == 0.0) {
      if (origin[axis] < lo[axis] || origin[axis] > hi[axis]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double a = (lo[axis] - origin[axis]) / direction[axis], b = (hi[axis] - origin[axis]) / direction[axis];
    if (a > b) std::swap(a, b);
    enter = std::max(enter, a);
    leave = std::min(leave, b);
  }
  return enter <= leave ? enter : std::numeric_limits<double>::infinity();
}

}  // namespace

// The side pairs of a submapped block with a reflex corner that face each
// other across it or across something outside it (Block::facing and
// facing_outside): from points along side s straight into (out of) the
// block, the first side of the block hit, where it runs the opposite way. A
// block without a reflex corner is a logical rectangle, which cannot fold.
void find_facing_sides(Block& b) {
  const int m = static_cast<int>(b.sides.size());
  if (m < 4 || std::none_of(b.corners.begin(), b.corners.end(), [](const BlockCorner& c) { return c.type == 3; }))
    return;
  std::vector<int> dirs(m, 0);
  for (int i = 1; i < m; ++i) dirs[i] = ((dirs[i - 1] + 2 - b.corners[i].type) % 4 + 4) % 4;
  std::vector<std::vector<Vec2>> lines(m);
  for (int i = 0; i < m; ++i) {
    for (const OutlinePiece& piece : b.sides[i].pieces) {
      for (const Vec2 p : piece.points)
        if (lines[i].empty() || distance(lines[i].back(), p) > 0.0) lines[i].push_back(p);
    }
  }
  // Each side's bounding box, a little larger than the side so that rounding
  // never drops a hit: a ray that misses it, or enters it only beyond the
  // nearest hit so far, cannot hit the side.
  std::vector<Box> boxes(m);
  for (int i = 0; i < m; ++i) {
    Box& box = boxes[i];
    box = lines[i].empty() ? Box{{0, 0}, {0, 0}} : bounding_box(lines[i]);
    const double margin = 1e-9 * (1.0 + std::abs(box.min.x) + std::abs(box.min.y) + distance(box.min, box.max));
    box.min = box.min - Vec2{margin, margin};
    box.max = box.max + Vec2{margin, margin};
  }
  std::set<std::pair<int, int>> inside, outside;
  for (int s = 0; s < m; ++s) {
    const std::vector<Vec2>& line = lines[s];
    double length = 0.0;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) length += distance(line[k], line[k + 1]);
    if (!(length > 0.0)) continue;
    // Rays from five places along side s (a side across may face only part
    // of it), along the inward (left) normal there and against it; and from
    // an end at a reflex corner, where the inward normal runs on along the
    // next (or last) side: a side it meets there must stay beyond that
    // corner, or two reflex corners nearly in line interlock logically.
    std::vector<double> fractions{0.1, 0.3, 0.5, 0.7, 0.9};
    if (b.corners[s].type == 3) fractions.push_back(0.0);
    if (b.corners[(s + 1) % m].type == 3) fractions.push_back(1.0);
    for (const double fraction : fractions) {
      Vec2 from, inward;
      double walked = 0.0;
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        const double step = distance(line[k], line[k + 1]);
        if (walked + step >= fraction * length && step > 0.0) {
          from = line[k] + (line[k + 1] - line[k]) * ((fraction * length - walked) / step);
          inward = perp(normalized(line[k + 1] - line[k]));
          break;
        }
        walked += step;
      }
      for (const bool into : {true, false}) {
        const Vec2 ray = into ? inward : -inward;
        int hit = -1;
        double nearest = std::numeric_limits<double>::infinity();
        for (int t = 0; t < m; ++t) {
          if (!(ray_box_entry(from, ray, boxes[t]) < nearest)) continue;
          for (std::size_t k = 0; k + 1 < lines[t].size(); ++k) {
            const Vec2 a = lines[t][k], d = lines[t][k + 1] - a;
            const double denominator = cross(ray, d);
            if (std::abs(denominator) <= 1e-12 * norm(d)) continue;
            const double u = cross(a - from, d) / denominator, v = cross(a - from, ray) / denominator;
            if (u > 1e-9 * length && u < nearest && v >= 0.0 && v <= 1.0) nearest = u, hit = t;
          }
        }
        if (hit >= 0 && hit != s && dirs[hit] == (dirs[s] + 2) % 4) (into ? inside : outside).insert({s, hit});
      }
    }
  }
  b.facing.assign(inside.begin(), inside.end());
  b.facing_outside.assign(outside.begin(), outside.end());
}

}  // namespace mm
