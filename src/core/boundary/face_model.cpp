#include "boundary/face_model.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "boundary/validate.hpp"
#include "geometry/polygon.hpp"

namespace mm {
namespace {

// Tangent joins within this angle of a straight continuation are smooth.
constexpr double kSmoothAngle = 0.5 * kPi / 180.0;
// A join closer than this to tangent is one to the curves' precision.
constexpr double kKinkAngle = 1e-6;
// A B-spline is taken as a straight line if it stays within this fraction of
// the face size of its chord, and as an arc if it stays within a fraction of
// the arc's radius and of the face size: CAD systems approximate arcs to
// about 1e-3 of the radius, and the design intent of such an edge is the arc.
constexpr double kLineTolerance = 1e-6;
constexpr double kArcRadiusTolerance = 1e-3;
constexpr double kArcSizeTolerance = 1e-5;
// Two circles (or lines) are one when their centres and radii agree to this
// fraction of the face's size.
constexpr double kSameCurveTolerance = 1e-6;
// A piece of a circle or line shorter than this fraction of the face's size
// is joined to its neighbour on the same curve (join_pieces_of_one_curve).
constexpr double kShortPiece = 1e-2;
// Circular edges in a row whose centres and radii agree within this
// fraction of the face's size are taken as arcs of one circle.
constexpr double kSameCircleTolerance = 1e-4;
// Tangents closer than this to opposite directions make a (near) cusp.
constexpr double kCuspAngle = 1.0 * kPi / 180.0;

std::string format(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::string format(Vec2 p) {
  return "(" + format(p.x) + ", " + format(p.y) + ")";
}

// Parameter pieces [lo, hi] split at B-spline knots, and so that a circle or
// ellipse piece spans at most an eighth of a turn.
std::vector<double> pieces(const BoundaryEdge& edge) {
  const double lo = std::min(edge.t_start, edge.t_end);
  const double hi = std::max(edge.t_start, edge.t_end);
  std::vector<double> cuts{lo};
  for (double b : breakpoints(edge.curve, lo, hi)) cuts.push_back(b);
  cuts.push_back(hi);
  const CurveType type = curve_type(edge.curve);
  int per_piece = 1;
  if (type == CurveType::Circle || type == CurveType::Ellipse) {
    per_piece = std::max(1, static_cast<int>(std::ceil((hi - lo) / (kPi / 4))));
  } else if (type == CurveType::BSpline || type == CurveType::Other) {
    per_piece = 4;
  }
  std::vector<double> result;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    for (int k = 0; k < per_piece; ++k) result.push_back(cuts[i] + (cuts[i + 1] - cuts[i]) * k / per_piece);
  }
  result.push_back(hi);
  return result;
}

// Adaptive 10-point Gauss-Legendre quadrature of f over [a, b].
template <class F>
double gauss(const F& f, double a, double b) {
  static const double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244, 0.8650633666889845,
                              0.9739065285171717};
  static const double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820, 0.1494513491505806,
                              0.0666713443086881};
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  double sum = 0.0;
  for (int i = 0; i < 5; ++i) sum += w[i] * (f(mid - half * x[i]) + f(mid + half * x[i]));
  return sum * half;
}

// Bisects until the two halves agree with the whole to a relative 1e-13 or
// to the absolute floor (kept fixed: halving it would soon ask for more than
// double precision holds); the depth cap bounds the work on pathological input.
template <class F>
double integrate(const F& f, double a, double b, double whole, double floor, int depth) {
  const double mid = 0.5 * (a + b);
  const double left = gauss(f, a, mid), right = gauss(f, mid, b);
  const double tolerance = std::max(floor, 1e-13 * (std::abs(left) + std::abs(right)));
  if (depth >= 16 || std::abs(left + right - whole) <= tolerance) return left + right;
  return integrate(f, a, mid, left, floor, depth + 1) + integrate(f, mid, b, right, floor, depth + 1);
}

// Integral of f(t) over the edge's parameter range, signed by the direction of travel.
template <class F>
double integrate_edge(const BoundaryEdge& edge, const F& f, double tolerance) {
  const std::vector<double> cuts = pieces(edge);
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    total += integrate(f, cuts[i], cuts[i + 1], gauss(f, cuts[i], cuts[i + 1]), tolerance, 0);
  }
  return edge.t_end >= edge.t_start ? total : -total;
}

Vec2 evaluate_point(const BoundaryEdge& edge, double t) {
  return evaluate_point(edge.curve, t);
}

// Rough bounding-box diagonal, used to scale tolerances before anything is
// checked; NaN if a point is not finite (a NaN in a file).
double rough_size(const RawFace& raw) {
  Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const auto& loop : raw.loops) {
    for (const auto& edge : loop) {
      for (int i = 0; i <= 16; ++i) {
        const Vec2 p = evaluate_point(edge, edge.t_start + (edge.t_end - edge.t_start) * i / 16.0);
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return std::nan("");
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      }
    }
  }
  return lo.x <= hi.x ? distance(lo, hi) : 0.0;
}

