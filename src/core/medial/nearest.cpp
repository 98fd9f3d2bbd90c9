#include "medial/nearest.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace mm {
namespace {

double lo(const BoundaryEdge& e) {
  return std::min(e.t_start, e.t_end);
}
double hi(const BoundaryEdge& e) {
  return std::max(e.t_start, e.t_end);
}

// The first zero of g(t) = (C(t) - m) . C'(t) downhill from t, by safeguarded
// Newton. Plain Newton does not always settle: with m near a centre of
// curvature (a medial point near a curvature contact, on a long gently
// curved B-spline) the distance is nearly flat, g' = |C'|^2 + (C - m) . C''
// nearly 0, and its steps jump to and fro across the minimum. So first walk
// downhill until g changes sign (steps growing from the Newton step, none
// longer than a quarter of the distance to m along the curve, so no dip of
// the boundary is stepped over), then Newton steps within that bracket,
// bisecting whenever one leaves it.
double bracketed_nearest(const BoundaryEdge& edge, double a, double b, double t, Vec2 m) {
  const auto g_of = [&](double u, double* slope) {
    const CurvePoint c = evaluate(edge.curve, u);
    if (slope) *slope = dot(c.d1, c.d1) + dot(c.p - m, c.d2);
    return dot(c.p - m, c.d1);
  };
  const auto longest_step = [&](double u) {
    const CurvePoint c = evaluate(edge.curve, u);
    return 0.25 * std::max(norm(c.p - m), 1e-300) / std::max(norm(c.d1), 1e-300);
  };
  double slope = 0.0;
  double g = g_of(t, &slope);
  const double way = g > 0 ? -1.0 : 1.0;  // downhill
  double behind = t, ahead = t;           // g(behind) has g's sign, g(ahead) the other
  bool bracketed = g == 0.0;
  double step = slope > 0 ? std::abs(g / slope) * 1.5 : 0.0;
  for (int i = 0; i < 200 && !bracketed; ++i) {
    // No step below what a parameter far from 0 can resolve.
    const double least = std::max(1e-12 * (b - a), 8 * std::numeric_limits<double>::epsilon() * std::abs(behind));
    step = std::max(std::min(step, longest_step(behind)), least);
    ahead = std::clamp(behind + way * step, a, b);
    if (ahead == behind) return behind;  // at an end, still going down: the end is nearest
    if (g_of(ahead, nullptr) * way >= 0.0) {
      bracketed = true;
    } else {
      behind = ahead;
      step *= 2;
    }
  }
  if (!bracketed || ahead == behind) return behind;
  double low = std::min(behind, ahead), high = std::max(behind, ahead);  // g(low) < 0 <= g(high)
  t = 0.5 * (low + high);
  for (int i = 0; i < 100 && high - low > 1e-15 * (b - a); ++i) {
    g = g_of(t, &slope);
    if (g == 0.0) break;
    (g < 0 ? low : high) = t;
    const double newton = slope > 0 ? t - g / slope : low - 1.0;
    const double next = newton > low && newton < high ? newton : 0.5 * (low + high);
    if (next == t) break;
    t = next;
  }
  return t;
}

// Nearest parameter to m of a single edge's part [a, b], from the guess t: a
// local search, like nearest_on_run.
double nearest_parameter(const BoundaryEdge& edge, double a, double b, double t, Vec2 m) {
  if (const auto* line = std::get_if<LineCurve>(&edge.curve)) {
    return std::clamp(dot(m - line->origin, line->direction), a, b);
  }
  if (const auto* circle = std::get_if<CircleCurve>(&edge.curve)) {
    // Go from t towards the circle's nearest point by the shorter way round,
    // stopping at an end of the arc if one comes first: a local search, like
    // Newton's below, so that each end of an arc keeps its own side.
    const Vec2 d = m - circle->center;
    if (norm(d) < 1e-300) return std::clamp(t, a, b);
    const double u = circle->sense * (std::atan2(d.y, d.x) - circle->start_angle);
    const double turn = std::remainder(u - t, 2 * kPi);
    return std::clamp(std::clamp(t, a, b) + turn, a, b);
  }
  // General curve: Newton's method on g(t) = (C(t) - m) . C'(t) = 0, kept in range.
  t = std::clamp(t, a, b);
  CurvePoint c = evaluate(edge.curve, t);
  bool settled = false;
  for (int i = 0; i < 50 && !settled; ++i) {
    const double g = dot(c.p - m, c.d1);
    const double h = dot(c.d1, c.d1) + dot(c.p - m, c.d2);
    double next = h > 0 ? t - g / h : t - g / std::max(dot(c.d1, c.d1), 1e-300);
    next = std::clamp(next, a, b);
    // A step must not lead further away: where the distance is flat (m near
    // a centre of curvature) or the curve bends back, a full Newton step can
    // jump to another part of the curve; shorten it until it goes downhill.
    const double here = dot(c.p - m, c.p - m);
    Vec2 q = evaluate_point(edge.curve, next);
    for (int k = 0; k < 60 && !(dot(q - m, q - m) <= here); ++k) {  // NaN halves on too
      // Halving a step of one unit in the last place can round back to the
      // same parameter: then every further try is this same point again.
      const double shorter = t + 0.5 * (next - t);
      if (shorter == next) break;
      next = shorter;
      q = next == t ? c.p : evaluate_point(edge.curve, next);
    }
    settled = std::abs(next - t) <= 1e-15 * (b - a);
    if (!settled && next != t) c = evaluate(edge.curve, next);
    t = next;
  }
  // The edge's other end is never taken instead, however near: that jump
  // across the edge made a foot on one side of a long curve land on the
  // corner at its far end (a junction's three feet became two, fuzz
  // elliptic_10_129; a genuine branch was pruned, bspline_1_977).
  return settled ? t : bracketed_nearest(edge, a, b, t, m);
}

}  // namespace

