#include "boundary/curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace mm {
namespace {

CurvePoint evaluate_line(const LineCurve& c, double t) {
  return {c.origin + t * c.direction, c.direction, {0.0, 0.0}};
}

CurvePoint evaluate_circle(const CircleCurve& c, double t) {
  const double a = c.start_angle + c.sense * t;
  const Vec2 u{std::cos(a), std::sin(a)};
  return {c.center + c.radius * u, c.sense * c.radius * perp(u), -c.radius * u};
}

CurvePoint evaluate_ellipse(const EllipseCurve& c, double t) {
  const Vec2 x = c.major_axis;
  const Vec2 y = c.sense * perp(x);
  const double ct = std::cos(t), st = std::sin(t);
  const Vec2 offset = c.major_radius * ct * x + c.minor_radius * st * y;
  return {c.center + offset, -c.major_radius * st * x + c.minor_radius * ct * y, -1.0 * offset};
}

// Index of the knot span holding t (clamped to the valid range).
int find_span(const BSplineCurve& c, double t) {
  const int n = static_cast<int>(c.poles.size()) - 1;
  const int p = c.degree;
  if (t >= c.knots[n + 1]) return n;
  if (t <= c.knots[p]) return p;
  const auto it = std::upper_bound(c.knots.begin() + p, c.knots.begin() + n + 1, t);
  return static_cast<int>(it - c.knots.begin()) - 1;
}

// Degree kDegree, or c.degree when kDegree is 0. Fixed degrees let the
// compiler unroll the loops below; the arithmetic is the same, bit for bit.
template <int kDegree>
int degree_of(const BSplineCurve& c) {
  return kDegree > 0 ? kDegree : c.degree;
}

// Basis functions and their first two derivatives at t on span i
// (Piegl & Tiller, The NURBS Book, algorithm A2.3).
template <int kDegree>
void basis_derivatives(const BSplineCurve& c, int i, double t, double ders[3][32]) {
  const int p = degree_of<kDegree>(c);
  constexpr int kSize = kDegree > 0 ? kDegree + 1 : 32;
  double ndu[kSize][kSize];
  double left[kSize], right[kSize];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - c.knots[i + 1 - j];
    right[j] = c.knots[i + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  double a[2][kSize < 3 ? 3 : kSize];  // a[.][k] for k up to 2
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= 2; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= 2; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }
}

template <int kDegree>
CurvePoint evaluate_bspline(const BSplineCurve& c, double t) {
  const int degree = degree_of<kDegree>(c);
  const int span = find_span(c, t);
  double ders[3][32];  // basis_derivatives fills [0..2][0..degree], all that is read
  basis_derivatives<kDegree>(c, span, t, ders);
  const bool rational = !c.weights.empty();
  // Homogeneous sums: A = sum N w P, W = sum N w, for value and derivatives.
  Vec2 a[3];
  double w[3] = {0.0, 0.0, 0.0};
  for (int j = 0; j <= degree; ++j) {
    const int idx = span - degree + j;
    const double wj = rational ? c.weights[idx] : 1.0;
    for (int k = 0; k < 3; ++k) {
      a[k] = a[k] + ders[k][j] * wj * c.poles[idx];
      w[k] += ders[k][j] * wj;
    }
  }
  const Vec2 p = a[0] / w[0];
  const Vec2 d1 = (a[1] - w[1] * p) / w[0];
  const Vec2 d2 = (a[2] - 2.0 * w[1] * d1 - w[2] * p) / w[0];
  return {p, d1, d2};
}

// The basis functions alone at t on span i: the first column of
// basis_derivatives' table by the same arithmetic (The NURBS Book, A2.2),
// so a point evaluated from them is bit for bit the point evaluate gives.
template <int kDegree>
void basis_functions(const BSplineCurve& c, int i, double t, double n[32]) {
  const int p = degree_of<kDegree>(c);
  constexpr int kSize = kDegree > 0 ? kDegree + 1 : 32;
  double left[kSize], right[kSize];
  n[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - c.knots[i + 1 - j];
    right[j] = c.knots[i + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = n[r] / (right[r + 1] + left[j - r]);
      n[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    n[j] = saved;
  }
}

template <int kDegree>
Vec2 evaluate_bspline_point(const BSplineCurve& c, double t) {
  const int degree = degree_of<kDegree>(c);
  const int span = find_span(c, t);
  double n[32];
  basis_functions<kDegree>(c, span, t, n);
  const bool rational = !c.weights.empty();
  Vec2 a;
  double w = 0.0;
  for (int j = 0; j <= degree; ++j) {
    const int idx = span - degree + j;
    const double wj = rational ? c.weights[idx] : 1.0;
    a = a + n[j] * wj * c.poles[idx];
    w += n[j] * wj;
  }
  return a / w;
}

// f(std::integral_constant<int, d>()) with d the curve's degree up to 10
// (the shared real CAD faces have 3, 5, 7 and rational 10), else 0 (the
// degree read from the curve).
template <class F>
decltype(auto) with_degree(const BSplineCurve& c, F f) {
  if (c.degree < 1 || c.degree > 30) throw std::invalid_argument("unsupported B-spline degree");
  switch (c.degree) {
    case 1: return f(std::integral_constant<int, 1>());
    case 2: return f(std::integral_constant<int, 2>());
    case 3: return f(std::integral_constant<int, 3>());
    case 4: return f(std::integral_constant<int, 4>());
    case 5: return f(std::integral_constant<int, 5>());
    case 6: return f(std::integral_constant<int, 6>());
    case 7: return f(std::integral_constant<int, 7>());
    case 8: return f(std::integral_constant<int, 8>());
    case 9: return f(std::integral_constant<int, 9>());
    case 10: return f(std::integral_constant<int, 10>());
    default: return f(std::integral_constant<int, 0>());
  }
}

// The second derivative of a B-spline of degree p >= 2 on a knot span is a
// convex combination of the p - 1 control points of its second-derivative
// curve there (The NURBS Book, eq. 3.8 applied twice), so the largest of
// their lengths bounds it.
double bspline_second_derivative_bound(const BSplineCurve& c, double lo, double hi) {
  if (!c.weights.empty()) return std::numeric_limits<double>::infinity();
  const int p = c.degree;
  if (p < 2) return 0.0;  // straight between knots
  const int span = find_span(c, 0.5 * (lo + hi));
  const auto& u = c.knots;
  // First-derivative control point Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}).
  const auto q = [&](int i) {
    const double du = u[i + p + 1] - u[i + 1];
    return du > 0.0 ? (p / du) * (c.poles[i + 1] - c.poles[i]) : Vec2{};
  };
  double bound = 0.0;
  for (int i = span - p; i <= span - 2; ++i) {
    const double du = u[i + p + 1] - u[i + 2];
    if (du <= 0.0) continue;  // its basis function is zero on the span
    bound = std::max(bound, norm(((p - 1) / du) * (q(i + 1) - q(i))));
  }
  return bound;
}

}  // namespace

CurveType curve_type(const Curve& curve) {
  return static_cast<CurveType>(curve.index());
}

const char* curve_type_name(CurveType type) {
  switch (type) {
    case CurveType::Line: return "line";
    case CurveType::Circle: return "circle";
    case CurveType::Ellipse: return "ellipse";
    case CurveType::BSpline: return "bspline";
    case CurveType::Other: return "other";
  }
  return "other";
}

CurvePoint evaluate(const Curve& curve, double t) {
  struct Visitor {
    double t;
    CurvePoint operator()(const LineCurve& c) const { return evaluate_line(c, t); }
    CurvePoint operator()(const CircleCurve& c) const { return evaluate_circle(c, t); }
    CurvePoint operator()(const EllipseCurve& c) const { return evaluate_ellipse(c, t); }
    CurvePoint operator()(const BSplineCurve& c) const {
      return with_degree(c, [&](auto d) { return evaluate_bspline<decltype(d)::value>(c, t); });
    }
    CurvePoint operator()(const OtherCurve& c) const { return c.evaluate(t); }
  };
  return std::visit(Visitor{t}, curve);
}

Vec2 evaluate_point(const Curve& curve, double t) {
  if (const auto* bs = std::get_if<BSplineCurve>(&curve))
    return with_degree(*bs, [&](auto d) { return evaluate_bspline_point<decltype(d)::value>(*bs, t); });
  return evaluate(curve, t).p;
}

std::vector<double> breakpoints(const Curve& curve, double lo, double hi) {
  std::vector<double> result;
  // Knots within rounding of the ends (edge ranges are often a knot +- 1e-13)
  // would make empty pieces.
  const double margin = 1e-9 * (hi - lo);
  if (const auto* bs = std::get_if<BSplineCurve>(&curve)) {
    for (double k : bs->knots) {
      if (k > lo + margin && k < hi - margin && (result.empty() || k > result.back() + margin)) result.push_back(k);
    }
  }
  return result;
}

double second_derivative_bound(const Curve& curve, double lo, double hi) {
  switch (curve_type(curve)) {
    case CurveType::Line: return 0.0;
    case CurveType::Circle: return std::get<CircleCurve>(curve).radius;
    case CurveType::Ellipse: {
      const EllipseCurve& e = std::get<EllipseCurve>(curve);
      return std::max(e.major_radius, e.minor_radius);
    }
    case CurveType::BSpline: return bspline_second_derivative_bound(std::get<BSplineCurve>(curve), lo, hi);
    case CurveType::Other: break;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace mm
