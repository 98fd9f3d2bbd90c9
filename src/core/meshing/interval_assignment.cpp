// Interval assignment as one integer program solved by CBC: integer counts per
// segment and per template parameter, continuous deviations from the goals.
#include "meshing/interval_assignment.hpp"

#include <coin/Cbc_C_Interface.h>

#include <algorithm>
#include <cmath>
#include <coin/CbcModel.hpp>
#include <coin/OsiClpSolverInterface.hpp>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm {
namespace {

constexpr double kUnbounded = std::numeric_limits<double>::max();
// One lattice step in each logical direction (0 east, 1 north, 2 west, 3 south).
constexpr int kStepX[4] = {1, 0, -1, 0}, kStepY[4] = {0, 1, 0, -1};
constexpr double kTimeLimitSeconds = 10.0;
// CBC's branch and bound without CbcMain1's set-up: tried first on problems
// of a face or two (a few hundred rows), where it is proven optimal within
// a few nodes; CbcMain1's cuts are what larger ones need.
constexpr int kPlainRows = 2000;
constexpr int kPlainNodes = 200;

// Column -> coefficient, in column order: rows come out deterministic, and a
// segment that appears on opposite sides of one block cancels out. A sorted
// vector rather than a std::map: columns mostly arrive in increasing order,
// so an entry is nearly always appended, with no node to allocate.
class LinearExpr {
 public:
  using Entry = std::pair<int, double>;
  LinearExpr() = default;
  LinearExpr(int col, double coef) : entries_{{col, coef}} {}

  // The coefficient of `col`, added as 0 if absent.
  double& operator[](int col) {
    if (entries_.empty() || entries_.back().first < col) return entries_.emplace_back(col, 0.0).second;
    const auto it = find(col);
    if (it != entries_.end() && it->first == col) return it->second;
    return entries_.insert(it, Entry{col, 0.0})->second;
  }
  double at(int col) const {
    const auto it = find(col);
    if (it == entries_.end() || it->first != col)
      throw std::out_of_range("LinearExpr: no column " + std::to_string(col));
    return it->second;
  }
  bool empty() const { return entries_.empty(); }
  std::vector<Entry>::const_iterator begin() const { return entries_.begin(); }
  std::vector<Entry>::const_iterator end() const { return entries_.end(); }

 private:
  std::vector<Entry>::iterator find(int col) {
    return std::lower_bound(entries_.begin(), entries_.end(), col, [](const Entry& e, int c) { return e.first < c; });
  }
  std::vector<Entry>::const_iterator find(int col) const {
    return std::lower_bound(entries_.begin(), entries_.end(), col, [](const Entry& e, int c) { return e.first < c; });
  }

  std::vector<Entry> entries_;
};

void add_to(LinearExpr& e, const LinearExpr& other, double factor) {
  for (const auto& [col, coef] : other) e[col] += factor * coef;
}

LinearExpr difference(const LinearExpr& a, const LinearExpr& b) {
  LinearExpr e = a;
  add_to(e, b, -1.0);
  return e;
}

LinearExpr column(int col) {
  return LinearExpr(col, 1.0);
}

std::string block_name(size_t b) {
  return "interval assignment: block " + std::to_string(b);
}

int expected_sides(const BlockShape& block) {
  switch (block.kind) {
    case BlockTemplate::Disc: return 1;
    case BlockTemplate::OneSided: return 1;
    case BlockTemplate::TwoSided: return 2;
    case BlockTemplate::Midpoint:
    case BlockTemplate::Submap: return -1;
  }
  return -1;
}

void validate(const IntervalProblem& problem) {
  for (size_t s = 0; s < problem.segments.size(); ++s) {
    const IntervalSegment& seg = problem.segments[s];
    if (!std::isfinite(seg.goal) || seg.goal < 0)
      throw std::invalid_argument("interval assignment: segment " + std::to_string(s) + " has goal " +
                                  std::to_string(seg.goal) + " (must be finite and >= 0)");
    if (seg.min_count < 1)
      throw std::invalid_argument("interval assignment: segment " + std::to_string(s) + " has min_count " +
                                  std::to_string(seg.min_count) + " (must be >= 1)");
  }
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    const BlockShape& block = problem.blocks[b];
    const size_t sides = block.side_segments.size();
    const int expected = expected_sides(block);
    if (expected > 0 && static_cast<int>(sides) != expected)
      throw std::invalid_argument(block_name(b) + " has " + std::to_string(sides) + " sides, its template needs " +
                                  std::to_string(expected));
    if (block.kind == BlockTemplate::Midpoint && sides != 3 && sides != 5 && sides != 6)
      throw std::invalid_argument(block_name(b) + ": midpoint subdivision takes 3, 5 or 6 sides, not " +
                                  std::to_string(sides));
    if (block.kind == BlockTemplate::Submap && sides < 2)
      throw std::invalid_argument(block_name(b) + ": a submapped block needs at least 2 sides");
    const size_t corners = block.kind == BlockTemplate::Disc ? 0 : sides;
    if (block.corner_types.size() != corners)
      throw std::invalid_argument(block_name(b) + " has " + std::to_string(block.corner_types.size()) +
                                  " corner types for " + std::to_string(corners) + " corners");
    for (int type : block.corner_types)
      if (type < 0 || type > 4)
        throw std::invalid_argument(block_name(b) + " has corner type " + std::to_string(type) + " (must be 0..4)");
    if (block.facing_goals.size() > block.facing.size())
      throw std::invalid_argument(block_name(b) + ": more facing goals than facing pairs");
    for (double goal : block.facing_goals)
      if (!std::isfinite(goal) || goal < 0)
        throw std::invalid_argument(block_name(b) + " has facing goal " + std::to_string(goal) +
                                    " (must be finite and >= 0)");
    if (!block.spoke_goals.empty() && (block.kind != BlockTemplate::Midpoint || block.spoke_goals.size() != sides))
      throw std::invalid_argument(block_name(b) + ": spoke goals are one per side of a midpoint block");
    for (double goal : block.spoke_goals)
      if (!std::isfinite(goal) || goal < 0)
        throw std::invalid_argument(block_name(b) + " has spoke goal " + std::to_string(goal) +
                                    " (must be finite and >= 0)");
    std::vector<std::pair<int, int>> pairs = block.facing;
    pairs.insert(pairs.end(), block.facing_outside.begin(), block.facing_outside.end());
    for (const auto& [s, t] : pairs)
      if (block.kind != BlockTemplate::Submap || s < 0 || t < 0 || s >= static_cast<int>(sides) ||
          t >= static_cast<int>(sides))
        throw std::invalid_argument(block_name(b) + ": facing sides " + std::to_string(s) + " and " +
                                    std::to_string(t) + " are not two sides of a submapped block");
    for (size_t i = 0; i < sides; ++i) {
      if (block.side_segments[i].empty())
        throw std::invalid_argument(block_name(b) + ": side " + std::to_string(i) + " has no segment");
      for (int s : block.side_segments[i])
        if (s < 0 || s >= static_cast<int>(problem.segments.size()))
          throw std::invalid_argument(block_name(b) + ": side " + std::to_string(i) + " names segment " +
                                      std::to_string(s) + ", there are " + std::to_string(problem.segments.size()));
    }
  }
  for (size_t i = 0; i < problem.equal_sums.size(); ++i) {
    for (const std::vector<int>* chain : {&problem.equal_sums[i].first, &problem.equal_sums[i].second}) {
      for (int s : *chain)
        if (s < 0 || s >= static_cast<int>(problem.segments.size()))
          throw std::invalid_argument("interval assignment: equal sums " + std::to_string(i) + " name segment " +
                                      std::to_string(s) + ", there are " + std::to_string(problem.segments.size()));
    }
  }
}

