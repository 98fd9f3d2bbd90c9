// Interval assignment on hand-built problems: exact and rounded goals, submap
// outlines, shared segments, every template's equations, lower bounds, an
// impossible problem and a face-sized one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>

#include "meshing/interval_assignment.hpp"

namespace mm {
namespace {

// Every block's conditions, checked from the documentation alone: a submap's
// logical outline (side i heading the sum of the left turns before it)
// closes, and each template's parameters are >= 1 and satisfy its equations.
void expect_valid(const IntervalProblem& problem, const IntervalAssignment& a) {
  ASSERT_EQ(a.counts.size(), problem.segments.size());
  ASSERT_EQ(a.params.size(), problem.blocks.size());
  for (size_t s = 0; s < a.counts.size(); ++s) EXPECT_GE(a.counts[s], problem.segments[s].min_count) << "segment " << s;
  auto midpoint = [](const std::vector<long>& n, const std::vector<int>& c, const std::string& what) {
    const size_t m = n.size();
    ASSERT_EQ(c.size(), m) << what;
    for (size_t i = 0; i < m; ++i) EXPECT_EQ(n[i], c[(i + m - 1) % m] + c[(i + 1) % m]) << what << " side " << i;
  };
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    const BlockShape& block = problem.blocks[b];
    const std::vector<int>& p = a.params[b];
    const std::string what = "block " + std::to_string(b);
    for (int value : p) EXPECT_GE(value, 1) << what;
    std::vector<long> n;
    for (const auto& side : block.side_segments) {
      long total = 0;
      for (int s : side) total += a.counts[s];
      EXPECT_GE(total, 1) << what;
      n.push_back(total);
    }
    switch (block.kind) {
      case BlockTemplate::Submap: {
        EXPECT_TRUE(p.empty()) << what;
        double x = 0, y = 0, heading = 0;
        for (size_t i = 0; i < n.size(); ++i) {
          if (i > 0) heading += (2 - block.corner_types[i]) * M_PI / 2;
          x += n[i] * std::cos(heading);
          y += n[i] * std::sin(heading);
        }
        EXPECT_NEAR(x, 0.0, 1e-6) << what << " outline does not close";
        EXPECT_NEAR(y, 0.0, 1e-6) << what << " outline does not close";
        break;
      }
      case BlockTemplate::Midpoint: midpoint(n, p, what); break;
      case BlockTemplate::TwoSided:
        ASSERT_EQ(p.size(), 5u) << what;
        midpoint({n[0] - p[0], n[1] - p[1], p[0] + p[1]}, {p[2], p[3], p[4]}, what);
        break;
      case BlockTemplate::OneSided: {
        ASSERT_EQ(p.size(), 7u) << what;
        const long rest0 = n[0] - p[0] - p[1], rest1 = p[0] + p[1];
        midpoint({rest0 - p[2], rest1 - p[3], p[2] + p[3]}, {p[4], p[5], p[6]}, what);
        break;
      }
      case BlockTemplate::Disc:
        ASSERT_EQ(p.size(), 2u) << what;
        EXPECT_EQ(n[0], 2L * p[0] + 2L * p[1]) << what;
        break;
    }
  }
}

// The objective assign_intervals minimises (within 8 times the goal):
// relative deviation within one interval below the goal and above it, how
// many times too large the intervals are further below.
double deviation(const IntervalProblem& problem, const std::vector<int>& counts) {
  double total = 0;
  for (size_t s = 0; s < counts.size(); ++s) {
    const double g = std::max(problem.segments[s].goal, 1.0), n = counts[s];
    total += n >= g - 1 ? std::abs(n - g) / g : 1 / g + g / n - g / (g - 1);
  }
  return total;
}

// One segment per side.
BlockShape block(BlockTemplate kind, std::vector<int> corner_types, std::vector<int> segments) {
  BlockShape b;
  b.kind = kind;
  b.corner_types = std::move(corner_types);
  for (int s : segments) b.side_segments.push_back({s});
  return b;
}

std::vector<int> iota(int n) {
  std::vector<int> v(n);
  std::iota(v.begin(), v.end(), 0);
  return v;
}

IntervalProblem single(BlockTemplate kind, std::vector<int> corner_types, std::vector<double> goals) {
  IntervalProblem p;
  for (double g : goals) p.segments.push_back({g, 1});
  p.blocks.push_back(block(kind, std::move(corner_types), iota(static_cast<int>(goals.size()))));
  return p;
}

IntervalProblem submap(std::vector<int> corner_types, std::vector<double> goals) {
  return single(BlockTemplate::Submap, std::move(corner_types), std::move(goals));
}

TEST(IntervalAssignment, SquareTakesExactGoalsAndRoundsOthers) {
  IntervalProblem exact = submap({1, 1, 1, 1}, {5, 5, 5, 5});
  IntervalAssignment a = assign_intervals(exact);
  expect_valid(exact, a);
  EXPECT_EQ(a.counts, (std::vector<int>{5, 5, 5, 5}));

  IntervalProblem up = submap({1, 1, 1, 1}, {4.6, 7.7, 4.6, 7.7});
  a = assign_intervals(up);
  expect_valid(up, a);
  EXPECT_EQ(a.counts, (std::vector<int>{5, 8, 5, 8}));

  IntervalProblem down = submap({1, 1, 1, 1}, {4.4, 2.2, 4.4, 2.2});
  a = assign_intervals(down);
  EXPECT_EQ(a.counts, (std::vector<int>{4, 2, 4, 2}));
}

// Halfway between two counts both deviate alike: the fewer intervals win.
// A goal below a segment's lower bound gives way to the bound.
TEST(IntervalAssignment, HalfwayGoalsTakeTheFewerAndBoundsHold) {
  IntervalProblem half = submap({1, 1, 1, 1}, {4.5, 2.5, 4.5, 2.5});
  IntervalAssignment a = assign_intervals(half);
  expect_valid(half, a);
  EXPECT_EQ(a.counts, (std::vector<int>{4, 2, 4, 2}));

  IntervalProblem bound = submap({1, 1, 1, 1}, {0.3, 3, 0.3, 3});
  bound.segments[0].min_count = bound.segments[2].min_count = 2;
  a = assign_intervals(bound);
  expect_valid(bound, a);
  EXPECT_EQ(a.counts, (std::vector<int>{2, 3, 2, 3}));
}

TEST(IntervalAssignment, RectangleOppositeSidesBecomeEqualNearTheirGoals) {
  // Bottom wants 10, top 12: both take 11, which deviates least from both
  // (10 would make the top's intervals 1.2 times too large). Left and right
  // are met exactly.
  IntervalProblem p = submap({1, 1, 1, 1}, {10, 5, 12, 5});
  IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts, (std::vector<int>{11, 5, 11, 5}));

