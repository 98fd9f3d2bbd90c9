#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "boundary/face_model.hpp"
#include "quality/quad_measures.hpp"
#include "quality/quality.hpp"
#include "report/mesh_files.hpp"

namespace mm {
namespace {

double degrees(double d) {
  return d * kPi / 180.0;
}

// A structured nx by ny grid over [0, width] x [0, height]; boundary nodes
// expect 1 element at the four corners and 2 elsewhere.
QuadMesh grid(int nx, int ny, double width, double height) {
  QuadMesh mesh;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.nodes.push_back({width * i / nx, height * j / ny});
      NodePlace place;
      const bool on_x = i == 0 || i == nx;
      const bool on_y = j == 0 || j == ny;
      if (on_x || on_y) {
        place.loop = 0;
        place.corner_elements = on_x && on_y ? 1 : 2;
        place.face_corner = on_x && on_y;
      }
      mesh.places.push_back(place);
    }
  }
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      mesh.block_of_quad.push_back(0);
    }
  }
  return mesh;
}

// A polygon of m corners split into m quads around a centre node: corner i,
// mid-side i, centre, mid-side i - 1. The centre's valence is m.
void add_fan(QuadMesh& mesh, Vec2 centre, int m) {
  const int first = static_cast<int>(mesh.nodes.size());
  std::vector<Vec2> corners;
  for (int i = 0; i < m; ++i) {
    const double a = 2.0 * kPi * i / m;
    corners.push_back(centre + Vec2{std::cos(a), std::sin(a)});
  }
  for (int i = 0; i < m; ++i) {
    mesh.nodes.push_back(corners[i]);
    mesh.places.push_back({0, i, 0.0, true, 1});
    mesh.nodes.push_back(0.5 * (corners[i] + corners[(i + 1) % m]));
    mesh.places.push_back({0, i, 0.5, false, 2});
  }
  const int centre_id = static_cast<int>(mesh.nodes.size());
  mesh.nodes.push_back(centre);
  mesh.places.push_back({});
  for (int i = 0; i < m; ++i) {
    const int corner = first + 2 * i;
    const int mid_after = corner + 1;
    const int mid_before = first + 2 * ((i + m - 1) % m) + 1;
    mesh.quads.push_back({corner, mid_after, centre_id, mid_before});
  }
}

TEST(Quality, UnitSquareIsPerfect) {
  EXPECT_DOUBLE_EQ(scaled_jacobian({0, 0}, {1, 0}, {1, 1}, {0, 1}), 1.0);
  const QualityReport r = measure_quality(grid(1, 1, 1.0, 1.0));
  EXPECT_EQ(r.quads, 1);
  EXPECT_EQ(r.nodes, 4);
  EXPECT_EQ(r.triangles, 0);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_DOUBLE_EQ(r.min_scaled_jacobian, 1.0);
  EXPECT_DOUBLE_EQ(r.mean_scaled_jacobian, 1.0);
  EXPECT_NEAR(r.min_angle, 90.0, 1e-12);
  EXPECT_NEAR(r.max_angle, 90.0, 1e-12);
  EXPECT_EQ(r.worst_element, 0);
  EXPECT_NEAR(r.area, 1.0, 1e-15);
  EXPECT_TRUE(r.irregular_interior.empty());
  EXPECT_TRUE(r.irregular_boundary.empty());
}

TEST(Quality, RhombusOfSixtyDegrees) {
  const Vec2 a{0, 0}, b{2, 0}, d{2 * std::cos(degrees(60)), 2 * std::sin(degrees(60))};
  const Vec2 c = b + d;
  EXPECT_NEAR(scaled_jacobian(a, b, c, d), std::sin(degrees(60)), 1e-14);
  QuadMesh mesh;
  mesh.nodes = {a, b, c, d};
  mesh.places.resize(4);
  mesh.quads = {{0, 1, 2, 3}};
  const QualityReport r = measure_quality(mesh);
  EXPECT_NEAR(r.min_scaled_jacobian, std::sin(degrees(60)), 1e-14);
  EXPECT_NEAR(r.min_angle, 60.0, 1e-12);
  EXPECT_NEAR(r.max_angle, 120.0, 1e-12);
  EXPECT_NEAR(r.area, 4.0 * std::sin(degrees(60)), 1e-14);
  EXPECT_EQ(r.inverted, 0);
}

TEST(Quality, ClockwiseQuadIsInverted) {
  QuadMesh mesh = grid(2, 1, 2.0, 1.0);
  std::swap(mesh.quads[1][1], mesh.quads[1][3]);  // the second quad runs clockwise
  EXPECT_DOUBLE_EQ(scaled_jacobian({0, 0}, {0, 1}, {1, 1}, {1, 0}), -1.0);
  const QualityReport r = measure_quality(mesh);
  EXPECT_EQ(r.inverted, 1);
  EXPECT_EQ(r.worst_element, 1);
  EXPECT_DOUBLE_EQ(r.min_scaled_jacobian, -1.0);
  EXPECT_DOUBLE_EQ(r.mean_scaled_jacobian, 0.0);
  EXPECT_NEAR(r.area, 0.0, 1e-15);  // signed: the inverted quad cancels the good one
}