// dir_0 = 0, dir_{i+1} = dir_i + (2 - type_{i+1}) mod 4; the turning must close.
std::vector<int> submap_directions(const BlockShape& block, size_t b) {
  const std::vector<int>& types = block.corner_types;
  int turning = 0;
  for (int type : types) turning += 2 - type;
  if (turning != 4)
    throw std::invalid_argument(block_name(b) + ": submap outline turns " + std::to_string(turning) +
                                " quarter turns, a closed counter-clockwise outline turns 4");
  std::vector<int> dirs(types.size(), 0);
  for (size_t i = 1; i < types.size(); ++i) dirs[i] = ((dirs[i - 1] + 2 - types[i]) % 4 + 4) % 4;
  return dirs;
}

// The integer program: columns are added as the blocks need them.
class Model {
 public:
  int add_column(double lower, double upper, double cost, bool integer) {
    lower_.push_back(lower);
    upper_.push_back(upper);
    cost_.push_back(cost);
    integer_.push_back(integer);
    return static_cast<int>(lower_.size()) - 1;
  }
  int add_integer(double lower) { return add_column(lower, kUnbounded, 0.0, true); }

  // `goal`: the row of a segment's goal deviation (see add_goal_deviation).
  void add_equation(const LinearExpr& e, double rhs, bool goal = false) {
    LinearExpr row;
    for (const auto& [col, coef] : e)
      if (coef != 0.0) row[col] = coef;
    if (row.empty()) return;
    rows_.push_back({std::move(row), rhs});
    goal_row_.push_back(goal);
  }

  // |e| costs `weight`: e = plus - minus with both >= 0.
  void add_deviation(const LinearExpr& e, double target, double weight) {
    LinearExpr row = e;
    row[add_column(0.0, kUnbounded, weight, false)] -= 1.0;
    row[add_column(0.0, kUnbounded, weight, false)] += 1.0;
    add_equation(row, target);
  }

  size_t columns() const { return lower_.size(); }
  void set_cost(int col, double cost) { cost_[col] = cost; }
  // Clp's tolerances are absolute (1e-7 on reduced costs): every cost is
  // multiplied by this so that the smallest tie-break stays well above them.
  void set_cost_scale(double scale) { cost_scale_ = scale; }

  struct Outcome {
    bool infeasible = false;
    bool proven_optimal = false;
    std::vector<double> values;
  };

  // lp_only: no branch and bound; values stay empty (and infeasible false)
  // when the LP optimum is fractional.
  Outcome solve(bool lp_only = false) const;
  bool complete_at_no_cost(std::vector<double>& x) const;
  double least_cost(std::vector<double>& x) const;

 private:
  bool fill_continuous(std::vector<double>& x, bool only_goal_rows_cost) const;

  std::vector<double> lower_, upper_, cost_;
  double cost_scale_ = 1.0;
  std::vector<bool> integer_;
  std::vector<std::pair<LinearExpr, double>> rows_;
  std::vector<char> goal_row_;
};

// x holds every integer column; fills in the continuous ones (each belongs
// to one row, coefficient +-1, lower bound 0) at their least cost, row by
// row, cheapest first (each row's costs rise with the distance from its
// target, so a column of negative cost is worth using only towards it).
// False if some row cannot be met, or, with only_goal_rows_cost, if a row
// other than a goal row would cost something.
bool Model::fill_continuous(std::vector<double>& x, bool only_goal_rows_cost) const {
  std::vector<std::pair<double, int>> free;  // (cost, column)
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    double residual = rows_[r].second;
    free.clear();
    for (const auto& [col, coef] : rows_[r].first) {
      if (integer_[col])
        residual -= coef * x[col];
      else
        free.push_back({cost_[col], col});
    }
    std::sort(free.begin(), free.end());
    for (const auto& [cost, col] : free) {
      const double coef = rows_[r].first.at(col);
      x[col] = 0.0;
      if (residual * coef <= 0.0) continue;
      if (only_goal_rows_cost && cost > 0.0 && !goal_row_[r]) return false;
      x[col] = std::min(upper_[col], residual / coef);
      residual -= coef * x[col];
    }
    if (std::abs(residual) > 1e-9) return false;
  }
  return true;
}

// True if the continuous columns meet every row with only the goal rows
// costing anything: with every count at its own goal's least deviation, no
// answer is then cheaper, and the LP is not needed.
bool Model::complete_at_no_cost(std::vector<double>& x) const {
  return fill_continuous(x, true);
}

// The objective with the continuous columns at their least cost; infinite
// if some row cannot be met.
double Model::least_cost(std::vector<double>& x) const {
  if (!fill_continuous(x, false)) return kUnbounded;
  double total = 0.0;
  for (std::size_t c = 0; c < x.size(); ++c) total += cost_[c] * x[c];
  return total;
}

// CBC's solver keeps global state (CbcMain1): one solve at a time.
std::mutex& cbc_mutex() {
  static std::mutex m;
  return m;
}

bool integral(const OsiSolverInterface& solver, const double* x) {
  for (int c = 0; c < solver.getNumCols(); ++c)
    if (solver.isInteger(c) && std::abs(x[c] - std::round(x[c])) > 1e-9) return false;
  return true;
}