// Points along the edge in the direction of travel, several per piece.
std::vector<Vec2> dense_points(const BoundaryEdge& edge, int per_piece) {
  std::vector<double> cuts = pieces(edge);
  if (edge.t_end < edge.t_start) std::reverse(cuts.begin(), cuts.end());
  std::vector<Vec2> points;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    for (int k = 0; k < per_piece; ++k) {
      points.push_back(evaluate_point(edge, cuts[i] + (cuts[i + 1] - cuts[i]) * k / per_piece));
    }
  }
  points.push_back(evaluate_point(edge, cuts.back()));
  return points;
}

// Least-squares circle through the points (algebraic fit: x^2 + y^2 + D x +
// E y + F = 0), centred on their mean for conditioning. False if degenerate.
bool fit_circle(const std::vector<Vec2>& pts, Vec2& center, double& radius) {
  Vec2 mean;
  for (const Vec2& p : pts) mean = mean + p;
  mean = mean / static_cast<double>(pts.size());
  double suu = 0, suv = 0, svv = 0, su = 0, sv = 0, sz = 0, szu = 0, szv = 0;
  for (const Vec2& q : pts) {
    const Vec2 p = q - mean;
    const double z = dot(p, p);
    suu += p.x * p.x, suv += p.x * p.y, svv += p.y * p.y, su += p.x, sv += p.y;
    sz += z, szu += z * p.x, szv += z * p.y;
  }
  const double n = static_cast<double>(pts.size());
  // Normal equations for (D, E, F) by Cramer's rule.
  const double m[3][3] = {{suu, suv, su}, {suv, svv, sv}, {su, sv, n}};
  const double rhs[3] = {-szu, -szv, -sz};
  const auto det3 = [](const double a[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double det = det3(m);
  if (!(std::abs(det) > 1e-300)) return false;
  double solution[3];
  for (int c = 0; c < 3; ++c) {
    double mc[3][3];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) mc[r][k] = k == c ? rhs[r] : m[r][k];
    solution[c] = det3(mc) / det;
  }
  const Vec2 c{-0.5 * solution[0], -0.5 * solution[1]};
  const double r2 = dot(c, c) - solution[2];
  if (!(r2 > 0.0) || !std::isfinite(r2)) return false;
  center = mean + c;
  radius = std::sqrt(r2);
  return true;
}

// The circle through a and b (centre on their bisector) nearest the points
// in the algebraic sense: |p - c|^2 - |a - c|^2 is linear in the centre's
// place t along the bisector, so t is a 1-D least-squares answer. False for
// a chord of no length or points all on the chord's line.
bool fit_circle_through(Vec2 a, Vec2 b, const std::vector<Vec2>& pts, Vec2& center, double& radius) {
  const double chord = distance(a, b);
  if (!(chord > 0.0)) return false;
  const Vec2 mid = 0.5 * (b - a);  // relative to a, for conditioning
  const Vec2 normal = perp((b - a) / chord);
  double gh = 0.0, hh = 0.0;
  for (const Vec2& q : pts) {
    const Vec2 p = q - a;
    const double g = dot(p, p) - 2.0 * dot(p, mid), h = 2.0 * dot(p, normal);
    gh += g * h, hh += h * h;
  }
  if (!(hh > 0.0)) return false;
  const Vec2 c = mid + (gh / hh) * normal;
  center = a + c;
  radius = norm(c);
  return std::isfinite(radius);
}

// A B-spline whose points all lie on a straight line or a circle within the
// tolerance is replaced by that exact line or arc (STEP often stores arcs so).
// The arc is the circle through the edge's own vertices that fits its points
// best: a circle fitted freely to a B-spline that only approximates one (an
// arc interpolated through points) misses the vertices by a hair, and the
// medial axis then takes the joins for kinks.
void recognise_simple_curve(BoundaryEdge& edge, double size) {
  if (curve_type(edge.curve) != CurveType::BSpline) return;
  const std::vector<Vec2> pts = dense_points(edge, 8);
  const Vec2 a = pts.front(), b = pts.back();
  const double chord = distance(a, b);
  const double tolerance = kLineTolerance * size;
  if (chord > tolerance) {
    const Vec2 dir = (b - a) / chord;
    bool straight = true;
    for (const Vec2& p : pts) {
      const double along = dot(p - a, dir);
      straight =
          straight && std::abs(cross(dir, p - a)) <= tolerance && along >= -tolerance && along <= chord + tolerance;
    }
    if (straight) {
      edge.curve = LineCurve{a, dir};
      edge.t_start = 0.0;
      edge.t_end = chord;
      return;
    }
  }
  const std::size_t n = pts.size();
  Vec2 center;
  double radius = 0.0;
  if (!fit_circle(pts, center, radius)) return;
  const double arc_tolerance = std::min(kArcRadiusTolerance * radius, kArcSizeTolerance * size);
  double sweep = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(distance(center, pts[i]) - radius) > arc_tolerance) return;
    if (i > 0) {
      const double step = signed_angle(pts[i - 1] - center, pts[i] - center);
      if (sweep != 0.0 && step * sweep < 0.0) return;  // doubles back: not one arc
      sweep += step;
    }
  }
  if (std::abs(sweep) < 1e-9) return;
  // Through the vertices, when that circle holds the points as well (not for
  // a whole circle, whose vertices are one point).
  Vec2 through_center;
  double through_radius = 0.0;
  if (fit_circle_through(edge.start, edge.end, pts, through_center, through_radius) &&
      std::all_of(pts.begin(), pts.end(),
                  [&](Vec2 p) { return std::abs(distance(through_center, p) - through_radius) <= arc_tolerance; })) {
    center = through_center, radius = through_radius;
    const double turn = signed_angle(edge.start - center, edge.end - center);  // in (-pi, pi]
    // The turn the points make, to the nearest whole turn of the vertices'.
    sweep = turn + 2.0 * kPi * std::round((sweep - turn) / (2.0 * kPi));
    if (std::abs(sweep) < 1e-9) return;
  }
  const Vec2 r0 = edge.start - center;
  edge.curve = CircleCurve{center, radius, std::atan2(r0.y, r0.x), sweep > 0 ? 1 : -1};
  edge.t_start = 0.0;
  edge.t_end = std::abs(sweep);
}

