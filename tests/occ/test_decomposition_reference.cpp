// Decomposition of the reference faces (known answers), of every shared and
// real CAD face (all checks), the face split by OCC along the splits, and
// the decompose command.
#include <gtest/gtest.h>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <fstream>
#include <nlohmann/json.hpp>

#include "decomposition_checks.hpp"
#include "medial/medial_axis.hpp"
#include "occ/occ_face.hpp"
#include "occ/occ_split.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

struct Case {
  FaceModel face;
  MeshFlow flow;
  Decomposition d;
};

Case decomposed(const std::string& name, double merge = 0.75) {
  Case c{test::reference_face(name), {}, {}};
  const MedialAxis axis = compute_medial_axis(c.face);
  c.flow = compute_mesh_flow(c.face, axis);
  DecompositionOptions options;
  options.merge = merge > 0;
  if (merge > 0) options.tolerance.radius_factor = merge;
  c.d = decompose(c.face, axis, c.flow, options);
  const auto problems = test::decomposition_problems(c.face, c.flow, c.d);
  EXPECT_TRUE(problems.empty()) << ::testing::PrintToString(problems);
  return c;
}

std::vector<std::pair<BlockKind, int>> blocks(const Decomposition& d) {
  std::vector<std::pair<BlockKind, int>> list;
  for (const Block& b : d.blocks) list.emplace_back(b.kind, static_cast<int>(b.corners.size()));
  std::sort(list.begin(), list.end());
  return list;
}

TEST(DecompositionReference, CircleIsOneZeroSidedBlock) {
  const Case c = decomposed("circle");
  EXPECT_TRUE(c.d.splits.empty());
  ASSERT_EQ(c.d.blocks.size(), 1u);
  EXPECT_EQ(c.d.blocks[0].kind, BlockKind::Polygon);
  EXPECT_EQ(c.d.blocks[0].corners.size(), 0u);
  ASSERT_GE(c.d.blocks[0].singularity, 0);
  EXPECT_EQ(c.d.singularities[c.d.blocks[0].singularity].k, -4);
}

TEST(DecompositionReference, SquareAndRectangleAreOneFourSidedBlock) {
  for (const char* name : {"square", "rectangle"}) {
    const Case c = decomposed(name);
    EXPECT_TRUE(c.d.splits.empty()) << name;
    EXPECT_EQ(blocks(c.d), (std::vector<std::pair<BlockKind, int>>{{BlockKind::Polygon, 4}})) << name;
  }
}

TEST(DecompositionReference, RegularPolygonsAreOneBlockOfTheirSides) {
  for (const auto& [name, sides, k] : {std::tuple{"triangle", 3, -1}, {"pentagon", 5, 1}, {"hexagon", 6, 2}}) {
    const Case c = decomposed(name);
    EXPECT_TRUE(c.d.splits.empty()) << name;
    ASSERT_EQ(c.d.blocks.size(), 1u) << name;
    EXPECT_EQ(c.d.blocks[0].kind, BlockKind::Polygon) << name;
    EXPECT_EQ(static_cast<int>(c.d.blocks[0].corners.size()), sides) << name;
    ASSERT_GE(c.d.blocks[0].singularity, 0) << name;
    EXPECT_EQ(c.d.singularities[c.d.blocks[0].singularity].k, k) << name;
  }
}

TEST(DecompositionReference, IndentsLAndTAreOneSubmapBlockWithNoSplit) {
  for (const char* name : {"indents", "L_shape", "T_shape"}) {
    const Case c = decomposed(name);
    EXPECT_TRUE(c.d.splits.empty()) << name;
    ASSERT_EQ(c.d.blocks.size(), 1u) << name;
    EXPECT_EQ(c.d.blocks[0].kind, BlockKind::Submap) << name;
  }
}

TEST(DecompositionReference, AnnulusIsOneSplitBetweenItsLoopsAndOneSubmapBlock) {
  const Case c = decomposed("annulus");
  ASSERT_EQ(c.d.splits.size(), 1u);
  const auto& line = c.d.splits[0].polyline;
  EXPECT_NEAR(std::min(norm(line.front()), norm(line.back())), 1.0, 1e-6);
  EXPECT_NEAR(std::max(norm(line.front()), norm(line.back())), 2.0, 1e-6);
  EXPECT_EQ(blocks(c.d), (std::vector<std::pair<BlockKind, int>>{{BlockKind::Submap, 4}}));
}

