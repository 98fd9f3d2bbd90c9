// Splitting faces into block faces along decomposition splits: counts, areas
// against the boundary model's exact area, validity, and where the block
// vertices and split edges lie.
#include <gtest/gtest.h>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <filesystem>
#include <gp_Ax1.hxx>
#include <gp_Trsf.hxx>
#include <sstream>
#include <variant>

#include "occ/occ_face.hpp"
#include "occ/occ_split.hpp"
#include "occ/occ_split_io.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

using Polylines = std::vector<std::vector<Vec2>>;

struct Face {
  TopoDS_Face occ;
  FaceModel model;
};

Face from_shape(const TopoDS_Shape& shape, const std::string& name) {
  const TopoDS_Face face = test::first_face(shape);
  return {face, face_model_from_occ(face, name)};
}

std::string reference_path(const std::string& name) {
  return test::shared_dir() + "/geometry/" + name + ".brep";
}

Face reference(const std::string& name) {
  return from_shape(read_shape(reference_path(name)), name);
}

// Adaptive integration: the fixed-order one is 7.5e-5 off on B-spline faces.
double area_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(shape, props, 1e-12);
  return props.Mass();
}

Vec2 in_frame(const Frame& f, const gp_Pnt& p) {
  const gp_XYZ d = p.XYZ() - gp_XYZ(f.origin[0], f.origin[1], f.origin[2]);
  return {d.Dot(gp_XYZ(f.x_dir[0], f.x_dir[1], f.x_dir[2])), d.Dot(gp_XYZ(f.y_dir[0], f.y_dir[1], f.y_dir[2]))};
}

gp_Pnt in_3d(const Frame& f, Vec2 p) {
  const auto q = to_3d(f, p);
  return gp_Pnt(q[0], q[1], q[2]);
}

std::vector<Vec2> vertices_2d(const TopoDS_Shape& shape, const Frame& frame) {
  TopTools_IndexedMapOfShape vertices;
  TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
  std::vector<Vec2> points;
  for (int i = 1; i <= vertices.Extent(); ++i) {
    points.push_back(in_frame(frame, BRep_Tool::Pnt(TopoDS::Vertex(vertices(i)))));
  }
  return points;
}

bool has_vertex(const TopoDS_Face& block, const Frame& frame, Vec2 p, double tolerance) {
  for (const Vec2& q : vertices_2d(block, frame)) {
    if (distance(p, q) <= tolerance) return true;
  }
  return false;
}

// Every block valid, its area one of the expected ones (in any order), and the
// areas adding up to the boundary model's own exact area.
void expect_blocks(const std::vector<TopoDS_Face>& blocks, const FaceModel& model, std::vector<double> expected) {
  ASSERT_EQ(blocks.size(), expected.size());
  std::vector<double> areas;
  double sum = 0.0;
  for (const TopoDS_Face& block : blocks) {
    EXPECT_TRUE(BRepCheck_Analyzer(block).IsValid());
    areas.push_back(area_of(block));
    sum += areas.back();
  }
  std::sort(areas.begin(), areas.end());
  std::sort(expected.begin(), expected.end());
  for (std::size_t i = 0; i < areas.size(); ++i) EXPECT_NEAR(areas[i], expected[i], 1e-9 * model.area);
  EXPECT_NEAR(sum, model.area, 1e-9 * model.area);
}

// The block whose vertices include p.
const TopoDS_Face* block_at(const std::vector<TopoDS_Face>& blocks, const Frame& frame, Vec2 p) {
  for (const TopoDS_Face& block : blocks) {
    if (has_vertex(block, frame, p, 1e-9)) return &block;
  }
  return nullptr;
}

Face scaled(const Face& face, double factor) {
  gp_Trsf scale;
  scale.SetScale(gp_Pnt(0, 0, 0), factor);
  return from_shape(BRepBuilderAPI_Transform(face.occ, scale, /*copy=*/true).Shape(), "scaled");
}