void reverse_loop(std::vector<BoundaryEdge>& loop) {
  std::reverse(loop.begin(), loop.end());
  for (auto& edge : loop) {
    std::swap(edge.t_start, edge.t_end);
    std::swap(edge.start, edge.end);
  }
}

// Joins each edge's end to the next edge's start at one shared vertex.
void snap_loop(std::vector<BoundaryEdge>& loop, int loop_index, double gap_tolerance, const std::string& name) {
  for (std::size_t i = 0; i < loop.size(); ++i) {
    BoundaryEdge& a = loop[i];
    BoundaryEdge& b = loop[(i + 1) % loop.size()];
    const Vec2 pa = evaluate_point(a, a.t_end), pb = evaluate_point(b, b.t_start);
    const double gap = distance(pa, pb);
    if (gap > gap_tolerance) {
      throw InputError(name + ": open wire: loop " + std::to_string(loop_index + 1) + " has a gap of " + format(gap) +
                       " between edge " + std::to_string(a.source_index) + " and edge " +
                       std::to_string(b.source_index) + " at " + format(pa));
    }
    a.end = b.start = 0.5 * (pa + pb);
  }
}

// Edge `of` as a line from a to b, parameter 0 at a to its length at b.
BoundaryEdge line_part(const BoundaryEdge& of, Vec2 a, Vec2 b) {
  BoundaryEdge part = of;
  const double length = distance(a, b);
  part.curve = LineCurve{a, (b - a) / length};
  part.t_start = 0.0;
  part.t_end = length;
  part.start = a;
  part.end = b;
  return part;
}

// Straight edges are rebuilt through their snapped vertices so they stay exact.
void rebuild_lines(std::vector<BoundaryEdge>& loop) {
  for (auto& edge : loop)
    if (curve_type(edge.curve) == CurveType::Line) edge = line_part(edge, edge.start, edge.end);
}

// Consecutive arcs of one circle, fitted piece by piece (a bolt head's or a
// washer's circle written as two to four B-spline arcs, as several STEP
// exporters write circles), come out with centres and radii a hair apart;
// the medial axis of such a loop is then a little cycle round the centre,
// not the centre itself. A run of consecutive circular edges whose centres
// and radii agree within `close` is put on the one circle fitted through
// all their samples (taken before recognition, from the file's own curves)
// when every sample lies within that circle's arc tolerance: each edge keeps
// its sense along the loop, its vertices move onto the circle at their
// angles, and neighbours share those vertices exactly.
void unify_circles(std::vector<BoundaryEdge>& loop, const std::vector<std::vector<Vec2>>& samples, double close,
                   double size) {
  const std::size_t n = loop.size();
  const auto circle = [&](std::size_t i) { return std::get_if<CircleCurve>(&loop[i % n].curve); };
  const auto same = [&](std::size_t i, std::size_t j) {
    const CircleCurve *a = circle(i), *b = circle(j);
    return a && b && distance(a->center, b->center) <= close && std::abs(a->radius - b->radius) <= close;
  };
  // A run starts where the edge before is not on its circle (or at 0 when all are).
  std::size_t first = 0;
  while (first < n && same(first + n - 1, first)) ++first;
  const bool whole_loop = first == n;
  if (whole_loop) first = 0;
  for (std::size_t begin = first; begin < first + n;) {
    std::size_t end = begin + 1;
    while (end < begin + n && same(end - 1, end) && !(whole_loop && end == first + n)) ++end;
    const std::size_t count = end - begin;
    const std::size_t next_begin = end;
    if (count < 2 || !circle(begin)) {
      begin = next_begin;
      continue;
    }
    std::vector<Vec2> points;
    for (std::size_t k = begin; k < end; ++k) points.insert(points.end(), samples[k % n].begin(), samples[k % n].end());
    Vec2 center;
    double radius = 0.0;
    const bool fitted = fit_circle(points, center, radius);
    const double tolerance = std::min(kArcRadiusTolerance * radius, kArcSizeTolerance * size);
    if (!fitted || std::any_of(points.begin(), points.end(),
                               [&](Vec2 p) { return std::abs(distance(p, center) - radius) > tolerance; })) {
      begin = next_begin;
      continue;
    }
    const auto on_circle = [&](Vec2 p) {
      const Vec2 u = (p - center) / std::max(distance(p, center), 1e-300);
      return center + radius * u;
    };
    // The vertices at the run's ends and between its edges, moved onto the circle.
    std::vector<Vec2> vertices{on_circle(loop[begin % n].start)};
    for (std::size_t k = begin; k < end; ++k) vertices.push_back(on_circle(loop[k % n].end));
    if (whole_loop) vertices.back() = vertices.front();
    for (std::size_t k = begin; k < end; ++k) {
      BoundaryEdge& edge = loop[k % n];
      const CircleCurve& own = *circle(k);
      const int sense = own.sense * (edge.t_end > edge.t_start ? 1 : -1);
      const Vec2 a = vertices[k - begin] - center, b = vertices[k - begin + 1] - center;
      double sweep = sense * signed_angle(a, b);
      if (sweep <= 0.0) sweep += 2.0 * kPi;  // a whole circle's one edge, or an arc over half a turn
      edge.curve = CircleCurve{center, radius, std::atan2(a.y, a.x), sense};
      edge.t_start = 0.0;
      edge.t_end = sweep;
      edge.start = vertices[k - begin];
      edge.end = vertices[k - begin + 1];
    }
    // The run's end vertices are also its neighbours'.
    if (!whole_loop) {
      loop[(begin + n - 1) % n].end = vertices.front();
      loop[end % n].start = vertices.back();
    }
    begin = next_begin;
  }
}