TEST(DecompositionReference, PlateWithHoleIsFourPentagonsAroundItsJunctions) {
  const Case c = decomposed("plate_with_hole");
  EXPECT_EQ(c.d.splits.size(), 4u);
  EXPECT_EQ(blocks(c.d), (std::vector<std::pair<BlockKind, int>>(4, {BlockKind::Polygon, 5})));
}

TEST(DecompositionReference, HalfDiscIsTwoTrianglesSplitOnItsAxis) {
  const Case c = decomposed("half_disk");
  ASSERT_EQ(c.d.splits.size(), 1u);
  for (const Vec2 p : c.d.splits[0].polyline) EXPECT_NEAR(p.x, 0.0, 1e-6);
  EXPECT_EQ(blocks(c.d), (std::vector<std::pair<BlockKind, int>>(2, {BlockKind::Polygon, 3})));
}

TEST(DecompositionReference, StadiumIsTwoTwoSidedBlocks) {
  const Case c = decomposed("stadium");
  EXPECT_EQ(c.d.splits.size(), 1u);
  EXPECT_EQ(blocks(c.d), (std::vector<std::pair<BlockKind, int>>(2, {BlockKind::Polygon, 2})));
}

// Fig. 26: the medial topology at a low merge factor, two 2-sided blocks at a high one.
TEST(DecompositionReference, EllipseFollowsItsMedialTopologyOrMergesIntoTwoHalves) {
  const Case fine = decomposed("ellipse", 0.25);
  EXPECT_EQ(fine.d.blocks.size(), 4u);
  ASSERT_EQ(fine.d.singularities.size(), 4u);
  for (const DecomposedSingularity& s : fine.d.singularities) EXPECT_EQ(s.k, -1);
  EXPECT_EQ(blocks(fine.d),
            (std::vector<std::pair<BlockKind, int>>{
                {BlockKind::Polygon, 3}, {BlockKind::Polygon, 3}, {BlockKind::Polygon, 4}, {BlockKind::Polygon, 4}}));
  const Case coarse = decomposed("ellipse", 1.0);
  EXPECT_EQ(coarse.d.splits.size(), 1u);
  EXPECT_EQ(blocks(coarse.d), (std::vector<std::pair<BlockKind, int>>(2, {BlockKind::Polygon, 2})));
}

double area_of(const TopoDS_Face& face) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props, 1e-12);
  return props.Mass();
}

std::vector<std::string> all_shared_faces() {
  auto files = test::brep_files(test::shared_dir() + "/geometry");
  for (const auto& f : test::brep_files(test::shared_dir() + "/realcad/faces")) files.push_back(f);
  return files;
}

// Every face in ../shared at three merge settings passes every check, and
// OCC splits the real face along the splits into valid faces, one per block.
TEST(DecompositionReference, EverySharedFaceTilesAndSplitsInOcc) {
  for (const std::string& path : all_shared_faces()) {
    const TopoDS_Face occ_face = face_of_shape(read_shape(path), std::nullopt, path);
    const FaceModel face = face_model_from_occ(occ_face, path);
    const MedialAxis axis = compute_medial_axis(face);
    const MeshFlow flow = compute_mesh_flow(face, axis);
    for (const double merge : {0.0, 0.25, 0.75, 1.0}) {
      DecompositionOptions options;
      options.merge = merge > 0;
      options.tolerance.radius_factor = merge > 0 ? merge : 0.75;
      Decomposition d;
      ASSERT_NO_THROW(d = decompose(face, axis, flow, options)) << path << " merge " << merge;
      const auto problems = test::decomposition_problems(face, flow, d);
      EXPECT_TRUE(problems.empty()) << path << " merge " << merge << ": " << ::testing::PrintToString(problems);
      if (merge != 0.75) continue;
      std::vector<std::vector<Vec2>> lines;
      for (const Split& s : d.splits) lines.push_back(s.polyline);
      std::vector<TopoDS_Face> pieces;
      ASSERT_NO_THROW(pieces = split_face(occ_face, face.frame, lines)) << path;
      // One OCC face per block, where every split is well above OCC's own
      // tolerance (the crank arm's 0.025 degree spikes get splits shorter
      // than its edges' tolerance, which OCC cannot cut).
      double shortest = 1e300;
      for (const auto& line : lines) shortest = std::min(shortest, distance(line.front(), line.back()));
      if (shortest > 1e-3 * face.size) EXPECT_EQ(pieces.size(), d.blocks.size()) << path;
      double area = 0.0;
      for (const TopoDS_Face& piece : pieces) {
        EXPECT_TRUE(BRepCheck_Analyzer(piece).IsValid()) << path;
        area += area_of(piece);
      }
      EXPECT_NEAR(area, area_of(occ_face), 1e-8 * face.area) << path;
    }
  }
}