// The LP relaxation by Clp first: the goal deviations' breakpoints at
// integers make it integral on most faces, and an integral LP optimum is the
// integer program's. That spares CBC's set-up (CbcMain1's parameters,
// preprocessing and cut generators: about 2 ms a face, several times the LP).
// A fractional one goes to CBC's branch and bound: plain (CbcModel alone) on
// small problems, else or when that is not done within kPlainNodes nodes
// CbcMain1 with its cuts (plain branching took 10 times longer on a 40 x 40
// grid with midpoint blocks).
Model::Outcome Model::solve(bool lp_only) const {
  const int n_cols = static_cast<int>(columns());
  const int n_rows = static_cast<int>(rows_.size());
  // Compressed sparse columns, as loadProblem takes them: count each
  // column's entries, then fill them in row order.
  std::vector<CoinBigIndex> starts(n_cols + 1, 0);
  for (const auto& row : rows_)
    for (const auto& entry : row.first) ++starts[entry.first + 1];
  for (int c = 0; c < n_cols; ++c) starts[c + 1] += starts[c];
  std::vector<int> indices(starts[n_cols]);
  std::vector<double> values(starts[n_cols]);
  std::vector<CoinBigIndex> next(starts.begin(), starts.end() - 1);
  for (int r = 0; r < n_rows; ++r)
    for (const auto& [col, coef] : rows_[r].first) {
      indices[next[col]] = r;
      values[next[col]++] = coef;
    }
  std::vector<double> rhs(n_rows);
  for (int r = 0; r < n_rows; ++r) rhs[r] = rows_[r].second;
  std::vector<double> cost = cost_;
  for (double& c : cost) c *= cost_scale_;

  std::lock_guard<std::mutex> lock(cbc_mutex());
  OsiClpSolverInterface solver;
  solver.messageHandler()->setLogLevel(0);
  solver.getModelPtr()->setLogLevel(0);
  solver.loadProblem(n_cols, n_rows, starts.data(), indices.data(), values.data(), lower_.data(), upper_.data(),
                     cost.data(), rhs.data(), rhs.data());
  for (int c = 0; c < n_cols; ++c)
    if (integer_[c]) solver.setInteger(c);
  solver.setObjSense(1.0);
  solver.initialSolve();

  Outcome outcome;
  if (solver.isProvenPrimalInfeasible()) {
    outcome.infeasible = true;
    return outcome;
  }
  if (solver.isProvenOptimal() && integral(solver, solver.getColSolution())) {
    outcome.values.assign(solver.getColSolution(), solver.getColSolution() + n_cols);
    outcome.proven_optimal = true;
    return outcome;
  }
  if (lp_only) return outcome;
  if (n_rows <= kPlainRows) {
    CbcModel plain(solver);
    plain.setLogLevel(0);
    plain.messageHandler()->setLogLevel(0);
    plain.setMaximumNodes(kPlainNodes);
    // No strong branching: these trees have a few nodes, and trying
    // candidate branches on each cost more than the whole search did.
    plain.setNumberStrong(0);
    plain.setNumberBeforeTrust(0);
    plain.branchAndBound();
    if (plain.isProvenOptimal() && plain.bestSolution()) {
      outcome.values.assign(plain.bestSolution(), plain.bestSolution() + n_cols);
      outcome.proven_optimal = true;
      return outcome;
    }
    if (plain.isProvenInfeasible()) {
      outcome.infeasible = true;
      return outcome;
    }
  }
  std::unique_ptr<Cbc_Model, void (*)(Cbc_Model*)> model(Cbc_newModel(), Cbc_deleteModel);
  Cbc_loadProblem(model.get(), n_cols, n_rows, starts.data(), indices.data(), values.data(), lower_.data(),
                  upper_.data(), cost.data(), rhs.data(), rhs.data());
  for (int c = 0; c < n_cols; ++c)
    if (integer_[c]) Cbc_setInteger(model.get(), c);
  Cbc_setObjSense(model.get(), 1.0);
  Cbc_setLogLevel(model.get(), 0);
  Cbc_setParameter(model.get(), "log", "0");
  Cbc_setParameter(model.get(), "slog", "0");
  Cbc_setMaximumSeconds(model.get(), kTimeLimitSeconds);
  // Measured on a 40 x 40 grid with midpoint blocks: CBC's default
  // heuristics cost several times the branching itself; the feasibility
  // pump alone still finds an integer answer early.
  Cbc_setParameter(model.get(), "heur", "off");
  Cbc_setParameter(model.get(), "feas", "on");
  Cbc_solve(model.get());

  const double* best = Cbc_bestSolution(model.get());
  if (best) {
    outcome.values.assign(best, best + n_cols);
    outcome.proven_optimal = Cbc_isProvenOptimal(model.get());
    return outcome;
  }
  if (Cbc_isProvenInfeasible(model.get()) || Cbc_isInitialSolveProvenPrimalInfeasible(model.get()) ||
      (Cbc_status(model.get()) == 0 && !Cbc_isSecondsLimitReached(model.get()))) {
    outcome.infeasible = true;
    return outcome;
  }
  throw std::runtime_error("interval assignment: CBC found no integer solution within " +
                           std::to_string(static_cast<int>(kTimeLimitSeconds)) + " s (status " +
                           std::to_string(Cbc_status(model.get())) + ", secondary " +
                           std::to_string(Cbc_secondaryStatus(model.get())) + ")");
}

struct BuiltModel {
  Model model;
  std::vector<int> count_columns;               // per segment
  std::vector<std::vector<int>> param_columns;  // per block
};

// The cost of n intervals on a segment wanting `goal` (g = max(goal, 1), as a
// segment shorter than the target still gets one interval): |n - g| / g
// within one interval below the goal and anywhere above it (where a count
// piles up, faster beyond twice it: see add_goal_deviation), so that a goal
// alone rounds to the nearest count; further below it grows as g / n, how
// many times too large the elements are, as fast as n / g grows for too
// small ones. (|n - g| / g all the way charged at most 1 for any coarsening
// but without bound for refining, so a side that must match a much shorter
// one took the short one's count: a wedge or a ring with elements several
// times the target size.) Between two goals forced equal the optimum is then
// near their geometric mean. Coarser than g / kSteepRatio the cost goes on
// linearly at its slope there: no unit of deviation costs more than
// kSteepRatio, so the facing and slit rows can stay above them all.
constexpr double kSteepRatio = 8.0;
// A count this many times its goal is piled up (see assign_intervals).
constexpr double kPiledUp = 8.0;

double goal_cost(double n, double g) {
  if (n >= g - 1.0) return std::abs(n - g) / g;
  return 1.0 / g + g / n - g / (g - 1.0);  // continuous at g - 1, and convex
}