// Edge a followed by edge b as one edge, when both lie on one circle (or one
// line) and run on along it the same way; nothing otherwise.
std::optional<BoundaryEdge> joined_on_one_curve(const BoundaryEdge& a, const BoundaryEdge& b, double close) {
  const double dir_a = a.t_end > a.t_start ? 1.0 : -1.0, dir_b = b.t_end > b.t_start ? 1.0 : -1.0;
  const auto* circle_a = std::get_if<CircleCurve>(&a.curve);
  const auto* circle_b = std::get_if<CircleCurve>(&b.curve);
  if (circle_a && circle_b) {
    if (distance(circle_a->center, circle_b->center) > close || std::abs(circle_a->radius - circle_b->radius) > close)
      return std::nullopt;
    if (circle_a->sense * dir_a != circle_b->sense * dir_b) return std::nullopt;  // turning opposite ways
    BoundaryEdge joined = a;
    joined.t_end = a.t_end + dir_a * std::abs(b.t_end - b.t_start);  // the parameter is the angle on both
    joined.end = b.end;
    if (std::abs(joined.t_end - joined.t_start) > 2.0 * kPi + 1e-9 ||
        distance(evaluate_point(joined.curve, joined.t_end), b.end) > close)
      return std::nullopt;
    return joined;
  }
  const auto* line_a = std::get_if<LineCurve>(&a.curve);
  const auto* line_b = std::get_if<LineCurve>(&b.curve);
  if (line_a && line_b) {
    const Vec2 along_a = dir_a * line_a->direction, along_b = dir_b * line_b->direction;
    if (dot(along_a, along_b) <= 0.0 || std::abs(cross(along_a, b.end - a.start)) > close) return std::nullopt;
    return line_part(a, a.start, b.end);
  }
  return std::nullopt;
}

// A piece shorter than short_length and its neighbour on the same circle or
// line become one edge: CAD files cut circles at their seams and into arcs
// (a nut's outline: arcs of 25.18 and 0.048 of one circle), and every vertex
// is a point the mesh must put a node on, so such a piece left a needle
// there. Long pieces stay apart: joining a keyed gear's two bore halves put
// the teeth's excess intervals on one piece that bunched them at the keyway
// (gear_30_keyed at 0.01 of its diagonal: worst shape 0.51 -> 0.23).
void join_pieces_of_one_curve(std::vector<BoundaryEdge>& loop, double close, double short_length) {
  for (std::size_t i = 0; loop.size() > 1 && i < loop.size();) {
    const std::size_t next = (i + 1) % loop.size();
    const bool short_piece = std::min(edge_length(loop[i]), edge_length(loop[next])) < short_length;
    const std::optional<BoundaryEdge> joined =
        short_piece ? joined_on_one_curve(loop[i], loop[next], close) : std::nullopt;
    if (!joined) {
      ++i;
      continue;
    }
    loop[i] = *joined;
    loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(next));
    if (next == 0) i = 0;  // the loop's first edge was taken into its last
  }
}

// Interior angle at the vertex where edge `in` ends and edge `out` starts.
double interior_angle(const BoundaryEdge& in, const BoundaryEdge& out) {
  const double turn = signed_angle(edge_tangent(in, in.t_end), edge_tangent(out, out.t_start));
  const double from_antiparallel = kPi - std::abs(turn);
  if (from_antiparallel > kCuspAngle) return kPi - turn;
  // Nearly a cusp: a tiny change of tangent flips the angle between about 0
  // and 2pi, so short chords along both curves (from each curve's own end, not
  // the snapped vertex) decide on which side the material is.
  const double reach = 1e-2 * std::min(edge_length(in), edge_length(out));
  const CurvePoint end_in = evaluate(in.curve, in.t_end), start_out = evaluate(out.curve, out.t_start);
  const double step_in = reach / std::max(norm(end_in.d1), 1e-300) * (in.t_end > in.t_start ? 1 : -1);
  const double step_out = reach / std::max(norm(start_out.d1), 1e-300) * (out.t_end > out.t_start ? 1 : -1);
  const Vec2 back = evaluate_point(in, in.t_end - step_in) - end_in.p;
  const Vec2 ahead = evaluate_point(out, out.t_start + step_out) - start_out.p;
  const bool spike = signed_angle(ahead, back) >= 0.0;  // counter-clockwise from ahead to back is short
  return spike ? from_antiparallel : 2.0 * kPi - from_antiparallel;
}