TEST(DecomposeCommand, PrintsBlocksSplitsAndFixedAsJsonAndDrawsThem) {
  const std::string svg = test::scratch_dir() + "/plate_decomposition.svg";
  const std::string brep = test::scratch_dir() + "/plate_blocks.brep";
  const auto r = test::run_cli("decompose " + test::shared_dir() + "/geometry/plate_with_hole.brep --json --svg " +
                               svg + " --blocks " + brep);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["blocks"].size(), 4u);
  double area = 0.0;
  for (const auto& b : json["blocks"]) {
    EXPECT_EQ(b["kind"], "polygon");
    EXPECT_EQ(b["sides"], 5);
    EXPECT_EQ(b["singularity"]["k"], 1);
    EXPECT_GT(b["boundary"].size(), 5u);
    area += b["area"].get<double>();
  }
  EXPECT_NEAR(area, json["face_area"].get<double>(), 1e-9);
  EXPECT_EQ(json["splits"].size(), 4u);
  EXPECT_EQ(json["splits"][0]["polyline"].size(), 3u);
  EXPECT_TRUE(json["fixed"].empty());
  EXPECT_TRUE(json["wrapped_holes"].empty());  // a round hole has no corner
  // trimesh_boxsides_179's two slots, each run round by one submapped block.
  const auto slots =
      test::run_cli("decompose " + test::shared_dir() + "/realcad/faces/trimesh_boxsides_179.brep --json");
  ASSERT_EQ(slots.exit_code, 0) << slots.err;
  EXPECT_EQ(nlohmann::json::parse(slots.out)["wrapped_holes"], nlohmann::json::parse("[1, 6]"));
  std::ifstream picture(svg);
  const std::string text((std::istreambuf_iterator<char>(picture)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_GE(static_cast<int>(std::count(text.begin(), text.end(), '\n')), 20);
  // The blocks as faces of a BREP file that reads back as 4 faces.
  const auto info = test::run_cli("info " + brep + " --json");
  ASSERT_EQ(info.exit_code, 2) << info.err;  // several faces: the reader lists them
  EXPECT_NE(info.err.find("holds 4 faces"), std::string::npos) << info.err;
}

TEST(DecomposeCommand, MergeOptionsChangeTheEllipse) {
  const std::string file = test::shared_dir() + "/geometry/ellipse.brep";
  const auto fine = test::run_cli("decompose " + file + " --merge 0.25 --json");
  const auto coarse = test::run_cli("decompose " + file + " --merge 1 --json");
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  ASSERT_EQ(coarse.exit_code, 0) << coarse.err;
  EXPECT_EQ(nlohmann::json::parse(fine.out)["blocks"].size(), 4u);
  EXPECT_EQ(nlohmann::json::parse(coarse.out)["blocks"].size(), 2u);
}

TEST(DecomposeCommand, BadArgumentsExitTwoWithOneLine) {
  const std::string file = test::shared_dir() + "/geometry/square.brep";
  for (const std::string& args :
       std::vector<std::string>{"decompose " + file, "decompose " + file + " --json --merge 3",
                                "decompose " + file + " --json --merge 0.5 --no-merge",
                                "decompose " + file + " --json --blocks out.txt", "decompose /no/such.brep --json"}) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("medialmesh: "), std::string::npos) << args;
  }
}

}  // namespace
}  // namespace mm