TEST(Split, SquareBySegmentGivesTwoFaces) {
  const Face square = reference("square");  // [0, 2] x [0, 2]
  const auto blocks = split_face(square.occ, square.model.frame, {{{0.5, 0}, {1, 2}}});
  expect_blocks(blocks, square.model, {1.5, 2.5});
  // The left block is the trapezoid (0,0) (0.5,0) (1,2) (0,2).
  const TopoDS_Face* left = block_at(blocks, square.model.frame, {0, 0});
  ASSERT_NE(left, nullptr);
  EXPECT_NEAR(area_of(*left), 1.5, 1e-12);
  for (Vec2 p : {Vec2{0.5, 0}, Vec2{1, 2}, Vec2{0, 2}}) EXPECT_TRUE(has_vertex(*left, square.model.frame, p, 1e-12));
}

TEST(Split, RectangleByBentPolyline) {
  const Face rectangle = reference("rectangle");  // [0, 4] x [0, 1]
  const auto blocks = split_face(rectangle.occ, rectangle.model.frame, {{{1, 0}, {2, 0.5}, {1.5, 1}}});
  // Left: (0,0) (1,0) (2,0.5) (1.5,1) (0,1), area 1.625 by the shoelace formula.
  expect_blocks(blocks, rectangle.model, {1.625, 4 - 1.625});
  for (const TopoDS_Face& block : blocks) EXPECT_TRUE(has_vertex(block, rectangle.model.frame, {2, 0.5}, 1e-12));
}

TEST(Split, TJunctionGivesThreeFaces) {
  const Face square = reference("square");
  // The second split starts 3e-9 short of the first one.
  const auto blocks = split_face(square.occ, square.model.frame, {{{1, 0}, {1, 2}}, {{1 + 3e-9, 1}, {2, 1}}});
  expect_blocks(blocks, square.model, {2, 1, 1});
  for (const TopoDS_Face& block : blocks) EXPECT_TRUE(has_vertex(block, square.model.frame, {1, 1}, 1e-12));
}

// On a part 1000 times larger, 1e-9 of its size is beyond OCC's 1e-7
// tolerance: ends that stop that short must still cut.
TEST(Split, EndsShortOfTheBoundaryOrASplitOnALargeFaceStillCut) {
  const Face big = scaled(reference("square"), 1000.0);  // [0, 2000]^2
  const double gap = 1e-9 * big.model.size;
  ASSERT_GT(gap, 1e-7);
  const auto blocks = split_face(big.occ, big.model.frame,
                                 {{{1000, gap}, {1000, 2000 - gap}}, {{1000 + gap, 1000}, {2000 - gap, 1000}}});
  expect_blocks(blocks, big.model, {2e6, 1e6, 1e6});
  for (const TopoDS_Face& block : blocks) EXPECT_TRUE(has_vertex(block, big.model.frame, {1000, 1000}, 1e-9));
  EXPECT_NE(block_at(blocks, big.model.frame, {2000, 1000}), nullptr);
  EXPECT_NE(block_at(blocks, big.model.frame, {1000, 0}), nullptr);
}

// The triangle's k = -1 decomposition: three splits from the midpoints of its
// sides to its centre, where their ends miss each other by 1e-9 of the size
// of a part 1000 times larger, beyond OCC's tolerance.
TEST(Split, ThreeSplitsMeetingAtAPointGiveThreeBlocks) {
  const Face triangle = scaled(reference("triangle"), 1000.0);
  const auto& corners = triangle.model.corners;
  ASSERT_EQ(corners.size(), 3u);
  const Vec2 centre = (corners[0].position + corners[1].position + corners[2].position) / 3.0;
  const double gap = 1e-9 * triangle.model.size;
  ASSERT_GT(gap, 1e-7);
  Polylines splits;
  for (int i = 0; i < 3; ++i) {
    const Vec2 midpoint = 0.5 * (corners[i].position + corners[(i + 1) % 3].position);
    const Vec2 miss = gap * Vec2{std::cos(2.0 * i), std::sin(2.0 * i)};
    splits.push_back({midpoint, centre + miss});
  }
  const auto blocks = split_face(triangle.occ, triangle.model.frame, splits);
  expect_blocks(blocks, triangle.model, std::vector<double>(3, triangle.model.area / 3));
  // One common vertex near the centre, and each block a quadrilateral.
  const std::vector<Vec2> first = vertices_2d(blocks[0], triangle.model.frame);
  const Vec2 meet = *std::min_element(first.begin(), first.end(),
                                      [&](Vec2 a, Vec2 b) { return distance(a, centre) < distance(b, centre); });
  EXPECT_LT(distance(meet, centre), 2 * gap);
  for (const TopoDS_Face& block : blocks) {
    EXPECT_EQ(vertices_2d(block, triangle.model.frame).size(), 4u);
    EXPECT_TRUE(has_vertex(block, triangle.model.frame, meet, 0.0));
  }
}

