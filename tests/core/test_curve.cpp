// Curve evaluation: the own NURBS evaluator against exact circles, and
// derivatives of every kind against finite differences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "boundary/curve.hpp"

namespace mm {
namespace {

// Quarter circle of radius 2 as a rational quadratic B-spline.
BSplineCurve quarter_circle() {
  const double w = std::sqrt(0.5);
  return BSplineCurve{2, {0, 0, 0, 1, 1, 1}, {{2, 0}, {2, 2}, {0, 2}}, {1, w, 1}};
}

TEST(Curve, RationalBSplineLiesOnItsCircle) {
  const Curve c = quarter_circle();
  for (int i = 0; i <= 20; ++i) {
    const CurvePoint cp = evaluate(c, i / 20.0);
    EXPECT_NEAR(norm(cp.p), 2.0, 1e-14);
    EXPECT_NEAR(dot(cp.p, cp.d1), 0.0, 1e-12);  // tangent is perpendicular to the radius
  }
  EXPECT_NEAR(evaluate(c, 1.0).p.x, 0.0, 1e-15);
}

void expect_derivatives_match(const Curve& c, double t) {
  const double h = 1e-5;
  const CurvePoint a = evaluate(c, t - h), b = evaluate(c, t + h), m = evaluate(c, t);
  const Vec2 d1 = (b.p - a.p) / (2 * h);
  const Vec2 d2 = (b.d1 - a.d1) / (2 * h);
  EXPECT_NEAR(m.d1.x, d1.x, 1e-6 * (1 + norm(d1)));
  EXPECT_NEAR(m.d1.y, d1.y, 1e-6 * (1 + norm(d1)));
  EXPECT_NEAR(m.d2.x, d2.x, 1e-5 * (1 + norm(d2)));
  EXPECT_NEAR(m.d2.y, d2.y, 1e-5 * (1 + norm(d2)));
}

TEST(Curve, DerivativesMatchFiniteDifferences) {
  expect_derivatives_match(quarter_circle(), 0.3);
  expect_derivatives_match(CircleCurve{{1, 2}, 3, 0.4, -1}, 1.1);
  expect_derivatives_match(EllipseCurve{{0, 1}, normalized({1, 1}), 3, 1, -1}, 2.0);
  const BSplineCurve cubic{3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0}, {1, 2}, {2, -1}, {3, 3}, {4, 0}}, {}};
  expect_derivatives_match(cubic, 0.2);
  expect_derivatives_match(cubic, 0.7);
}

// A clamped B-spline of the given degree on random knots (some interior
// ones doubled) and random poles.
BSplineCurve random_bspline(int degree, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), coord(-5.0, 5.0);
  BSplineCurve c;
  c.degree = degree;
  std::vector<double> interior;
  for (int k = 0; k < 6; ++k) {
    interior.push_back(unit(rng));
    if (degree > 2 && unit(rng) < 0.3) interior.push_back(interior.back());
  }
  std::sort(interior.begin(), interior.end());
  c.knots.assign(degree + 1, 0.0);
  c.knots.insert(c.knots.end(), interior.begin(), interior.end());
  c.knots.insert(c.knots.end(), degree + 1, 1.0);
  for (std::size_t i = 0; i + degree + 1 < c.knots.size(); ++i) c.poles.push_back({coord(rng), coord(rng)});
  return c;
}

TEST(Curve, EveryDegreeMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  for (int degree = 1; degree <= 12; ++degree) {  // 11 and 12 take the general loops
    const BSplineCurve c = random_bspline(degree, rng);
    for (double t : {0.13, 0.41, 0.77}) {
      if (degree >= 3) expect_derivatives_match(c, t);
      EXPECT_EQ(evaluate_point(c, t).x, evaluate(c, t).p.x);  // the point alone, bit for bit
      EXPECT_EQ(evaluate_point(c, t).y, evaluate(c, t).p.y);
    }
  }
}

// The bound holds at every point of each knot span, and so the chord of any
// piece of a span stays within bound * dt^2 / 8 of the curve.
TEST(Curve, SecondDerivativeBoundHoldsOnEveryKnotSpan) {
  std::mt19937 rng(11);
  for (int degree = 1; degree <= 9; ++degree) {
    for (int trial = 0; trial < 5; ++trial) {
      const BSplineCurve c = random_bspline(degree, rng);
      std::vector<double> cuts{0.0};
      for (double b : breakpoints(c, 0.0, 1.0)) cuts.push_back(b);
      cuts.push_back(1.0);
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double lo = cuts[k], hi = cuts[k + 1];
        const double bound = second_derivative_bound(c, lo, hi);
        ASSERT_TRUE(std::isfinite(bound));
        const Vec2 a = evaluate_point(c, lo), b = evaluate_point(c, hi);
        for (int i = 0; i <= 50; ++i) {
          const double t = lo + (hi - lo) * i / 50;
          const CurvePoint p = evaluate(c, t);
          // At a knot evaluate takes the next span's second derivative.
          if (i < 50) EXPECT_LE(norm(p.d2), bound * (1 + 1e-9) + 1e-9) << "degree " << degree << " t " << t;
          const Vec2 chord = a + ((t - lo) / (hi - lo)) * (b - a);
          EXPECT_LE(distance(p.p, chord), bound * (hi - lo) * (hi - lo) / 8 + 1e-12);
        }
      }
    }
  }
  EXPECT_EQ(second_derivative_bound(LineCurve{{0, 0}, {1, 0}}, 0.0, 1.0), 0.0);
  EXPECT_EQ(second_derivative_bound(CircleCurve{{1, 2}, 3, 0.4, -1}, 0.0, 1.0), 3.0);
  EXPECT_EQ(second_derivative_bound(quarter_circle(), 0.0, 1.0), std::numeric_limits<double>::infinity());
}

TEST(Curve, BreakpointsAreInteriorKnots) {
  const BSplineCurve cubic{3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0}, {1, 2}, {2, -1}, {3, 3}, {4, 0}}, {}};
  EXPECT_EQ(breakpoints(cubic, 0.0, 1.0), std::vector<double>{0.5});
  EXPECT_TRUE(breakpoints(cubic, 0.6, 1.0).empty());
  EXPECT_TRUE(breakpoints(CircleCurve{}, 0.0, 6.0).empty());
}

}  // namespace
}  // namespace mm