// True if n lies where goal_cost is |n - g| / g.
bool within_relative(double n, const IntervalSegment& seg) {
  return n >= std::max(seg.goal, 1.0) - 1.0 - 1e-9;
}

// The columns of a count below `base` (= floor of its goal g) in `row`: 1 / g
// a unit (`ratio` false), or goal_cost's secants (see add_goal_deviation).
// Returns the steepest unit cost.
double add_shortfall(Model& model, LinearExpr& row, double g, double base, int min_count, bool ratio) {
  double steepest = 1.0 / g, k = base;
  if (ratio) {
    const double lowest = std::max<double>(min_count, std::ceil(g / kSteepRatio));
    while (k > lowest) {
      const double next = std::max(lowest, k - std::max(1.0, std::floor(k / 16.0)));
      steepest = (goal_cost(next, g) - goal_cost(k, g)) / (k - next);
      row[model.add_column(0.0, k - next, steepest, false)] += 1.0;
      k = next;
    }
    if (k > min_count) steepest = std::max(steepest, goal_cost(k - 1.0, g) - goal_cost(k, g));
  }
  if (!ratio || k > min_count) row[model.add_column(0.0, kUnbounded, steepest, false)] += 1.0;
  return steepest;
}

// The cost as the LP sees it at integer n: from floor(goal) up one unit it
// changes by (1 - 2 frac) / g, then by 1 / g a unit. Going down: `ratio`
// false, 1 / g a unit (|n - g| / g all the way: the first stage, see
// assign_intervals); true, pieces between breakpoints at their secants'
// slopes, exact at every integer below 32 and steps of a sixteenth of n
// above (a few dozen columns on a segment of hundreds of intervals).
// Breakpoints at integers make the relaxation's optimum integral on chains
// of equal sides, which spares CBC most of its branching. Returns the
// steepest unit cost either way.
double add_goal_deviation(Model& model, int n, const IntervalSegment& seg, bool ratio, bool convex) {
  const double g = std::max(seg.goal, 1.0);
  const double base = std::floor(seg.goal);
  LinearExpr row = column(n);
  row[model.add_column(0.0, 1.0, (1.0 - 2.0 * (seg.goal - base)) / g, false)] -= 1.0;
  // `convex`: from twice the goal on, each unit costs more than the one
  // before (the cost grows as (n / 2g)^2, the unit's cost n / 2g^2, at every
  // integer for 8 units, then in steps of a quarter of the way past 2g, up
  // to 8g, linearly beyond): a count a block forces up is spread over the
  // segments that can take it, not piled onto one (a gear ring's bore took
  // all the teeth's excess on one side of its keyway, and the submapped
  // lattice folded there). Without, 1 / g a unit all the way up.
  double above = base + 1.0, slope = 1.0 / g;
  const double knee = convex ? std::max(above, std::ceil(2.0 * g)) : above;
  const double cap = std::max(knee, std::ceil(kPiledUp * g));
  if (knee > above) row[model.add_column(0.0, knee - above, slope, false)] -= 1.0;
  for (above = knee; convex && above < cap;) {
    const double next = std::min(cap, above + std::max(1.0, std::floor((above - knee) / 4.0)));
    slope = (above + next) / (4.0 * g * g);  // the secant of (n / 2g)^2
    row[model.add_column(0.0, next - above, slope, false)] -= 1.0;
    above = next;
  }
  if (convex) slope = cap / (2.0 * g * g);  // the unit's cost at the cap, on beyond
  row[model.add_column(0.0, kUnbounded, slope, false)] -= 1.0;
  const double steepest_above = slope;
  const double steepest = add_shortfall(model, row, g, base, seg.min_count, ratio);
  model.add_equation(row, base, true);
  return std::max(steepest, steepest_above);
}

// A midpoint block's line from its centre to a side (c columns) coarser
// than its goal costs as a segment's count below its goal does; finer, nothing
// (a regular triangle's lines are shorter than half its sides, which they
// equal in intervals). Not a goal row: the direct answer must not need it.
// Returns the steepest unit cost.
double add_spoke_floor(Model& model, int c, double goal, bool ratio) {
  const double base = std::floor(goal);
  if (base < 2.0) return 0.0;  // c >= 1 anyway
  LinearExpr row = column(c);
  row[model.add_column(0.0, kUnbounded, 0.0, false)] -= 1.0;  // above the goal: free
  const double steepest = add_shortfall(model, row, goal, base, 1, ratio);
  model.add_equation(row, base);
  return steepest;
}

// Lattice lines across facing sides beyond kCrowding times the goal (and a
// few more) crowd through the narrows between the two sides (a slot near
// the outline: 20 lines in a gap of 3 elements, folded at fine sizes).
constexpr double kCrowding = 2.0;
constexpr double kCrowdingSlack = 4.0;

double crowding_cap(double goal) {
  const double g = std::max(goal, 1.0);
  return std::floor(std::max(kCrowding * g, g + kCrowdingSlack));
}

// Which facing pairs of a submapped block get a crowding row (Crowded).
using Crowded = std::set<std::pair<size_t, size_t>>;  // block, index into its facing pairs

// Lines across beyond the cap cost as intervals above a segment's goal.
// Not a goal row (see direct_outcome).
void add_crowding(Model& model, const LinearExpr& across, double goal) {
  const double g = std::max(goal, 1.0);
  LinearExpr row = across;
  row[model.add_column(0.0, kUnbounded, 0.0, false)] += 1.0;      // room left
  row[model.add_column(0.0, kUnbounded, 1.0 / g, false)] -= 1.0;  // crowded
  model.add_equation(row, crowding_cap(goal));
}

// The midpoint equations L_i = c_{i-1} + c_{i+1}; returns the c columns.
std::vector<int> add_midpoint(Model& model, const std::vector<LinearExpr>& sides) {
  const int m = static_cast<int>(sides.size());
  std::vector<int> c(m);
  for (int i = 0; i < m; ++i) c[i] = model.add_integer(1.0);
  for (int i = 0; i < m; ++i) {
    LinearExpr row = sides[i];
    row[c[(i + m - 1) % m]] -= 1.0;
    row[c[(i + 1) % m]] -= 1.0;
    model.add_equation(row, 0.0);
  }
  return c;
}