BoundaryIndex::BoundaryIndex(const FaceModel& face) : face_(face) {
  for (const Loop& loop : face.loops) corner_.emplace_back(loop.edges.size(), false);
  reflex_ = corner_;
  for (const Corner& c : face.corners) {
    corner_[c.loop][c.vertex] = true;
    reflex_[c.loop][c.vertex] = c.angle > kPi;
  }
}

BoundaryPlace BoundaryIndex::place(int loop, int e, double t) const {
  const BoundaryEdge& edge = face_.loops[loop].edges[e];
  BoundaryPlace p{loop, e, t, -1, evaluate_point(edge.curve, t)};
  // At a corner the place is the snapped vertex (neighbouring curves may end
  // a file's tolerance apart); elsewhere it is the curve's own point.
  const double tol = 1e-12 * std::max(1.0, std::abs(edge.t_end - edge.t_start));
  const int next = (e + 1) % edge_count(loop);
  if (std::abs(t - edge.t_start) <= tol && is_corner(loop, e)) {
    p.point = edge.start;
    p.corner = e;
  } else if (std::abs(t - edge.t_end) <= tol && is_corner(loop, next)) {
    p.point = edge.end;
    p.corner = next;
  }
  return p;
}

namespace {

BoundaryPlace nearest_from_inside(const BoundaryIndex& index, const BoundaryPlace& start, Vec2 m);

// From a corner the nearest place is the corner itself while m is in the
// corner's normal wedge, else a point of one of the two edges meeting there,
// reached by going down the distance from the corner (never a jump to a far
// part of the edge).
BoundaryPlace nearest_from_corner(const BoundaryIndex& index, const BoundaryPlace& corner, Vec2 m) {
  const int count = index.edge_count(corner.loop);
  const int after = corner.corner, before = (corner.corner + count - 1) % count;
  BoundaryPlace best = corner;
  best.corner_itself = true;
  // The edge ending at the corner, then the one starting there (the same
  // edge when the loop is one closed curve with its seam at the corner).
  for (const bool from_end : {true, false}) {
    const int e = from_end ? before : after;
    const BoundaryEdge& edge = index.edge(corner.loop, e);
    const Vec2 into = from_end ? -1.0 * edge_tangent(edge, edge.t_end) : edge_tangent(edge, edge.t_start);
    if (dot(m - corner.point, into) <= 0.0) continue;  // moving onto this edge leads away from m
    BoundaryPlace start{corner.loop, e, from_end ? edge.t_end : edge.t_start, -1, corner.point};
    const BoundaryPlace found = nearest_from_inside(index, start, m);
    if (distance(found.point, m) < distance(best.point, m) * (1 - 1e-14)) best = found;
  }
  return best;
}

BoundaryPlace nearest_from_inside(const BoundaryIndex& index, const BoundaryPlace& start, Vec2 m) {
  int e = start.edge;
  double t = start.t;
  const int count = index.edge_count(start.loop);
  for (int step = 0; step <= count; ++step) {
    const BoundaryEdge& edge = index.edge(start.loop, e);
    t = nearest_parameter(edge, lo(edge), hi(edge), t, m);
    BoundaryPlace here = index.place(start.loop, e, t);
    const bool at_start = std::abs(t - edge.t_start) <= 1e-12 * std::abs(edge.t_end - edge.t_start);
    const bool at_end = std::abs(t - edge.t_end) <= 1e-12 * std::abs(edge.t_end - edge.t_start);
    if (here.corner >= 0 || (!at_start && !at_end)) return here;
    // At a tangent join: carry on along the neighbouring edge unless it leads away.
    const int next = at_end ? (e + 1) % count : (e + count - 1) % count;
    const BoundaryEdge& neighbour = index.edge(start.loop, next);
    const double nt =
        nearest_parameter(neighbour, lo(neighbour), hi(neighbour), at_end ? neighbour.t_start : neighbour.t_end, m);
    const BoundaryPlace there = index.place(start.loop, next, nt);
    if (distance(there.point, m) >= distance(here.point, m) * (1 - 1e-14)) return here;
    e = next;
    t = nt;
  }
  return index.place(start.loop, e, t);
}

}  // namespace

