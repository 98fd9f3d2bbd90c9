#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>
#include <stdexcept>

#include "face_builders.hpp"
#include "meshing/smoothing.hpp"
#include "quality/quad_measures.hpp"

namespace mm {
namespace {

using test::arc;
using test::face;
using test::line;
using test::polygon;

// Verdict's shape of a quad (quality/quad_measures, checked against VTK's
// vtkMeshQuality), independent of the smoother's own arithmetic.
double quad_shape(const QuadMesh& mesh, int q) {
  const auto& quad = mesh.quads[q];
  return measure_quad({mesh.nodes[quad[0]], mesh.nodes[quad[1]], mesh.nodes[quad[2]], mesh.nodes[quad[3]]}).shape;
}

double min_shape(const QuadMesh& mesh) {
  double worst = 1.0;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) worst = std::min(worst, quad_shape(mesh, static_cast<int>(q)));
  return worst;
}

double mean_shape(const QuadMesh& mesh) {
  double sum = 0.0;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) sum += quad_shape(mesh, static_cast<int>(q));
  return sum / mesh.quads.size();
}

int inverted(const QuadMesh& mesh) {
  int count = 0;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) count += quad_shape(mesh, static_cast<int>(q)) <= 0.0;
  return count;
}

// The place of a point on the face's boundary (found on lines and circles),
// the node put exactly on its curve; a face vertex is a corner at the start
// of the edge it begins.
NodePlace locate(const FaceModel& f, Vec2& p) {
  for (std::size_t l = 0; l < f.loops.size(); ++l) {
    for (std::size_t e = 0; e < f.loops[l].edges.size(); ++e) {
      const BoundaryEdge& edge = f.loops[l].edges[e];
      NodePlace place{static_cast<int>(l), static_cast<int>(e), edge.t_start, false, 2};
      if (distance(edge_point(edge, edge.t_start).p, p) < 1e-9) {
        for (const Corner& corner : f.corners) place.face_corner |= distance(corner.position, p) < 1e-9;
        p = edge_point(edge, place.t).p;
        return place;
      }
      double t = 0.0;
      if (const auto* segment = std::get_if<LineCurve>(&edge.curve)) {
        t = dot(p - segment->origin, segment->direction);
      } else if (const auto* circle = std::get_if<CircleCurve>(&edge.curve)) {
        t = circle->sense * (std::atan2(p.y - circle->center.y, p.x - circle->center.x) - circle->start_angle);
        t = std::fmod(std::fmod(t, 2 * kPi) + 2 * kPi, 2 * kPi);
      }
      const double lo = std::min(edge.t_start, edge.t_end), hi = std::max(edge.t_start, edge.t_end);
      if (t < lo || t > hi || distance(edge_point(edge, t).p, p) > 1e-9) continue;
      place.t = t;
      p = edge_point(edge, t).p;
      return place;
    }
  }
  return NodePlace{};
}

// A structured (nx + 1) x (ny + 1) grid; node (i, j) at position(i, j),
// counter-clockwise quads when i runs to the right of j.
QuadMesh grid_mesh(const FaceModel& f, int nx, int ny, const std::function<Vec2(int, int)>& position) {
  QuadMesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      Vec2 p = position(i, j);
      const bool boundary = i == 0 || j == 0 || i == nx || j == ny;
      mesh.places.push_back(boundary ? locate(f, p) : NodePlace{});
      mesh.nodes.push_back(p);
    }
  }
  const auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      mesh.block_of_quad.push_back(0);
    }
  return mesh;
}

FaceModel unit_square() {
  return face({polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})}, "square");
}

QuadMesh perturbed_square_grid(const FaceModel& square, int n, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shake(-amplitude / n, amplitude / n);
  return grid_mesh(square, n, n, [&](int i, int j) {
    const Vec2 p{double(i) / n, double(j) / n};
    if (i == 0 || j == 0 || i == n || j == n) return p;
    return p + Vec2{shake(rng), shake(rng)};
  });
}

// A quarter of the annulus 1 < r < 2 in the first quadrant.
FaceModel quarter_annulus() {
  const double s = std::sqrt(0.5);
  return face(
      {{line({1, 0}, {2, 0}), arc({2, 0}, {0, 2}, 2 - 2 * s), line({0, 2}, {0, 1}), arc({0, 1}, {1, 0}, -(1 - s))}},
      "quarter annulus");
}

// Polar grid on the quarter annulus: i along the radius, j along the angle;
// jitter shifts boundary nodes along their side by up to that part of a spacing.
QuadMesh polar_grid(const FaceModel& f, int nr, int na, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-jitter, jitter);
  return grid_mesh(f, nr, na, [&](int i, int j) {
    double r = 1.0 + double(i) / nr, a = 0.5 * kPi * j / na;
    const bool corner = (i == 0 || i == nr) && (j == 0 || j == na);
    if (!corner && (i == 0 || i == nr)) a += 0.5 * kPi * shift(rng) / na;
    if (!corner && (j == 0 || j == na)) r += shift(rng) / nr;
    return Vec2{r * std::cos(a), r * std::sin(a)};
  });
}