  // A long side facing a short one (a wedge's side opposite half of a cut
  // across it, goals 15 and 2): near sqrt(30), not the short side's 2, which
  // made elements 7 times the target size along the long side.
  p = submap({1, 1, 1, 1}, {15, 4, 2, 4});
  a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_GE(a.counts[0], 5);
  EXPECT_LE(a.counts[0], 6);
}

TEST(IntervalAssignment, EqualSumsTieTwoFacesBlocks) {
  // Two rectangles of two faces: the first's right side (segment 1, goal 5)
  // is the second's left side cut in two (segments 7 and 8, goals 2 and 2.5).
  IntervalProblem p = submap({1, 1, 1, 1}, {10, 5, 10, 5});
  BlockShape second;
  second.kind = BlockTemplate::Submap;
  second.corner_types = {1, 1, 1, 1};
  second.side_segments = {{4}, {5}, {6}, {7, 8}};
  p.blocks.push_back(second);
  for (double goal : {3.0, 4.0, 3.0, 2.0, 2.5}) p.segments.push_back({goal, 1});
  p.equal_sums.push_back({{1}, {7, 8}});
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[1], a.counts[7] + a.counts[8]);
  EXPECT_EQ(a.counts[5], a.counts[7] + a.counts[8]);
  p.equal_sums.push_back({{0}, {9}});
  EXPECT_THROW(assign_intervals(p), std::invalid_argument);
}

