#include "quality/quad_measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mm {
namespace {

constexpr double kHuge = std::numeric_limits<double>::max();
constexpr double kTiny = std::numeric_limits<double>::min();

}  // namespace

QuadMeasures measure_quad(const std::array<Vec2, 4>& p) {
  QuadMeasures m;
  // Side i runs from corner i to corner i + 1.
  const std::array<Vec2, 4> side{p[1] - p[0], p[2] - p[1], p[3] - p[2], p[0] - p[3]};
  std::array<double, 4> length2{}, length{};
  for (int i = 0; i < 4; ++i) length2[i] = dot(side[i], side[i]), length[i] = std::sqrt(length2[i]);
  // Corner i lies between side i - 1 (arriving) and side i (leaving): its
  // Jacobian is the area their two vectors span.
  std::array<double, 4> corner_area{};
  for (int i = 0; i < 4; ++i) corner_area[i] = cross(side[(i + 3) % 4], side[i]);

  m.area = 0.5 * (cross(p[0], p[1]) + cross(p[1], p[2]) + cross(p[2], p[3]) + cross(p[3], p[0]));
  m.jacobian = *std::min_element(corner_area.begin(), corner_area.end());

  const double shortest2 = *std::min_element(length2.begin(), length2.end());
  const double longest2 = *std::max_element(length2.begin(), length2.end());
  const bool collapsed_side = shortest2 <= kTiny;

  m.scaled_jacobian = kHuge;
  m.shape = kHuge;
  m.condition = 0.0;
  for (int i = 0; i < 4; ++i) {
    const int before = (i + 3) % 4;
    m.scaled_jacobian = std::min(m.scaled_jacobian, corner_area[i] / (length[i] * length[before]));
    m.shape = std::min(m.shape, corner_area[i] / (length2[i] + length2[before]));
    const double condition = corner_area[i] < kTiny ? kHuge : 0.5 * (length2[i] + length2[before]) / corner_area[i];
    m.condition = std::max(m.condition, condition);
  }
  if (collapsed_side) m.scaled_jacobian = 0.0, m.shape = 0.0;
  m.shape = std::max(0.0, 2.0 * m.shape);
  if (m.shape < kTiny) m.shape = 0.0;

  m.edge_ratio = shortest2 < kTiny ? kHuge : std::sqrt(longest2 / shortest2);

  const double area_sum = std::abs(cross(side[0], side[1])) + std::abs(cross(side[2], side[3]));
  const double perimeter = length[0] + length[1] + length[2] + length[3];
  m.aspect_ratio = area_sum < kTiny ? kHuge : 0.5 * std::sqrt(longest2) * perimeter / area_sum;

  // The two principal axes join the midpoints of opposite sides (times 2);
  // the cross derivative is what keeps the quad from being a parallelogram.
  const Vec2 axis_1 = p[1] + p[2] - p[3] - p[0];
  const Vec2 axis_2 = p[2] + p[3] - p[0] - p[1];
  const Vec2 cross_derivative = p[0] + p[2] - p[1] - p[3];
  const double axis_1_length = norm(axis_1), axis_2_length = norm(axis_2);
  m.skew = axis_1_length < kTiny || axis_2_length < kTiny
               ? 0.0
               : std::abs(dot(axis_1, axis_2)) / (axis_1_length * axis_2_length);
  const double shorter_axis = std::min(axis_1_length, axis_2_length);
  m.taper = shorter_axis < kTiny ? kHuge : norm(cross_derivative) / shorter_axis;

  const Vec2 diagonal_1 = p[2] - p[0], diagonal_2 = p[3] - p[1];
  const double diagonal2 = std::max(dot(diagonal_1, diagonal_1), dot(diagonal_2, diagonal_2));
  m.stretch = diagonal2 < kTiny ? kHuge : std::sqrt(2.0 * shortest2 / diagonal2);
  return m;
}

double jacobian_ratio(const std::array<Vec2, 8>& p) {
  // Serendipity shape functions' derivatives at (xi, eta), nodes at the
  // reference corners (-1,-1), (1,-1), (1,1), (-1,1), then mid-sides.
  constexpr double kXi[4] = {-1.0, 1.0, 1.0, -1.0};
  constexpr double kEta[4] = {-1.0, -1.0, 1.0, 1.0};
  const double g = std::sqrt(0.6);
  const double gauss[3] = {-g, 0.0, g};
  double least = kHuge, most = -kHuge;
  for (double xi : gauss) {
    for (double eta : gauss) {
      Vec2 d_xi{}, d_eta{};
      for (int i = 0; i < 4; ++i) {
        const double a = kXi[i], b = kEta[i];
        // N = (1 + a xi)(1 + b eta)(a xi + b eta - 1) / 4
        const double n_xi = 0.25 * a * (1.0 + b * eta) * (2.0 * a * xi + b * eta);
        const double n_eta = 0.25 * b * (1.0 + a * xi) * (a * xi + 2.0 * b * eta);
        d_xi = d_xi + n_xi * p[i];
        d_eta = d_eta + n_eta * p[i];
      }
      // Mid-side nodes: sides 0 and 2 at eta = -1, +1 (N = (1 - xi^2)(1 + b eta) / 2),
      // sides 1 and 3 at xi = +1, -1 (N = (1 + a xi)(1 - eta^2) / 2).
      for (int s : {0, 2}) {
        const double b = s == 0 ? -1.0 : 1.0;
        d_xi = d_xi + (-xi * (1.0 + b * eta)) * p[4 + s];
        d_eta = d_eta + (0.5 * b * (1.0 - xi * xi)) * p[4 + s];
      }
      for (int s : {1, 3}) {
        const double a = s == 1 ? 1.0 : -1.0;
        d_xi = d_xi + (0.5 * a * (1.0 - eta * eta)) * p[4 + s];
        d_eta = d_eta + (-eta * (1.0 + a * xi)) * p[4 + s];
      }
      const double det = cross(d_xi, d_eta);
      least = std::min(least, det);
      most = std::max(most, det);
    }
  }
  return most > 0.0 ? least / most : -1.0;  // folded everywhere
}

}  // namespace mm