// A regular polygon cut into one quad per side around a centre node (of
// valence `sides`), each quad then split into k x k quads bilinearly; the
// centre sits off the middle by `offset`.
QuadMesh fan_mesh(const FaceModel& f, const std::vector<Vec2>& corners, Vec2 centre, int k) {
  QuadMesh mesh;
  const auto add = [&](Vec2 p, bool boundary) {
    mesh.places.push_back(boundary ? locate(f, p) : NodePlace{});
    mesh.nodes.push_back(p);
    return static_cast<int>(mesh.nodes.size()) - 1;
  };
  // Every quad gets its own nodes, then equal points are merged.
  const int sides = static_cast<int>(corners.size());
  for (int s = 0; s < sides; ++s) {
    const Vec2 c = corners[s], next = 0.5 * (corners[s] + corners[(s + 1) % sides]);
    const Vec2 prev = 0.5 * (corners[s] + corners[(s + sides - 1) % sides]);
    const Vec2 v[4] = {c, next, centre, prev};  // counter-clockwise
    std::vector<int> ids;
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) {
        const double u = double(i) / k, w = double(j) / k;
        const Vec2 p = (1 - u) * (1 - w) * v[0] + u * (1 - w) * v[1] + u * w * v[2] + (1 - u) * w * v[3];
        int id = -1;
        for (std::size_t m = 0; m < mesh.nodes.size(); ++m)
          if (distance(mesh.nodes[m], p) < 1e-9) id = static_cast<int>(m);
        ids.push_back(id >= 0 ? id : add(p, j == 0 || i == 0));
      }
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const auto at = [&](int a, int b) { return ids[b * (k + 1) + a]; };
        mesh.quads.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        mesh.block_of_quad.push_back(s);
      }
  }
  return mesh;
}

TEST(Smoothing, PerturbedGridGetsBetterWorstAndMean) {
  const FaceModel square = unit_square();
  QuadMesh mesh = perturbed_square_grid(square, 12, 0.3, 7);
  const double min_before = min_shape(mesh), mean_before = mean_shape(mesh);
  const SmoothingResult result = smooth_mesh(square, mesh, {});
  EXPECT_GT(min_shape(mesh), min_before + 0.1);
  EXPECT_GT(mean_shape(mesh), mean_before + 0.02);
  EXPECT_NEAR(result.min_shape_before, min_before, 1e-12);
  EXPECT_NEAR(result.min_shape_after, min_shape(mesh), 1e-12);
  EXPECT_EQ(result.inverted_after, 0);
  EXPECT_GE(result.sweeps, 1);
  EXPECT_LE(result.sweeps, SmoothingOptions{}.max_sweeps);
}

TEST(Smoothing, RegularGridsStayPut) {
  const FaceModel square = unit_square();
  // Uniform and graded tensor grids are already as good as they get.
  for (const double power : {1.0, 1.7}) {
    QuadMesh mesh = grid_mesh(square, 9, 7, [&](int i, int j) { return Vec2{std::pow(i / 9.0, power), j / 7.0}; });
    const QuadMesh original = mesh;
    smooth_mesh(square, mesh, {});
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n) EXPECT_LT(distance(mesh.nodes[n], original.nodes[n]), 1e-12);
  }
  // A polar grid is not quite a fixed point, but hardly moves.
  const FaceModel sector = quarter_annulus();
  QuadMesh mesh = polar_grid(sector, 6, 12, 0.0, 1);
  const QuadMesh original = mesh;
  const double min_before = min_shape(mesh);
  smooth_mesh(sector, mesh, {});
  EXPECT_GE(min_shape(mesh), min_before);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) EXPECT_LT(distance(mesh.nodes[n], original.nodes[n]), 0.02);
}

TEST(Smoothing, NeverLowersTheWorstElement) {
  const FaceModel square = unit_square(), sector = quarter_annulus();
  for (unsigned seed = 0; seed < 50; ++seed) {
    QuadMesh mesh =
        seed % 2 ? perturbed_square_grid(square, 8 + seed % 5, 0.3, seed) : polar_grid(sector, 5, 9, 0.4, seed);
    ASSERT_EQ(inverted(mesh), 0) << "seed " << seed;
    const double before = min_shape(mesh);
    const SmoothingResult result = smooth_mesh(seed % 2 ? square : sector, mesh, {});
    EXPECT_GE(min_shape(mesh), before) << "seed " << seed;
    EXPECT_GE(result.min_shape_after, result.min_shape_before) << "seed " << seed;
    EXPECT_EQ(result.inverted_after, 0) << "seed " << seed;
  }
}