BoundaryPlace nearest_on_run(const BoundaryIndex& index, const BoundaryPlace& start, Vec2 m) {
  if (start.corner >= 0 && start.corner_itself) return nearest_from_corner(index, start, m);
  // An edge's place at a corner searches its own edge again from there.
  BoundaryPlace from = start;
  from.corner = -1;
  const BoundaryPlace found = nearest_from_inside(index, from, m);
  return found.corner >= 0 && index.is_reflex(found.loop, found.corner) ? nearest_from_corner(index, found, m) : found;
}

bool same_place(const BoundaryIndex& index, const BoundaryPlace& a, const BoundaryPlace& b, double tolerance) {
  if (a.loop != b.loop || distance(a.point, b.point) > tolerance) return false;
  if (a.edge == b.edge) return true;
  // Along the loop from one to the other, the edges between them by their
  // chords (no longer than the edges), either way round.
  const std::vector<BoundaryEdge>& edges = index.face().loops[a.loop].edges;
  const int n = static_cast<int>(edges.size());
  const double reach = 4 * tolerance;
  const auto along = [&](const BoundaryPlace& from, const BoundaryPlace& to) {
    double walked = distance(from.point, edges[from.edge].end);
    for (int e = (from.edge + 1) % n; e != to.edge && walked <= reach; e = (e + 1) % n)
      walked += distance(edges[e].start, edges[e].end);
    return walked + distance(edges[to.edge].start, to.point);
  };
  return std::min(along(a, b), along(b, a)) <= reach;
}

namespace {

// Distances from m agree to 1e-13 of the face size, or to what doubles hold
// at m's distance from the origin (a tiny face far from it).
double distance_tolerance(const BoundaryIndex& index, Vec2 m) {
  return std::max(1e-13 * index.face().size,
                  16 * std::numeric_limits<double>::epsilon() * (std::abs(m.x) + std::abs(m.y)));
}

}  // namespace

