// The boundary model of every reference face: areas, holes, edges, corners
// and the Poincare-Hopf total, checked against what each shape is.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_Transform.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gp_Ax1.hxx>
#include <gp_Trsf.hxx>
#include <map>
#include <sstream>

#include "occ/occ_face.hpp"
#include "occ/occ_reader.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

using test::first_face;
using test::shared_dir;

FaceModel model_of(const std::string& path) {
  return read_face_models(path, {}).front();
}

std::map<int, int> nc_counts(const FaceModel& face) {
  std::map<int, int> counts;
  for (const Corner& c : face.corners) ++counts[c.nc];
  return counts;
}

std::map<std::string, int> edge_types(const FaceModel& face) {
  std::map<std::string, int> counts;
  for (const Loop& loop : face.loops) {
    for (const BoundaryEdge& e : loop.edges) ++counts[curve_type_name(curve_type(e.curve))];
  }
  return counts;
}

struct Expected {
  std::string name;
  double area;  // from the shape's dimensions
  int holes;
  std::map<std::string, int> edges;
  std::map<int, int> nc;  // corner type -> count
  int sum_k;
};

// What each reference face is, worked out from its shape (dimensions read off the
// drawings: e.g. the stadium is a 3 x 1 slot with round ends, the plate a 4 x 4 square
// with a hole of radius 1).
std::vector<Expected> expected_faces() {
  const double pi = kPi;
  return {
      {"L_shape", 3.0, 0, {{"line", 6}}, {{1, 5}, {3, 1}}, 0},
      {"T_shape", 5.0, 0, {{"line", 8}}, {{1, 6}, {3, 2}}, 0},
      {"annulus", pi * (4 - 1), 1, {{"circle", 2}}, {}, 0},
      {"circle", pi, 0, {{"circle", 1}}, {}, -4},
      {"ellipse", 2 * pi, 0, {{"ellipse", 1}}, {}, -4},
      {"half_disk", pi / 2, 0, {{"circle", 1}, {"line", 1}}, {{1, 2}}, -2},
      {"hexagon", 1.5 * std::sqrt(3.0), 0, {{"line", 6}}, {{1, 6}}, 2},
      {"indents", 8.0 - 4 * 0.6 * 0.3, 0, {{"line", 12}}, {{1, 8}, {3, 4}}, 0},
      {"pentagon", 2.5 * std::sin(0.4 * pi), 0, {{"line", 5}}, {{1, 5}}, 1},
      {"pinched_rectangle", 6.0 - 2 * 0.5 * 4 * 0.45, 0, {{"line", 6}}, {{1, 4}, {2, 2}}, 0},
      {"plate_with_hole", 16 - pi, 1, {{"line", 4}, {"circle", 1}}, {{1, 4}}, 4},
      {"rectangle", 4.0, 0, {{"line", 4}}, {{1, 4}}, 0},
      {"square", 4.0, 0, {{"line", 4}}, {{1, 4}}, 0},
      {"stadium", 3.0 + pi / 4, 0, {{"line", 2}, {"circle", 2}}, {}, -4},
      {"triangle", std::sqrt(3.0), 0, {{"line", 3}}, {{1, 3}}, -1},
      // Faces whose area has no short formula are checked against a fine polygon below.
      {"squeezed_rectangle", -1, 0, {{"line", 2}, {"circle", 2}}, {{1, 4}}, 0},
      {"bracket", -1, 3, {{"line", 8}, {"circle", 5}}, {{1, 4}, {3, 1}}, 11},
      {"aerofoil3", -1, 3, {{"line", 4}, {"bspline", 3}}, {{1, 4}, {4, 3}}, 6},
  };
}

TEST(ReferenceFaces, EveryFaceIsCovered) {
  EXPECT_EQ(test::brep_files(shared_dir() + "/geometry").size(), expected_faces().size());
}

TEST(ReferenceFaces, MatchTheirShapes) {
  for (const Expected& e : expected_faces()) {
    SCOPED_TRACE(e.name);
    const std::string path = shared_dir() + "/geometry/" + e.name + ".brep";
    const FaceModel face = model_of(path);
    const double oracle = test::discretised_area(first_face(read_shape(path)), 20000);
    EXPECT_NEAR(face.area, oracle, 1e-7 * face.area);
    if (e.area > 0) {
      EXPECT_NEAR(face.area, e.area, 1e-12 * e.area);
    }
    EXPECT_EQ(face.holes(), e.holes);
    EXPECT_EQ(face.euler(), 1 - e.holes);
    EXPECT_EQ(edge_types(face), e.edges);
    EXPECT_EQ(nc_counts(face), e.nc);
    EXPECT_EQ(predicted_sum_k(face), e.sum_k);
  }
}