// The joins whose interior angle is more than smooth_angle off pi, in loop order.
std::vector<Corner> find_corners(const FaceModel& face, double smooth_angle) {
  std::vector<Corner> corners;
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    const auto& edges = face.loops[li].edges;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const BoundaryEdge& in = edges[(i + edges.size() - 1) % edges.size()];
      const double angle = interior_angle(in, edges[i]);
      if (std::abs(angle - kPi) <= smooth_angle) continue;
      corners.push_back({static_cast<int>(li), static_cast<int>(i), edges[i].start, angle, optimal_corner_type(angle)});
    }
  }
  return corners;
}

}  // namespace

int optimal_corner_type(double angle) {
  const double degrees = angle * 180.0 / kPi;
  if (degrees < 45.0) return 0;
  if (degrees < 135.0) return 1;
  if (degrees < 225.0) return 2;
  if (degrees < 315.0) return 3;
  return 4;
}

int predicted_sum_k(const FaceModel& face) {
  int sum = 0;
  for (const Corner& c : face.corners) sum += 2 - c.nc;
  return sum - 4 * face.euler();
}

CurvePoint edge_point(const BoundaryEdge& edge, double t) {
  return evaluate(edge.curve, t);
}

std::pair<double, double> closest_param(const BoundaryEdge& edge, double ta, double tb, Vec2 p) {
  constexpr int kSteps = 64;
  const auto param = [&](int i) { return ta + (tb - ta) * i / kSteps; };
  const auto gap = [&](double t) { return distance(edge_point(edge, t).p, p); };
  int best = 0;
  double best_gap = gap(ta);
  for (int i = 1; i <= kSteps; ++i) {
    const double d = gap(param(i));
    if (d < best_gap) {
      best = i;
      best_gap = d;
    }
  }
  double lo = param(std::max(best - 1, 0));
  double hi = param(std::min(best + 1, kSteps));
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 80; ++i) {
    const double a = hi - golden * (hi - lo);
    const double b = lo + golden * (hi - lo);
    if (gap(a) < gap(b)) {
      hi = b;
    } else {
      lo = a;
    }
  }
  const double t = 0.5 * (lo + hi);
  const double d = gap(t);
  return d < best_gap ? std::make_pair(t, d) : std::make_pair(param(best), best_gap);
}

Vec2 edge_tangent(const BoundaryEdge& edge, double t) {
  const double direction = edge.t_end >= edge.t_start ? 1.0 : -1.0;
  const CurvePoint cp = evaluate(edge.curve, t);
  if (norm(cp.d1) > 1e-12 * (1.0 + norm(cp.d2))) return normalized(direction * cp.d1);
  // Degenerate parametrisation (repeated poles): the chord a little way in gives the direction.
  const double step = 1e-6 * (edge.t_end - edge.t_start);
  const bool at_start = std::abs(t - edge.t_start) < std::abs(t - edge.t_end);
  const Vec2 other = evaluate_point(edge, at_start ? t + step : t - step);
  return normalized(at_start ? other - cp.p : cp.p - other);
}

double edge_sagitta(const BoundaryEdge& edge, double from, double to) {
  if (std::holds_alternative<LineCurve>(edge.curve)) return 0.0;
  if (const auto* circle = std::get_if<CircleCurve>(&edge.curve))
    return circle->radius * (1.0 - std::cos(std::min(std::abs(to - from), 2.0 * kPi) / 2.0));
  constexpr int kSteps = 8;
  const Vec2 a = edge_point(edge, from).p, b = edge_point(edge, to).p;
  double most = 0.0;
  for (int k = 1; k < kSteps; ++k)
    most = std::max(most, distance_to_segment(edge_point(edge, from + (to - from) * k / kSteps).p, a, b));
  return most;
}

double edge_length(const BoundaryEdge& edge) {
  const auto speed = [&](double t) { return norm(evaluate(edge.curve, t).d1); };
  double polygon = 0.0;  // length of the polygon through the piece ends, for the absolute floor
  const std::vector<double> cuts = pieces(edge);
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    polygon += distance(evaluate_point(edge, cuts[i]), evaluate_point(edge, cuts[i + 1]));
  }
  return std::abs(integrate_edge(edge, speed, 1e-15 * polygon + 1e-300));
}

double signed_area(const Loop& loop) {
  if (loop.edges.empty()) return 0.0;
  const Vec2 ref = loop.edges.front().start;  // near the loop, for less cancellation
  double scale = 0.0;                         // the loop's extent, from points along every edge
  for (const auto& e : loop.edges) {
    for (double t : pieces(e)) scale = std::max(scale, distance(evaluate_point(e, t), ref));
  }
  // Straight connectors close the small gaps between a curve's ends and its
  // snapped vertices, so the boundary integral runs over a closed path.
  const auto segment = [&](Vec2 a, Vec2 b) { return 0.5 * cross(a - ref, b - a); };
  double area = 0.0;
  for (const auto& edge : loop.edges) {
    area +=
        segment(edge.start, evaluate_point(edge, edge.t_start)) + segment(evaluate_point(edge, edge.t_end), edge.end);
    const auto integrand = [&](double t) {
      const CurvePoint cp = evaluate(edge.curve, t);
      return 0.5 * cross(cp.p - ref, cp.d1);
    };
    area += integrate_edge(edge, integrand, 1e-16 * scale * scale + 1e-300);
  }
  return area;
}