TEST(Smoothing, BoundaryNodesSlideAlongTheirExactCurves) {
  const FaceModel sector = quarter_annulus();
  QuadMesh mesh = polar_grid(sector, 6, 12, 0.45, 3);
  const QuadMesh original = mesh;
  const double before = min_shape(mesh);
  smooth_mesh(sector, mesh, {});
  EXPECT_GT(min_shape(mesh), before + 0.05);
  int moved = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const NodePlace &place = mesh.places[n], &was = original.places[n];
    ASSERT_EQ(place.loop, was.loop);
    ASSERT_EQ(place.edge, was.edge);
    if (place.loop < 0) continue;
    if (place.face_corner) {
      EXPECT_EQ(mesh.nodes[n].x, original.nodes[n].x);
      EXPECT_EQ(mesh.nodes[n].y, original.nodes[n].y);
      continue;
    }
    moved += distance(mesh.nodes[n], original.nodes[n]) > 1e-3;
    const BoundaryEdge& edge = sector.loops[place.loop].edges[place.edge];
    EXPECT_LT(distance(mesh.nodes[n], edge_point(edge, place.t).p), 1e-14);
    if (const auto* circle = std::get_if<CircleCurve>(&edge.curve))
      EXPECT_NEAR(distance(mesh.nodes[n], circle->center), circle->radius, 1e-12 * circle->radius);
    else
      EXPECT_NEAR(mesh.nodes[n].x * mesh.nodes[n].y, 0.0, 1e-14);  // on an axis
  }
  EXPECT_GT(moved, 10);
  // Along each side the nodes keep their order in the edge's direction.
  const auto check_order = [&](const std::vector<int>& side) {
    for (std::size_t k = 1; k + 1 < side.size(); ++k) {
      const NodePlace& place = mesh.places[side[k]];
      const BoundaryEdge& edge = sector.loops[0].edges[place.edge];
      const auto fraction = [&](int n) {
        const NodePlace& p = mesh.places[n];
        if (p.edge != place.edge) return n == side.front() ? 0.0 : 1.0;
        return (p.t - edge.t_start) / (edge.t_end - edge.t_start);
      };
      EXPECT_LT(fraction(side[k - 1]), fraction(side[k]));
      EXPECT_LT(fraction(side[k]), fraction(side[k + 1]));
    }
  };
  const int nr = 6, na = 12;
  const auto id = [&](int i, int j) { return j * (nr + 1) + i; };
  std::vector<int> bottom, outer, left, inner;
  for (int i = 0; i <= nr; ++i) bottom.push_back(id(i, 0)), left.push_back(id(nr - i, na));
  for (int j = 0; j <= na; ++j) outer.push_back(id(nr, j)), inner.push_back(id(0, na - j));
  for (const auto& side : {bottom, outer, left, inner}) check_order(side);
}

// The joint search (SmoothingOptions::joint_search_only) on meshes the
// node search has settled: squares whose bottom side's nodes crowd to the
// right and top side's to the left (both sides fixed, as a shared edge's
// are; the left and right sides' nodes slide), so the lattice shears over
// every row. It never lowers the worst element, leaves none inverted,
// keeps boundary nodes on their curves, in order, and the corners in
// place. (Where it lifts the worst element, lattices sheared beside
// singularities of real faces, MeshReference tests it.)
TEST(Smoothing, JointSearchKeepsTheNodeSearchesBounds) {
  const FaceModel square = unit_square();
  int searched = 0;  // meshes poor enough for the search
  for (const int n : {8, 12, 16})
    for (const double power : {3.0, 4.0, 5.0, 6.0, 8.0}) {
      QuadMesh mesh = grid_mesh(square, n, n, [&](int i, int j) {
        const double u = double(i) / n, v = double(j) / n;
        return Vec2{(1 - v) * (1 - std::pow(1 - u, power)) + v * std::pow(u, power), v};
      });
      SmoothingOptions options;
      for (int i = 0; i <= n; ++i) options.fixed.push_back(i), options.fixed.push_back(n * (n + 1) + i);
      smooth_mesh(square, mesh, options);
      const QuadMesh settled = mesh;
      const double before = min_shape(mesh);
      options.joint_search_only = true;
      const SmoothingResult r = smooth_mesh(square, mesh, options);
      searched += before < 0.75;
      EXPECT_GE(min_shape(mesh), before) << n << " " << power;
      EXPECT_NEAR(r.min_shape_after, min_shape(mesh), 1e-12);
      EXPECT_EQ(r.inverted_after, 0) << n << " " << power;
      for (std::size_t k = 0; k < mesh.nodes.size(); ++k) {
        const NodePlace& place = mesh.places[k];
        if (place.face_corner) {
          EXPECT_EQ(distance(mesh.nodes[k], settled.nodes[k]), 0.0);
        }
        if (place.loop < 0) continue;
        const BoundaryEdge& edge = square.loops[place.loop].edges[place.edge];
        EXPECT_LT(distance(mesh.nodes[k], edge_point(edge, place.t).p), 1e-12);
      }
      // The left and right sides' nodes keep their order up the side, and
      // each interval there at least a quarter of its length before.
      for (int j = 1; j <= n; ++j)
        for (const int column : {0, n}) {
          const int below = (j - 1) * (n + 1) + column, above = j * (n + 1) + column;
          EXPECT_LT(mesh.nodes[below].y, mesh.nodes[above].y);
          EXPECT_GE(distance(mesh.nodes[below], mesh.nodes[above]),
                    0.25 * distance(settled.nodes[below], settled.nodes[above]) * (1 - 1e-9))
              << n << " " << power << " " << column << " " << j;
        }
    }
  EXPECT_GT(searched, 5);
}

