// Singularities of every reference and real CAD face: the Poincare-Hopf
// invariant everywhere, the known answers of the reference shapes, and the
// singularities command of the CLI.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "medial/medial_axis.hpp"
#include "occ/occ_reader.hpp"
#include "singularity/merge.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

MeshFlow flow_of(const FaceModel& face) {
  return compute_mesh_flow(face, compute_medial_axis(face));
}

Vec2 corner_centroid(const FaceModel& face) {
  Vec2 sum;
  for (const Corner& c : face.corners) sum = sum + c.position;
  return sum / static_cast<double>(face.corners.size());
}

// Every singularity has the given k and lies at one of the expected points,
// each point taken once.
void expect_at(const MeshFlow& flow, int k, std::vector<Vec2> expected, double tolerance) {
  ASSERT_EQ(flow.singularities.size(), expected.size());
  for (const Singularity& s : flow.singularities) {
    EXPECT_EQ(s.k, k);
    const auto near =
        std::find_if(expected.begin(), expected.end(), [&](Vec2 e) { return distance(e, s.p) <= tolerance; });
    ASSERT_NE(near, expected.end()) << "unexpected singularity at " << s.p.x << ", " << s.p.y;
    expected.erase(near);
  }
}

TEST(SingularityReference, PoincareHopfHoldsOnEveryReferenceAndRealFace) {
  for (const char* folder : {"/geometry", "/realcad/faces"}) {
    for (const std::string& path : test::brep_files(test::shared_dir() + folder)) {
      SCOPED_TRACE(path);
      const FaceModel face = read_face_models(path, {}).front();
      const MeshFlow flow = flow_of(face);
      EXPECT_EQ(flow.sum_k(), predicted_sum_k(face));
      for (const FlowRun& run : flow.runs) EXPECT_LE(run.n, 2);
      // Merging keeps the sum: groups of net 0 vanish, the others add up.
      int merged = 0;
      for (const SingularityGroup& g : merge_singularities(flow.singularities, {})) merged += g.k;
      EXPECT_EQ(merged, predicted_sum_k(face));
    }
  }
}

