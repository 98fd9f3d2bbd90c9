// Several faces meshed together: shared pieces of boundary get the same
// nodes, coplanar or not, with T-junctions, and the merged mesh is one
// conforming mesh whose open sides are the outline of the union.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "face_builders.hpp"
#include "mesh_checks.hpp"
#include "pipeline/pipeline.hpp"

namespace mm {
namespace {

using Point3 = std::array<double, 3>;

FaceModel framed(std::vector<std::vector<BoundaryEdge>> loops, const std::string& name, Frame frame) {
  RawFace raw;
  raw.name = name;
  raw.loops = std::move(loops);
  raw.frame = frame;
  return build_face_model(raw);
}

FaceModel rect(double x0, double y0, double x1, double y1, const std::string& name, Frame frame = {}) {
  return framed({test::polygon({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})}, name, frame);
}

MeshedFaces mesh_all(const std::vector<FaceModel>& faces, double size, int order = 1) {
  PipelineOptions options;
  options.meshing.size = size;
  options.meshing.order = order;
  return mesh_faces(faces, options);
}

double length3(const Point3& a, const Point3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// What a user checks of the merged mesh: every face's own mesh valid, no two
// nodes at one point, no inverted element, the area of the faces, every
// side in one or two elements, and the open sides exactly the union's
// outline: each on it (on_outline at its middle) and as long as it together.
void expect_conformal(const std::vector<FaceModel>& faces, const MeshedFaces& m, double size,
                      const std::function<bool(const Point3&)>& on_outline, double outline_length) {
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto problems = test::mesh_problems(faces[f], m.faces[f].blocks.mesh, size);
    EXPECT_TRUE(problems.empty()) << faces[f].name << ": " << ::testing::PrintToString(problems);
  }
  const MergedMesh& mesh = m.mesh;
  double smallest = 1e300;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    for (std::size_t j = i + 1; j < mesh.nodes.size(); ++j)
      smallest = std::min(smallest, length3(mesh.nodes[i], mesh.nodes[j]));
  EXPECT_GT(smallest, 1e-6 * size);
  EXPECT_EQ(m.quality.inverted, 0);
  double area = 0.0;
  for (const FaceModel& f : faces) area += f.area;
  EXPECT_NEAR(m.quality.area, area, 5e-3 * area);  // chords across round holes
  std::map<std::pair<int, int>, int> uses;
  for (const auto& q : mesh.quads)
    for (int i = 0; i < 4; ++i) ++uses[{std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}];
  double open_length = 0.0;
  for (const auto& [side, count] : uses) {
    EXPECT_TRUE(count == 1 || count == 2) << count;
    if (count != 1) continue;
    const Point3 &a = mesh.nodes[side.first], &b = mesh.nodes[side.second];
    const Point3 mid{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
    EXPECT_TRUE(on_outline(mid)) << mid[0] << " " << mid[1] << " " << mid[2];
    open_length += length3(a, b);
  }
  EXPECT_NEAR(open_length, outline_length, 2e-2 * outline_length);
  EXPECT_EQ(mesh.face_of_quad.size(), mesh.quads.size());
}

// Nodes of face f's own mesh on a 3-D line through p along d.
int nodes_on_line(const FaceModel& face, const QuadMesh& mesh, Point3 p, Point3 d) {
  int count = 0;
  std::vector<bool> corner(mesh.nodes.size(), false);
  for (const auto& q : mesh.quads)
    for (int n : q) corner[n] = true;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (!corner[n]) continue;
    const Point3 x = to_3d(face.frame, mesh.nodes[n]);
    const Point3 r{x[0] - p[0], x[1] - p[1], x[2] - p[2]};
    const Point3 c{r[1] * d[2] - r[2] * d[1], r[2] * d[0] - r[0] * d[2], r[0] * d[1] - r[1] * d[0]};
    if (std::hypot(c[0], c[1], c[2]) < 1e-9) ++count;
  }
  return count;
}

bool near(double a, double b) {
  return std::abs(a - b) < 1e-9;
}

TEST(MultiFace, RectangleSplitByALineMeshesAsOneConformalGrid) {
  const std::vector<FaceModel> faces{rect(0, 0, 1.2, 1, "left"), rect(1.2, 0, 2, 1, "right")};
  const MeshedFaces m = mesh_all(faces, 0.1);
  ASSERT_EQ(shared_edge_count(m.shared), 1);
  expect_conformal(
      faces, m, 0.1, [](const Point3& p) { return near(p[0], 0) || near(p[0], 2) || near(p[1], 0) || near(p[1], 1); },
      6.0);
  const int left = nodes_on_line(faces[0], m.faces[0].blocks.mesh, {1.2, 0, 0}, {0, 1, 0});
  const int right = nodes_on_line(faces[1], m.faces[1].blocks.mesh, {1.2, 0, 0}, {0, 1, 0});
  EXPECT_EQ(left, right);
  EXPECT_EQ(left, 11);
  // Two mapped grids side by side: one regular grid, 21 x 11 nodes.
  EXPECT_EQ(m.mesh.nodes.size(), 21u * 11u);
  EXPECT_TRUE(m.quality.irregular_interior.empty());
  EXPECT_TRUE(m.quality.irregular_boundary.empty());
  EXPECT_EQ(m.quality.nodes, static_cast<int>(m.mesh.nodes.size()));
  EXPECT_EQ(m.quality.quads, m.faces[0].quality.quads + m.faces[1].quality.quads);
}

TEST(MultiFace, OrderTwoSharesTheMidSideNodesToo) {
  const std::vector<FaceModel> faces{rect(0, 0, 1, 1, "left"), rect(1, 0, 2, 1, "right")};
  const MeshedFaces m = mesh_all(faces, 0.25, 2);
  ASSERT_EQ(m.mesh.order(), 2);
  // 9 x 5 corner nodes, and one mid-side node per element side: 8 x 5 + 9 x 4.
  EXPECT_EQ(m.mesh.nodes.size(), 9u * 5u + 8u * 5u + 9u * 4u);
}

TEST(MultiFace, PlateWithAHoleSplitThroughTheHole) {
  // Left and right halves of a 4 x 2 plate with a hole of radius 0.5 at (2, 1).
  const std::vector<FaceModel> faces{
      test::face({{test::line({0, 0}, {2, 0}), test::line({2, 0}, {2, 0.5}), test::arc({2, 0.5}, {2, 1.5}, -0.5),
                   test::line({2, 1.5}, {2, 2}), test::line({2, 2}, {0, 2}), test::line({0, 2}, {0, 0})}},
                 "left half"),
      test::face({{test::line({2, 0}, {4, 0}), test::line({4, 0}, {4, 2}), test::line({4, 2}, {2, 2}),
                   test::line({2, 2}, {2, 1.5}), test::arc({2, 1.5}, {2, 0.5}, -0.5), test::line({2, 0.5}, {2, 0})}},
                 "right half")};
  const MeshedFaces m = mesh_all(faces, 0.15);
  EXPECT_EQ(shared_edge_count(m.shared), 2);
  const auto on_outline = [](const Point3& p) {
    const double r = std::hypot(p[0] - 2, p[1] - 1);
    return near(p[0], 0) || near(p[0], 4) || near(p[1], 0) || near(p[1], 2) || (r < 0.5 + 1e-9 && r > 0.49);
  };
  expect_conformal(faces, m, 0.15, on_outline, 12.0 + kPi);
  EXPECT_EQ(nodes_on_line(faces[0], m.faces[0].blocks.mesh, {2, 0, 0}, {0, 1, 0}),
            nodes_on_line(faces[1], m.faces[1].blocks.mesh, {2, 0, 0}, {0, 1, 0}));
}

TEST(MultiFace, TwoFacesOfABoxAtRightAnglesShareTheirEdge) {
  // The bottom of a unit box (z = 0, seen from -z) and its front (y = 0, seen from -y).
  Frame bottom;
  bottom.y_dir = {0, -1, 0};
  bottom.normal = {0, 0, -1};
  Frame front;
  front.y_dir = {0, 0, 1};
  front.normal = {0, -1, 0};
  const std::vector<FaceModel> faces{rect(0, -1, 1, 0, "bottom", bottom), rect(0, 0, 1, 1, "front", front)};
  const MeshedFaces m = mesh_all(faces, 0.1);
  ASSERT_EQ(shared_edge_count(m.shared), 1);
  const auto on_outline = [](const Point3& p) {
    return (near(p[2], 0) && (near(p[0], 0) || near(p[0], 1) || near(p[1], 1))) ||
           (near(p[1], 0) && (near(p[0], 0) || near(p[0], 1) || near(p[2], 1)));
  };
  expect_conformal(faces, m, 0.1, on_outline, 6.0);
  EXPECT_EQ(nodes_on_line(faces[0], m.faces[0].blocks.mesh, {0, 0, 0}, {1, 0, 0}), 11);
  EXPECT_EQ(nodes_on_line(faces[1], m.faces[1].blocks.mesh, {0, 0, 0}, {1, 0, 0}), 11);
  EXPECT_EQ(m.mesh.nodes.size(), 11u * 21u);
  // A node on the fold has 2 + 2 elements: regular.
  EXPECT_TRUE(m.quality.irregular_interior.empty());
  EXPECT_TRUE(m.quality.irregular_boundary.empty());
}

TEST(MultiFace, TJunctionSplitsTheLongEdge) {
  // A's top edge is covered by B's and C's bottom edges; B and C meet at (1, 0).
  const std::vector<FaceModel> faces{rect(0, -1, 2, 0, "A"), rect(0, 0, 1, 1, "B"), rect(1, 0, 2, 1, "C")};
  const MeshedFaces m = mesh_all(faces, 0.125);
  EXPECT_EQ(shared_edge_count(m.shared), 3);  // A-B, A-C, B-C
  expect_conformal(
      faces, m, 0.125,
      [](const Point3& p) { return near(p[0], 0) || near(p[0], 2) || near(p[1], -1) || near(p[1], 1); }, 8.0);
  EXPECT_EQ(nodes_on_line(faces[0], m.faces[0].blocks.mesh, {0, 0, 0}, {1, 0, 0}), 17);
  EXPECT_EQ(m.mesh.nodes.size(), 17u * 17u);
  // (1, 0) has 2 elements in A and 1 each in B and C: 4, as wanted.
  EXPECT_TRUE(m.quality.irregular_interior.empty());
}

TEST(MultiFace, EdgesOverlappingInPartShareTheOverlap) {
  // B sits on A shifted right: A's top edge and B's bottom edge share x in [1, 2].
  const std::vector<FaceModel> faces{rect(0, 0, 2, 1, "A"), rect(1, 1, 3, 2, "B")};
  const MeshedFaces m = mesh_all(faces, 0.125);
  EXPECT_EQ(shared_edge_count(m.shared), 1);
  const auto on_outline = [](const Point3& p) {
    const double x = p[0], y = p[1];
    const bool low = y<1 + 1e-9, high = y> 1 - 1e-9;
    return (low && (near(y, 0) || near(x, 0) || near(x, 2))) || (high && (near(y, 2) || near(x, 1) || near(x, 3))) ||
           (near(y, 1) && (x < 1 + 1e-9 || x > 2 - 1e-9));
  };
  expect_conformal(faces, m, 0.125, on_outline, 10.0);
  int on_overlap = 0;
  for (const auto& p : m.mesh.nodes) on_overlap += near(p[1], 1) && p[0] > 1 - 1e-9 && p[0] < 2 + 1e-9;
  EXPECT_EQ(on_overlap, 9);
}

TEST(MultiFace, FacesWithoutASharedEdgeAreMeshedSideBySide) {
  const std::vector<FaceModel> faces{rect(0, 0, 1, 1, "one"), rect(3, 0, 4, 1, "two")};
  const MeshedFaces m = mesh_all(faces, 0.1);
  EXPECT_TRUE(m.shared.empty());
  expect_conformal(
      faces, m, 0.1,
      [](const Point3& p) {
        return near(p[0], 0) || near(p[0], 1) || near(p[0], 3) || near(p[0], 4) || near(p[1], 0) || near(p[1], 1);
      },
      8.0);
  EXPECT_EQ(m.mesh.nodes.size(), 2u * 11u * 11u);
}

TEST(MultiFace, OneFaceMeshesAsMeshFaceDoes) {
  const FaceModel face = test::face({test::polygon({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 2}, {0, 2}})}, "L");
  PipelineOptions options;
  options.meshing.size = 0.2;
  const MeshedFace one = mesh_face(face, options);
  const MeshedFaces all = mesh_faces({face}, options);
  ASSERT_EQ(all.mesh.nodes.size(), one.blocks.mesh.nodes.size());
  ASSERT_EQ(all.mesh.quads, one.blocks.mesh.quads);
  EXPECT_EQ(all.quality.irregular_interior.size(), one.quality.irregular_interior.size());
  EXPECT_EQ(all.quality.irregular_boundary.size(), one.quality.irregular_boundary.size());
  EXPECT_DOUBLE_EQ(all.quality.min_scaled_jacobian, one.quality.min_scaled_jacobian);
}

// One quad per face, the faces' frames the plane z = 0.
QuadMesh one_quad(double x0) {
  QuadMesh mesh;
  for (Vec2 p : {Vec2{x0, 0}, Vec2{x0 + 1, 0}, Vec2{x0 + 1, 1}, Vec2{x0, 1}}) {
    mesh.nodes.push_back(p);
    NodePlace place;
    place.loop = 0;
    place.corner_elements = 1;
    mesh.places.push_back(place);
  }
  mesh.quads.push_back({0, 1, 2, 3});
  mesh.block_of_quad.push_back(0);
  return mesh;
}

TEST(MultiFace, MergeJoinsPartnersAndNamesTheFacesWhenOneIsMissing) {
  const std::vector<FaceModel> faces{rect(0, 0, 1, 1, "left"), rect(1, 0, 2, 1, "right")};
  const QuadMesh left = one_quad(0), right = one_quad(1);
  SharedPiece piece;
  piece.face_a = 0;
  piece.face_b = 1;
  piece.edge_a = 2;
  piece.edge_b = 4;
  piece.nodes_a = {1, 2};  // (1, 0), (1, 1)
  piece.nodes_b = {0, 3};
  const MergedMesh merged = merge_face_meshes(faces, {&left, &right}, {piece}, 1e-6);
  EXPECT_EQ(merged.nodes.size(), 6u);
  EXPECT_EQ(merged.node_of[1][0], merged.node_of[0][1]);
  EXPECT_EQ(std::count(merged.on_boundary.begin(), merged.on_boundary.end(), true), 6);
  // A partner off by more than the tolerance: a self-check error naming both faces and edges.
  const QuadMesh apart = one_quad(1.01);
  try {
    merge_face_meshes(faces, {&left, &apart}, {piece}, 1e-6);
    FAIL() << "no error";
  } catch (const SelfCheckError& e) {
    const std::string message = e.what();
    for (const char* word : {"left", "right", "Edge2", "Edge4"})
      EXPECT_NE(message.find(word), std::string::npos) << message;
  }
}

TEST(MultiFace, NoFacesIsAnInputError) {
  EXPECT_THROW(mesh_faces({}, PipelineOptions{}), InputError);
}

TEST(MultiFace, DiscFillsTheHoleOfAPlate) {
  // The whole circle is shared: a plate's hole and the disc inside it. The
  // circles start off the splits (a split ending at a circle's seam leaves
  // the plate's decomposition a boundary piece of no length; see the README).
  const auto circle = [](int sense) {
    return BoundaryEdge{CircleCurve{{2, 1}, 0.6, 1.0, sense}, 0.0, 2 * kPi, 0, {}, {}};
  };
  const std::vector<FaceModel> faces{
      test::face({test::polygon({{0, 0}, {4, 0}, {4, 2}, {0, 2}}), {circle(-1)}}, "plate"),
      test::face({{circle(1)}}, "disc")};
  const MeshedFaces m = mesh_all(faces, 0.15);
  EXPECT_EQ(shared_edge_count(m.shared), 1);
  expect_conformal(
      faces, m, 0.15, [](const Point3& p) { return near(p[0], 0) || near(p[0], 4) || near(p[1], 0) || near(p[1], 2); },
      12.0);
  // Order 2: each face puts the mid-side nodes of the circle on its own
  // curve; they are joined, one per side of the merged corner mesh.
  const MeshedFaces q = mesh_all(faces, 0.15, 2);
  std::set<std::pair<int, int>> sides;
  std::set<int> corners;
  for (const auto& quad : q.mesh.quads) {
    for (int i = 0; i < 4; ++i) {
      corners.insert(quad[i]);
      sides.insert({std::min(quad[i], quad[(i + 1) % 4]), std::max(quad[i], quad[(i + 1) % 4])});
    }
  }
  EXPECT_EQ(q.mesh.nodes.size(), corners.size() + sides.size());
}

TEST(MultiFace, CoplanarFacesSplitByAnArc) {
  // A 2 x 1 rectangle cut by an arc from (1, 0) to (1, 1) bulging right by 0.1.
  const std::vector<FaceModel> faces{test::face({{test::line({0, 0}, {1, 0}), test::arc({1, 0}, {1, 1}, 0.1),
                                                  test::line({1, 1}, {0, 1}), test::line({0, 1}, {0, 0})}},
                                                "left"),
                                     test::face({{test::line({1, 0}, {2, 0}), test::line({2, 0}, {2, 1}),
                                                  test::line({2, 1}, {1, 1}), test::arc({1, 1}, {1, 0}, -0.1)}},
                                                "right")};
  const MeshedFaces m = mesh_all(faces, 0.1);
  EXPECT_EQ(shared_edge_count(m.shared), 1);
  expect_conformal(
      faces, m, 0.1, [](const Point3& p) { return near(p[0], 0) || near(p[0], 2) || near(p[1], 0) || near(p[1], 1); },
      6.0);
}

}  // namespace
}  // namespace mm