TEST(Smoothing, FoldedQuadIsUntangled) {
  const FaceModel square = unit_square();
  const int n = 6;
  QuadMesh mesh = grid_mesh(square, n, n, [&](int i, int j) { return Vec2{double(i) / n, double(j) / n}; });
  // Drag node (2, 2) past its right neighbour (3, 2).
  mesh.nodes[2 * (n + 1) + 2] = Vec2{3.3 / n, 2.1 / n};
  ASSERT_GT(inverted(mesh), 0);
  const SmoothingResult result = smooth_mesh(square, mesh, {});
  EXPECT_GT(result.inverted_before, 0);
  EXPECT_EQ(result.inverted_after, 0);
  EXPECT_EQ(inverted(mesh), 0);
  EXPECT_GT(result.min_shape_after, 0.5);
}

TEST(Smoothing, ReflexBlockCornerFoldIsUntangled) {
  // The valence-3 centre of a triangle placed past the midline makes one
  // block non-convex, so its transfinite grid folds near the centre.
  std::vector<Vec2> corners;
  for (int s = 0; s < 3; ++s) corners.push_back({std::cos(2 * kPi * s / 3), std::sin(2 * kPi * s / 3)});
  const FaceModel triangle = face({polygon(corners)}, "triangle");
  QuadMesh mesh = fan_mesh(triangle, corners, 0.3 * corners[0], 10);
  ASSERT_GT(inverted(mesh), 0);
  const SmoothingResult result = smooth_mesh(triangle, mesh, {});
  EXPECT_GT(result.inverted_before, 0);
  EXPECT_EQ(result.inverted_after, 0);
  EXPECT_EQ(inverted(mesh), 0);
}

TEST(Smoothing, IrregularNodesImproveTheirWorstElement) {
  for (const int sides : {3, 5}) {
    std::vector<Vec2> corners;
    for (int s = 0; s < sides; ++s)
      corners.push_back({std::cos(2 * kPi * s / sides + 0.3), std::sin(2 * kPi * s / sides + 0.3)});
    const FaceModel polygon_face = face({polygon(corners)}, "polygon");
    // The centre of valence `sides` starts well off the middle.
    QuadMesh mesh = fan_mesh(polygon_face, corners, 0.45 * corners[0], 4);
    const double before = min_shape(mesh), mean_before = mean_shape(mesh);
    const SmoothingResult result = smooth_mesh(polygon_face, mesh, {});
    EXPECT_GT(min_shape(mesh), before + 0.05) << sides << " sides";
    EXPECT_GT(mean_shape(mesh), mean_before) << sides << " sides";
    EXPECT_EQ(result.inverted_after, 0);
  }
}

TEST(Smoothing, RejectsOrderTwoAndBrokenMeshes) {
  const FaceModel square = unit_square();
  QuadMesh mesh = perturbed_square_grid(square, 4, 0.2, 1);
  QuadMesh order2 = mesh;
  order2.midside.assign(order2.quads.size(), {0, 0, 0, 0});
  EXPECT_THROW(smooth_mesh(square, order2, {}), std::invalid_argument);
  QuadMesh bad_node = mesh;
  bad_node.quads[0][2] = 1000;
  EXPECT_THROW(smooth_mesh(square, bad_node, {}), std::invalid_argument);
  QuadMesh bad_place = mesh;
  bad_place.places[0].edge = 9;
  EXPECT_THROW(smooth_mesh(square, bad_place, {}), std::invalid_argument);
  QuadMesh interior_on_boundary = mesh;
  interior_on_boundary.places[1] = NodePlace{};
  EXPECT_THROW(smooth_mesh(square, interior_on_boundary, {}), std::invalid_argument);
}

}  // namespace
}  // namespace mm
