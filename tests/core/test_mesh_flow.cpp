// Mesh flow and singularities of hand-built faces with known answers, the
// Poincare-Hopf invariant on random faces, and merging.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "face_builders.hpp"
#include "singularity/merge.hpp"
#include "svg/svg_writer.hpp"

namespace mm {
namespace {

using test::arc;
using test::face;
using test::full_circle;
using test::line;
using test::polygon;

MeshFlow flow_of(const FaceModel& f) {
  return compute_mesh_flow(f, compute_medial_axis(f));
}

std::vector<Vec2> regular_polygon(int sides) {
  std::vector<Vec2> pts;
  for (int i = 0; i < sides; ++i) pts.push_back({std::cos(2 * kPi * i / sides), std::sin(2 * kPi * i / sides)});
  return pts;
}

void expect_single(const MeshFlow& flow, int k, Vec2 p, SingularitySource at) {
  ASSERT_EQ(flow.singularities.size(), 1u);
  EXPECT_EQ(flow.singularities[0].k, k);
  EXPECT_NEAR(flow.singularities[0].p.x, p.x, 1e-9);
  EXPECT_NEAR(flow.singularities[0].p.y, p.y, 1e-9);
  EXPECT_EQ(flow.singularities[0].at, at);
}

TEST(MeshFlow, RectangleAndSquareHaveNone) {
  EXPECT_TRUE(flow_of(face({polygon({{0, 0}, {4, 0}, {4, 1}, {0, 1}})})).singularities.empty());
  EXPECT_TRUE(flow_of(face({polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})})).singularities.empty());
}

TEST(MeshFlow, RectangleFlowsStraightAlongItsMiddleAndDiagonallyIntoItsCorners) {
  const FaceModel f = face({polygon({{0, 0}, {4, 0}, {4, 1}, {0, 1}})});
  const MedialAxis axis = compute_medial_axis(f);
  const MeshFlow flow = compute_mesh_flow(f, axis);
  ASSERT_EQ(flow.runs.size(), axis.edges.size());  // no switches: one run per edge
  for (const FlowRun& run : flow.runs) {
    const bool middle = std::abs(run.points.front().y - 0.5) < 1e-9 && std::abs(run.points.back().y - 0.5) < 1e-9;
    EXPECT_EQ(run.n, middle ? 0 : 1);
  }
}

TEST(MeshFlow, RegularPolygonsHaveOneSingularityAtTheCentre) {
  expect_single(flow_of(face({polygon(regular_polygon(3))})), -1, {0, 0}, SingularitySource::Junction);
  expect_single(flow_of(face({polygon(regular_polygon(5))})), 1, {0, 0}, SingularitySource::Junction);
  // k = +2 comes out of the general junction balance, not a special case.
  expect_single(flow_of(face({polygon(regular_polygon(6))})), 2, {0, 0}, SingularitySource::Junction);
}

TEST(MeshFlow, CircleIsMinusFourAtItsCentre) {
  expect_single(flow_of(face({{full_circle({1, 2}, 1.5, 1)}})), -4, {1, 2}, SingularitySource::FiniteContact);
}

TEST(MeshFlow, StadiumIsMinusTwoAtEachArcCentre) {
  const FaceModel f =
      face({{line({-1, -1}, {1, -1}), arc({1, -1}, {1, 1}, 1.0), line({1, 1}, {-1, 1}), arc({-1, 1}, {-1, -1}, 1.0)}});
  const MeshFlow flow = flow_of(f);
  ASSERT_EQ(flow.singularities.size(), 2u);
  for (const Singularity& s : flow.singularities) {
    EXPECT_EQ(s.k, -2);
    EXPECT_EQ(s.at, SingularitySource::FiniteContact);
    EXPECT_NEAR(std::abs(s.p.x), 1.0, 1e-9);
    EXPECT_NEAR(s.p.y, 0.0, 1e-9);
  }
}

