// Curve evaluation: the own NURBS evaluator against exact circles, and
// derivatives of every kind against finite differences.
#include <gtest/gtest.h>

#include <cmath>

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

TEST(Curve, BreakpointsAreInteriorKnots) {
  const BSplineCurve cubic{3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}, {{0, 0}, {1, 2}, {2, -1}, {3, 3}, {4, 0}}, {}};
  EXPECT_EQ(breakpoints(cubic, 0.0, 1.0), std::vector<double>{0.5});
  EXPECT_TRUE(breakpoints(cubic, 0.6, 1.0).empty());
  EXPECT_TRUE(breakpoints(CircleCurve{}, 0.0, 6.0).empty());
}

}  // namespace
}  // namespace mm