TEST(IntervalAssignment, FlatCornerSplitsASideKeepingItsHeading) {
  // The bottom is two sides meeting at a flat corner (type 2): 4 + 6 = top.
  IntervalProblem p = submap({1, 2, 1, 1, 1}, {4, 6, 5, 9, 5});
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[0] + a.counts[1], a.counts[3]);
  EXPECT_EQ(a.counts[2], a.counts[4]);
  EXPECT_LE(deviation(p, a.counts), deviation(p, {4, 5, 5, 9, 5}) + 1e-9);
}

TEST(IntervalAssignment, EmptyProblemHasAnEmptyAnswer) {
  const IntervalAssignment a = assign_intervals(IntervalProblem{});
  EXPECT_TRUE(a.counts.empty());
  EXPECT_TRUE(a.params.empty());
}

// A notch cut into a block's right side, one interval deep by its goal,
// beside a bottom one interval wide by its goal: the goals alone put the
// notch's inner wall onto the block's left side (the lattice folds); with
// the two sides given as facing, the bottom grows to keep them apart.
TEST(IntervalAssignment, FacingSidesStayAnIntervalApart) {
  // Sides: bottom E, right N, notch floor W, notch wall N, notch roof E,
  // right N, top W, left S.
  IntervalProblem p = submap({1, 1, 1, 3, 3, 1, 1, 1}, {1, 2, 1.2, 2, 3, 2, 3, 6});
  IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[0] - a.counts[2], 0);  // the wall at the left side's x
  p.blocks[0].facing = {{3, 7}};
  a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_GE(a.counts[0] - a.counts[2], 1);
  p.blocks[0].facing = {{3, 8}};
  EXPECT_THROW(assign_intervals(p), std::invalid_argument);
}

// A rectangle whose bottom and top face each other three elements apart
// while its sides want 20 and 30: the lattice's lines across them are
// capped (a crowding row), and the answer names that pair. Solved again
// with the pair given from the start (as mesh_blocks does after a
// separation round, sparing the solves that find it again), the counts are
// the same; pairs the problem does not have are ignored.
TEST(IntervalAssignment, CrowdedFacingPairsCarryOverToTheNextSolve) {
  IntervalProblem p = submap({1, 1, 1, 1}, {3, 20, 3, 30});
  p.blocks[0].facing = {{0, 2}};
  p.blocks[0].facing_goals = {3.0};
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  ASSERT_EQ(a.crowded.size(), 1u);
  EXPECT_EQ(a.crowded[0], (std::pair<std::size_t, std::size_t>{0, 0}));
  const IntervalAssignment again = assign_intervals(p, a.crowded);
  EXPECT_EQ(again.counts, a.counts);
  EXPECT_EQ(again.crowded, a.crowded);
  const IntervalAssignment unknown = assign_intervals(p, {{5, 0}, {0, 3}});
  EXPECT_EQ(unknown.counts, a.counts);
}