TEST(MeshFlow, HalfDiscSwitchesWhereTheParabolaReachesThreeQuarterPi) {
  const FaceModel f = face({{line({-1, 0}, {1, 0}), arc({1, 0}, {-1, 0}, 1.0)}});
  const MeshFlow flow = flow_of(f);
  ASSERT_EQ(flow.singularities.size(), 2u);
  for (const Singularity& s : flow.singularities) {
    EXPECT_EQ(s.k, -1);
    EXPECT_EQ(s.at, SingularitySource::FlowSwitch);
    // On y = (1 - x^2) / 2 the radii meet at 3 pi / 4 where x = sqrt(2) - 1.
    EXPECT_NEAR(std::abs(s.p.x), std::sqrt(2.0) - 1, 1e-8);
    EXPECT_NEAR(s.p.y, std::sqrt(2.0) - 1, 1e-8);
  }
}

TEST(MeshFlow, ConcaveCornersAddNoSpuriousSingularities) {
  // docs/flux_balance.md section 2, the arm terms. L-shape, a T and a slot cut into a rectangle: every concave corner
  // turns its cross arms along the axis, which must balance the flow switches.
  EXPECT_TRUE(flow_of(face({polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})})).singularities.empty());
  EXPECT_TRUE(
      flow_of(face({polygon({{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 3}, {1, 3}, {1, 1}, {0, 1}})})).singularities.empty());
  EXPECT_TRUE(flow_of(face({polygon({{0, 0}, {4, 0}, {4, 2}, {2.3, 2}, {2.3, 1.4}, {1.7, 1.4}, {1.7, 2}, {0, 2}})}))
                  .singularities.empty());
}

// An axis that does not balance (the square's centre junction cut off from
// its four edges) is an error naming the face and the check, not a result.
// docs/flux_balance.md section 5: a flare's flow is the corner's own, n = nc,
// so its k = 0 even where the flare's edge switches to n = 2 further on (on a
// thin strip with a shallow step, where the disc reaches the step's concave
// corner). Taking the far end's flow at the corner gave each flare k = +1.
TEST(MeshFlow, FlaresBesideAShallowStepOnAThinStripAreBalanced) {
  for (const double step : {0.005, 0.02}) {
    const FaceModel f =
        face({polygon({{0, 0}, {2, 0}, {2, step}, {2.5, step}, {2.5, 0}, {10, 0}, {10, 0.1}, {0, 0.1}})});
    const MedialAxis axis = compute_medial_axis(f);
    const MeshFlow flow = compute_mesh_flow(f, axis);
    EXPECT_EQ(flow.sum_k(), predicted_sum_k(f));
    EXPECT_EQ(predicted_sum_k(f), 0);
    int flares = 0;
    for (const MedialVertex& v : axis.vertices) flares += v.kind == MedialVertexKind::Flare;
    EXPECT_EQ(flares, 6);  // the strip's four corners and the step's two convex ones
    for (const Singularity& s : flow.singularities) {
      EXPECT_NE(s.at, SingularitySource::Flare) << "k = " << s.k << " at " << s.p.x << ", " << s.p.y;
      EXPECT_LE(std::abs(s.k), 1);
    }
  }
}