TEST(ReferenceFaces, CornerAnglesComeFromTangents) {
  // Half disc: the arc meets the diameter at right angles, though chords would say 45+.
  for (const Corner& c : model_of(shared_dir() + "/geometry/half_disk.brep").corners) {
    EXPECT_NEAR(c.angle, kPi / 2, 1e-12);
  }
  // Squeezed rectangle: arcs bulge inwards, so the corners are sharper than 90 degrees.
  for (const Corner& c : model_of(shared_dir() + "/geometry/squeezed_rectangle.brep").corners) {
    EXPECT_LT(c.angle, kPi / 2 - 0.1);
  }
  // Stadium: the arcs join the straight sides tangentially, so it has no corner.
  EXPECT_TRUE(model_of(shared_dir() + "/geometry/stadium.brep").corners.empty());
}

// index.csv: file, source, face, surface, orientation, area, area_gprop, edges, holes, ...
struct IndexRow {
  std::string file;
  double area;
  int edges;
  int holes;
};

std::vector<IndexRow> realcad_index() {
  std::ifstream in(shared_dir() + "/realcad/faces/index.csv");
  std::string line;
  std::getline(in, line);  // header
  std::vector<IndexRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (cells.size() < 9) continue;
    rows.push_back({cells[0], std::stod(cells[5]), std::stoi(cells[7]), std::stoi(cells[8])});
  }
  return rows;
}

TEST(RealCadFaces, MatchTheIndex) {
  const auto rows = realcad_index();
  EXPECT_EQ(rows.size(), test::brep_files(shared_dir() + "/realcad/faces").size());
  for (const IndexRow& row : rows) {
    SCOPED_TRACE(row.file);
    const std::string path = shared_dir() + "/realcad/faces/" + row.file;
    const FaceModel face = model_of(path);
    // The index's area comes from a fine discretisation, itself good to about 1e-6.
    EXPECT_NEAR(face.area, row.area, 5e-6 * row.area);
    EXPECT_EQ(face.holes(), row.holes);
    std::size_t edges = 0;
    for (const Loop& loop : face.loops) edges += loop.edges.size();
    // The source's edges, less the short pieces of a circle joined to their
    // neighbour on it: the nut's 0.048 seam piece, and two arcs of 4.57 of
    // the interface plate (under a hundredth of its size).
    const int joined = row.file == "occt_pumpnut_1.brep" ? 1 : row.file == "trimesh_baseiface_10.brep" ? 2 : 0;
    EXPECT_EQ(static_cast<int>(edges), row.edges - joined);
    int sum = 0;
    for (const Corner& c : face.corners) {
      EXPECT_EQ(c.nc, optimal_corner_type(c.angle));
      sum += 2 - c.nc;
    }
    EXPECT_EQ(predicted_sum_k(face), sum - 4 * face.euler());
  }
}

TEST(RealCadFaces, TinyEdgesAndCuspsKeepTheirCorners) {
  // Crank arm: two arcs meet back to back at a zero-angle spike on either side of the hub.
  const FaceModel crank = model_of(shared_dir() + "/realcad/faces/occt_crankarm_30.brep");
  EXPECT_EQ(nc_counts(crank), (std::map<int, int>{{0, 2}, {1, 4}}));
  // Laser-cut panel: 0.05 mm edges beside 25 mm ones are corners like any other.
  const FaceModel panel = model_of(shared_dir() + "/realcad/faces/trimesh_boxsides_51.brep");
  EXPECT_EQ(panel.corners.size(), 60u);
  EXPECT_EQ(predicted_sum_k(panel), 0);
}

TEST(RealCadFaces, BSplineCircleIsRecognised) {
  // The pump cover's bore is stored as one closed B-spline: it comes out as a circle.
  const FaceModel cover = model_of(shared_dir() + "/realcad/faces/occt_pumpcover_8.brep");
  EXPECT_EQ(edge_types(cover), (std::map<std::string, int>{{"circle", 2}}));
  EXPECT_TRUE(cover.corners.empty());
}