// The plate's hole and outer square from its boundary model; the radial
// splits from the hole to the middle of each side.
Polylines plate_splits(const FaceModel& plate) {
  const auto& hole = std::get<CircleCurve>(plate.loops[1].edges[0].curve);
  const Box box = bounding_box(plate);
  const Vec2 c = hole.center;
  const double r = hole.radius;
  return {{c + Vec2{r, 0}, {box.max.x, c.y}},
          {c + Vec2{0, r}, {c.x, box.max.y}},
          {c - Vec2{r, 0}, {box.min.x, c.y}},
          {c - Vec2{0, r}, {c.x, box.min.y}}};
}

TEST(Split, PlateWithHoleIntoFourByRadialSplits) {
  const Face plate = reference("plate_with_hole");  // [-2, 2]^2, hole of radius 1 at the origin
  const Polylines splits = plate_splits(plate.model);
  EXPECT_NEAR(distance(splits[0][0], {1, 0}), 0.0, 1e-12);
  const auto blocks = split_face(plate.occ, plate.model.frame, splits);
  expect_blocks(blocks, plate.model, std::vector<double>(4, (16 - kPi) / 4));
  // Each quarter holds one outer corner and the ends of two splits.
  for (Vec2 corner : {Vec2{2, 2}, Vec2{-2, 2}, Vec2{-2, -2}, Vec2{2, -2}}) {
    const TopoDS_Face* block = block_at(blocks, plate.model.frame, corner);
    ASSERT_NE(block, nullptr);
    EXPECT_TRUE(has_vertex(*block, plate.model.frame, {corner.x / 2, 0}, 1e-12));
    EXPECT_TRUE(has_vertex(*block, plate.model.frame, {0, corner.y / 2}, 1e-12));
    EXPECT_TRUE(has_vertex(*block, plate.model.frame, {corner.x, 0}, 1e-12));
  }
}

TEST(Split, AnnulusCutOnceStaysOneFaceWithTheCutInside) {
  const Face annulus = reference("annulus");  // radii 1 and 2 about the origin
  const auto blocks = split_face(annulus.occ, annulus.model.frame, {{{0, 1}, {0, 2}}});
  expect_blocks(blocks, annulus.model, {3 * kPi});
  // The cut is an internal edge of the face, ending on both circles.
  int cuts = 0;
  for (TopExp_Explorer it(blocks[0], TopAbs_EDGE); it.More(); it.Next()) {
    const BRepAdaptor_Curve curve(TopoDS::Edge(it.Current()));
    if (curve.GetType() != GeomAbs_Line) continue;
    ++cuts;
    EXPECT_EQ(it.Current().Orientation(), TopAbs_INTERNAL);
    const Vec2 a = in_frame(annulus.model.frame, curve.Value(curve.FirstParameter()));
    const Vec2 b = in_frame(annulus.model.frame, curve.Value(curve.LastParameter()));
    EXPECT_NEAR(std::min(norm(a), norm(b)), 1.0, 1e-12);
    EXPECT_NEAR(std::max(norm(a), norm(b)), 2.0, 1e-12);
  }
  EXPECT_EQ(cuts, 1);
}

// B-spline boundaries: the aerofoil's main element cut to the top and bottom
// sides from its highest and lowest points (on the B-spline, by our evaluator).
TEST(Split, AerofoilAcrossItsMainElementGivesTwoFaces) {
  const Face aerofoil = reference("aerofoil3");  // box [-1, 3] x [-1.5, 1.5], main element in x [0, 1]
  const std::vector<Vec2> element = sample_loop(aerofoil.model.loops[1], 1e-4 * aerofoil.model.size);
  const auto by_y = [](Vec2 a, Vec2 b) { return a.y < b.y; };
  const Vec2 top = *std::max_element(element.begin(), element.end(), by_y);
  const Vec2 bottom = *std::min_element(element.begin(), element.end(), by_y);
  const auto blocks = split_face(aerofoil.occ, aerofoil.model.frame, {{top, {top.x, 1.5}}, {bottom, {bottom.x, -1.5}}});
  ASSERT_EQ(blocks.size(), 2u);
  double sum = 0.0;
  for (const TopoDS_Face& block : blocks) {
    EXPECT_TRUE(BRepCheck_Analyzer(block).IsValid());
    EXPECT_TRUE(has_vertex(block, aerofoil.model.frame, {top.x, 1.5}, 1e-12));
    EXPECT_TRUE(has_vertex(block, aerofoil.model.frame, {bottom.x, -1.5}, 1e-12));
    sum += area_of(block);
  }
  EXPECT_NEAR(sum, aerofoil.model.area, 1e-9 * aerofoil.model.area);
}