// docs/flux_balance.md sections 4 and 5: a rectangle with a half-ellipse on
// top. The axis ends in curvature contacts at the cap's two smooth joins with
// the sides, each taking its neighbour's touches, which lie either side of
// the join. Where the loop starts at a join, the gap between them passes the
// loop's vertex 0 and must add the loop's phi (the two corners' 2 - nc) on
// top of the plain phi difference: the answer may not depend on where the
// loop starts (a plain difference gave that end k = -3 and the face a sum of
// -4). The -1 on each side is the switch to n = 2 towards the cap's end.
TEST(MeshFlow, CurvatureContactAtTheLoopsStartIsBalancedLikeAnyOther) {
  const double a = 2.0, b = 0.8, h = 1.0;
  const BoundaryEdge cap{EllipseCurve{{0, h}, {1, 0}, a, b, 1}, 0.0, kPi, 0, {}, {}};
  const std::vector<BoundaryEdge> edges{cap, line({-a, h}, {-a, 0}), line({-a, 0}, {a, 0}), line({a, 0}, {a, h})};
  std::vector<Vec2> first;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    std::vector<BoundaryEdge> loop(edges.begin() + start, edges.end());
    loop.insert(loop.end(), edges.begin(), edges.begin() + start);
    const FaceModel f = face({loop}, "capped rectangle from edge " + std::to_string(start));
    ASSERT_EQ(predicted_sum_k(f), -2);
    const MeshFlow flow = flow_of(f);
    ASSERT_EQ(flow.singularities.size(), 2u) << f.name;
    std::vector<Vec2> places;
    for (const Singularity& s : flow.singularities) {
      EXPECT_EQ(s.k, -1) << f.name;  // the switch to n = 2 towards each end of the cap
      places.push_back(s.p);
    }
    std::sort(places.begin(), places.end(), [](Vec2 p, Vec2 q) { return p.x < q.x; });
    EXPECT_NEAR(places[0].x, -places[1].x, 1e-9) << f.name;  // mirror images, one at each end
    EXPECT_GT(places[1].x, 0.5 * a) << f.name;
    EXPECT_NEAR(places[0].y, places[1].y, 1e-9) << f.name;
    if (first.empty()) first = places;
    for (std::size_t i = 0; i < places.size(); ++i) EXPECT_NEAR(distance(places[i], first[i]), 0.0, 1e-9) << f.name;
  }
}

TEST(MeshFlow, UnbalancedResultIsASelfCheckError) {
  const FaceModel square = face({polygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}})}, "the square");
  MedialAxis axis = compute_medial_axis(square);
  const auto centre = std::find_if(axis.vertices.begin(), axis.vertices.end(),
                                   [](const MedialVertex& v) { return v.edges.size() == 4; });
  ASSERT_NE(centre, axis.vertices.end());
  centre->edges.clear();
  try {
    compute_mesh_flow(square, axis);
    FAIL() << "no SelfCheckError";
  } catch (const SelfCheckError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("the square: self-check failed: mesh flow: sum of k ", 0), 0u) << e.what();
  }
}

TEST(MeshFlow, AnnulusHasNone) {
  EXPECT_TRUE(flow_of(face({{full_circle({0, 0}, 2, 1)}, {full_circle({0, 0}, 1, -1)}})).singularities.empty());
}

// Sum of k over the face equals sum(2 - nc) - 4 chi on random faces of two
// families; flow types stay in 0..2 except next to near-cusps.
TEST(MeshFlow, PoincareHopfHoldsOnRandomFaces) {
  std::mt19937 rng(20261121);  // the medial axis test's faces, then notched ones
  int checked = 0, rejected = 0;
  std::vector<std::string> failures;
  while (checked < 1300) {
    FaceModel f;
    try {
      f = checked < 1000 ? test::random_face(rng, checked) : test::random_notched_face(rng, checked);
    } catch (const InputError&) {
      ++rejected;
      continue;
    }
    const MedialAxis axis = compute_medial_axis(f);
    const MeshFlow flow = compute_mesh_flow(f, axis);
    bool ok = flow.sum_k() == predicted_sum_k(f);
    for (const FlowRun& run : flow.runs) ok &= run.n >= 0 && run.n <= 2;
    if (!ok) {
      failures.push_back(f.name + ": sum k " + std::to_string(flow.sum_k()) + ", predicted " +
                         std::to_string(predicted_sum_k(f)));
      SvgCanvas canvas(bounding_box(f), 800);
      draw_face(canvas, f);
      std::vector<SingularityMark> marks;
      for (const Singularity& s : flow.singularities) marks.push_back({s.p, s.k});
      draw_mesh_flow(canvas, f, flow, marks);
      canvas.save("flow_face_" + std::to_string(checked) + ".svg");
    }
    ++checked;
  }
  EXPECT_TRUE(failures.empty()) << ::testing::PrintToString(failures);
  EXPECT_LT(rejected, 300);
}