// TwoSided on sides n_0, n_1: u, v, then the midpoint c_0..c_2 of the rest.
// `balance` weighs a tie-break towards an even triangle (L_0 ~ L_1 ~ L_2):
// the equations leave u and v free, and lopsided choices make poor elements.
std::vector<int> add_two_sided(Model& model, const LinearExpr& n0, const LinearExpr& n1, double balance) {
  const int u = model.add_integer(1.0);
  const int v = model.add_integer(1.0);
  LinearExpr l0 = n0, l1 = n1, l2 = column(u);
  l0[u] -= 1.0;
  l1[v] -= 1.0;
  l2[v] += 1.0;
  std::vector<int> params{u, v};
  for (int c : add_midpoint(model, {l0, l1, l2})) params.push_back(c);
  model.add_deviation(difference(l0, l2), 0.0, balance);
  model.add_deviation(difference(l1, l2), 0.0, balance);
  return params;
}

// Blocks [0, block_limit) only, so that a failure can be traced to a block.
BuiltModel build(const IntervalProblem& problem, size_t block_limit, bool ratio, bool convex,
                 const Crowded& crowded = {}) {
  BuiltModel built;
  Model& model = built.model;
  double smallest_weight = 1.0, steepest = 1.0, total_goal = 0.0;
  for (const IntervalSegment& seg : problem.segments) {
    const double lower = seg.min_count;
    const int n = model.add_integer(lower);
    steepest = std::max(steepest, add_goal_deviation(model, n, seg, ratio, convex));
    built.count_columns.push_back(n);
    smallest_weight = std::min(smallest_weight, 1.0 / std::max(seg.goal, 1.0));
    total_goal += std::max(seg.goal, lower);
  }
  for (const BlockShape& block : problem.blocks) {
    for (double goal : block.spoke_goals) {
      Model scratch;  // only the spoke's unit costs, for `fold`
      steepest = std::max(steepest, add_spoke_floor(scratch, scratch.add_integer(1.0), goal, ratio));
    }
  }
  // Facing sides short of each other and slits that do not close fold the
  // lattice: dearer than any unit of goal deviation.
  const double fold = 4.0 * steepest;
  // Far below one unit of the goal deviation, so it only breaks ties.
  const double balance = 0.01 * smallest_weight / (1.0 + total_goal);
  // Last, among answers alike in both, the fewest intervals: all counts
  // together cost less than one unit of the balance tie-break. (Without it
  // the answer among equal costs is whichever the solver meets first.)
  const double fewer = balance / (1.0 + total_goal);
  for (int n : built.count_columns) model.set_cost(n, fewer);
  model.set_cost_scale(std::clamp(1e-5 / fewer, 1.0, 1e6));

  for (size_t b = 0; b < std::min(block_limit, problem.blocks.size()); ++b) {
    const BlockShape& block = problem.blocks[b];
    std::vector<LinearExpr> sides;
    for (const std::vector<int>& segs : block.side_segments) {
      LinearExpr side;
      for (int s : segs) side[built.count_columns[s]] += 1.0;
      sides.push_back(side);
    }
    std::vector<int> params;
    switch (block.kind) {
      case BlockTemplate::Submap: {
        const std::vector<int> dirs = submap_directions(block, b);
        LinearExpr along[4];
        for (size_t i = 0; i < sides.size(); ++i) add_to(along[dirs[i]], sides[i], 1.0);
        model.add_equation(difference(along[0], along[2]), 0.0);
        model.add_equation(difference(along[1], along[3]), 0.0);
        // Facing sides: t at least one interval from s along s's inward
        // (left) normal, or its outward one for sides facing across the
        // outside, short of it at a cost above any goal's deviation. Where
        // each side starts is kept dense over the count columns (the sides
        // use no other): a map per side made these rows cost more than
        // solving them on blocks of a hundred sides.
        const std::size_t counts = built.count_columns.size();
        using Dense = std::vector<double>;
        std::vector<Dense> x(sides.size(), Dense(counts, 0.0)), y = x;  // where each side starts
        for (size_t i = 1; i < sides.size(); ++i) {
          x[i] = x[i - 1], y[i] = y[i - 1];
          for (int s : block.side_segments[i - 1]) {
            x[i][s] += kStepX[dirs[i - 1]];
            y[i][s] += kStepY[dirs[i - 1]];
          }
        }
        // Dense entry s is segment s, whose count is column count_columns[s].
        const auto sparse = [&](const Dense& dense) {
          LinearExpr e;
          for (std::size_t s = 0; s < counts; ++s)
            if (dense[s] != 0.0) e[built.count_columns[s]] = dense[s];
          return e;
        };
        // side, other side, the normal's direction, crowding row, its goal
        std::vector<std::tuple<int, int, int, bool, double>> apart;
        for (size_t i = 0; i < block.facing.size(); ++i) {
          const auto [s, t] = block.facing[i];
          const bool crowd = crowded.count({b, i}) > 0;
          apart.emplace_back(s, t, (dirs[s] + 1) % 4, crowd, crowd ? block.facing_goals[i] : 0.0);
        }
        for (const auto& [s, t] : block.facing_outside) apart.emplace_back(s, t, (dirs[s] + 3) % 4, false, 0.0);
        for (const auto& [s, t, normal, crowd, goal] : apart) {
          Dense dense(counts);
          for (std::size_t k = 0; k < counts; ++k)
            dense[k] = (x[t][k] - x[s][k]) * kStepX[normal] + (y[t][k] - y[s][k]) * kStepY[normal];
          const LinearExpr across = sparse(dense);
          LinearExpr gap = across;
          gap[model.add_column(0.0, kUnbounded, 0.0, false)] -= 1.0;   // surplus
          gap[model.add_column(0.0, kUnbounded, fold, false)] += 1.0;  // shortfall
          model.add_equation(gap, 1.0);
          if (crowd) add_crowding(model, across, goal);
        }
        // A segment the outline runs along twice (a split to a hole) whose
        // outline between the two runs turns a full clockwise round (a hole
        // with corners) is a slit: its two runs must be one logical line,
        // so the round between them closes (softly, like facing sides).
        const auto place = [&](size_t side, size_t upto) {  // after the first `upto` segments of the side
          Dense px = x[side], py = y[side];
          for (size_t k = 0; k < upto; ++k) {
            px[block.side_segments[side][k]] += kStepX[dirs[side]];
            py[block.side_segments[side][k]] += kStepY[dirs[side]];
          }
          return std::make_pair(px, py);
        };
        const auto minus = [](Dense a, const Dense& b) {
          for (std::size_t k = 0; k < a.size(); ++k) a[k] -= b[k];
          return a;
        };
        for (size_t i = 0; i < sides.size(); ++i) {
          for (size_t a = 0; a < block.side_segments[i].size(); ++a) {
            for (size_t j = i + 1; j < sides.size(); ++j) {
              const auto& later = block.side_segments[j];
              const auto found = std::find(later.begin(), later.end(), block.side_segments[i][a]);
              if (found == later.end()) continue;
              int turning = 0;
              for (size_t k = i + 1; k < j; ++k) turning += 2 - block.corner_types[k];
              turning += 2 - block.corner_types[j];
              // The arrival and departure corners' +1 each and the round's -4,
              // between the runs or (6 = 4 + 2) round the rest of the outline.
              if (turning != -2 && turning != 6) continue;
              const auto [x0, y0] = place(i, a + 1);
              const auto [x1, y1] = place(j, static_cast<size_t>(found - later.begin()));
              model.add_deviation(sparse(minus(x1, x0)), 0.0, fold);
              model.add_deviation(sparse(minus(y1, y0)), 0.0, fold);
            }
          }
        }
        break;
      }
      case BlockTemplate::Midpoint:
        params = add_midpoint(model, sides);
        for (size_t i = 0; i < block.spoke_goals.size(); ++i)
          add_spoke_floor(model, params[i], block.spoke_goals[i], ratio);
        break;
      case BlockTemplate::TwoSided: params = add_two_sided(model, sides[0], sides[1], balance); break;
      case BlockTemplate::OneSided: {
        const int u = model.add_integer(1.0);
        const int v = model.add_integer(1.0);
        LinearExpr rest0 = sides[0], rest1 = column(u);
        rest0[u] -= 1.0;
        rest0[v] -= 1.0;
        rest1[v] += 1.0;
        params = {u, v};
        for (int p : add_two_sided(model, rest0, rest1, balance)) params.push_back(p);
        model.add_deviation(difference(column(u), column(v)), 0.0, balance);
        model.add_deviation(difference(rest0, rest1), 0.0, balance);
        break;
      }
      case BlockTemplate::Disc: {
        const int a = model.add_integer(1.0);
        const int bb = model.add_integer(1.0);
        // n = 2 half, half = a + b: with the half count its own integer the
        // relaxation's odd n (an odd goal) is branched on at once; through a
        // and b alone each branch left a fractional a or b beside an odd n
        // and the search went 200 nodes deep unproven (the circle at 0.007
        // of its diagonal: 13 ms for 3 rows).
        const int half = model.add_integer(1.0);
        LinearExpr row = sides[0];
        row[half] -= 2.0;
        model.add_equation(row, 0.0);
        LinearExpr halves = column(half);
        halves[a] -= 1.0;
        halves[bb] -= 1.0;
        model.add_equation(halves, 0.0);
        model.add_deviation(difference(column(a), column(bb)), 0.0, balance);
        params = {a, bb};
        break;
      }
    }
    built.param_columns.push_back(params);
  }
  for (const EqualSums& pair : problem.equal_sums) {
    LinearExpr row;
    for (int s : pair.first) row[built.count_columns[s]] += 1.0;
    for (int s : pair.second) row[built.count_columns[s]] -= 1.0;
    model.add_equation(row, 0.0);
  }
  return built;
}