TEST(Quality, BowTieIsInverted) {
  // Corners 2 and 3 swapped: the sides 1-2 and 3-0 cross.
  const double sj = scaled_jacobian({0, 0}, {1, 0}, {0, 1}, {1, 1});
  EXPECT_LE(sj, 0.0);
  QuadMesh mesh;
  mesh.nodes = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  mesh.places.resize(4);
  mesh.quads = {{0, 1, 2, 3}};
  const QualityReport r = measure_quality(mesh);
  EXPECT_EQ(r.inverted, 1);
  EXPECT_EQ(r.min_scaled_jacobian, sj);
}

TEST(Quality, CollapsedEdgeIsInverted) {
  EXPECT_EQ(scaled_jacobian({0, 0}, {1, 0}, {1, 0}, {0, 1}), 0.0);
}

TEST(Quality, StructuredGridHasNoIrregularNode) {
  const QualityReport r = measure_quality(grid(4, 4, 3.0, 2.0));
  EXPECT_EQ(r.quads, 16);
  EXPECT_EQ(r.nodes, 25);
  EXPECT_TRUE(r.irregular_interior.empty());
  EXPECT_TRUE(r.irregular_boundary.empty());
  EXPECT_NEAR(r.min_scaled_jacobian, 1.0, 1e-14);
  EXPECT_NEAR(r.area, 6.0, 1e-13);
}

TEST(Quality, GridAreaIsExactWithUnevenSpacing) {
  QuadMesh mesh = grid(5, 3, 1.0, 1.0);
  // Move every node off the uniform grid except the outline: the area stays 1.
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (mesh.places[n].loop < 0)
      mesh.nodes[n] = mesh.nodes[n] + Vec2{0.03 * std::sin(7.0 * n), 0.02 * std::cos(5.0 * n)};
  }
  const QualityReport r = measure_quality(mesh);
  EXPECT_NEAR(r.area, 1.0, 1e-14);
  EXPECT_LT(r.min_scaled_jacobian, 1.0);
  EXPECT_GT(r.min_scaled_jacobian, 0.5);
  EXPECT_LT(r.min_scaled_jacobian, r.mean_scaled_jacobian);
}

TEST(Quality, ReportsValenceThreeAndFiveInteriorNodes) {
  QuadMesh mesh;
  add_fan(mesh, {0, 0}, 3);
  add_fan(mesh, {5, 0}, 5);
  const QualityReport r = measure_quality(mesh);
  EXPECT_EQ(r.quads, 8);
  EXPECT_EQ(r.inverted, 0);
  ASSERT_EQ(r.irregular_interior.size(), 2u);
  EXPECT_EQ(r.irregular_interior[0].node, 6);
  EXPECT_EQ(r.irregular_interior[0].elements, 3);
  EXPECT_EQ(r.irregular_interior[0].expected, 4);
  EXPECT_NEAR(r.irregular_interior[0].p.x, 0.0, 0.0);
  EXPECT_EQ(r.irregular_interior[1].elements, 5);
  EXPECT_NEAR(r.irregular_interior[1].p.x, 5.0, 0.0);
  EXPECT_TRUE(r.irregular_boundary.empty());
}

TEST(Quality, BoundaryNodeWithMoreElementsThanItsCornerWants) {
  QuadMesh mesh = grid(3, 2, 3.0, 2.0);
  mesh.places[1].corner_elements = 1;  // node (1, 0) lies on the bottom side, between two quads
  const QualityReport r = measure_quality(mesh);
  ASSERT_EQ(r.irregular_boundary.size(), 1u);
  EXPECT_EQ(r.irregular_boundary[0].node, 1);
  EXPECT_EQ(r.irregular_boundary[0].elements, 2);
  EXPECT_EQ(r.irregular_boundary[0].expected, 1);
  EXPECT_TRUE(r.irregular_interior.empty());
}

TEST(Quality, MidsideNodesHaveNoValence) {
  QuadMesh mesh = grid(1, 1, 1.0, 1.0);
  for (int i = 0; i < 4; ++i) {
    mesh.nodes.push_back(0.5 * (mesh.nodes[mesh.quads[0][i]] + mesh.nodes[mesh.quads[0][(i + 1) % 4]]));
    mesh.places.push_back({0, i, 0.5, false, 2});
  }
  mesh.midside = {{4, 5, 6, 7}};
  const QualityReport r = measure_quality(mesh);
  EXPECT_EQ(r.nodes, 8);
  EXPECT_TRUE(r.irregular_boundary.empty());
  EXPECT_NEAR(r.area, 1.0, 1e-15);
}