double edge_area_integral(const BoundaryEdge& edge, double t_from, double t_to, Vec2 ref) {
  const double lo = std::min(t_from, t_to), hi = std::max(t_from, t_to);
  if (!(hi > lo)) return 0.0;
  // Lines and conics in closed form: the triangle from ref over the chord,
  // and for a circle or ellipse the segment between chord and arc, sense * a
  // * b * (u - sin u) / 2 over u of parameter. Not from the centre: a nearly
  // straight arc's centre lies far off (radius 83 000 on a face 33 across,
  // OCCT's Bottom.brep face 108), and the cross product with it lost 1e-6 of
  // area a piece, more than the decomposition's blocks may be off in sum.
  const double sign = t_to >= t_from ? 1.0 : -1.0;
  const Vec2 start = evaluate_point(edge, lo);
  const double triangle = 0.5 * cross(start - ref, evaluate_point(edge, hi) - start);
  const auto segment = [&](double sense, double ab) {
    const double u = hi - lo;
    // u - sin u by its series where the subtraction would cancel.
    const double u2 = u * u;
    const double lost =
        u < 0.1 ? u * u2 / 6.0 * (1.0 - u2 / 20.0 * (1.0 - u2 / 42.0 * (1.0 - u2 / 72.0))) : u - std::sin(u);
    return 0.5 * sense * ab * lost;
  };
  switch (curve_type(edge.curve)) {
    case CurveType::Line: return sign * triangle;
    case CurveType::Circle: {
      const CircleCurve& c = std::get<CircleCurve>(edge.curve);
      return sign * (triangle + segment(c.sense, c.radius * c.radius));
    }
    case CurveType::Ellipse: {
      const EllipseCurve& e = std::get<EllipseCurve>(edge.curve);
      return sign * (triangle + segment(e.sense, e.major_radius * e.minor_radius));
    }
    default: break;  // B-splines and other curves: by quadrature below
  }
  std::vector<double> cuts{lo};
  for (double t : pieces(edge)) {
    if (t > lo && t < hi) cuts.push_back(t);
  }
  cuts.push_back(hi);
  // The absolute floor scales with how far the curve reaches from ref: not
  // from its ends alone, which for a closed curve from ref round to ref (a
  // blunt trailing edge shorter than the tolerance) lie at ref itself, where
  // a floor of 0 sent every span to the depth cap (40 s on one aerofoil).
  double reach = distance(evaluate_point(edge, 0.5 * (lo + hi)), ref);
  for (double t : cuts) reach = std::max(reach, distance(evaluate_point(edge, t), ref));
  reach *= 2.0;
  const auto integrand = [&](double t) {
    const CurvePoint cp = evaluate(edge.curve, t);
    return 0.5 * cross(cp.p - ref, cp.d1);
  };
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    total += integrate(integrand, cuts[i], cuts[i + 1], gauss(integrand, cuts[i], cuts[i + 1]),
                       1e-16 * reach * reach + 1e-300, 0);
  }
  return t_to >= t_from ? total : -total;
}

std::vector<double> sample_edge_parameters(const BoundaryEdge& edge, double chord_tolerance, double max_turn) {
  std::vector<double> cuts = pieces(edge);
  if (edge.t_end < edge.t_start) std::reverse(cuts.begin(), cuts.end());
  std::vector<double> params{edge.t_start};
  if (curve_type(edge.curve) == CurveType::Line) {
    params.push_back(edge.t_end);
    return params;
  }
  // Bisect a parameter interval until its chord is close enough to the curve.
  const auto refine = [&](auto&& self, double a, double b, int depth) -> void {
    const CurvePoint pa = evaluate(edge.curve, a), pb = evaluate(edge.curve, b);
    const double m = 0.5 * (a + b);
    const Vec2 pm = evaluate_point(edge, m);
    const Vec2 chord = pb.p - pa.p;
    const double len = norm(chord);
    const double deviation = len > 0 ? std::abs(cross(chord, pm - pa.p)) / len : distance(pm, pa.p);
    const double turn = std::abs(signed_angle(pa.d1, pb.d1));
    if (depth < 24 && (deviation > chord_tolerance || turn > max_turn)) {
      self(self, a, m, depth + 1);
      self(self, m, b, depth + 1);
    } else {
      params.push_back(b);
    }
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) refine(refine, cuts[i], cuts[i + 1], 0);
  params.back() = edge.t_end;
  return params;
}

std::vector<Vec2> edge_points(const BoundaryEdge& edge, const std::vector<double>& params) {
  std::vector<Vec2> points;
  for (double t : params) points.push_back(evaluate_point(edge, t));
  points.front() = edge.start;
  points.back() = edge.end;
  return points;
}

std::vector<Vec2> sample_edge(const BoundaryEdge& edge, double chord_tolerance) {
  return edge_points(edge, sample_edge_parameters(edge, chord_tolerance));
}

std::vector<Vec2> sample_loop(const Loop& loop, double chord_tolerance) {
  std::vector<Vec2> result;
  for (const auto& edge : loop.edges) {
    std::vector<Vec2> pts = sample_edge(edge, chord_tolerance);
    result.insert(result.end(), pts.begin(), pts.end() - 1);
  }
  return result;
}