long to_int(double value) {
  return std::lround(value);
}

// Every block's equations, recomputed from the answer alone.
std::string first_violation(const IntervalProblem& problem, const IntervalAssignment& a) {
  if (a.counts.size() != problem.segments.size()) return "one count per segment";
  for (size_t s = 0; s < a.counts.size(); ++s) {
    const int lower = problem.segments[s].min_count;
    if (a.counts[s] < lower)
      return "segment " + std::to_string(s) + " has " + std::to_string(a.counts[s]) + " < " + std::to_string(lower);
  }
  for (size_t i = 0; i < problem.equal_sums.size(); ++i) {
    long difference = 0;
    for (int s : problem.equal_sums[i].first) difference += a.counts[s];
    for (int s : problem.equal_sums[i].second) difference -= a.counts[s];
    if (difference != 0) return "equal sums " + std::to_string(i) + " differ by " + std::to_string(difference);
  }
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    const BlockShape& block = problem.blocks[b];
    const std::string name = "block " + std::to_string(b);
    std::vector<long> n;
    for (const std::vector<int>& segs : block.side_segments) {
      long total = 0;
      for (int s : segs) total += a.counts[s];
      n.push_back(total);
    }
    const std::vector<int>& p = a.params[b];
    for (int value : p)
      if (value < 1) return name + " has a template parameter < 1";
    auto midpoint_holds = [](const std::vector<long>& l, const int* c) {
      const size_t m = l.size();
      for (size_t i = 0; i < m; ++i)
        if (l[i] != c[(i + m - 1) % m] + c[(i + 1) % m]) return false;
      return true;
    };
    bool holds = true;
    switch (block.kind) {
      case BlockTemplate::Submap: {
        const std::vector<int> dirs = submap_directions(block, b);
        long along[4] = {0, 0, 0, 0};
        for (size_t i = 0; i < n.size(); ++i) along[dirs[i]] += n[i];
        holds = p.empty() && along[0] == along[2] && along[1] == along[3];
        break;
      }
      case BlockTemplate::Midpoint: holds = p.size() == n.size() && midpoint_holds(n, p.data()); break;
      case BlockTemplate::TwoSided:
        holds = p.size() == 5 && midpoint_holds({n[0] - p[0], n[1] - p[1], p[0] + p[1]}, p.data() + 2);
        break;
      case BlockTemplate::OneSided:
        holds =
            p.size() == 7 && midpoint_holds({n[0] - p[0] - p[1] - p[2], p[0] + p[1] - p[3], p[2] + p[3]}, p.data() + 4);
        break;
      case BlockTemplate::Disc: holds = p.size() == 2 && n[0] == 2L * p[0] + 2L * p[1]; break;
    }
    if (!holds) return name + " breaks its template's equations";
  }
  return {};
}

IntervalAssignment read_answer(const BuiltModel& built, const std::vector<double>& values) {
  IntervalAssignment a;
  for (int col : built.count_columns) a.counts.push_back(static_cast<int>(to_int(values[col])));
  for (const std::vector<int>& cols : built.param_columns) {
    std::vector<int> p;
    for (int col : cols) p.push_back(static_cast<int>(to_int(values[col])));
    a.params.push_back(p);
  }
  return a;
}

