// The harmonic solve on grids whose answer is known: an affine map of the
// boundary extends to the same affine map inside (the five-point mean
// reproduces linear functions), in few iterations however large the grid.
#include <gtest/gtest.h>

#include <stdexcept>

#include "meshing/harmonic_solver.hpp"

namespace mm {
namespace {

// The lattice point (i, j) of an n x n grid mapped onto a unit parallelogram.
Vec2 affine(double i, double j, int n) {
  return Vec2{0.3 + (1.2 * i + 0.4 * j) / n, -0.7 + (0.1 * i + 0.9 * j) / n};
}

struct Grid {
  HarmonicSystem system;
  std::vector<Vec2> rhs;
};

// The (n+1) x (n+1) lattice with its border fixed at the affine map.
Grid grid(int n) {
  Grid g;
  const int inner = n - 1;
  const auto id = [&](int i, int j) { return (j - 1) * inner + (i - 1); };
  g.rhs.assign(inner * inner, Vec2{0.0, 0.0});
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) {
      const int k = id(i, j);
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int a = i + di, b = j + dj;
        if (a < 1 || a >= n || b < 1 || b >= n)
          g.rhs[k] = g.rhs[k] + affine(a, b, n);
        else
          g.system.neighbour.push_back(id(a, b));
      }
      g.system.degree.push_back(4.0);
      g.system.offset.push_back(static_cast<int>(g.system.neighbour.size()));
    }
  return g;
}

TEST(HarmonicSolver, AffineBoundaryGivesTheAffineMapInFewIterations) {
  for (int n : {4, 30, 300}) {
    const Grid g = grid(n);
    std::vector<Vec2> x(g.rhs.size(), Vec2{0.0, 0.0});
    const HarmonicSolve solve = solve_harmonic(g.system, g.rhs, x, 1e-12, 200);
    EXPECT_TRUE(solve.converged) << n;
    // Measured 1, 19 and 53; plain conjugate gradients need over a thousand at n = 300.
    EXPECT_LT(solve.iterations, 80) << n;
    double worst = 0.0;
    for (int j = 1; j < n; ++j)
      for (int i = 1; i < n; ++i) worst = std::max(worst, distance(x[(j - 1) * (n - 1) + (i - 1)], affine(i, j, n)));
    EXPECT_LT(worst, 1e-9) << n;
  }
}

TEST(HarmonicSolver, StartingAtTheAnswerTakesNoIteration) {
  const int n = 20;
  const Grid g = grid(n);
  std::vector<Vec2> x;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) x.push_back(affine(i, j, n));
  EXPECT_EQ(solve_harmonic(g.system, g.rhs, x, 1e-9, 200).iterations, 0);
}

TEST(HarmonicSolver, SizesThatDoNotFitAreRejected) {
  const Grid g = grid(5);
  std::vector<Vec2> short_start(3);
  EXPECT_THROW(solve_harmonic(g.system, g.rhs, short_start, 1e-9, 10), std::invalid_argument);
  HarmonicSystem bad = g.system;
  bad.neighbour[0] = 1000;
  std::vector<Vec2> x(g.rhs.size());
  EXPECT_THROW(solve_harmonic(bad, g.rhs, x, 1e-9, 10), std::invalid_argument);
}

// Nodes whose neighbours are all fixed do not coarsen: that level is solved
// by sweeps (exact here), not factored, however many nodes it has.
TEST(HarmonicSolver, NodesWithOnlyFixedNeighboursAreSolvedBySweeps) {
  HarmonicSystem system;
  std::vector<Vec2> rhs;
  for (int i = 0; i < 1000; ++i) {
    system.degree.push_back(4.0);
    system.offset.push_back(0);
    rhs.push_back(4.0 * Vec2{double(i), -double(i)});
  }
  std::vector<Vec2> x(rhs.size(), Vec2{0.0, 0.0});
  const HarmonicSolve solve = solve_harmonic(system, rhs, x, 1e-12, 10);
  EXPECT_TRUE(solve.converged);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(distance(x[i], Vec2{double(i), -double(i)}), 0.0) << i;
}

TEST(HarmonicSolver, PartWithoutAFixedNeighbourIsRejected) {
  // Two free nodes joined only to each other: the map is not determined.
  HarmonicSystem system;
  system.offset = {0, 1, 2};
  system.neighbour = {1, 0};
  system.degree = {1.0, 1.0};
  std::vector<Vec2> rhs(2), x(2);
  EXPECT_THROW(solve_harmonic(system, rhs, x, 1e-9, 10), std::invalid_argument);
  system.degree = {0.5, 1.0};  // fewer than its free neighbours
  EXPECT_THROW(solve_harmonic(system, rhs, x, 1e-9, 10), std::invalid_argument);
}

}  // namespace
}  // namespace mm