Bisected bisect(const BoundaryIndex& index, Vec2 m, BoundaryPlace a, BoundaryPlace b) {
  const double tolerance = distance_tolerance(index, m);
  Bisected result;
  for (int i = 0; i < 60; ++i) {
    a = nearest_on_run(index, a, m);
    b = nearest_on_run(index, b, m);
    const double da = distance(m, a.point), db = distance(m, b.point);
    result = {m, 0.5 * (da + db), a, b, false};
    const double h = da - db;
    if (std::abs(h) <= tolerance) {
      result.converged = true;
      break;
    }
    if (da < 1e-300 || db < 1e-300) break;
    const Vec2 g = (m - a.point) / da - (m - b.point) / db;
    const double g2 = dot(g, g);
    if (g2 < 1e-24) break;  // both feet in one direction: no bisector here
    m = m - (h / g2) * g;
  }
  return result;
}

namespace {

// Newton's method on the centre m, each place moved by foot(i, place, m) to
// its nearest point to m before each step.
template <class Foot>
Equidistant solve_equidistant(const BoundaryIndex& index, Vec2 m, std::vector<BoundaryPlace> places, Foot foot) {
  const double tolerance = distance_tolerance(index, m);
  Equidistant result;
  for (int i = 0; i < 60; ++i) {
    for (std::size_t k = 0; k < places.size(); ++k) places[k] = foot(k, places[k], m);
    const double d0 = distance(m, places[0].point), d1 = distance(m, places[1].point),
                 d2 = distance(m, places[2].point);
    result = {m, (d0 + d1 + d2) / 3, places, false};
    const double f1 = d0 - d1, f2 = d0 - d2;
    if (std::abs(f1) <= tolerance && std::abs(f2) <= tolerance) {
      result.converged = true;
      break;
    }
    if (d0 < 1e-300 || d1 < 1e-300 || d2 < 1e-300) break;
    const Vec2 g0 = (m - places[0].point) / d0, g1 = (m - places[1].point) / d1, g2 = (m - places[2].point) / d2;
    const Vec2 r1 = g0 - g1, r2 = g0 - g2;  // Jacobian rows
    const double det = cross(r1, r2);
    if (std::abs(det) < 1e-14) break;
    // Solve [r1; r2] step = [f1; f2].
    const Vec2 step{(f1 * r2.y - f2 * r1.y) / det, (r1.x * f2 - r2.x * f1) / det};
    m = m - step;
  }
  return result;
}

}  // namespace

Equidistant equidistant(const BoundaryIndex& index, Vec2 m, const std::vector<BoundaryPlace>& places) {
  return solve_equidistant(index, m, places,
                           [&](std::size_t, const BoundaryPlace& p, Vec2 at) { return nearest_on_run(index, p, at); });
}

Equidistant equidistant_within(const BoundaryIndex& index, Vec2 m, const std::vector<BoundaryPlace>& places,
                               const std::vector<std::array<double, 2>>& windows) {
  Equidistant result = solve_equidistant(index, m, places, [&](std::size_t k, const BoundaryPlace& p, Vec2 at) {
    const BoundaryEdge& edge = index.edge(p.loop, p.edge);
    const auto [a, b] = windows[k];
    return index.place(p.loop, p.edge, nearest_parameter(edge, a, b, p.t, at));
  });
  // A foot held at a window's end is no nearest point of the boundary.
  for (std::size_t k = 0; k < result.places.size() && result.converged; ++k) {
    const double span = windows[k][1] - windows[k][0];
    const double t = result.places[k].t;
    result.converged = t > windows[k][0] + 1e-9 * span && t < windows[k][1] - 1e-9 * span;
  }
  return result;
}

double curvature(const BoundaryEdge& edge, double t) {
  const CurvePoint c = evaluate(edge.curve, t);
  const double speed = norm(c.d1);
  const double direction = edge.t_end >= edge.t_start ? 1.0 : -1.0;
  return direction * cross(c.d1, c.d2) / (speed * speed * speed);
}

}  // namespace mm
