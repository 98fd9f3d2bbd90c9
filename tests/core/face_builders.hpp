#pragma once
// Building blocks for hand-made test faces.
#include <algorithm>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm::test {

inline BoundaryEdge line(Vec2 a, Vec2 b) {
  const double length = distance(a, b);
  return BoundaryEdge{LineCurve{a, (b - a) / length}, 0.0, length, 0, {}, {}};
}

// Closed polygon through the points, in their order.
inline std::vector<BoundaryEdge> polygon(const std::vector<Vec2>& pts) {
  std::vector<BoundaryEdge> edges;
  for (std::size_t i = 0; i < pts.size(); ++i) edges.push_back(line(pts[i], pts[(i + 1) % pts.size()]));
  return edges;
}

// Full circle; sense +1 counter-clockwise (an outer loop), -1 clockwise (a hole).
inline BoundaryEdge full_circle(Vec2 center, double radius, int sense) {
  return BoundaryEdge{CircleCurve{center, radius, 0.0, sense}, 0.0, 2 * kPi, 0, {}, {}};
}

// Circular arc from a to b bulging by `bulge` to the right of a->b (outwards
// for a counter-clockwise loop); a negative bulge goes inwards.
inline BoundaryEdge arc(Vec2 a, Vec2 b, double bulge) {
  const Vec2 m = 0.5 * (a + b), right = -1.0 * perp(normalized(b - a));
  const double c = 0.5 * distance(a, b), h = std::abs(bulge);
  const double radius = (c * c + h * h) / (2 * h);
  const Vec2 side = bulge > 0 ? right : -1.0 * right;
  const Vec2 center = m + (h - radius) * side;
  const Vec2 ra = a - center, rb = b - center;
  // Turn from a to b through the bulge point m + h * side.
  const double sweep = signed_angle(ra, rb);
  const Vec2 apex = m + h * side - center;
  const int sense = signed_angle(ra, apex) * sweep > 0 && std::abs(signed_angle(ra, apex)) < std::abs(sweep)
                        ? (sweep > 0 ? 1 : -1)
                        : (sweep > 0 ? -1 : 1);
  const double span = sense * sweep > 0 ? std::abs(sweep) : 2 * kPi - std::abs(sweep);
  return BoundaryEdge{CircleCurve{center, radius, std::atan2(ra.y, ra.x), sense}, 0.0, span, 0, {}, {}};
}

inline FaceModel face(std::vector<std::vector<BoundaryEdge>> loops, const std::string& name = "face") {
  RawFace raw;
  raw.name = name;
  raw.loops = std::move(loops);
  return build_face_model(raw);
}

// Star-shaped polygons, some sides replaced by arcs bulging in or out, with up
// to two round holes: a face the property checks must hold on.
inline FaceModel random_face(std::mt19937& rng, int number) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int sides = 3 + static_cast<int>(unit(rng) * 8);
  std::vector<double> angles;
  for (int i = 0; i < sides; ++i) angles.push_back((i + 0.15 + 0.7 * unit(rng)) * 2 * kPi / sides);
  std::vector<Vec2> pts;
  for (double a : angles) {
    const double r = 0.7 + 0.3 * unit(rng);
    pts.push_back({r * std::cos(a), r * std::sin(a)});
  }
  std::vector<BoundaryEdge> outer;
  for (int i = 0; i < sides; ++i) {
    const Vec2 a = pts[i], b = pts[(i + 1) % sides];
    const double kind = unit(rng);
    if (kind < 0.5) {
      outer.push_back(line(a, b));
    } else {
      const double chord = distance(a, b);
      const double bulge = (kind < 0.8 ? 0.3 : -0.08) * chord * (0.2 + 0.8 * unit(rng));
      outer.push_back(arc(a, b, bulge));
    }
  }
  std::vector<std::vector<BoundaryEdge>> loops{outer};
  const int holes = static_cast<int>(unit(rng) * 3);
  for (int h = 0; h < holes; ++h) {
    const Vec2 c{(h == 0 ? -0.22 : 0.22) + 0.05 * (unit(rng) - 0.5), 0.1 * (unit(rng) - 0.5)};
    loops.push_back({full_circle(c, 0.05 + 0.1 * unit(rng), -1)});
  }
  return face(loops, "random face " + std::to_string(number));
}

// A rectangle with slanted notches cut into its top and bottom sides (concave
// corners of many angles) and up to two round holes.
inline FaceModel random_notched_face(std::mt19937& rng, int number) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double width = 3.0, height = 1.0 + unit(rng);
  const auto notches = [&](bool top) {
    std::vector<Vec2> pts;
    const int count = 1 + static_cast<int>(unit(rng) * 3);
    const double slot = width / count;
    for (int i = 0; i < count; ++i) {
      const double x1 = slot * (i + 0.15 + 0.2 * unit(rng)), x2 = slot * (i + 0.55 + 0.3 * unit(rng));
      const double depth = (0.1 + 0.3 * unit(rng)) * height, s1 = 0.3 * (unit(rng) - 0.5) * (x2 - x1),
                   s2 = 0.3 * (unit(rng) - 0.5) * (x2 - x1);
      const double y0 = top ? height : 0.0, y1 = top ? height - depth : depth;
      pts.insert(pts.end(), {{x1, y0}, {x1 + s1, y1}, {x2 + s2, y1}, {x2, y0}});
    }
    if (top) std::reverse(pts.begin(), pts.end());
    return pts;
  };
  std::vector<Vec2> outline{{0, 0}};
  for (Vec2 p : notches(false)) outline.push_back(p);
  outline.push_back({width, 0});
  outline.push_back({width, height});
  for (Vec2 p : notches(true)) outline.push_back(p);
  outline.push_back({0, height});
  std::vector<std::vector<BoundaryEdge>> loops{polygon(outline)};
  const int holes = static_cast<int>(unit(rng) * 3);
  for (int h = 0; h < holes; ++h) {
    const Vec2 c{0.4 + 2.2 * unit(rng), 0.5 * height + 0.1 * (unit(rng) - 0.5)};
    loops.push_back({full_circle(c, 0.03 + 0.05 * unit(rng), -1)});
  }
  return face(loops, "random notched face " + std::to_string(number));
}

// The random faces of the meshing test and of mesh_census, in one order:
// every third a notched face, the others random faces; meshed at 0.08 and
// 0.03 of the diagonal in turn.
inline FaceModel random_meshing_face(std::mt19937& rng, int number) {
  return number % 3 == 2 ? random_notched_face(rng, number) : random_face(rng, number);
}
inline double random_meshing_size(const FaceModel& face, int number) {
  return (number % 2 ? 0.03 : 0.08) * face.size;
}

// The mesh census's generator seed (tests/core/mesh_census.cpp).
constexpr unsigned kCensusSeed = 20261123;

// The census's faces of the given numbers, with their numbers, in order: the
// generator run from its seed up to the largest (faces it refuses left out).
inline std::vector<std::pair<int, FaceModel>> census_faces(const std::vector<int>& numbers) {
  std::mt19937 rng(kCensusSeed);
  const int last = numbers.empty() ? -1 : *std::max_element(numbers.begin(), numbers.end());
  std::vector<std::pair<int, FaceModel>> faces;
  for (int number = 0; number <= last; ++number) {
    try {
      FaceModel face = random_meshing_face(rng, number);
      if (std::find(numbers.begin(), numbers.end(), number) != numbers.end())
        faces.emplace_back(number, std::move(face));
    } catch (const InputError&) {
    }
  }
  return faces;
}

}  // namespace mm::test