// A rectangle with a rectangular hole, cut once from its left side to the
// middle of the hole's left wall: the outline runs along the cut both ways,
// and round the hole between, so the hole's logical outline must close for
// the two runs to be one line (the goals alone leave it open: its left wall
// wants 1 + 1 intervals, its right wall 1).
TEST(IntervalAssignment, CutToAHoleWithCornersIsASlit) {
  IntervalProblem p;
  // Segments: bottom, right, top, left upper, the cut, hole left upper, top,
  // right, bottom, left lower, left lower of the block.
  for (double goal : {6.0, 6.0, 6.0, 3.0, 2.0, 1.0, 2.0, 1.0, 2.0, 1.0, 3.0}) p.segments.push_back({goal, 1});
  BlockShape b;
  b.kind = BlockTemplate::Submap;
  b.corner_types = {1, 1, 1, 1, 1, 1, 3, 3, 3, 3, 1, 1};
  b.side_segments = {{0}, {1}, {2}, {3}, {4}, {5}, {6}, {7}, {8}, {9}, {4}, {10}};
  p.blocks.push_back(b);
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[7], a.counts[5] + a.counts[9]);
  EXPECT_EQ(a.counts[6], a.counts[8]);
}

TEST(IntervalAssignment, LShapedSubmap) {
  // Headings 0, 1, 2, 1, 2, 3: the reflex corner 3 turns right.
  const std::vector<int> types{1, 1, 1, 3, 1, 1};
  IntervalProblem consistent = submap(types, {10, 4, 4, 4, 6, 8});
  IntervalAssignment a = assign_intervals(consistent);
  expect_valid(consistent, a);
  EXPECT_EQ(a.counts, (std::vector<int>{10, 4, 4, 4, 6, 8}));

  // Inconsistent goals: no worse than a hand-made answer that closes.
  IntervalProblem off = submap(types, {10.3, 4.2, 3.1, 4.4, 5.2, 9.6});
  a = assign_intervals(off);
  expect_valid(off, a);
  EXPECT_EQ(a.counts[0], a.counts[2] + a.counts[4]);
  EXPECT_EQ(a.counts[5], a.counts[1] + a.counts[3]);
  EXPECT_LE(deviation(off, a.counts), deviation(off, {10, 4, 4, 4, 6, 8}) + 1e-9);
}

TEST(IntervalAssignment, UShapedSubmap) {
  // Bottom, right, right arm top, down into the notch, notch bottom (reflex),
  // up out of it (reflex), left arm top, left side.
  IntervalProblem p = submap({1, 1, 1, 1, 3, 3, 1, 1}, {12, 8, 3.6, 5, 4.4, 5.3, 4, 7.7});
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  const std::vector<int>& n = a.counts;
  EXPECT_EQ(n[0], n[2] + n[4] + n[6]);
  EXPECT_EQ(n[1] + n[5], n[3] + n[7]);
  EXPECT_LE(deviation(p, n), deviation(p, {12, 8, 4, 5, 4, 5, 4, 8}) + 1e-9);
}

TEST(IntervalAssignment, SegmentSharedByTwoBlocksGetsOneCount) {
  // Two squares side by side; segment 1 is A's right and B's left side.
  IntervalProblem p;
  for (double g : {6.0, 5.0, 6.0, 3.0, 4.0, 7.0, 4.0}) p.segments.push_back({g, 1});
  p.blocks.push_back(block(BlockTemplate::Submap, {1, 1, 1, 1}, {0, 1, 2, 3}));
  p.blocks.push_back(block(BlockTemplate::Submap, {1, 1, 1, 1}, {4, 5, 6, 1}));
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  // The vertical chain 3 = 1 = 5 settles where the weighted deviation is least.
  EXPECT_EQ(a.counts[1], 5);
  EXPECT_EQ(a.counts[3], 5);
  EXPECT_EQ(a.counts[5], 5);
  EXPECT_EQ(a.counts[0], 6);
  EXPECT_EQ(a.counts[4], 4);
}

TEST(IntervalAssignment, TriangleWithOddGoalSumBecomesEven) {
  IntervalProblem p = single(BlockTemplate::Midpoint, {1, 1, 1}, {5, 4, 4});
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ((a.counts[0] + a.counts[1] + a.counts[2]) % 2, 0);
  EXPECT_EQ(std::abs(a.counts[0] - 5) + std::abs(a.counts[1] - 4) + std::abs(a.counts[2] - 4), 1);
}

