// norm() inlines glibc's hypot: it must give the library's bits everywhere,
// or meshes would change with the last bit of a distance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "geometry/vec2.hpp"

namespace mm {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

TEST(Vec2, NormIsTheLibrarysHypotBitForBit) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-40.0, 40.0);
  int mismatches = 0;
  for (int i = 0; i < 2'000'000; ++i) {
    const double x = unit(random) * std::pow(10.0, i % 3 == 0 ? exponent(random) : 0.0);
    double y = unit(random) * std::pow(10.0, i % 3 == 0 ? exponent(random) : 0.0);
    if (i % 5 == 1) y = x * (1.0 + 1e-9 * unit(random));          // nearly equal sides
    if (i % 7 == 2) y = x * std::ldexp(1.0 + unit(random), -54);  // at the small-side cut
    if (!same_bits(norm({x, y}), std::hypot(x, y))) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const double x : {0.0, -0.0, 1e-320, 1e-160, 3.0, 1e160, 1e300, inf, -inf, nan}) {
    for (const double y : {0.0, 4e-320, 2e-155, -4.0, 7e155, 1e308, inf, nan})
      EXPECT_TRUE(same_bits(norm({x, y}), std::hypot(x, y))) << x << " " << y;
  }
}

}  // namespace
}  // namespace mm