TEST(Split, ReversedFaceGivesTheSameBlocks) {
  const Face square = reference("square");
  const TopoDS_Face reversed = TopoDS::Face(square.occ.Reversed());
  const FaceModel model = face_model_from_occ(reversed, "reversed");
  // Seen from the reversed normal, x keeps its direction and y flips.
  const auto blocks = split_face(reversed, model.frame,
                                 {{in_frame(model.frame, gp_Pnt(0.5, 0, 0)), in_frame(model.frame, gp_Pnt(1, 2, 0))}});
  expect_blocks(blocks, model, {1.5, 2.5});
}

// A face moved and rotated in 3-D: the splits, given in its own frame, lie on
// its plane and end where the original splits end, moved.
TEST(Split, MovedAndRotatedFaceSplitsOnItsPlane) {
  const Face plate = reference("plate_with_hole");
  const Polylines splits = plate_splits(plate.model);
  gp_Trsf rotation, translation;
  rotation.SetRotation(gp_Ax1(gp_Pnt(0.3, -0.2, 0.1), gp_Dir(1, 2, 3)), 1.1);
  translation.SetTranslation(gp_Vec(12.5, -7.25, 40.0));
  const gp_Trsf move = translation * rotation;
  // Moved geometry, and the same face under a location.
  for (const TopoDS_Shape& shape :
       {BRepBuilderAPI_Transform(plate.occ, move, /*copy=*/true).Shape(), plate.occ.Moved(TopLoc_Location(move))}) {
    const Face moved = from_shape(shape, "moved");
    const gp_Pln plane = BRepAdaptor_Surface(moved.occ).Plane();
    Polylines moved_splits;
    for (const auto& split : splits) {
      moved_splits.push_back({});
      for (Vec2 p : split) {
        moved_splits.back().push_back(in_frame(moved.model.frame, in_3d(plate.model.frame, p).Transformed(move)));
      }
    }
    const auto edges = split_edges_3d(moved.model.frame, moved_splits);
    ASSERT_EQ(edges.size(), 4u);
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const BRepAdaptor_Curve curve(edges[i]);
      for (int k = 0; k <= 10; ++k) {
        const double t = curve.FirstParameter() + k * (curve.LastParameter() - curve.FirstParameter()) / 10;
        EXPECT_LT(plane.Distance(curve.Value(t)), 1e-9);
      }
      const gp_Pnt start = in_3d(plate.model.frame, splits[i].front()).Transformed(move);
      const gp_Pnt end = in_3d(plate.model.frame, splits[i].back()).Transformed(move);
      EXPECT_LT(curve.Value(curve.FirstParameter()).Distance(start), 1e-9);
      EXPECT_LT(curve.Value(curve.LastParameter()).Distance(end), 1e-9);
    }
    const auto blocks = split_face(moved.occ, moved.model.frame, moved_splits);
    expect_blocks(blocks, moved.model, std::vector<double>(4, (16 - kPi) / 4));
    for (const TopoDS_Face& block : blocks) {
      for (TopExp_Explorer it(block, TopAbs_VERTEX); it.More(); it.Next()) {
        EXPECT_LT(plane.Distance(BRep_Tool::Pnt(TopoDS::Vertex(it.Current()))), 1e-9);
      }
    }
  }
}

TEST(Split, NoSplitsGiveTheFaceItself) {
  const Face plate = reference("plate_with_hole");
  expect_blocks(split_face(plate.occ, plate.model.frame, {}), plate.model, {16 - kPi});
}