// The end of an ellipse cut off by two lines: a triangle whose curved side
// wants nearly the other two together. By the sides alone the line from the
// centre to the curve gets one interval (elements 20 times the target along
// it); its goal (its length over the target size) gives it most of those.
TEST(IntervalAssignment, TriangleLineToItsLongSideKeepsNearItsGoal) {
  IntervalProblem p = single(BlockTemplate::Midpoint, {1, 1, 1}, {114, 57, 57});
  const IntervalAssignment alone = assign_intervals(p);
  expect_valid(p, alone);
  EXPECT_EQ(alone.params[0][0], 1);
  p.blocks[0].spoke_goals = {20.0, 10.0, 10.0};
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_GE(a.params[0][0], 12) << ::testing::PrintToString(a.counts);
  // The curved side gives way by less than a third.
  EXPECT_GE(a.counts[0], 2 * 114 / 3) << ::testing::PrintToString(a.counts);
  // Lines finer than their goal cost nothing: a regular triangle keeps its sides.
  IntervalProblem regular = single(BlockTemplate::Midpoint, {1, 1, 1}, {10, 10, 10});
  regular.blocks[0].spoke_goals = {2.9, 2.9, 2.9};
  EXPECT_EQ(assign_intervals(regular).counts, (std::vector<int>{10, 10, 10}));
  IntervalProblem bad = regular;
  bad.blocks[0].spoke_goals = {1.0, 1.0};
  EXPECT_THROW(assign_intervals(bad), std::invalid_argument);
}

TEST(IntervalAssignment, FiveAndSixSidedMidpointBlocks) {
  IntervalProblem five = single(BlockTemplate::Midpoint, {1, 1, 1, 1, 1}, {6, 7.5, 5, 9, 6.2});
  IntervalAssignment a = assign_intervals(five);
  expect_valid(five, a);
  EXPECT_EQ(a.params[0].size(), 5u);

  IntervalProblem six = single(BlockTemplate::Midpoint, {1, 1, 1, 1, 1, 1}, {4, 6, 4, 6, 4, 7});
  a = assign_intervals(six);
  expect_valid(six, a);
  EXPECT_EQ(a.params[0].size(), 6u);
}

TEST(IntervalAssignment, DiscLoopIsTwiceAPlusB) {
  IntervalProblem p = single(BlockTemplate::Disc, {}, {20});
  IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[0], 20);
  EXPECT_LE(std::abs(a.params[0][0] - a.params[0][1]), 1);  // inner rectangle near square

  IntervalProblem odd = single(BlockTemplate::Disc, {}, {13});
  a = assign_intervals(odd);
  expect_valid(odd, a);
  EXPECT_TRUE(a.counts[0] == 12 || a.counts[0] == 14);
}

TEST(IntervalAssignment, TwoSidedAndOneSidedParameters) {
  IntervalProblem two = single(BlockTemplate::TwoSided, {1, 1}, {12, 10});
  IntervalAssignment a = assign_intervals(two);
  expect_valid(two, a);
  EXPECT_EQ(a.counts, (std::vector<int>{12, 10}));

  // The midpoint rest has sides summing to n_0 + n_1, so that sum turns even.
  IntervalProblem odd = single(BlockTemplate::TwoSided, {1, 1}, {12, 9});
  a = assign_intervals(odd);
  expect_valid(odd, a);
  EXPECT_EQ(std::abs(a.counts[0] - 12) + std::abs(a.counts[1] - 9), 1);

  IntervalProblem one = single(BlockTemplate::OneSided, {1}, {17});
  a = assign_intervals(one);
  expect_valid(one, a);
  EXPECT_EQ(a.params[0].size(), 7u);
  EXPECT_LE(std::abs(a.counts[0] - 17), 1);
}