TEST(Quality, BadNodeIndexIsAnInputError) {
  QuadMesh mesh = grid(1, 1, 1.0, 1.0);
  mesh.quads[0][2] = 9;
  EXPECT_THROW(measure_quality(mesh), InputError);
  mesh = grid(1, 1, 1.0, 1.0);
  mesh.places.pop_back();
  EXPECT_THROW(measure_quality(mesh), InputError);
}

TEST(Quality, EmptyMeshHasNoWorstElement) {
  const QualityReport r = measure_quality(QuadMesh{});
  EXPECT_EQ(r.quads, 0);
  EXPECT_EQ(r.worst_element, -1);
  EXPECT_EQ(r.inverted, 0);
}

// Verdict's quad measures on quads whose values follow from their definitions.
TEST(QuadMeasures, UnitSquareScoresBestOnEveryMeasure) {
  const QuadMeasures m = measure_quad({Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{0, 1}});
  EXPECT_DOUBLE_EQ(m.scaled_jacobian, 1.0);
  EXPECT_DOUBLE_EQ(m.shape, 1.0);
  EXPECT_DOUBLE_EQ(m.edge_ratio, 1.0);
  EXPECT_DOUBLE_EQ(m.aspect_ratio, 1.0);
  EXPECT_DOUBLE_EQ(m.skew, 0.0);
  EXPECT_DOUBLE_EQ(m.taper, 0.0);
  EXPECT_DOUBLE_EQ(m.stretch, 1.0);
  EXPECT_DOUBLE_EQ(m.condition, 1.0);
  EXPECT_DOUBLE_EQ(m.jacobian, 1.0);
  EXPECT_DOUBLE_EQ(m.area, 1.0);
}

TEST(QuadMeasures, ANeedleHasRightAnglesButAPoorShape) {
  // 1 x 10: the scaled Jacobian cannot see it, shape and edge ratio do.
  const QuadMeasures m = measure_quad({Vec2{0, 0}, Vec2{10, 0}, Vec2{10, 1}, Vec2{0, 1}});
  EXPECT_DOUBLE_EQ(m.scaled_jacobian, 1.0);
  EXPECT_NEAR(m.shape, 2.0 * 10.0 / 101.0, 1e-15);
  EXPECT_DOUBLE_EQ(m.edge_ratio, 10.0);
  EXPECT_NEAR(m.aspect_ratio, 0.5 * 10.0 * 22.0 / 20.0, 1e-14);
  EXPECT_NEAR(m.stretch, std::sqrt(2.0 / 101.0), 1e-15);
  EXPECT_NEAR(m.condition, 101.0 / 20.0, 1e-14);
  EXPECT_DOUBLE_EQ(m.skew, 0.0);
  EXPECT_DOUBLE_EQ(m.taper, 0.0);
}

TEST(QuadMeasures, RhombusAndTrapezoid) {
  const double h = std::sqrt(3.0) / 2.0;
  const QuadMeasures rhombus = measure_quad({Vec2{0, 0}, Vec2{1, 0}, Vec2{1.5, h}, Vec2{0.5, h}});
  EXPECT_NEAR(rhombus.scaled_jacobian, h, 1e-15);  // sin 60 degrees
  EXPECT_NEAR(rhombus.shape, h, 1e-15);            // equal sides: shape is the scaled Jacobian
  EXPECT_NEAR(rhombus.skew, 0.5, 1e-15);           // the principal axes meet at 60 degrees
  EXPECT_NEAR(rhombus.taper, 0.0, 1e-15);
  const QuadMeasures trapezoid = measure_quad({Vec2{0, 0}, Vec2{2, 0}, Vec2{1.5, 1}, Vec2{0.5, 1}});
  EXPECT_NEAR(trapezoid.taper, 0.5, 1e-15);  // cross derivative 1 over the shorter axis 2
  EXPECT_NEAR(trapezoid.skew, 0.0, 1e-15);
}

TEST(QuadMeasures, CollapsedSideScoresZeroShape) {
  const QuadMeasures m = measure_quad({Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{1, 1}});
  EXPECT_EQ(m.shape, 0.0);
  EXPECT_EQ(m.scaled_jacobian, 0.0);
  EXPECT_EQ(m.edge_ratio, std::numeric_limits<double>::max());
}