Box bounding_box(const FaceModel& face) {
  return bounding_box(sample_loop(face.loops.front(), 1e-3 * face.size));
}

Box bounding_box(const std::vector<Vec2>& points) {
  Box box{{1e300, 1e300}, {-1e300, -1e300}};
  for (const Vec2& p : points) {
    box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y)};
    box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y)};
  }
  return box;
}

std::array<double, 3> to_3d(const Frame& f, Vec2 p) {
  return {f.origin[0] + p.x * f.x_dir[0] + p.y * f.y_dir[0], f.origin[1] + p.x * f.x_dir[1] + p.y * f.y_dir[1],
          f.origin[2] + p.x * f.x_dir[2] + p.y * f.y_dir[2]};
}

// A hole's side and the outline (or two holes' sides) running along each
// other closer than this fraction of the face's size bound a sliver no
// element can cross well: the two loops are joined round it.
constexpr double kSliverWidth = 1e-6;

std::string point_text(Vec2 p) {
  std::ostringstream text;
  text << "(" << p.x << ", " << p.y << ")";
  return text.str();
}

// Where line edge `in` of one loop and line edge `other` of another run
// along each other the opposite ways over more than `reach`: the stretch's
// ends p, q in `in`'s direction. The material lies on neither side there
// (a slit of no width).
bool shared_stretch(const BoundaryEdge& in, const BoundaryEdge& other, double tolerance, double reach, Vec2& p,
                    Vec2& q) {
  if (curve_type(in.curve) != CurveType::Line || curve_type(other.curve) != CurveType::Line) return false;
  const double length = distance(in.start, in.end);
  const Vec2 u = (in.end - in.start) / length;
  if (std::abs(cross(u, other.start - in.start)) > tolerance || std::abs(cross(u, other.end - in.start)) > tolerance)
    return false;
  const double from = std::max(0.0, dot(other.end - in.start, u));
  const double to = std::min(length, dot(other.start - in.start, u));
  if (dot(other.end - other.start, u) >= 0.0 || to - from <= reach) return false;
  p = in.start + from * u;
  q = in.start + to * u;
  return true;
}

// Loop a (edge i) and loop b (edge j) joined round their shared stretch
// p..q: along edge i to p, along edge j from p round loop b back to q,
// along edge i from q on; parts shorter than `reach` are left out, and
// where one was, its neighbours' ends become one vertex on edge i's line by
// moving a line's end. Empty where a curve would have to move instead.
std::vector<BoundaryEdge> joined_round(const Loop& a, std::size_t i, const Loop& b, std::size_t j, Vec2 p, Vec2 q,
                                       double reach) {
  const BoundaryEdge &in = a.edges[i], &other = b.edges[j];
  std::vector<BoundaryEdge> joined;
  const auto add = [&](const BoundaryEdge& of, Vec2 from, Vec2 to) {
    if (distance(from, to) > reach) joined.push_back(line_part(of, from, to));
  };
  joined.insert(joined.end(), a.edges.begin(), a.edges.begin() + static_cast<std::ptrdiff_t>(i));
  add(in, in.start, p);
  add(other, p, other.end);
  for (std::size_t k = 1; k < b.edges.size(); ++k) joined.push_back(b.edges[(j + k) % b.edges.size()]);
  add(other, other.start, q);
  const std::size_t from_q = joined.size();
  add(in, q, in.end);
  joined.insert(joined.end(), a.edges.begin() + static_cast<std::ptrdiff_t>(i) + 1, a.edges.end());
  for (std::size_t k = 0; k < joined.size(); ++k) {
    BoundaryEdge& before = joined[k];
    BoundaryEdge& next = joined[(k + 1) % joined.size()];
    if (distance(before.end, next.start) == 0.0) continue;
    if ((k + 1) % joined.size() == from_q && curve_type(before.curve) == CurveType::Line)
      before = line_part(before, before.start, next.start);
    else if (curve_type(next.curve) == CurveType::Line)
      next = line_part(next, before.end, next.end);
    else
      return {};
  }
  return joined;
}

// Two loops running along each other the opposite ways closer than
// `width` (a U drawn as a rectangle with a hole whose side lies 6.4e-7 off
// the outline: SOT404.stp face 22) bound a slit or a sliver every element
// across is flat in: they become one loop round the stretch (joined_round),
// the one with the lower index kept (the outline stays loop 0). Loops
// oriented already. Returns whether two loops were joined.
bool splice_one_shared_stretch(std::vector<Loop>& loops, double width) {
  const double reach = 10.0 * width;
  for (std::size_t a = 0; a < loops.size(); ++a)
    for (std::size_t b = a + 1; b < loops.size(); ++b)
      for (std::size_t i = 0; i < loops[a].edges.size(); ++i)
        for (std::size_t j = 0; j < loops[b].edges.size(); ++j) {
          Vec2 p, q;
          if (!shared_stretch(loops[a].edges[i], loops[b].edges[j], width, reach, p, q)) continue;
          std::vector<BoundaryEdge> joined = joined_round(loops[a], i, loops[b], j, p, q, reach);
          if (joined.empty()) continue;
          loops[a].edges = std::move(joined);
          loops.erase(loops.begin() + static_cast<std::ptrdiff_t>(b));
          return true;
        }
  return false;
}