TEST(IntervalAssignment, FreeParametersAreBalanced) {
  // Equal sides of 12: a 4 x 4 quad leaves an even triangle of 8, 8, 8.
  IntervalProblem two = single(BlockTemplate::TwoSided, {1, 1}, {12, 12});
  IntervalAssignment a = assign_intervals(two);
  EXPECT_EQ(a.params[0], (std::vector<int>{4, 4, 4, 4, 4}));

  // 18 around: the quad takes 9 of them, the rest is the TwoSided block above halved.
  IntervalProblem one = single(BlockTemplate::OneSided, {1}, {18});
  a = assign_intervals(one);
  ASSERT_EQ(a.counts[0], 18);
  EXPECT_EQ(a.params[0][0] + a.params[0][1], 9);
  EXPECT_LE(std::abs(a.params[0][0] - a.params[0][1]), 1);
  EXPECT_EQ(std::vector<int>(a.params[0].begin() + 2, a.params[0].end()), (std::vector<int>{3, 3, 3, 3, 3}));
}

TEST(IntervalAssignment, LowerBoundsHoldWhenGoalsAreTiny) {
  IntervalProblem p = single(BlockTemplate::Disc, {}, {0.4});
  p.segments[0].min_count = 8;
  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  EXPECT_EQ(a.counts[0], 8);

  IntervalProblem tri = single(BlockTemplate::Midpoint, {1, 1, 1}, {0.2, 0.2, 0.2});
  const IntervalAssignment t = assign_intervals(tri);
  expect_valid(tri, t);
  EXPECT_EQ(t.counts, (std::vector<int>{2, 2, 2}));  // the smallest triangle midpoint subdivision allows
}

TEST(IntervalAssignment, ContradictoryBlocksThrowNamingTheBlock) {
  // Block 0: n0 = n1 + n2; block 1: n1 = n0 + n2, so n2 would be 0.
  IntervalProblem p;
  for (int s = 0; s < 7; ++s) p.segments.push_back({4.0, 1});
  BlockShape first = block(BlockTemplate::Submap, {1, 1, 1, 1}, {0, 3, 1, 4});
  first.side_segments[2] = {1, 2};
  BlockShape second = block(BlockTemplate::Submap, {1, 1, 1, 1}, {1, 5, 0, 6});
  second.side_segments[2] = {0, 2};
  p.blocks = {first, second};
  try {
    assign_intervals(p);
    FAIL() << "no counts satisfy both blocks";
  } catch (const IntervalsInfeasible& e) {
    EXPECT_NE(std::string(e.what()).find("block 1"), std::string::npos) << e.what();
  }
}

TEST(IntervalAssignment, BadInputIsRejected) {
  IntervalProblem open_outline = submap({1, 1, 1, 2}, {4, 4, 4, 4});
  try {
    assign_intervals(open_outline);
    FAIL() << "a submap outline turning 3 quarter turns";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("block 0"), std::string::npos) << e.what();
  }
  IntervalProblem bad_segment = submap({1, 1, 1, 1}, {4, 4, 4, 4});
  bad_segment.blocks[0].side_segments[2] = {9};
  EXPECT_THROW(assign_intervals(bad_segment), std::invalid_argument);
  EXPECT_THROW(assign_intervals(single(BlockTemplate::Midpoint, {1, 1, 1, 1}, {4, 4, 4, 4})), std::invalid_argument);
}

