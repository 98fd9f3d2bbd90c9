#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "boundary/face_model.hpp"
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