TEST(SingularityReference, FacesWithoutSingularities) {
  for (const char* name : {"rectangle", "square", "annulus", "indents", "L_shape", "T_shape"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(flow_of(test::reference_face(name)).singularities.empty());
  }
}

TEST(SingularityReference, RegularPolygonsAtTheirCentres) {
  for (const auto& [name, k] : {std::pair{"triangle", -1}, {"pentagon", 1}, {"hexagon", 2}}) {
    SCOPED_TRACE(name);
    const FaceModel face = test::reference_face(name);
    expect_at(flow_of(face), k, {corner_centroid(face)}, 1e-9);
  }
}

TEST(SingularityReference, CircleStadiumAndHalfDisc) {
  const FaceModel circle = test::reference_face("circle");
  expect_at(flow_of(circle), -4, {0.5 * (bounding_box(circle).min + bounding_box(circle).max)}, 1e-9);
  expect_at(flow_of(test::reference_face("stadium")), -2, {{-1.5, 0}, {1.5, 0}}, 1e-9);
  const double x = std::sqrt(2.0) - 1;  // where y = (1 - x^2) / 2 meets the radii at 3 pi / 4
  expect_at(flow_of(test::reference_face("half_disk")), -1, {{-x, x}, {x, x}}, 1e-8);
}

TEST(SingularityReference, EllipseSwitchesAtQuarterAndThreeQuarterPi) {
  // Ellipse 2 x 1: the axis point (1.5 cos t, 0) touches (2 cos t, sin t);
  // the radii meet at 2 atan(2 tan t), which is 3 pi / 4 and pi / 4 at:
  const auto x_at = [](double medial_angle) { return 1.5 * std::cos(std::atan(0.5 * std::tan(medial_angle / 2))); };
  const double inner = x_at(3 * kPi / 4), outer = x_at(kPi / 4);
  EXPECT_NEAR(inner, 0.957, 1e-3);
  EXPECT_NEAR(outer, 1.469, 1e-3);
  expect_at(flow_of(test::reference_face("ellipse")), -1, {{-outer, 0}, {-inner, 0}, {inner, 0}, {outer, 0}}, 1e-8);
}

TEST(SingularityReference, PlateWithHoleHasPlusOneAtEachJunction) {
  const double x = 3.0 / (1.0 + std::sqrt(2.0));
  const MeshFlow flow = flow_of(test::reference_face("plate_with_hole"));
  expect_at(flow, 1, {{x, x}, {-x, x}, {x, -x}, {-x, -x}}, 1e-9);
  for (const Singularity& s : flow.singularities) EXPECT_EQ(s.at, SingularitySource::Junction);
}

FaceModel fuzz_face(const std::string& name) {
  return test::data_face("fuzz/" + name);
}

// docs/flux_balance.md section 5, found by the fuzz program: a thin strip
// (half-width 3e-5) with a notch 3e-6 deep. Each flare of the notch's convex
// corners switches to n = 2 where its disc reaches the notch's concave
// corner; the flare itself keeps the corner's n = nc and k = 0.
TEST(SingularityReference, FlaresOfATinyNotchInAThinStripAreBalanced) {
  const FaceModel face = fuzz_face("strip_1_18");
  const MeshFlow flow = flow_of(face);
  EXPECT_EQ(flow.sum_k(), 0);
  EXPECT_EQ(predicted_sum_k(face), 0);
  for (const Singularity& s : flow.singularities) {
    EXPECT_NE(s.at, SingularitySource::Flare);
    EXPECT_LE(std::abs(s.k), 1);
  }
}

// Section 3, found by the fuzz program: on a closed B-spline outline a ripple
// branch (medial angle under 45 degrees all along) is pruned from the axis,
// and the touch of the edge it left jumps past the ripple. That sliver
// carries the branch's k = -1 (reported as the junction it stands for, on
// the edge); the sum stays the Poincare-Hopf total.
TEST(SingularityReference, TouchJumpPastAPrunedBranchCarriesTheBranchesK) {
  const FaceModel face = fuzz_face("bspline_1_122");
  const MeshFlow flow = flow_of(face);
  EXPECT_EQ(flow.sum_k(), predicted_sum_k(face));
  int jumps = 0;
  for (const Singularity& s : flow.singularities) {
    EXPECT_LE(std::abs(s.k), 1);
    if (s.at == SingularitySource::Junction && s.vertex < 0) {
      ++jumps;
      EXPECT_EQ(s.k, -1);
      EXPECT_GE(s.edge, 0);
    }
  }
  EXPECT_EQ(jumps, 1);
}

TEST(SingularityCli, JsonListsSingularitiesAndTheirSum) {
  const auto result = test::run_cli("singularities " + test::shared_dir() + "/geometry/half_disk.brep --json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto report = nlohmann::json::parse(result.out);
  ASSERT_EQ(report["singularities"].size(), 2u);
  for (const auto& s : report["singularities"]) {
    EXPECT_EQ(s["k"], -1);
    EXPECT_EQ(s["at"], "flow_switch");
    EXPECT_NEAR(s["y"].get<double>(), std::sqrt(2.0) - 1, 1e-8);
  }
  EXPECT_EQ(report["sum_k"], -2);
  EXPECT_EQ(report["predicted_sum_k"], -2);
  EXPECT_FALSE(report["flow"].empty());
}

TEST(SingularityCli, MergeGroupsAndKeepsMembers) {
  // The ellipse's -1 pairs lie 0.51 apart with radii 0.53 and 0.83: apart at
  // factor 0.75, merged into two -2 at factor 1.
  const std::string file = test::shared_dir() + "/geometry/ellipse.brep";
  const auto apart = nlohmann::json::parse(test::run_cli("singularities " + file + " --merge --json").out);
  EXPECT_EQ(apart["singularities"].size(), 4u);
  const auto result = test::run_cli("singularities " + file + " --merge 1 --json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto merged = nlohmann::json::parse(result.out);
  ASSERT_EQ(merged["singularities"].size(), 2u);
  for (const auto& g : merged["singularities"]) {
    EXPECT_EQ(g["k"], -2);
    EXPECT_EQ(g["at"], "merged");
    EXPECT_EQ(g["members"].size(), 2u);
  }
  EXPECT_EQ(merged["unmerged"].size(), 4u);
  EXPECT_EQ(merged["sum_k"], -4);
}

TEST(SingularityCli, RejectsAMergeFactorOutOfRange) {
  const auto result = test::run_cli("singularities " + test::shared_dir() + "/geometry/ellipse.brep --merge 2 --json");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("merge factor"), std::string::npos) << result.err;
}

TEST(SingularityCli, SvgShowsFlowColoursAndLabels) {
  const std::string svg = test::scratch_dir() + "/hexagon_flow.svg";
  const auto result = test::run_cli("singularities " + test::shared_dir() + "/geometry/hexagon.brep --svg " + svg);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("stroke:#2ca02c"), std::string::npos);  // n = 1 runs
  EXPECT_NE(text.str().find(">+2</text>"), std::string::npos);      // the centre's k
}

}  // namespace
}  // namespace mm
