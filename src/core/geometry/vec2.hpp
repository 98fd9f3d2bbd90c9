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
inline double norm(Vec2 a) {
  return std::hypot(a.x, a.y);
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
// Signed angle turning a into b, in (-pi, pi].
inline double signed_angle(Vec2 a, Vec2 b) {
  return std::atan2(cross(a, b), dot(a, b));
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace mm
