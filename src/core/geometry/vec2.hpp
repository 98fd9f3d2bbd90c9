#pragma once
// Plain 2-D vector used throughout the core.
#include <cmath>

namespace mm {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator-(Vec2 a) {
  return {-a.x, -a.y};
}
inline Vec2 operator*(double s, Vec2 a) {
  return {s * a.x, s * a.y};
}
inline Vec2 operator*(Vec2 a, double s) {
  return {s * a.x, s * a.y};
}
inline Vec2 operator/(Vec2 a, double s) {
  return {a.x / s, a.y / s};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
// std::hypot as glibc (2.35 on) computes it, inlined for components between
// 2^-500 and 2^500: the rounded sqrt(x^2 + y^2) with glibc's one correction
// step, so the same bits (test Vec2.NormIsTheLibrarysHypotBitForBit) without
// a call and its range checks; it is the hottest call of the medial axis'
// self-check. Zero, tiny, huge or NaN components go to the library.
inline double norm(Vec2 a) {
  const double ax = std::fabs(a.x), ay = std::fabs(a.y);
  const double big = ax < ay ? ay : ax, small = ax < ay ? ax : ay;
  if (!(big <= 0x1p500 && small >= 0x1p-500)) return std::hypot(a.x, a.y);
  if (small <= big * 0x1p-54) return big + small;
  double h = std::sqrt(big * big + small * small);
  double t1, t2;
  if (h <= 2.0 * small) {
    const double delta = h - small;
    t1 = big * (2.0 * delta - big);
    t2 = (delta - 2.0 * (big - small)) * delta;
  } else {
    const double delta = h - big;
    t1 = 2.0 * delta * (big - 2.0 * small);
    t2 = (4.0 * delta - small) * small + delta * delta;
  }
  return h - (t1 + t2) / (2.0 * h);
}
inline double distance(Vec2 a, Vec2 b) {
  return norm(a - b);
}
inline Vec2 perp(Vec2 a) {
  return {-a.y, a.x};
}  // turned +90 degrees
inline Vec2 normalized(Vec2 a) {
  const double n = norm(a);
  return n > 0.0 ? a / n : a;
}
// v turned counter-clockwise by `angle` radians.
inline Vec2 rotated(Vec2 v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
// Signed angle turning a into b, in (-pi, pi].
inline double signed_angle(Vec2 a, Vec2 b) {
  return std::atan2(cross(a, b), dot(a, b));
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace mm