// A 40 x 40 grid of mapped cells with random goals, a saw of triangles along
// its top and a row of pentagons down its right side.
TEST(IntervalAssignment, FaceSizedProblemIsSolvedAndValid) {
  constexpr int kCells = 40;
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> goal(2.0, 12.0);
  IntervalProblem p;
  auto new_segment = [&] {
    p.segments.push_back({goal(rng), 1});
    return static_cast<int>(p.segments.size()) - 1;
  };
  std::vector<std::vector<int>> horizontal(kCells, std::vector<int>(kCells + 1));  // [x][y]
  std::vector<std::vector<int>> vertical(kCells + 1, std::vector<int>(kCells));    // [x][y]
  for (auto& column : horizontal)
    for (int& s : column) s = new_segment();
  for (auto& column : vertical)
    for (int& s : column) s = new_segment();
  for (int x = 0; x < kCells; ++x)
    for (int y = 0; y < kCells; ++y)
      p.blocks.push_back(block(BlockTemplate::Submap, {1, 1, 1, 1},
                               {horizontal[x][y], vertical[x + 1][y], horizontal[x][y + 1], vertical[x][y]}));
  std::vector<int> teeth(kCells + 1);
  for (int& s : teeth) s = new_segment();
  for (int x = 0; x < kCells; ++x)
    p.blocks.push_back(block(BlockTemplate::Midpoint, {1, 1, 1}, {horizontal[x][kCells], teeth[x + 1], teeth[x]}));
  std::vector<int> rungs(kCells + 1);
  for (int& s : rungs) s = new_segment();
  for (int y = 0; y < kCells; ++y)
    p.blocks.push_back(block(BlockTemplate::Midpoint, {1, 1, 1, 1, 1},
                             {vertical[kCells][y], rungs[y], new_segment(), new_segment(), rungs[y + 1]}));
  ASSERT_GT(p.segments.size(), 3000u);

  const IntervalAssignment a = assign_intervals(p);
  expect_valid(p, a);
  // Each column of horizontal segments shares one count, somewhere among its goals.
  for (int x = 0; x < kCells; ++x) {
    double low = 1e9, high = 0;
    for (int s : horizontal[x]) {
      low = std::min(low, p.segments[s].goal);
      high = std::max(high, p.segments[s].goal);
    }
    EXPECT_GE(a.counts[horizontal[x][0]], std::floor(low)) << x;
    EXPECT_LE(a.counts[horizontal[x][0]], std::ceil(high)) << x;
  }
}

// An S-shaped submap block (east, north, west, north, west, south, east,
// south; reflex corners 3 and 7) whose middle is too short: its arms cross.
// The pairs that keep it apart run opposite ways across the block; kept
// apart one by one as mesh_blocks does, the counts give a simple outline.
TEST(IntervalAssignment, FoldedSubmapOutlineNamesTheSidesToKeepApart) {
  BlockShape s;
  s.kind = BlockTemplate::Submap;
  s.corner_types = {1, 1, 1, 3, 1, 1, 1, 3};
  for (int i = 0; i < 8; ++i) s.side_segments.push_back({i});
  EXPECT_TRUE(folded_sides(s, {4, 1, 2, 1, 3, 1, 1, 1}).empty());
  const std::vector<FoldedSides> pairs = folded_sides(s, {2, 1, 3, 2, 1, 1, 2, 2});
  ASSERT_FALSE(pairs.empty());
  for (const FoldedSides& p : pairs) {
    EXPECT_FALSE(p.outside);
  }
  IntervalProblem problem;
  for (const double goal : {2.0, 1.0, 3.0, 2.0, 1.0, 1.0, 2.0, 2.0}) problem.segments.push_back({goal, 1});
  problem.blocks = {s};
  IntervalAssignment a = assign_intervals(problem);
  EXPECT_FALSE(folded_sides(problem.blocks[0], a.counts).empty());
  for (int round = 0; round < 8; ++round) {
    const std::vector<FoldedSides> folded = folded_sides(problem.blocks[0], a.counts);
    auto& facing = problem.blocks[0].facing;
    const auto fresh = std::find_if(folded.begin(), folded.end(), [&](const FoldedSides& f) {
      return std::find(facing.begin(), facing.end(), std::make_pair(f.s, f.t)) == facing.end();
    });
    if (fresh == folded.end()) break;
    facing.emplace_back(fresh->s, fresh->t);
    a = assign_intervals(problem);
  }
  expect_valid(problem, a);
  EXPECT_TRUE(folded_sides(problem.blocks[0], a.counts).empty());
}

}  // namespace
}  // namespace mm