// Moving a face anywhere in 3-D changes nothing in 2-D but a rigid motion.
TEST(Placement, RotatedAndTranslatedFaceGivesTheSameModel) {
  gp_Trsf rotation, translation;
  rotation.SetRotation(gp_Ax1(gp_Pnt(0.3, -0.2, 0.1), gp_Dir(1, 2, 3)), 1.1);
  translation.SetTranslation(gp_Vec(12.5, -7.25, 40.0));
  const gp_Trsf move = translation * rotation;
  for (const std::string& path : test::brep_files(shared_dir() + "/geometry")) {
    SCOPED_TRACE(path);
    const TopoDS_Shape shape = read_shape(path);
    const TopoDS_Shape moved = BRepBuilderAPI_Transform(shape, move, /*copy=*/true).Shape();
    const FaceModel a = face_model_from_occ(first_face(shape), "original");
    const FaceModel b = face_model_from_occ(first_face(moved), "moved");
    EXPECT_NEAR(a.area, b.area, 1e-10 * a.area);
    EXPECT_EQ(a.holes(), b.holes());
    EXPECT_EQ(edge_types(a), edge_types(b));
    ASSERT_EQ(a.corners.size(), b.corners.size());
    // Corners map back to the moved 3-D points, with the same angles and types.
    for (const Corner& ca : a.corners) {
      const auto p = to_3d(a.frame, ca.position);
      const gp_Pnt expected = gp_Pnt(p[0], p[1], p[2]).Transformed(move);
      bool found = false;
      for (const Corner& cb : b.corners) {
        const auto q = to_3d(b.frame, cb.position);
        if (expected.Distance(gp_Pnt(q[0], q[1], q[2])) < 1e-9 * a.size) {
          found = true;
          EXPECT_NEAR(ca.angle, cb.angle, 1e-9);
          EXPECT_EQ(ca.nc, cb.nc);
        }
      }
      EXPECT_TRUE(found) << "corner at " << ca.position.x << ", " << ca.position.y;
    }
  }
}

TEST(Placement, FaceInTheXYPlaneKeepsWorldCoordinates) {
  const FaceModel face = model_of(shared_dir() + "/geometry/indents.brep");
  bool found = false;
  for (const Corner& c : face.corners) found = found || (distance(c.position, {1.7, 0.6}) < 1e-12);
  EXPECT_TRUE(found);
}

TEST(StepInput, FaceOfAStepFileMatchesItsBrepExtract) {
  const std::string step = shared_dir() + "/realcad/step/trimesh_featuretype.STEP";
  const FaceModel from_step = read_face_models(step, {18}).front();
  const FaceModel from_brep = model_of(shared_dir() + "/realcad/faces/trimesh_featuretype_18.brep");
  EXPECT_NEAR(from_step.area, from_brep.area, 1e-9 * from_brep.area);
  EXPECT_EQ(from_step.holes(), from_brep.holes());
  EXPECT_EQ(nc_counts(from_step), nc_counts(from_brep));
  EXPECT_EQ(predicted_sum_k(from_step), predicted_sum_k(from_brep));
  // Several faces at once, in the order asked.
  const auto both = read_face_models(step, {23, 50});
  ASSERT_EQ(both.size(), 2u);
  EXPECT_NEAR(both[0].area, model_of(shared_dir() + "/realcad/faces/trimesh_featuretype_23.brep").area, 1e-6);
}

TEST(IgesInput, FaceWrittenAsIgesReadsBack) {
  // OCC's own IGES writer makes the file; reading it must give the same model.
  const std::string brep = shared_dir() + "/geometry/plate_with_hole.brep";
  const std::string iges = test::scratch_dir() + "/plate_with_hole.igs";
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", /*brep mode=*/1);
  writer.AddShape(read_shape(brep));
  writer.ComputeModel();
  ASSERT_TRUE(writer.Write(iges.c_str()));
  const FaceModel from_iges = read_face_models(iges, {}).front();
  const FaceModel from_brep = model_of(brep);
  EXPECT_NEAR(from_iges.area, from_brep.area, 1e-9 * from_brep.area);
  EXPECT_EQ(from_iges.holes(), 1);
  EXPECT_EQ(nc_counts(from_iges), nc_counts(from_brep));
  EXPECT_EQ(predicted_sum_k(from_iges), 4);
}

TEST(StepInput, EveryPlanarFaceOfTheStepFilesReads) {
  for (const char* name : {"trimesh_featuretype.STEP", "trimesh_base_interface_AP214.STEP"}) {
    SCOPED_TRACE(name);
    const std::string path = shared_dir() + "/realcad/step/" + name;
    const TopoDS_Shape shape = read_shape(path);
    int planar = 0;
    for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) {
      try {
        const FaceModel face = face_model_from_occ(TopoDS::Face(it.Current()), name);
        ++planar;
        EXPECT_GT(face.area, 0.0);
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not planar"), std::string::npos) << e.what();
      }
    }
    EXPECT_GT(planar, 5);
  }
}

}  // namespace
}  // namespace mm