TEST(MeshFlow, RunsCoverEveryEdgeAndSplitOnlyAtFlowChanges) {
  const FaceModel f = face({polygon({{0, 0}, {4, 0}, {4, 2}, {2.3, 2}, {2.3, 1.4}, {1.7, 1.4}, {1.7, 2}, {0, 2}})});
  const MedialAxis axis = compute_medial_axis(f);
  const MeshFlow flow = compute_mesh_flow(f, axis);
  std::vector<int> runs_per_edge(axis.edges.size(), 0);
  for (std::size_t i = 0; i < flow.runs.size(); ++i) {
    ++runs_per_edge[flow.runs[i].edge];
    if (i > 0 && flow.runs[i].edge == flow.runs[i - 1].edge) {
      EXPECT_NE(flow.runs[i].n, flow.runs[i - 1].n);
      EXPECT_NEAR(distance(flow.runs[i].points.front(), flow.runs[i - 1].points.back()), 0.0, 1e-12);
    }
  }
  for (std::size_t e = 0; e < axis.edges.size(); ++e) {
    EXPECT_GE(runs_per_edge[e], 1);
    const auto first =
        std::find_if(flow.runs.begin(), flow.runs.end(), [&](const FlowRun& r) { return r.edge == int(e); });
    EXPECT_NEAR(distance(first->points.front(), axis.edges[e].points.front().p), 0.0, 1e-12);
  }
}

Singularity at(Vec2 p, int k, double r) {
  return {p, r, k, SingularitySource::FlowSwitch, 0, -1};
}

TEST(MergeSingularities, GroupsByMedialRadiusAndSumsK) {
  const std::vector<Singularity> list{at({0, 0}, -1, 1.0), at({0.5, 0}, -1, 0.6), at({3, 0}, 1, 1.0)};
  // 0.5 apart: merged at factor 1 (reach 0.6), apart at 0.75 (reach 0.45).
  const auto merged = merge_singularities(list, {1.0, 0.0});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].k, -2);
  EXPECT_EQ(merged[0].members, (std::vector<int>{0, 1}));
  EXPECT_NEAR(merged[0].p.x, 0.25, 1e-15);
  EXPECT_EQ(merged[1].k, 1);
  EXPECT_EQ(merge_singularities(list, {0.75, 0.0}).size(), 3u);
  // A target mesh size replaces the radius rule.
  const auto coarse = merge_singularities(list, {0.75, 5.0});
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_EQ(coarse[0].k, -1);
}

TEST(MergeSingularities, OppositeSignsCancel) {
  const auto merged = merge_singularities({at({0, 0}, 1, 1.0), at({0.1, 0}, -1, 1.0)}, {});
  EXPECT_TRUE(merged.empty());
}

TEST(MergeSingularities, RejectsAFactorOutsideItsRange) {
  EXPECT_THROW(merge_singularities({}, {0.2, 0.0}), InputError);
  EXPECT_THROW(merge_singularities({}, {1.5, 0.0}), InputError);
  EXPECT_THROW(merge_singularities({}, {0.75, -1.0}), InputError);
}

TEST(MergeSingularities, HalfDiscPairMergesOnlyAtACoarseMeshSize) {
  // The half disc's two -1 lie 0.83 apart at medial radius 0.41: apart at
  // every radius factor, one -2 group for a target mesh size of 1.
  const FaceModel f = face({{line({-1, 0}, {1, 0}), arc({1, 0}, {-1, 0}, 1.0)}});
  const MeshFlow flow = flow_of(f);
  EXPECT_EQ(merge_singularities(flow.singularities, {}).size(), 2u);
  EXPECT_EQ(merge_singularities(flow.singularities, {1.0, 0.0}).size(), 2u);
  const auto coarse = merge_singularities(flow.singularities, {0.75, 1.0});
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_EQ(coarse[0].k, -2);
  EXPECT_NEAR(coarse[0].p.x, 0.0, 1e-8);
}

}  // namespace
}  // namespace mm
