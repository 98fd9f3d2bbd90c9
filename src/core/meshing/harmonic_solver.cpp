#include "meshing/harmonic_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mm {
namespace {

// Below this many unknowns a level is solved exactly (dense Cholesky).
constexpr int kCoarsest = 200;
// Piecewise-constant prolongation undershoots the smooth error; scaling the
// coarse correction up (the usual remedy for plain aggregation) keeps the
// V-cycle a symmetric positive definite preconditioner and roughly halves
// the iterations on these meshes.
constexpr double kCoarseScale = 1.8;

// Symmetric sparse matrix, rows in compressed form; the diagonal apart.
struct Level {
  int n = 0;
  bool unit = false;     // every off-diagonal entry is -1 (the finest level): no values to read
  std::vector<int> row;  // entries of row i: col/value[row[i] .. row[i + 1])
  std::vector<int> col;
  std::vector<double> value;
  std::vector<double> diagonal;
  std::vector<int> aggregate;    // fine node -> node of the next level
  std::vector<double> cholesky;  // coarsest level only: dense lower factor, n x n
  std::vector<int> first;        // and where each row of the factor starts (its envelope)
  std::vector<int> last;         // and where each of its columns ends
  mutable std::vector<Vec2> residual, coarse_rhs, coarse_x;
};

// Greedy aggregation: a node whose neighbours are all free starts an
// aggregate of itself and them; leftovers join a neighbouring aggregate.
int aggregate(const Level& level, std::vector<int>& of) {
  of.assign(level.n, -1);
  int count = 0;
  for (int i = 0; i < level.n; ++i) {
    if (of[i] >= 0) continue;
    bool free = true;
    for (int k = level.row[i]; k < level.row[i + 1] && free; ++k) free = of[level.col[k]] < 0;
    if (!free) continue;
    of[i] = count;
    for (int k = level.row[i]; k < level.row[i + 1]; ++k) of[level.col[k]] = count;
    ++count;
  }
  for (int i = 0; i < level.n; ++i) {
    if (of[i] >= 0) continue;
    for (int k = level.row[i]; k < level.row[i + 1]; ++k)
      if (of[level.col[k]] >= 0) {
        of[i] = of[level.col[k]];
        break;
      }
    if (of[i] < 0) of[i] = count++;  // no neighbour at all
  }
  return count;
}

// The Galerkin product P^T A P for piecewise-constant P.
Level coarsen(const Level& fine, const std::vector<int>& of, int n) {
  Level coarse;
  coarse.n = n;
  coarse.diagonal.assign(n, 0.0);
  std::vector<int> first(n + 1, 0), members(fine.n);
  for (int i = 0; i < fine.n; ++i) ++first[of[i] + 1];
  for (int c = 0; c < n; ++c) first[c + 1] += first[c];
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (int i = 0; i < fine.n; ++i) members[fill[of[i]]++] = i;
  std::vector<int> slot(n, -1);
  coarse.row.assign(1, 0);
  for (int c = 0; c < n; ++c) {
    const int start = static_cast<int>(coarse.col.size());
    for (int m = first[c]; m < first[c + 1]; ++m) {
      const int i = members[m];
      coarse.diagonal[c] += fine.diagonal[i];
      for (int k = fine.row[i]; k < fine.row[i + 1]; ++k) {
        const int d = of[fine.col[k]];
        if (d == c) {
          coarse.diagonal[c] += fine.value[k];
        } else if (slot[d] < 0) {
          slot[d] = static_cast<int>(coarse.col.size());
          coarse.col.push_back(d);
          coarse.value.push_back(fine.value[k]);
        } else {
          coarse.value[slot[d]] += fine.value[k];
        }
      }
    }
    for (std::size_t k = start; k < coarse.col.size(); ++k) slot[coarse.col[k]] = -1;
    coarse.row.push_back(static_cast<int>(coarse.col.size()));
  }
  return coarse;
}

// Cholesky's factor keeps within the matrix's envelope: row i of the factor
// is zero left of the first entry of row i of the matrix. The loops skip
// what lies outside (zeros that would only be subtracted): on a block's
// nodes, numbered row by row, the envelope is a band as wide as the block.
void factor_dense(Level& level) {
  const int n = level.n;
  std::vector<double>& a = level.cholesky;
  a.assign(static_cast<std::size_t>(n) * n, 0.0);
  level.first.resize(n);
  for (int i = 0; i < n; ++i) {
    a[i * n + i] = level.diagonal[i];
    level.first[i] = i;
    for (int k = level.row[i]; k < level.row[i + 1]; ++k) {
      a[i * n + level.col[k]] = level.value[k];
      level.first[i] = std::min(level.first[i], level.col[k]);
    }
  }
  level.last.resize(n);
  for (int i = 0; i < n; ++i) level.last[i] = i;
  for (int i = 0; i < n; ++i)
    for (int j = level.first[i]; j < i; ++j) level.last[j] = std::max(level.last[j], i);
  const std::vector<int>& first = level.first;
  for (int j = 0; j < n; ++j) {
    double d = a[j * n + j];
    for (int k = first[j]; k < j; ++k) d -= a[j * n + k] * a[j * n + k];
    if (!(d > 0.0)) throw std::invalid_argument("harmonic solve: a part of the block has no fixed neighbour");
    d = std::sqrt(d);
    a[j * n + j] = d;
    for (int i = j + 1; i <= level.last[j]; ++i) {
      if (first[i] > j) continue;
      double s = a[i * n + j];
      for (int k = std::max(first[i], first[j]); k < j; ++k) s -= a[i * n + k] * a[j * n + k];
      a[i * n + j] = s / d;
    }
  }
}

void solve_dense(const Level& level, const std::vector<Vec2>& b, std::vector<Vec2>& x) {
  const int n = level.n;
  const std::vector<double>& a = level.cholesky;
  x = b;
  for (int i = 0; i < n; ++i) {
    Vec2 s = x[i];
    for (int k = level.first[i]; k < i; ++k) s = s - a[i * n + k] * x[k];
    x[i] = s / a[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    Vec2 s = x[i];
    for (int k = i + 1; k <= level.last[i]; ++k) s = s - a[k * n + i] * x[k];
    x[i] = s / a[i * n + i];
  }
}

// s minus the off-diagonal part of row i times x.
inline Vec2 row_rest(const Level& level, Vec2 s, const std::vector<Vec2>& x, int i) {
  if (level.unit) {
    for (int k = level.row[i]; k < level.row[i + 1]; ++k) s = s + x[level.col[k]];
  } else {
    for (int k = level.row[i]; k < level.row[i + 1]; ++k) s = s - level.value[k] * x[level.col[k]];
  }
  return s;
}

void gauss_seidel(const Level& level, const std::vector<Vec2>& b, std::vector<Vec2>& x, bool forward) {
  for (int step = 0; step < level.n; ++step) {
    const int i = forward ? step : level.n - 1 - step;
    x[i] = row_rest(level, b[i], x, i) / level.diagonal[i];
  }
}

// One V-cycle from x = 0: forward Gauss-Seidel, coarse correction, backward
// Gauss-Seidel (so the preconditioner is symmetric).
void v_cycle(const std::vector<Level>& levels, std::size_t l, const std::vector<Vec2>& b, std::vector<Vec2>& x) {
  const Level& level = levels[l];
  if (l + 1 == levels.size()) {
    if (!level.cholesky.empty()) {
      solve_dense(level, b, x);
    } else {  // too large to factor (coarsening stalled): a symmetric sweep
      x.assign(level.n, Vec2{0.0, 0.0});
      gauss_seidel(level, b, x, true);
      gauss_seidel(level, b, x, false);
    }
    return;
  }
  x.assign(level.n, Vec2{0.0, 0.0});
  gauss_seidel(level, b, x, true);
  const Level& next = levels[l + 1];
  level.coarse_rhs.assign(next.n, Vec2{0.0, 0.0});
  for (int i = 0; i < level.n; ++i) {
    const Vec2 r = row_rest(level, b[i] - level.diagonal[i] * x[i], x, i);
    level.coarse_rhs[level.aggregate[i]] = level.coarse_rhs[level.aggregate[i]] + r;
  }
  v_cycle(levels, l + 1, level.coarse_rhs, level.coarse_x);
  for (int i = 0; i < level.n; ++i) x[i] = x[i] + kCoarseScale * level.coarse_x[level.aggregate[i]];
  gauss_seidel(level, b, x, false);
}

}  // namespace

HarmonicSolve solve_harmonic(const HarmonicSystem& system, const std::vector<Vec2>& rhs, std::vector<Vec2>& x,
                             double tolerance, int max_iterations) {
  const int n = static_cast<int>(system.degree.size());
  if (static_cast<int>(system.offset.size()) != n + 1 || static_cast<int>(rhs.size()) != n ||
      static_cast<int>(x.size()) != n || system.offset.back() != static_cast<int>(system.neighbour.size()))
    throw std::invalid_argument("harmonic solve: " + std::to_string(n) + " degrees, " +
                                std::to_string(system.offset.size()) + " offsets, " + std::to_string(rhs.size()) +
                                " right-hand sides and " + std::to_string(x.size()) + " unknowns do not fit");
  HarmonicSolve result;
  if (n == 0) {
    result.converged = true;
    return result;
  }
  for (int c : system.neighbour)
    if (c < 0 || c >= n) throw std::invalid_argument("harmonic solve: a neighbour is not a free node");
  for (int i = 0; i < n; ++i)
    if (system.offset[i] > system.offset[i + 1] || !(system.degree[i] >= system.offset[i + 1] - system.offset[i]) ||
        !(system.degree[i] > 0.0))
      throw std::invalid_argument("harmonic solve: node " + std::to_string(i) +
                                  " has a degree below its free neighbours or no neighbour");
  // Each connected part needs a node with a fixed neighbour (a degree above
  // its free neighbours), or its map is not determined: checked here, not
  // left to the factor, which a start that already fits never reaches.
  std::vector<char> seen(n, 0);
  std::vector<int> part;
  for (int start = 0; start < n; ++start) {
    if (seen[start]) continue;
    bool anchored = false;
    part.assign(1, start);
    seen[start] = 1;
    for (std::size_t k = 0; k < part.size(); ++k) {
      const int i = part[k];
      anchored = anchored || system.degree[i] > system.offset[i + 1] - system.offset[i];
      for (int e = system.offset[i]; e < system.offset[i + 1]; ++e)
        if (!seen[system.neighbour[e]]) seen[system.neighbour[e]] = 1, part.push_back(system.neighbour[e]);
    }
    if (!anchored) throw std::invalid_argument("harmonic solve: a part of the block has no fixed neighbour");
  }

  // The product with the matrix, and the residual of the start: a start
  // that already solves the system (a block placed harmonically before)
  // needs no multigrid levels, whose set-up (a dense factor of up to 800
  // unknowns) costs more than the rest of a small block's solve.
  const auto apply = [&](const std::vector<Vec2>& v, std::vector<Vec2>& out) {
    for (int i = 0; i < n; ++i) {
      Vec2 s = system.degree[i] * v[i];
      for (int k = system.offset[i]; k < system.offset[i + 1]; ++k) s = s - v[system.neighbour[k]];
      out[i] = s;
    }
  };
  std::vector<Vec2> residual(n), z, direction, product(n);
  apply(x, product);
  const auto largest_step = [&] {
    double largest = 0.0;
    for (int i = 0; i < n; ++i)
      largest = std::max(largest, std::max(std::abs(residual[i].x), std::abs(residual[i].y)) / system.degree[i]);
    return largest;
  };
  for (int i = 0; i < n; ++i) residual[i] = rhs[i] - product[i];
  if (largest_step() <= tolerance) {
    result.converged = true;
    return result;
  }

  std::vector<Level> levels(1);
  levels[0].n = n;
  levels[0].unit = true;
  levels[0].row = system.offset;
  levels[0].col = system.neighbour;
  levels[0].value.assign(system.neighbour.size(), -1.0);
  levels[0].diagonal = system.degree;
  while (levels.back().n > kCoarsest) {
    std::vector<int> of;
    const int count = aggregate(levels.back(), of);
    if (count >= levels.back().n) break;  // nothing to join: solve this level directly
    Level next = coarsen(levels.back(), of, count);
    levels.back().aggregate = std::move(of);
    levels.push_back(std::move(next));
  }
  // Coarsening stalls only where nodes have no free neighbour (each its own
  // aggregate); such a level is solved by sweeps, not factored.
  if (levels.back().n <= 4 * kCoarsest) factor_dense(levels.back());
  const Level& top = levels[0];

  // Preconditioned conjugate gradients, each coordinate its own scalars.
  v_cycle(levels, 0, residual, z);
  direction = z;
  double rz[2] = {0.0, 0.0};
  for (int i = 0; i < n; ++i) rz[0] += residual[i].x * z[i].x, rz[1] += residual[i].y * z[i].y;
  while (result.iterations < max_iterations) {
    ++result.iterations;
    // One pass each for the product with its scalars and for the updates
    // with the stopping measure.
    double pap[2] = {0.0, 0.0};
    for (int i = 0; i < n; ++i) {
      Vec2 s = top.diagonal[i] * direction[i];
      for (int k = top.row[i]; k < top.row[i + 1]; ++k) s = s - direction[top.col[k]];
      product[i] = s;
      pap[0] += direction[i].x * s.x, pap[1] += direction[i].y * s.y;
    }
    const double alpha[2] = {pap[0] > 0.0 ? rz[0] / pap[0] : 0.0, pap[1] > 0.0 ? rz[1] / pap[1] : 0.0};
    double largest = 0.0;
    for (int i = 0; i < n; ++i) {
      x[i] = x[i] + Vec2{alpha[0] * direction[i].x, alpha[1] * direction[i].y};
      residual[i] = residual[i] - Vec2{alpha[0] * product[i].x, alpha[1] * product[i].y};
      largest = std::max(largest, std::max(std::abs(residual[i].x), std::abs(residual[i].y)) / top.diagonal[i]);
    }
    if (largest <= tolerance) {
      result.converged = true;
      break;
    }
    v_cycle(levels, 0, residual, z);
    double next[2] = {0.0, 0.0};
    for (int i = 0; i < n; ++i) next[0] += residual[i].x * z[i].x, next[1] += residual[i].y * z[i].y;
    const double beta[2] = {rz[0] > 0.0 ? next[0] / rz[0] : 0.0, rz[1] > 0.0 ? next[1] / rz[1] : 0.0};
    for (int i = 0; i < n; ++i) direction[i] = z[i] + Vec2{beta[0] * direction[i].x, beta[1] * direction[i].y};
    rz[0] = next[0], rz[1] = next[1];
  }
  return result;
}

}  // namespace mm