// The midpoint equations L_i = c_{i-1} + c_{i+1} solved for twice c_i
// (m = 3 and 5: the sum of all c less the sides covering the others; m = 6:
// two triangles, odd c on even sides and even c on odd ones).
std::vector<long> twice_midpoint_parameters(const std::vector<long>& sides) {
  const size_t m = sides.size();
  long total = 0;
  for (long l : sides) total += l;
  std::vector<long> twice(m);
  for (size_t i = 0; i < m; ++i) {
    if (m == 3) twice[i] = total - 2 * sides[i];
    if (m == 5) twice[i] = total - 2 * (sides[(i + 2) % 5] + sides[(i + 3) % 5]);
    if (m == 6) {
      twice[i] = -2 * sides[(i + 3) % 6];
      for (size_t k = (i + 1) % 2; k < 6; k += 2) twice[i] += sides[k];
    }
  }
  return twice;
}

// Submapped blocks have no template parameters and a midpoint block's
// follow from its sides: when every segment at its nearest count (the fewer
// on a tie, at least min_count) gives whole parameters >= 1 and meets the
// equations, and the facing and slit rows at no cost, that is the optimum,
// found without Clp (whose first call in a process also pays for loading it).
// Empty values when it is not.
Model::Outcome direct_outcome(const IntervalProblem& problem, const BuiltModel& built) {
  Model::Outcome outcome;
  for (const BlockShape& block : problem.blocks)
    if (block.kind != BlockTemplate::Submap && block.kind != BlockTemplate::Midpoint) return outcome;
  std::vector<double> x(built.model.columns(), 0.0);
  std::vector<long> counts(problem.segments.size());
  for (size_t s = 0; s < problem.segments.size(); ++s) {
    const IntervalSegment& seg = problem.segments[s];
    const long base = static_cast<long>(std::floor(seg.goal));
    counts[s] = std::max<long>(seg.min_count, seg.goal - static_cast<double>(base) > 0.5 ? base + 1 : base);
    x[built.count_columns[s]] = static_cast<double>(counts[s]);
  }
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    if (problem.blocks[b].kind != BlockTemplate::Midpoint) continue;
    std::vector<long> sides;
    for (const std::vector<int>& segs : problem.blocks[b].side_segments) {
      long total = 0;
      for (int s : segs) total += counts[s];
      sides.push_back(total);
    }
    const std::vector<long> twice = twice_midpoint_parameters(sides);
    for (size_t i = 0; i < twice.size(); ++i) {
      if (twice[i] < 2 || twice[i] % 2 != 0) return outcome;
      x[built.param_columns[b][i]] = static_cast<double>(twice[i] / 2);
    }
  }
  if (!built.model.complete_at_no_cost(x)) return outcome;
  outcome.values = std::move(x);
  outcome.proven_optimal = true;
  return outcome;
}

// Only on the error path: the shortest prefix of blocks that has no answer
// ends with the block to blame (feasibility only shrinks as blocks are added).
size_t first_impossible_block(const IntervalProblem& problem) {
  size_t feasible = 0, infeasible = problem.blocks.size();
  while (infeasible - feasible > 1) {
    const size_t mid = (feasible + infeasible) / 2;
    if (build(problem, mid, false, false).model.solve().infeasible)
      infeasible = mid;
    else
      feasible = mid;
  }
  return infeasible - 1;
}

// Whether a count lies far above its goal (a gear ring's bore side, 56 to 75
// times): then solved again with the unit costs growing from twice the goal
// (add_goal_deviation), which spreads such excess. Only then: those
// columns make the problem over twice as large, and on the shared faces,
// whose counts reach 4 times their goals at most, the solves took twice
// as long (fractional optima, more CBC) for no better mesh.
bool piled_up(const IntervalProblem& problem, const BuiltModel& built, const std::vector<double>& values) {
  for (size_t s = 0; s < problem.segments.size(); ++s) {
    const IntervalSegment& seg = problem.segments[s];
    if (values[built.count_columns[s]] >
        std::max<double>(std::ceil(kPiledUp * std::max(seg.goal, 1.0)), seg.min_count) + 0.5)
      return true;
  }
  return false;
}

// The counts (see assign_intervals), with crowding rows for the `crowded`
// facing pairs.
IntervalAssignment solve_in_stages(const IntervalProblem& problem, const Crowded& crowded) {
  // In goal_cost at once when its LP optimum is integral (as on most faces:
  // its breakpoints lie at integers): one LP where the stages below solve
  // two. It is then the least goal_cost, which the stages reach too, but
  // for the answers of exactly equal cost (all tie-breaks included) each
  // way may meet a different one (11 of 408 check meshes changed: a ring's
  // segments alike flipped, and smoothing's result with them). A
  // fractional optimum goes to the stages, whose first LP is integral more
  // often: branching on goal_cost took CBC 3.3 s on a fuzzed B-spline face
  // whose first stage needs none.
  {
    const BuiltModel direct = build(problem, problem.blocks.size(), true, false, crowded);
    Model::Outcome outcome = direct_outcome(problem, direct);
    if (outcome.values.empty()) outcome = direct.model.solve(true);
    if (!outcome.values.empty() && !piled_up(problem, direct, outcome.values))
      return read_answer(direct, outcome.values);
  }
  // First with |n - g| / g all the way down: if no count then lies more than
  // one interval below its goal, that answer costs the same in goal_cost and
  // nothing can cost less there (goal_cost is never below |n - g| / g, nor
  // are the fold rows cheaper), so it is kept: faces without such a conflict
  // keep the counts they had before goal_cost. Else solved again in goal_cost,
  // and that answer taken only if it costs less than the first one does in
  // goal_cost (not one of the answers of equal cost the solver meets first
  // on another path: rings of segments alike flipped, and smoothing's result
  // with them).
  BuiltModel built = build(problem, problem.blocks.size(), false, false, crowded);
  Model::Outcome outcome = direct_outcome(problem, built);
  if (outcome.values.empty()) outcome = built.model.solve();
  if (outcome.infeasible) {
    const size_t b = first_impossible_block(problem);
    throw IntervalsInfeasible(block_name(b) + " (" + std::to_string(problem.blocks[b].side_segments.size()) +
                              " sides): its template's conditions cannot hold together with those of the blocks "
                              "before it, whatever the goals");
  }
  const bool convex = piled_up(problem, built, outcome.values);
  if (convex) {
    built = build(problem, problem.blocks.size(), false, true, crowded);
    outcome = built.model.solve();
  }
  bool coarse = false;
  for (size_t s = 0; s < problem.segments.size(); ++s)
    coarse = coarse || !within_relative(outcome.values[built.count_columns[s]], problem.segments[s]);
  for (size_t b = 0; b < problem.blocks.size(); ++b)
    for (size_t i = 0; i < problem.blocks[b].spoke_goals.size(); ++i)
      coarse = coarse || outcome.values[built.param_columns[b][i]] < problem.blocks[b].spoke_goals[i] - 1.0 - 1e-9;
  IntervalAssignment answer = read_answer(built, outcome.values);
  if (coarse) {
    const BuiltModel second = build(problem, problem.blocks.size(), true, convex, crowded);
    Model::Outcome better;
    try {
      better = second.model.solve();
    } catch (const std::runtime_error&) {  // no answer within CBC's time: the first stands
      better.infeasible = true;
    }
    std::vector<double> first(second.model.columns(), 0.0);
    for (size_t s = 0; s < answer.counts.size(); ++s) first[second.count_columns[s]] = answer.counts[s];
    for (size_t b = 0; b < answer.params.size(); ++b)
      for (size_t i = 0; i < answer.params[b].size(); ++i) first[second.param_columns[b][i]] = answer.params[b][i];
    const double kept = second.model.least_cost(first);
    std::vector<double> found = better.values;
    if (!better.infeasible && second.model.least_cost(found) < kept - 1e-12 * (1.0 + std::abs(kept))) {
      outcome = better;
      answer = read_answer(second, better.values);
    }
  }
  if (!outcome.proven_optimal)
    answer.notes.push_back(
        "interval assignment: CBC stopped at its time limit; the counts are the best found, "
        "not proven to deviate least from the goals");
  return answer;
}