FaceModel build_face_model(RawFace raw) {
  const std::string& name = raw.name;
  if (raw.loops.empty()) throw InputError(name + ": face has no boundary");
  for (const auto& loop : raw.loops) {
    if (loop.empty()) throw InputError(name + ": face has an empty wire");
  }
  const double size = rough_size(raw);
  if (std::isnan(size) || std::isinf(size)) throw InputError(name + ": a curve has a NaN or infinite coordinate");
  if (!(size > 0.0)) throw InputError(name + ": face has no area");
  const double tolerance = std::max(raw.tolerance, 1e-9 * size);

  FaceModel face;
  face.name = name;
  face.size = size;
  face.tolerance = tolerance;
  face.frame = raw.frame;

  std::vector<double> areas;
  for (std::size_t li = 0; li < raw.loops.size(); ++li) {
    auto& edges = raw.loops[li];
    for (auto& edge : edges) {
      const double length = edge_length(edge);
      if (length <= 1e-12 * size) {
        throw InputError(name + ": edge " + std::to_string(edge.source_index) + " has zero length");
      }
      if (length <= tolerance) {
        throw InputError(name + ": edge " + std::to_string(edge.source_index) + " is shorter (" + format(length) +
                         ") than the tolerance " + format(tolerance));
      }
    }
    snap_loop(edges, static_cast<int>(li), 2.0 * tolerance, name);
    std::vector<std::vector<Vec2>> samples;
    for (auto& edge : edges) {
      samples.push_back(dense_points(edge, 8));
      recognise_simple_curve(edge, size);
    }
    unify_circles(edges, samples, kSameCircleTolerance * size, size);
    rebuild_lines(edges);
    join_pieces_of_one_curve(edges, kSameCurveTolerance * size, kShortPiece * size);
    face.loops.push_back(Loop{std::move(edges)});
    areas.push_back(signed_area(face.loops.back()));
  }

  // The outer loop encloses the largest area; orient it counter-clockwise and holes clockwise.
  const auto outer =
      std::max_element(areas.begin(), areas.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }) -
      areas.begin();
  std::rotate(face.loops.begin(), face.loops.begin() + outer, face.loops.begin() + outer + 1);
  std::rotate(areas.begin(), areas.begin() + outer, areas.begin() + outer + 1);
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    const bool want_positive = li == 0;
    if ((areas[li] > 0) != want_positive) {
      reverse_loop(face.loops[li].edges);
      areas[li] = -areas[li];
    }
    face.area += areas[li];
  }
  bool spliced = false;
  while (splice_one_shared_stretch(face.loops, std::max(tolerance, kSliverWidth * size))) spliced = true;
  if (spliced) {
    face.area = 0.0;  // less the slivers
    for (const Loop& loop : face.loops) face.area += signed_area(loop);
  }
  std::vector<std::vector<Vec2>> polylines;
  double spread = 0.0;  // area of the triangle fans: zero only if every loop is collinear
  for (const auto& loop : face.loops) {
    polylines.push_back(sample_loop(loop, 1e-5 * size));
    const auto& pts = polylines.back();
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) spread += std::abs(cross(pts[i] - pts[0], pts[i + 1] - pts[0]));
  }
  if (!(spread > 1e-12 * size * size)) throw InputError(name + ": face has no area");
  // One loop running back along itself bounds no material between: a
  // bridge of no width joining two parts of the face (SOT404.stp face 20,
  // two legs joined along their tops), or a spike. No block mesh has
  // elements there that are not flat.
  const double sliver = std::max(tolerance, kSliverWidth * size);
  for (const Loop& loop : face.loops)
    for (std::size_t i = 0; i < loop.edges.size(); ++i)
      for (std::size_t j = i + 1; j < loop.edges.size(); ++j) {
        Vec2 p, q;
        if (shared_stretch(loop.edges[i], loop.edges[j], sliver, 10.0 * sliver, p, q))
          throw InputError(name + ": the outline runs back along itself from " + point_text(p) + " to " +
                           point_text(q) + " (a part of no width joins two parts of the face; make them two faces)");
      }
  // Boost.Geometry's predicates compare with fixed epsilons: judged on a face of
  // size 1 near the origin, a face of 1e-6 or 1e6 gets the same answer.
  const Vec2 origin = polylines.front().front();
  for (auto& loop : polylines)
    for (Vec2& p : loop) p = (p - origin) / size;
  const std::string problem = find_region_problem(polylines);
  if (!problem.empty()) throw InputError(name + ": " + problem);
  if (!(face.area > 1e-12 * size * size)) throw InputError(name + ": face has no area");

  face.corners = find_corners(face, kSmoothAngle);
  return face;
}

std::string kinks_as_corners_note(const std::string& what, const std::string& failure, std::size_t kinks) {
  return what + " built with " + std::to_string(kinks) +
         " such joins as corners, as a fallback: with joins up to 0.5 degrees off tangent taken as smooth it did "
         "not pass its check (" +
         failure + ")";
}

FaceModel with_kinks_as_corners(const FaceModel& face) {
  FaceModel kinked = face;
  kinked.corners = find_corners(face, kKinkAngle);
  return kinked;
}

}  // namespace mm