TEST(QuadMeasures, JacobianRatioOfEightNodeQuads) {
  const Vec2 a{0, 0}, b{2, 0}, c{2.5, 1}, d{0.5, 1};
  const auto mid = [](Vec2 p, Vec2 q) { return 0.5 * (p + q); };
  // A parallelogram with straight sides: the Jacobian is constant.
  EXPECT_NEAR(jacobian_ratio({a, b, c, d, mid(a, b), mid(b, c), mid(c, d), mid(d, a)}), 1.0, 1e-14);
  // A side bent inwards: smaller where it bends.
  const double bent = jacobian_ratio({a, b, c, d, mid(a, b) + Vec2{0, 0.2}, mid(b, c), mid(c, d), mid(d, a)});
  EXPECT_GT(bent, 0.0);
  EXPECT_LT(bent, 0.9);
  // Bent past the opposite side: the element folds.
  EXPECT_LE(jacobian_ratio({a, b, c, d, mid(a, b) + Vec2{0, 1.2}, mid(b, c), mid(c, d), mid(d, a)}), 0.0);
}

TEST(Quality, ReportSummarisesTheVerdictMeasures) {
  // 10 square quads and 10 needles of 1 x 12 side by side.
  QuadMesh mesh = grid(10, 1, 10.0, 1.0);
  QuadMesh needles = grid(10, 1, 10.0, 12.0);
  const int offset = static_cast<int>(mesh.nodes.size());
  for (Vec2 p : needles.nodes) mesh.nodes.push_back(p + Vec2{20.0, 0.0});
  mesh.places.insert(mesh.places.end(), needles.places.begin(), needles.places.end());
  for (auto q : needles.quads) mesh.quads.push_back({q[0] + offset, q[1] + offset, q[2] + offset, q[3] + offset});
  const QualityReport r = measure_quality(mesh, 1.0);
  const MeasureSummary& shape = r.measure(Measure::Shape);
  EXPECT_NEAR(shape.min, 24.0 / 145.0, 1e-14);
  EXPECT_NEAR(shape.max, 1.0, 1e-14);
  EXPECT_NEAR(shape.mean, 0.5 * (1.0 + 24.0 / 145.0), 1e-14);
  EXPECT_GE(shape.worst_element, 10);
  EXPECT_NEAR(shape.worst_at.y, 6.0, 1e-14);
  const MeasureSummary& edge_ratio = r.measure(Measure::EdgeRatio);
  EXPECT_NEAR(edge_ratio.max, 12.0, 1e-14);
  EXPECT_GE(edge_ratio.worst_element, 10);
  EXPECT_EQ(r.poor_shape, 10);
  EXPECT_EQ(r.needles, 10);
  EXPECT_EQ(r.stretched, 10);
  EXPECT_EQ(r.poor_scaled_jacobian, 0);  // every corner is a right angle
  ASSERT_EQ(static_cast<int>(r.worst_elements.size()), kWorstListed);
  for (const WorstElement& w : r.worst_elements) EXPECT_GE(w.element, 10);
  // Sizes against H = 1: the squares are 1, the needles sqrt(12).
  EXPECT_NEAR(r.min_relative_size, 1.0, 1e-14);
  EXPECT_NEAR(r.max_relative_size, std::sqrt(12.0), 1e-14);
  EXPECT_NEAR(r.sizes_in_range, 0.5, 1e-15);
  EXPECT_EQ(r.min_jacobian_ratio, 1.0);  // order 1
}

TEST(Quality, OrderTwoReportsTheJacobianRatio) {
  QuadMesh mesh = grid(1, 1, 2.0, 1.0);
  for (Vec2 m : {Vec2{1.0, 0.3}, Vec2{2.0, 0.5}, Vec2{1.0, 1.0}, Vec2{0.0, 0.5}}) {
    mesh.nodes.push_back(m);
    mesh.places.push_back({});
  }
  mesh.midside = {{4, 5, 6, 7}};
  const QualityReport r = measure_quality(mesh);
  EXPECT_GT(r.min_jacobian_ratio, 0.0);
  EXPECT_LT(r.min_jacobian_ratio, 0.9);
}

std::string error_of_writing(const QuadMesh& mesh, const std::string& path) {
  try {
    write_mesh_file(mesh, Frame{}, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshFiles, UnknownExtensionNamesThePath) {
  const std::string message = error_of_writing(grid(1, 1, 1.0, 1.0), "/tmp/mesh.stl");
  EXPECT_NE(message.find("/tmp/mesh.stl"), std::string::npos) << message;
  EXPECT_NE(message.find("extension"), std::string::npos) << message;
}

TEST(MeshFiles, UnwritablePathNamesThePath) {
  const std::string path = "/nonexistent-folder/mesh.inp";
  const std::string message = error_of_writing(grid(1, 1, 1.0, 1.0), path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
}

TEST(MeshFiles, MidsideCountMustMatchQuads) {
  QuadMesh mesh = grid(2, 1, 2.0, 1.0);
  mesh.midside = {{0, 1, 2, 3}};
  const std::string message = error_of_writing(mesh, "/tmp/mesh.vtu");
  EXPECT_NE(message.find("mid-side"), std::string::npos) << message;
}

}  // namespace
}  // namespace mm
