#pragma once
// The linear system of a block's discrete harmonic map: every free node the
// mean of its neighbours, the outline fixed. Solved by conjugate gradients
// preconditioned by an aggregation multigrid V-cycle, so the iterations stay
// few however many nodes the block has (plain or diagonally preconditioned
// CG needs about the block's width in nodes).
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// Free nodes 0 .. n-1; node k's free neighbours are
// neighbour[offset[k] .. offset[k + 1]) and its degree counts every
// neighbour, fixed ones included. The matrix is D - A_free: symmetric, and
// positive definite when every connected part has a fixed neighbour.
struct HarmonicSystem {
  std::vector<int> offset{0};
  std::vector<int> neighbour;
  std::vector<double> degree;
};

struct HarmonicSolve {
  int iterations = 0;
  bool converged = false;
};

// Improves x (the start) until no node is more than `tolerance` from where
// its equation puts it (|residual| / degree), or max_iterations. Throws
// std::invalid_argument on sizes that do not fit the system.
HarmonicSolve solve_harmonic(const HarmonicSystem& system, const std::vector<Vec2>& rhs, std::vector<Vec2>& x,
                             double tolerance, int max_iterations);

}  // namespace mm