TEST(Split, SplitOutsideTheFaceIsAnInputError) {
  const Face plate = reference("plate_with_hole");
  // Through the hole, and beyond the outer square.
  for (const Polylines& splits : {Polylines{{{-2, 0}, {2, 0}}}, Polylines{{{1, 0}, {2, 0}}, {{0, 1}, {0, 2.5}}}}) {
    try {
      split_face(plate.occ, plate.model.frame, splits);
      ADD_FAILURE() << "no error";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("leaves the face"), std::string::npos) << error.what();
    }
  }
}

TEST(Split, ZeroLengthPiecesAreDropped) {
  const Frame frame;
  const auto edges = split_edges_3d(frame, {{{0, 0}, {0, 0}, {1, 0}, {1, 0}, {1, 1}}, {{3, 3}, {3, 3}}});
  ASSERT_EQ(edges.size(), 2u);
  // The two pieces of the polyline share their vertex.
  TopoDS_Vertex first_end, first_start, second_start, second_end;
  TopExp::Vertices(edges[0], first_start, first_end);
  TopExp::Vertices(edges[1], second_start, second_end);
  EXPECT_TRUE(first_end.IsSame(second_start));
  EXPECT_LT(BRep_Tool::Pnt(second_end).Distance(gp_Pnt(1, 1, 0)), 1e-15);
}

TopoDS_Shape shape_of_brep_text(const std::string& text) {
  TopoDS_Shape shape;
  std::istringstream stream(text);
  BRep_Builder builder;
  BRepTools::Read(shape, stream, builder);
  return shape;
}

int count(const TopoDS_Shape& shape, TopAbs_ShapeEnum type) {
  TopTools_IndexedMapOfShape items;
  TopExp::MapShapes(shape, type, items);
  return items.Extent();
}

TEST(SplitBrep, StringEntryPointsRoundTrip) {
  const Face plate = reference("plate_with_hole");
  std::ostringstream text;
  BRepTools::Write(plate.occ, text);
  const Polylines splits = plate_splits(plate.model);
  const TopoDS_Shape blocks = shape_of_brep_text(split_face_brep(text.str(), splits, "plate"));
  ASSERT_EQ(count(blocks, TopAbs_FACE), 4);
  EXPECT_NEAR(area_of(blocks), 16 - kPi, 1e-9);
  for (TopExp_Explorer it(blocks, TopAbs_FACE); it.More(); it.Next()) {
    EXPECT_TRUE(BRepCheck_Analyzer(it.Current()).IsValid());
    EXPECT_NEAR(area_of(it.Current()), (16 - kPi) / 4, 1e-9);
  }
  const TopoDS_Shape edges = shape_of_brep_text(split_edges_brep(text.str(), splits, "plate"));
  ASSERT_EQ(count(edges, TopAbs_EDGE), 4);
  for (TopExp_Explorer it(edges, TopAbs_EDGE); it.More(); it.Next()) {
    const BRepAdaptor_Curve curve(TopoDS::Edge(it.Current()));
    EXPECT_NEAR(curve.LastParameter() - curve.FirstParameter(), 1.0, 1e-12);
  }
}

TEST(SplitBrep, BadTextIsAnInputErrorNamingTheFace) {
  try {
    split_face_brep("not a brep", {{{0, 0}, {1, 1}}}, "my face");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("my face"), std::string::npos) << error.what();
  }
}

TEST(SplitBrep, WritesBlocksAsBrepAndStep) {
  const Polylines splits = plate_splits(reference("plate_with_hole").model);
  for (const std::string ext : {".brep", ".step"}) {
    const std::string out = test::scratch_dir() + "/plate_blocks" + ext;
    std::filesystem::remove(out);
    testing::internal::CaptureStdout();
    write_blocks_brep(reference_path("plate_with_hole"), 0, splits, out);
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "") << ext;
    const TopoDS_Shape blocks = read_shape(out);
    EXPECT_EQ(count(blocks, TopAbs_FACE), 4) << ext;
    EXPECT_NEAR(area_of(blocks), 16 - kPi, 1e-9) << ext;
  }
  EXPECT_THROW(write_blocks_brep(reference_path("plate_with_hole"), 0, splits, test::scratch_dir() + "/x.txt"),
               InputError);
  EXPECT_THROW(write_blocks_brep(reference_path("plate_with_hole"), 2, splits, test::scratch_dir() + "/x.brep"),
               InputError);
}

}  // namespace
}  // namespace mm