// Rounds of solving again with more facing pairs' crowding rows.
constexpr int kCrowdingRounds = 3;

// The facing pairs of submapped blocks with more lattice lines across them
// for the given counts than crowding_cap of their goal.
Crowded crowded_pairs(const IntervalProblem& problem, const std::vector<int>& counts) {
  Crowded crowded;
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    const BlockShape& block = problem.blocks[b];
    if (block.kind != BlockTemplate::Submap || block.facing_goals.empty()) continue;
    const std::vector<int> dirs = submap_directions(block, b);
    std::vector<long> x(block.side_segments.size(), 0), y = x;  // where each side starts
    for (size_t i = 1; i < block.side_segments.size(); ++i) {
      long n = 0;
      for (int seg : block.side_segments[i - 1]) n += counts[seg];
      x[i] = x[i - 1] + n * kStepX[dirs[i - 1]];
      y[i] = y[i - 1] + n * kStepY[dirs[i - 1]];
    }
    for (size_t i = 0; i < block.facing_goals.size(); ++i) {
      const auto [s, t] = block.facing[i];
      const int normal = (dirs[s] + 1) % 4;
      const long across = (x[t] - x[s]) * kStepX[normal] + (y[t] - y[s]) * kStepY[normal];
      if (block.facing_goals[i] > 0.0 && across > crowding_cap(block.facing_goals[i])) crowded.insert({b, i});
    }
  }
  return crowded;
}

}  // namespace

std::vector<FoldedSides> folded_sides(const BlockShape& block, const std::vector<int>& counts) {
  if (block.kind != BlockTemplate::Submap) return {};
  const std::vector<int> dirs = submap_directions(block, 0);
  const int sides = static_cast<int>(block.side_segments.size());
  // Sides s before t running opposite ways, as a facing pair by the turning between them.
  std::vector<FoldedSides> pairs;
  const auto add_pair = [&](int s, int t) {
    if (s < 0 || t >= sides || s >= t || (dirs[s] + 2) % 4 != dirs[t]) return;
    int turning = 0;  // from side s's direction round to side t's
    for (int c = s + 1; c <= t; ++c) turning += 2 - block.corner_types[c];
    if (turning == 2) pairs.push_back({s, t, false});
    if (turning == -2) pairs.push_back({s, t, true});
    if (turning == 6) pairs.push_back({t, s, true});
  };
  std::map<std::pair<int, int>, int> side_at;  // lattice point -> the side whose run reached it
  int x = 0, y = 0;
  for (int i = 0; i < sides; ++i) {
    int n = 0;
    for (const int seg : block.side_segments[i]) n += counts[seg];
    for (int k = 0; k < n; ++k, x += kStepX[dirs[i]], y += kStepY[dirs[i]]) {
      const auto [it, fresh] = side_at.emplace(std::make_pair(x, y), i);
      if (fresh) continue;
      const int other = it->second;
      // Sides along one segment both ways (a split to a hole) meet on purpose: a slit.
      const auto& mine = block.side_segments[i];
      if (std::any_of(block.side_segments[other].begin(), block.side_segments[other].end(),
                      [&](int seg) { return std::find(mine.begin(), mine.end(), seg) != mine.end(); }))
        continue;
      // Running opposite ways they are the pair; crossing, a side beside one
      // of them runs opposite to the other (past a reflex corner: the two
      // arms of an S whose middle got too short).
      add_pair(other, i);
      add_pair(other, i - 1);
      add_pair(other + 1, i);
      add_pair(other - 1, i);
      add_pair(other, i + 1);
      return pairs;
    }
  }
  return pairs;
}

IntervalAssignment assign_intervals(const IntervalProblem& problem,
                                    const std::vector<std::pair<std::size_t, std::size_t>>& crowded_before) {
  validate(problem);
  for (size_t b = 0; b < problem.blocks.size(); ++b)
    if (problem.blocks[b].kind == BlockTemplate::Submap) submap_directions(problem.blocks[b], b);

  if (problem.segments.empty()) return {};  // no block can name a segment either: validated above
  Crowded crowded;
  for (const auto& [b, i] : crowded_before)
    if (b < problem.blocks.size() && i < problem.blocks[b].facing_goals.size()) crowded.insert({b, i});
  IntervalAssignment answer = solve_in_stages(problem, crowded);
  // Facing sides the answer crowds get their crowding rows, and the counts
  // are solved again (only then: these rows change which of the answers of
  // equal cost the solver meets, and so the meshes of faces they would not
  // constrain at all).
  for (int round = 0; round < kCrowdingRounds; ++round) {
    const std::size_t before = crowded.size();
    for (const auto& pair : crowded_pairs(problem, answer.counts)) crowded.insert(pair);
    if (crowded.size() == before) break;
    answer = solve_in_stages(problem, crowded);
  }
  const std::string violation = first_violation(problem, answer);
  if (!violation.empty()) throw SelfCheckError("interval assignment", violation);
  answer.crowded.assign(crowded.begin(), crowded.end());
  return answer;
}

}  // namespace mm
