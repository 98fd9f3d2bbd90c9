#pragma once
// Exact 2-D boundary curves. Each kind keeps its defining data so later stages
// (medial axis, meshing) can work on the true geometry, not on a polyline.
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// Point and first two derivatives with respect to the curve's own parameter.
struct CurvePoint {
  Vec2 p;
  Vec2 d1;
  Vec2 d2;
};

// origin + t * direction, |direction| = 1, so t is arc length.
struct LineCurve {
  Vec2 origin;
  Vec2 direction;
};

// center + radius * (cos(a), sin(a)) with a = start_angle + sense * t.
struct CircleCurve {
  Vec2 center;
  double radius = 0.0;
  double start_angle = 0.0;
  int sense = 1;  // +1 counter-clockwise, -1 clockwise
};

// center + major_radius cos(t) X + minor_radius sin(t) Y, Y = sense * perp(X).
struct EllipseCurve {
  Vec2 center;
  Vec2 major_axis;  // unit X
  double major_radius = 0.0;
  double minor_radius = 0.0;
  int sense = 1;
};

// Non-periodic (rational) B-spline on [knots[degree], knots[poles]]: knots
// are the full sequence with repeats, clamped or not (a periodic curve comes
// unrolled from its seam), weights empty for a polynomial curve. Bezier
// curves come as this too.
struct BSplineCurve {
  int degree = 1;
  std::vector<double> knots;
  std::vector<Vec2> poles;
  std::vector<double> weights;
};

// Any other curve (hyperbola, parabola, offset curve) evaluated by its source.
struct OtherCurve {
  std::string name;
  std::function<CurvePoint(double)> evaluate;
};

using Curve = std::variant<LineCurve, CircleCurve, EllipseCurve, BSplineCurve, OtherCurve>;

enum class CurveType { Line, Circle, Ellipse, BSpline, Other };

CurveType curve_type(const Curve& curve);
const char* curve_type_name(CurveType type);  // "line", "circle", ...

CurvePoint evaluate(const Curve& curve, double t);
// evaluate(curve, t).p, bit for bit, without the derivatives (a B-spline's
// cost a good deal more than its point).
Vec2 evaluate_point(const Curve& curve, double t);

// Parameters inside (lo, hi) where the curve is only piecewise smooth (B-spline
// knots); integration and sampling split there.
std::vector<double> breakpoints(const Curve& curve, double lo, double hi);

// An upper bound of |C''(t)| over [lo, hi], an interval between two
// breakpoints; infinity where none is known (rational B-splines, other
// curves). A chord of that interval then stays within
// bound * (hi - lo)^2 / 8 of the curve.
double second_derivative_bound(const Curve& curve, double lo, double hi);

}  // namespace mm
