#include "meshing/mesh_blocks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include "geometry/polygon.hpp"
#include "meshing/block_templates.hpp"
#include "meshing/interval_assignment.hpp"
#include "meshing/smoothing.hpp"
#include "meshing/union_find.hpp"

namespace mm {
namespace {

// Every interval of a curved edge turns by at most this much, so that small
// holes and fillets stay resolved however large the target size is (a full
// circle gets at least 8 intervals).
constexpr double kMaxTurnPerInterval = kPi / 4.0;
// Below this worst shape after smoothing with the turning bound,
// boundary nodes are freed for at most this many more passes, stopping
// once a pass with no inverted element lifts the worst by less than the gain.
constexpr double kPoorAfterSmoothing = 0.3;
constexpr int kFreeSmoothingPasses = 4;
// Under this share of area / H^2 elements the mesh gets a "coarser than
// asked" note (the tests' element count check uses the same bound).
constexpr double kCoarseShare = 0.4;
// Untangling's reach with MeshingOptions::wide_untangling (8 rings
// otherwise). Measured on eight faces that stop with an inverted element at
// a fifth of the default size: 12 rings untangle 1, 16 rings 2, 24 rings 6.
constexpr int kWideUntangleRings = 24;
constexpr double kSmoothingGain = 1e-3;
// A piece of a block side's boundary shorter than this fraction of the
// target size joins its neighbour on the same edge (joined_boundary_pieces).
constexpr double kShortestPiece = 0.1;
// Faces meshed together: points of two faces are one when closer than ten
// times the file's tolerance, but never than this fraction of the size.
constexpr double kMostTolerance = 0.05;

// One piece of the outlines that gets one interval count: a run of a split
// between two of its polyline points (a split is cut where it crosses the
// medial axis, and blocks on either side share those runs), or a piece of a
// boundary edge used by exactly one block.
struct Segment {
  int split = -1;
  std::vector<Vec2> line;  // split runs: the polyline, in the segment's direction
  int loop = -1;
  int edge = -1;
  double t_from = 0.0;
  double t_to = 0.0;
  double length = 0.0;
  int min_count = 1;
  std::vector<int> nodes;      // along the segment's own direction, both ends included
  std::vector<double> params;  // boundary segments: curve parameter of each node
  // Several faces meshed together: a piece of boundary another face shares.
  // Its count is the other face's too, so spreading leaves it alone; the
  // face meshed first places its nodes, the others take those points
  // (targets, inner nodes in this face's plane, in the segment's direction).
  bool shared = false;
  std::vector<Vec2> targets;
};

struct PieceUse {
  int segment = -1;
  bool reversed = false;
};

// Several faces meshed together: the part of one boundary edge between two
// break points (its ends and the other faces' vertices on it), as this
// face's segments in order along the edge. Two faces' stretches that
// coincide in 3-D get the same nodes.
struct Stretch {
  int face = -1;
  int loop = -1;
  int edge = -1;
  double low = 0.0;  // parameters of its ends, in the edge's direction
  double high = 0.0;
  double length = 0.0;
  std::vector<int> segments;
  // Whether segment j runs in the stretch's direction: fixed when the
  // stretch is made, as moving a joint may leave a segment of no length
  // for a moment (its other end not yet moved), which has no direction.
  std::vector<bool> forward;
  bool along(std::size_t j) const { return forward[j]; }
};

// Samples a boundary piece is measured by for its intervals' sagitta, and
// the share of the allowed sagitta interval assignment aims within (the
// rest is for smoothing, which slides boundary nodes along the curve).
constexpr int kSagittaSamples = 256;
constexpr double kSagittaMargin = 0.8;

// A boundary piece sampled finely in its parameter: cumulative chord length
// and the turning of its tangent, for lengths, bounds and even spacing.
struct PieceSamples {
  std::vector<double> params;
  std::vector<Vec2> points;
  std::vector<double> arc;  // cumulative chord length
  double turning = 0.0;
};

PieceSamples sample_piece(const BoundaryEdge& edge, double t_from, double t_to, int steps) {
  PieceSamples s;
  s.params.resize(steps + 1);
  s.points.resize(steps + 1);
  s.arc.assign(steps + 1, 0.0);
  for (int i = 0; i <= steps; ++i) {
    s.params[i] = t_from + (t_to - t_from) * i / steps;
    s.points[i] = edge_point(edge, s.params[i]).p;
    if (i > 0) s.arc[i] = s.arc[i - 1] + distance(s.points[i], s.points[i - 1]);
  }
  for (int i = 1; i < steps; ++i) {
    const Vec2 a = s.points[i] - s.points[i - 1];
    const Vec2 b = s.points[i + 1] - s.points[i];
    if (norm(a) > 0.0 && norm(b) > 0.0) s.turning += std::abs(signed_angle(a, b));
  }
  return s;
}

// The farthest any sample between samples i and j lies from their chord.
double sagitta_between(const PieceSamples& s, std::size_t i, std::size_t j) {
  double most = 0.0;
  for (std::size_t k = i + 1; k < j; ++k)
    most = std::max(most, distance_to_segment(s.points[k], s.points[i], s.points[j]));
  return most;
}

// The fewest intervals, at least `least`, of equal length along the piece
// whose chords all stay within `most` of it (a long curved side with the
// intervals its opposite side has cut across the curve: a cambered slat's
// concave side in one interval left the face by a quarter of its area).
// Measured on the samples, so no more than the samples can tell apart.
int intervals_within_sagitta(const PieceSamples& s, double most, int least) {
  const std::size_t last = s.points.size() - 1;
  if (!(most > 0.0) || last < 2) return least;
  for (int n = std::max(1, least); n < static_cast<int>(last); ++n) {
    bool within = true;
    std::size_t from = 0;
    for (int k = 1; k <= n && within; ++k) {
      const double target = s.arc.back() * k / n;
      std::size_t to =
          k == n ? last : std::size_t(std::lower_bound(s.arc.begin(), s.arc.end(), target) - s.arc.begin());
      to = std::clamp(to, from + 1, last);
      within = sagitta_between(s, from, to) <= most;
      from = to;
    }
    if (within) return n;
  }
  return std::max(least, static_cast<int>(last));
}

// Parameter at a fraction of the piece's length, from the sampled table.
double param_at_length(const PieceSamples& s, double length) {
  const auto it = std::lower_bound(s.arc.begin(), s.arc.end(), length);
  if (it == s.arc.begin()) return s.params.front();
  if (it == s.arc.end()) return s.params.back();
  const std::size_t i = static_cast<std::size_t>(it - s.arc.begin());
  const double span = s.arc[i] - s.arc[i - 1];
  const double f = span > 0.0 ? (length - s.arc[i - 1]) / span : 0.0;
  return s.params[i - 1] + f * (s.params[i] - s.params[i - 1]);
}

Vec2 point_along_polyline(const std::vector<Vec2>& line, const std::vector<double>& arc, double length) {
  const auto it = std::lower_bound(arc.begin(), arc.end(), length);
  if (it == arc.begin()) return line.front();
  if (it == arc.end()) return line.back();
  const std::size_t i = static_cast<std::size_t>(it - arc.begin());
  const double span = arc[i] - arc[i - 1];
  const double f = span > 0.0 ? (length - arc[i - 1]) / span : 0.0;
  return line[i - 1] + f * (line[i] - line[i - 1]);
}

std::vector<double> cumulative_length(const std::vector<Vec2>& line) {
  std::vector<double> arc(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) arc[i] = arc[i - 1] + distance(line[i], line[i - 1]);
  return arc;
}

// The parameter halfway along the curve between two parameters, by equal chords.
double middle_param(const BoundaryEdge& edge, double ta, double tb) {
  const Vec2 a = edge_point(edge, ta).p;
  const Vec2 b = edge_point(edge, tb).p;
  double lo = ta;
  double hi = tb;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const Vec2 p = edge_point(edge, mid).p;
    if (distance(a, p) < distance(p, b)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

double quad_area(const QuadMesh& mesh, const std::array<int, 4>& q) {
  double twice = 0.0;
  for (int i = 0; i < 4; ++i) twice += cross(mesh.nodes[q[i]], mesh.nodes[q[(i + 1) % 4]]);
  return 0.5 * twice;
}

std::string at(Vec2 p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

// Extra break parameters per loop and edge of a face: where the vertices and
// block outline ends of the faces meshed with it lie on its edges.
using EdgeCuts = std::vector<std::vector<std::vector<double>>>;

// Rounds of interval assignment that may each keep more sides apart.
constexpr int kMaxSeparationRounds = 8;

// Interval assignment of the problem make_problem() builds; when no counts
// satisfy the blocks at all, once more after relax() has changed the blocks
// (relax returns whether it changed any). Then, while the counts fold a
// submapped block's lattice outline onto itself (its outline would meet
// itself: no mesh), the two sides that meet are kept apart as facing sides
// (separate(block, sides) adds them to the block's shape, returning whether
// they were new; the next candidate pair when not) and the counts solved again.
template <class MakeProblem, class Relax, class Separate>
IntervalAssignment assign_or_relax(const MakeProblem& make_problem, const Relax& relax, const Separate& separate) {
  IntervalProblem problem = make_problem();
  IntervalAssignment assignment;
  try {
    assignment = assign_intervals(problem);
  } catch (const IntervalsInfeasible&) {
    if (!relax()) throw;
    problem = make_problem();
    assignment = assign_intervals(problem);
  }
  for (int round = 0; round < kMaxSeparationRounds; ++round) {
    bool separated = false;
    for (std::size_t b = 0; b < problem.blocks.size(); ++b) {
      for (const FoldedSides& folded : folded_sides(problem.blocks[b], assignment.counts)) {
        if (!separate(b, folded)) continue;
        separated = true;
        break;
      }
    }
    if (!separated) break;
    problem = make_problem();
    assignment = assign_intervals(problem, assignment.crowded);
  }
  return assignment;
}

// Adds a facing pair to a block's shape; false if it was there already.
bool add_facing(BlockShape& shape, const FoldedSides& folded) {
  auto& pairs = folded.outside ? shape.facing_outside : shape.facing;
  const std::pair<int, int> pair{folded.s, folded.t};
  if (std::find(pairs.begin(), pairs.end(), pair) != pairs.end()) return false;
  pairs.push_back(pair);
  return true;
}

// One face's blocks, in phases: prepare (segments and their shared ends),
// place (nodes on the segments for given interval counts, then the block
// templates), finish (smoothing, order 2, checks). run() does all three
// with the face's own interval assignment.
class BlockMesher {
 public:
  BlockMesher(const FaceModel& face, const Decomposition& d, const MeshingOptions& options, EdgeCuts cuts = {},
              double tolerance = 0.0)
      // Split ends meet the boundary to the decomposition's accuracy, which
      // on faces read with loose edge tolerances is looser than ours.
      : face_(face),
        d_(d),
        options_(options),
        cuts_(std::move(cuts)),
        tolerance_(std::max({1e-5 * face.size, 10.0 * face.tolerance, tolerance})) {}

  BlockMesh run() {
    prepare();
    start_stage(options_.progress, "interval counts");
    const auto t0 = std::chrono::steady_clock::now();
    IntervalAssignment intervals;
    std::vector<std::string> relaxed;
    try {
      intervals = assign_or_relax([&] { return interval_problem(); },
                                  [&] {
                                    relaxed = flatten_three_element_corners();
                                    return !relaxed.empty();
                                  },
                                  [&](std::size_t b, const FoldedSides& folded) { return separate(b, folded); });
    } catch (const SelfCheckError&) {
      throw;
    } catch (const std::exception& e) {
      fail(std::string("the blocks cannot be given interval counts: ") + e.what());
    }
    const auto t1 = std::chrono::steady_clock::now();
    start_stage(options_.progress, "blocks", static_cast<int>(d_.blocks.size()));
    place(intervals.counts, intervals.params);
    const auto t2 = std::chrono::steady_clock::now();
    start_stage(options_.progress, options_.smooth ? "smoothing" : "checks");
    BlockMesh result = finish();
    const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    result.stage_seconds.insert(result.stage_seconds.begin(),
                                {{"intervals", seconds(t0, t1)}, {"placement", seconds(t1, t2)}});
    result.notes.insert(result.notes.begin(), relaxed.begin(), relaxed.end());
    result.notes.insert(result.notes.end(), intervals.notes.begin(), intervals.notes.end());
    flag_if_coarse(result);
    return result;
  }

  void flag_if_coarse(BlockMesh& result) const {
    if (const std::string coarse = coarser_than_asked(result.mesh); !coarse.empty()) {
      result.notes.push_back(coarse);
      result.coarser_than_asked = true;
    }
  }

  // A note when the mesh has far fewer elements than the face's area over
  // H^2 (under kCoarseShare of them, on faces that want more than 20): a
  // block whose opposite sides differ greatly in length holds their counts
  // together, far below the long side's goal (a thin lens's body typed as a
  // rectangle with each long side opposite a short one, fuzz
  // elliptic_28_944: 14 elements at any size). Valid, but not what was asked.
  std::string coarser_than_asked(const QuadMesh& mesh) const {
    const double expected = face_.area / (options_.size * options_.size);
    if (expected <= 20 || static_cast<double>(mesh.quads.size()) >= kCoarseShare * expected) return {};
    std::ostringstream note;
    note.precision(4);
    note << "coarser than asked: " << mesh.quads.size() << " elements where the face's area / H^2 is " << expected
         << " (the blocks' conditions held interval counts far below their goals)";
    return note.str();
  }

  void prepare() {
    collect_segments();
    join_segment_ends();
  }

  void place(const std::vector<int>& counts, const std::vector<std::vector<int>>& params) {
    counts_ = counts;
    spread_along_boundary_runs(counts_);
    place_segment_nodes(counts_);
    for (std::size_t b = 0; b < d_.blocks.size(); ++b) {
      step(options_.progress);
      try {
        fill_block(shapes_[b], params[b], outline_of(static_cast<int>(b)), static_cast<int>(b), mesh_,
                   options_.regrid_wide_folds);
      } catch (const std::runtime_error& e) {
        fail(std::string("a block cannot be filled: ") + e.what());
      }
    }
  }

  // Smoothing, order 2 and the checks; the mesh handed on.
  BlockMesh finish() {
    BlockMesh result;
    const auto t2 = std::chrono::steady_clock::now();
    if (const int doublets = collapse_doublets())
      result.notes.push_back(std::to_string(doublets) +
                             " interior nodes of two elements (a singularity of k <= -2 fixed at one point, or "
                             "splits bending at one point whose elements add up to two) removed, their two "
                             "elements joined into one");
    if (options_.smooth) {
      // Boundary nodes slide along their curves (nodes facing each other
      // across a thin gap line up), but no interval comes to turn by more
      // than interval assignment allowed: sliding freely let single
      // intervals span too much of a small hole.
      SmoothingOptions smoothing;
      smoothing.max_boundary_turn = kMaxTurnPerInterval;
      smoothing.max_boundary_sagitta = kSagittaMargin * options_.max_sagitta * options_.size;
      if (options_.wide_untangling) smoothing.untangle_rings = kWideUntangleRings;
      // A piece of boundary shared with another face keeps the nodes both have.
      // Nor do the loop's vertices move: their two intervals lie on two edges
      // (or either side of a closed curve's seam).
      for (const Segment& s : segments_) {
        if (s.split >= 0) continue;
        if (s.shared) smoothing.fixed.insert(smoothing.fixed.end(), s.nodes.begin(), s.nodes.end());
        if (on_loop_vertex(s, 0)) smoothing.fixed.push_back(s.nodes.front());
        if (on_loop_vertex(s, static_cast<int>(s.nodes.size()) - 1)) smoothing.fixed.push_back(s.nodes.back());
      }
      // Unless an element stays folded or poor: then boundary nodes may give
      // way further, up to three times that turning (a block's few intervals
      // on a hole bunched where its sides meet, nodes facing each other
      // across a thin gap out of line). Without any bound, untangling a
      // cascade's first placement slid two nodes off a blade's round nose,
      // and one chord cut the nose off the mesh (elements outside the face,
      // though none inverted); with twice, a high-lift slot stayed folded
      // (fuzz aerofoil_3_361). Each free pass starts from the last one's nodes with
      // a fresh search (its chords and stalls reset), which climbs out of
      // optima one pass settles in; the best mesh seen is kept.
      SmoothingResult best = smooth_mesh(face_, mesh_, smoothing);
      const auto poor = [](const SmoothingResult& r) {
        return r.inverted_after > 0 || r.min_shape_after < kPoorAfterSmoothing;
      };
      if (poor(best)) {
        smoothing.max_boundary_turn = 3 * kMaxTurnPerInterval;
        QuadMesh trial = mesh_;
        for (int pass = 0; pass < kFreeSmoothingPasses && poor(best); ++pass) {
          check(options_.progress);
          const SmoothingResult r = smooth_mesh(face_, trial, smoothing);
          if (r.inverted_after < best.inverted_after ||
              (r.inverted_after == best.inverted_after && r.min_shape_after > best.min_shape_after))
            best = r, mesh_ = trial;
          if (r.inverted_after == 0 && r.min_shape_after < r.min_shape_before + kSmoothingGain) break;
        }
      }
      // Last, the nodes round the worst elements moved together, on the
      // best mesh seen: after the passes above, not in each, so that it
      // neither spares a face the free passes (by lifting it just over the
      // bar) nor starts them elsewhere; a mesh never comes out worse for it.
      if (best.inverted_after == 0) {
        check(options_.progress);
        SmoothingOptions joint = smoothing;
        joint.max_boundary_turn = kMaxTurnPerInterval;
        joint.joint_search_only = true;
        smooth_mesh(face_, mesh_, joint);
      }
    }
    const auto t3 = std::chrono::steady_clock::now();
    if (options_.order == 2) {
      add_midside_nodes();
      if (const int straightened = straighten_folding_curved_sides())
        result.notes.push_back("order 2: " + std::to_string(straightened) +
                               " boundary sides bent less than their curve (an element following the curve there "
                               "would have a Jacobian of the wrong sign)");
    }
    check_mesh();
    const auto t4 = std::chrono::steady_clock::now();
    const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    result.stage_seconds = {{"smoothing", seconds(t2, t3)}, {"mesh_check", seconds(t3, t4)}};
    result.segment_counts = counts_;
    result.mesh = std::move(mesh_);
    return result;
  }

  // The node that node n became when finish() removed nodes (-1: removed).
  int renumbered(int n) const { return renumbered_.empty() ? n : renumbered_[n]; }

  const std::vector<BlockShape>& shapes() const { return shapes_; }
  const std::vector<Segment>& segments() const { return segments_; }
  Segment& segment(int i) { return segments_[i]; }
  const BoundaryEdge& edge_of(const Segment& s) const { return face_.loops[s.loop].edges[s.edge]; }
  Vec2 node(int n) const { return mesh_.nodes[n]; }

  // Moves the vertex where segments j and j + 1 of a stretch meet (the end
  // of a split on the boundary) along the edge to the point nearest target.
  void move_joint(const Stretch& st, std::size_t j, Vec2 target) {
    const int i = st.segments[j];
    const int k = st.segments[j + 1];
    Segment& before = segments_[i];
    Segment& after = segments_[k];
    const bool before_along = st.along(j), after_along = st.along(j + 1);
    const int v = vertex_of_end_[2 * i + (before_along ? 1 : 0)];
    if (v != vertex_of_end_[2 * k + (after_along ? 0 : 1)])
      fail("two pieces of a shared edge do not meet at one vertex");
    // Searched up to the stretch's end, not only the next segment's: the
    // other face's nodes may lie further on than this face's own joints
    // (a face's splits meet an edge unevenly), and the later joints follow.
    const Segment& last = segments_[st.segments.back()];
    const double from = before_along ? before.t_from : before.t_to;
    const double to = st.along(st.segments.size() - 1) ? last.t_to : last.t_from;
    const double t = closest_param(edge_of(before), from, to, target).first;
    (before_along ? before.t_to : before.t_from) = t;
    (after_along ? after.t_from : after.t_to) = t;
    mesh_.nodes[v] = edge_point(edge_of(before), t).p;
    mesh_.places[v].t = t;
  }

  // The points a stretch's nodes take when this face places them, in the
  // stretch's direction: each segment's ends and its counts[i] - 1 inner
  // nodes by arc length (even_params, as place_segment_nodes puts them).
  std::vector<Vec2> stretch_points(const Stretch& st, const std::vector<int>& counts) const {
    std::vector<Vec2> points;
    for (std::size_t j = 0; j < st.segments.size(); ++j) {
      const Segment& s = segments_[st.segments[j]];
      std::vector<Vec2> own{edge_point(edge_of(s), s.t_from).p};
      for (const double t : even_params(s, counts[st.segments[j]])) own.push_back(edge_point(edge_of(s), t).p);
      own.push_back(edge_point(edge_of(s), s.t_to).p);
      if (!st.along(j)) std::reverse(own.begin(), own.end());
      points.insert(points.end(), own.begin() + (points.empty() ? 0 : 1), own.end());
    }
    return points;
  }

  Vec2 segment_end(const Segment& s, bool last) const {
    if (s.split >= 0) return last ? s.line.back() : s.line.front();
    return edge_point(edge_of(s), last ? s.t_to : s.t_from).p;
  }

  // The relaxation when no counts satisfy the blocks' templates. A corner of
  // a polygon block (5 or 6 sides) whose two sides run on as one side of the
  // neighbouring block holds 1 + 2 elements: a valence-3 node (k = -1) right
  // at the polygon's own k >= +1 centre. Midpoint subdivision then asks the
  // neighbour's side to equal the sum of two sides of the polygon, which
  // with a mapped neighbour round a ring contradicts the polygon's own
  // equations (found on fuzzed rings: a +1 and a -1 on one medial circle).
  // Taking such corners as flat (at most down to 4 sides) cancels that -1
  // against the centre: the polygon becomes mapped (or a pentagon), with no
  // valence-3 node there, and the index sum unchanged. Returns a note per
  // block changed (none: nothing to relax).
  std::vector<std::string> flatten_three_element_corners() {
    std::vector<std::set<std::pair<int, int>>> own(uses_.size());  // consecutive segments within one side
    for (std::size_t b = 0; b < uses_.size(); ++b)
      for (const auto& side : uses_[b])
        for (std::size_t k = 0; k + 1 < side.size(); ++k) own[b].insert({side[k].segment, side[k + 1].segment});
    std::vector<std::string> notes;
    for (std::size_t b = 0; b < uses_.size(); ++b) {
      auto& sides = uses_[b];
      BlockShape& shape = shapes_[b];
      if (shape.kind != BlockTemplate::Midpoint || sides.size() < 5) continue;
      int flattened = 0;
      for (std::size_t i = 0; i < sides.size() && sides.size() > 4;) {
        // Corner i: the end of side i - 1, the start of side i.
        const std::size_t before = (i + sides.size() - 1) % sides.size();
        const std::pair<int, int> across{sides[i].front().segment, sides[before].back().segment};
        bool found = false;
        for (std::size_t other = 0; other < own.size() && !found; ++other)
          found = other != b && own[other].count(across) > 0;
        if (!found) {
          ++i;
          continue;
        }
        // Side i joins side i - 1; corner i goes (at i = 0 the joined side
        // becomes side 0 and starts at the old last corner).
        sides[before].insert(sides[before].end(), sides[i].begin(), sides[i].end());
        shape.side_segments[before].insert(shape.side_segments[before].end(), shape.side_segments[i].begin(),
                                           shape.side_segments[i].end());
        sides.erase(sides.begin() + static_cast<std::ptrdiff_t>(i));
        shape.side_segments.erase(shape.side_segments.begin() + static_cast<std::ptrdiff_t>(i));
        shape.corner_types.erase(shape.corner_types.begin() + static_cast<std::ptrdiff_t>(i));
        if (i == 0) {
          std::rotate(sides.rbegin(), sides.rbegin() + 1, sides.rend());
          std::rotate(shape.side_segments.rbegin(), shape.side_segments.rbegin() + 1, shape.side_segments.rend());
          std::rotate(shape.corner_types.rbegin(), shape.corner_types.rbegin() + 1, shape.corner_types.rend());
        }
        ++flattened;
      }
      if (flattened == 0) continue;
      if (sides.size() == 4) shape.kind = BlockTemplate::Submap;
      notes.push_back("interval assignment: block " + std::to_string(b) + "'s template contradicts its neighbours'; " +
                      std::to_string(flattened) +
                      " of its corners (valence-3 points on a neighbour's side) taken as flat, "
                      "so it is meshed with " +
                      std::to_string(sides.size()) + " sides and its singularity cancels theirs");
    }
    return notes;
  }

  bool separate(std::size_t block, const FoldedSides& folded) { return add_facing(shapes_[block], folded); }

  IntervalProblem interval_problem() const {
    IntervalProblem problem;
    for (const Segment& s : segments_) {
      IntervalSegment is;
      is.goal = std::max(s.length / options_.size, 1e-9);
      is.min_count = s.min_count;
      problem.segments.push_back(is);
    }
    problem.blocks = shapes_;
    for (std::size_t b = 0; b < shapes_.size(); ++b) {
      if (shapes_[b].kind == BlockTemplate::Midpoint) problem.blocks[b].spoke_goals = spoke_goals(b);
      if (shapes_[b].kind == BlockTemplate::Submap) problem.blocks[b].facing_goals = facing_goals(b);
    }
    return problem;
  }

 private:
  void fail(const std::string& check) const { throw SelfCheckError(face_.name, "mesh: " + check); }

  // A midpoint block's distance from its centre (its singularity, else its
  // outline's mean point) to each side, over the target size.
  std::vector<double> spoke_goals(std::size_t b) const {
    const Block& block = d_.blocks[b];
    Vec2 centre;
    if (block.singularity >= 0) {
      centre = d_.singularities[block.singularity].p;
    } else {
      for (Vec2 p : block.outline) centre = centre + p;
      centre = centre / static_cast<double>(block.outline.size());
    }
    std::vector<double> goals;
    for (const std::vector<int>& side : shapes_[b].side_segments) {
      double nearest = std::numeric_limits<double>::max();
      for (const std::vector<Vec2>& line : side_lines(side))
        nearest = std::min(nearest, distance_to_polyline(line, centre));
      goals.push_back(nearest / options_.size);
    }
    return goals;
  }

  // A submapped block's narrowest distance between each facing pair of
  // sides, over the target size. Each pair's distance is kept for the later
  // rounds of interval assignment, which add pairs but move no segment.
  std::vector<double> facing_goals(std::size_t b) const {
    if (shapes_[b].facing.empty()) return {};
    const auto& sides = shapes_[b].side_segments;
    std::map<int, std::vector<std::vector<Vec2>>> lines;  // per side, sampled once for all its pairs
    const auto lines_of = [&](int side) -> const std::vector<std::vector<Vec2>>& {
      auto found = lines.find(side);
      if (found == lines.end()) found = lines.emplace(side, side_lines(sides[side])).first;
      return found->second;
    };
    std::vector<double> goals;
    for (const auto& [s, t] : shapes_[b].facing) {
      auto known = facing_distances_.find({sides[s], sides[t]});
      if (known == facing_distances_.end()) {
        double nearest = std::numeric_limits<double>::max();
        for (const std::vector<Vec2>& from : lines_of(s))
          for (const Vec2 p : from)
            for (const std::vector<Vec2>& to : lines_of(t)) nearest = std::min(nearest, distance_to_polyline(to, p));
        known = facing_distances_.emplace(std::make_pair(sides[s], sides[t]), nearest).first;
      }
      goals.push_back(known->second / options_.size);
    }
    return goals;
  }

  // The segments of a block side as polylines (boundary pieces sampled).
  std::vector<std::vector<Vec2>> side_lines(const std::vector<int>& side) const {
    std::vector<std::vector<Vec2>> lines;
    for (int id : side) {
      const Segment& s = segments_[id];
      lines.push_back(s.split >= 0 ? s.line : sample_piece(edge_of(s), s.t_from, s.t_to, 16).points);
    }
    return lines;
  }

  // Segments and, per block, the pieces of its sides as segments used
  // forwards or backwards; the block shapes for interval assignment.
  void collect_segments() {
    std::map<std::array<int, 3>, int> segment_of_run;
    for (std::size_t b = 0; b < d_.blocks.size(); ++b) {
      const Block& block = d_.blocks[b];
      BlockShape shape;
      shape.kind = template_of(block, static_cast<int>(b));
      for (const BlockCorner& c : block.corners) shape.corner_types.push_back(c.type);
      shape.facing = block.facing;
      shape.facing_outside = block.facing_outside;
      std::vector<std::vector<PieceUse>> sides;
      for (const BlockSide& side : block.sides) {
        std::vector<PieceUse> uses;
        std::vector<int> ids;
        for (const OutlinePiece& piece : joined_boundary_pieces(side.pieces, kShortestPiece * options_.size)) {
          if (piece.split < 0) {
            for (int id : boundary_segments(piece)) {
              uses.push_back({id, false});
              ids.push_back(id);
            }
            continue;
          }
          PieceUse use;
          const std::vector<Vec2>& polyline = d_.splits[piece.split].polyline;
          const int from = polyline_point(polyline, piece.points.front());
          const int to = polyline_point(polyline, piece.points.back());
          if (from == to) fail("a split piece of block " + std::to_string(b) + " has no length");
          const std::array<int, 3> run{piece.split, std::min(from, to), std::max(from, to)};
          auto found = segment_of_run.find(run);
          if (found == segment_of_run.end()) {
            Segment s;
            s.split = piece.split;
            s.line.assign(polyline.begin() + run[1], polyline.begin() + run[2] + 1);
            s.length = cumulative_length(s.line).back();
            found = segment_of_run.emplace(run, static_cast<int>(segments_.size())).first;
            segments_.push_back(std::move(s));
          }
          use.segment = found->second;
          use.reversed = from > to;
          uses.push_back(use);
          ids.push_back(use.segment);
        }
        sides.push_back(std::move(uses));
        shape.side_segments.push_back(std::move(ids));
      }
      uses_.push_back(std::move(sides));
      shapes_.push_back(std::move(shape));
    }
  }

  // A side's pieces with a straight piece of boundary shorter than
  // `shortest` joined to its neighbour on the same edge: the decomposition
  // cuts a side where the medial axis touches it, and every piece gets an
  // interval of its own however short (a near square of 6.691 x 6.698 had
  // its sides cut 0.0073 apart: at 0.095 a row of elements that thin across
  // the face, edge ratio 13). Longer pieces stay: they let interval
  // assignment spread a side's intervals; joining every piece under half
  // the size folded a keyed gear's bore and a fine trimesh_boxsides_179, and
  // joining curved pieces put an element of a fuzz aerofoil across its
  // section. No split ends between two pieces of one side (the outline
  // would turn into it), so their meeting point is no other block's.
  std::vector<OutlinePiece> joined_boundary_pieces(const std::vector<OutlinePiece>& pieces, double shortest) const {
    const auto length = [](const OutlinePiece& piece) { return cumulative_length(piece.points).back(); };
    const auto straight = [&](const OutlinePiece& piece) {
      return std::holds_alternative<LineCurve>(face_.loops[piece.loop].edges[piece.edge].curve);
    };
    std::vector<OutlinePiece> joined;
    for (const OutlinePiece& piece : pieces) {
      if (!joined.empty()) {
        OutlinePiece& last = joined.back();
        // Contiguous in parameter: a closed curve's pieces either side of
        // its seam are not (they meet at its start and end vertex).
        const double span = std::abs(last.t_to - last.t_from) + std::abs(piece.t_to - piece.t_from);
        if (last.split < 0 && piece.split < 0 && last.loop == piece.loop && last.edge == piece.edge &&
            (last.t_to - last.t_from) * (piece.t_to - piece.t_from) > 0.0 &&
            std::abs(piece.t_from - last.t_to) <= 1e-9 * span && straight(piece) &&
            std::min(length(last), length(piece)) < shortest) {
          last.t_to = piece.t_to;
          last.points.insert(last.points.end(), piece.points.begin() + (piece.points.empty() ? 0 : 1),
                             piece.points.end());
          continue;
        }
      }
      joined.push_back(piece);
    }
    return joined;
  }

  // A piece of boundary edge as segments, in its direction: one, or several
  // where the edge has break points (cuts_) inside the piece.
  std::vector<int> boundary_segments(const OutlinePiece& piece) {
    std::vector<double> params{piece.t_from};
    if (piece.loop < static_cast<int>(cuts_.size()) && piece.edge < static_cast<int>(cuts_[piece.loop].size())) {
      const BoundaryEdge& edge = face_.loops[piece.loop].edges[piece.edge];
      const Vec2 end = edge_point(edge, piece.t_to).p;
      std::vector<double> inside;
      for (double t : cuts_[piece.loop][piece.edge]) {
        if ((t - piece.t_from) * (piece.t_to - t) > 0.0) inside.push_back(t);
      }
      std::sort(inside.begin(), inside.end(),
                [&](double a, double b) { return (a - b) * (piece.t_to - piece.t_from) < 0.0; });
      // A break closer than the tolerance to one already kept or to the
      // piece's end would make an interval of no length.
      for (double t : inside) {
        const Vec2 p = edge_point(edge, t).p;
        if (distance(p, edge_point(edge, params.back()).p) > tolerance_ && distance(p, end) > tolerance_)
          params.push_back(t);
      }
    }
    params.push_back(piece.t_to);
    std::vector<int> ids;
    for (std::size_t i = 0; i + 1 < params.size(); ++i) {
      Segment s;
      s.loop = piece.loop;
      s.edge = piece.edge;
      s.t_from = params[i];
      s.t_to = params[i + 1];
      // A line's chords lie on it: only curves are sampled finely for the sagitta.
      const bool straight = std::holds_alternative<LineCurve>(edge_of(s).curve);
      const PieceSamples samples = sample_piece(edge_of(s), s.t_from, s.t_to, straight ? 64 : kSagittaSamples);
      s.length = samples.arc.back();
      s.min_count = std::max(1, static_cast<int>(std::ceil(samples.turning / kMaxTurnPerInterval - 1e-6)));
      if (!straight)
        s.min_count =
            intervals_within_sagitta(samples, kSagittaMargin * options_.max_sagitta * options_.size, s.min_count);
      ids.push_back(static_cast<int>(segments_.size()));
      segments_.push_back(std::move(s));
    }
    return ids;
  }

  // The polyline point a split piece starts or ends at.
  int polyline_point(const std::vector<Vec2>& polyline, Vec2 p) const {
    int best = 0;
    for (std::size_t i = 1; i < polyline.size(); ++i) {
      if (distance(polyline[i], p) < distance(polyline[best], p)) best = static_cast<int>(i);
    }
    if (distance(polyline[best], p) > tolerance_) fail("a split piece ends off its split's points at " + at(p));
    return best;
  }

  BlockTemplate template_of(const Block& block, int index) const {
    if (block.kind == BlockKind::Submap) {
      if (block.singularity >= 0) {
        throw SelfCheckError(face_.name, "mesh: block " + std::to_string(index) +
                                             " holds a k = " + std::to_string(d_.singularities[block.singularity].k) +
                                             " singularity but is not a logically convex polygon");
      }
      return BlockTemplate::Submap;
    }
    switch (block.corners.size()) {
      case 0: return BlockTemplate::Disc;
      case 1: return BlockTemplate::OneSided;
      case 2: return BlockTemplate::TwoSided;
      case 4: return BlockTemplate::Submap;
      default: return BlockTemplate::Midpoint;
    }
  }

  // Consecutive pieces of an outline meet: their ends are one vertex. The
  // vertices come from the outlines' topology, and their positions are only
  // checked to agree.
  void join_segment_ends() {
    std::vector<int> parent(2 * segments_.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto start_of = [](const PieceUse& u) { return 2 * u.segment + (u.reversed ? 1 : 0); };
    const auto end_of = [](const PieceUse& u) { return 2 * u.segment + (u.reversed ? 0 : 1); };
    for (const auto& sides : uses_) {
      std::vector<PieceUse> outline;
      for (const auto& side : sides) outline.insert(outline.end(), side.begin(), side.end());
      for (std::size_t i = 0; i < outline.size(); ++i) {
        const int a = find_root(parent, end_of(outline[i]));
        const int b = find_root(parent, start_of(outline[(i + 1) % outline.size()]));
        parent[a] = b;
      }
    }
    vertex_of_end_.assign(parent.size(), -1);
    std::map<int, int> vertex_of_root;
    for (std::size_t h = 0; h < parent.size(); ++h) {
      const int root = find_root(parent, static_cast<int>(h));
      const auto found = vertex_of_root.emplace(root, static_cast<int>(vertex_of_root.size())).first;
      vertex_of_end_[h] = found->second;
    }
    const std::size_t vertices = vertex_of_root.size();
    mesh_.nodes.assign(vertices, Vec2{});
    mesh_.places.assign(vertices, NodePlace{});
    std::vector<bool> placed(vertices, false);
    // Boundary ends first: a vertex on the boundary sits on the exact curve.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t h = 0; h < parent.size(); ++h) {
        const Segment& s = segments_[h / 2];
        if ((pass == 0) == (s.split >= 0)) continue;
        const int v = vertex_of_end_[h];
        const Vec2 p = segment_end(s, h % 2 == 1);
        if (placed[v]) {
          if (distance(mesh_.nodes[v], p) > tolerance_) {
            fail("block outlines that should meet are " + std::to_string(distance(mesh_.nodes[v], p)) + " apart at " +
                 at(p));
          }
          continue;
        }
        placed[v] = true;
        mesh_.nodes[v] = p;
        if (s.split < 0) mesh_.places[v] = boundary_place(s, h % 2 == 1 ? s.t_to : s.t_from, p);
      }
    }
  }

  NodePlace boundary_place(const Segment& s, double t, Vec2 p) const {
    NodePlace place;
    place.loop = s.loop;
    place.edge = s.edge;
    place.t = t;
    place.corner_elements = 2;
    const BoundaryEdge& edge = edge_of(s);
    const int edges = static_cast<int>(face_.loops[s.loop].edges.size());
    int vertex = -1;
    if (distance(p, edge.start) <= tolerance_) vertex = s.edge;
    if (distance(p, edge.end) <= tolerance_) vertex = (s.edge + 1) % edges;
    if (vertex >= 0) {
      place.face_corner = true;
      for (const Corner& c : face_.corners) {
        if (c.loop == s.loop && c.vertex == vertex) place.corner_elements = c.nc;
      }
    }
    return place;
  }

  // Interval assignment fixes what a side's pieces add up to; its linear
  // objective may then load a whole side's change onto one piece. Pieces of
  // boundary in a row on one side meet at no corner and no other block, so
  // their sum is spread over them by length again (largest remainders,
  // bounds kept).
  void spread_along_boundary_runs(std::vector<int>& counts) const {
    for (const auto& sides : uses_) {
      for (const auto& side : sides) {
        std::size_t begin = 0;
        while (begin < side.size()) {
          std::size_t end = begin;
          while (end < side.size() && segments_[side[end].segment].split < 0 && !segments_[side[end].segment].shared)
            ++end;
          if (end - begin > 1) spread(side, begin, end, counts);
          begin = end + 1;
        }
      }
    }
  }

  void spread(const std::vector<PieceUse>& side, std::size_t begin, std::size_t end, std::vector<int>& counts) const {
    int spare = 0;
    double length = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const Segment& s = segments_[side[i].segment];
      spare += counts[side[i].segment] - s.min_count;
      length += s.length;
      counts[side[i].segment] = s.min_count;
    }
    int total = spare;
    for (std::size_t i = begin; i < end; ++i) total += counts[side[i].segment];
    // One interval at a time to the piece furthest below its share by length.
    for (; spare > 0; --spare) {
      std::size_t neediest = begin;
      double most_missing = -1e300;
      for (std::size_t i = begin; i < end; ++i) {
        const double share = length > 0.0 ? total * segments_[side[i].segment].length / length : 0.0;
        const double missing = share - counts[side[i].segment];
        if (missing > most_missing) {
          most_missing = missing;
          neediest = i;
        }
      }
      ++counts[side[neediest].segment];
    }
  }

  // The parameters of a boundary segment's n - 1 inner nodes at equal arc
  // length along it.
  std::vector<double> even_params(const Segment& s, int n) const {
    const PieceSamples samples = sample_piece(edge_of(s), s.t_from, s.t_to, std::max(64, 16 * n));
    std::vector<double> params;
    for (int k = 1; k < n; ++k) params.push_back(param_at_length(samples, samples.arc.back() * k / n));
    return params;
  }

  void place_segment_nodes(const std::vector<int>& counts) {
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      Segment& s = segments_[i];
      const int n = counts[i];
      s.nodes.assign(1, vertex_of_end_[2 * i]);
      if (s.split >= 0) {
        const std::vector<Vec2>& line = s.line;
        const std::vector<double> arc = cumulative_length(line);
        for (int k = 1; k < n; ++k) add_node(s, point_along_polyline(line, arc, arc.back() * k / n), NodePlace{});
      } else {
        const std::vector<double> even = s.targets.empty() ? even_params(s, n) : std::vector<double>{};
        s.params.assign(1, s.t_from);
        for (int k = 1; k < n; ++k) {
          const double t =
              s.targets.empty() ? even[k - 1] : closest_param(edge_of(s), s.t_from, s.t_to, s.targets[k - 1]).first;
          NodePlace place;
          place.loop = s.loop;
          place.edge = s.edge;
          place.t = t;
          place.corner_elements = 2;
          add_node(s, edge_point(edge_of(s), t).p, place);
          s.params.push_back(t);
        }
        s.params.push_back(s.t_to);
      }
      s.nodes.push_back(vertex_of_end_[2 * i + 1]);
    }
  }

  void add_node(Segment& s, Vec2 p, const NodePlace& place) {
    s.nodes.push_back(static_cast<int>(mesh_.nodes.size()));
    mesh_.nodes.push_back(p);
    mesh_.places.push_back(place);
  }

  BlockOutline outline_of(int block) const {
    BlockOutline outline;
    const Block& b = d_.blocks[block];
    for (std::size_t side = 0; side < uses_[block].size(); ++side) {
      if (!b.corners.empty()) outline.corner_at.push_back(static_cast<int>(outline.nodes.size()));
      for (const PieceUse& use : uses_[block][side]) {
        std::vector<int> nodes = segments_[use.segment].nodes;
        if (use.reversed) std::reverse(nodes.begin(), nodes.end());
        outline.nodes.insert(outline.nodes.end(), nodes.begin(), nodes.end() - 1);
      }
    }
    return outline;
  }

  // Whether a boundary segment's node k lies on a vertex of its loop (the
  // segment's parameter there is the edge's own end, up to rounding: a
  // seam's parameter may come back from a projection as 4e-16).
  bool on_loop_vertex(const Segment& s, int k) const {
    const BoundaryEdge& edge = edge_of(s);
    const double rounding = 1e-12 * std::abs(edge.t_end - edge.t_start);
    return std::abs(s.params[k] - edge.t_start) <= rounding || std::abs(s.params[k] - edge.t_end) <= rounding;
  }

  // The parameter of a boundary segment's node k for the area check: its
  // place's where smoothing slid it along the edge, the segment's own at the
  // segment's ends. Any parameter works there as long as both segments at a
  // node take the same one (the check adds the step from the node onto the
  // curve), and the segment's own ends keep that so on every edge.
  double current_param(const Segment& s, int k) const {
    const NodePlace& place = mesh_.places[s.nodes[k]];
    if (k > 0 && k + 1 < static_cast<int>(s.nodes.size()) && place.loop == s.loop && place.edge == s.edge)
      return place.t;
    return s.params[k];
  }

  // Where node k of a boundary segment lies on the segment's curve now, for
  // the mid-side nodes: smoothing slides a split's end along the edge too,
  // but not the nodes on the loop's vertices (whose place may name the
  // other edge, or the other end of a closed curve's period).
  // A split end on a closed curve's seam, a hair off its vertex, may share
  // its node with the vertex and take the place at the period's other end
  // (Motor-c.brep face 43: the segment's 6.28319, the place's 0): on a
  // closed edge a place further from the segment's own parameter than half
  // the edge's range is that.
  double param_on_curve(const Segment& s, int k) const {
    const NodePlace& place = mesh_.places[s.nodes[k]];
    if (place.loop != s.loop || place.edge != s.edge || on_loop_vertex(s, k)) return s.params[k];
    const BoundaryEdge& edge = edge_of(s);
    const bool across_the_seam = distance(edge.start, edge.end) <= tolerance_ &&
                                 std::abs(place.t - s.params[k]) > 0.5 * std::abs(edge.t_end - edge.t_start);
    return across_the_seam ? s.params[k] : place.t;
  }

  // Each node's quads in compressed lists, so that the quads on a side are
  // found next to one of its nodes (linear in the mesh: no map of all sides).
  struct QuadsAtNodes {
    std::vector<int> first;  // node n's quads: quads[first[n] .. first[n + 1])
    std::vector<int> quads;
  };

  QuadsAtNodes quads_at_nodes() const {
    const std::size_t nodes = mesh_.nodes.size();
    QuadsAtNodes at;
    at.first.assign(nodes + 1, 0);
    for (const auto& q : mesh_.quads)
      for (int n : q) ++at.first[n + 1];
    for (std::size_t n = 0; n < nodes; ++n) at.first[n + 1] += at.first[n];
    at.quads.resize(at.first[nodes]);
    std::vector<int> fill(at.first.begin(), at.first.end() - 1);
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e)
      for (int n : mesh_.quads[e]) at.quads[fill[n]++] = static_cast<int>(e);
    return at;
  }

  // Order 2: a node in the middle of every element side, on the exact curve
  // for sides along the boundary.
  void add_midside_nodes() {
    const QuadsAtNodes at = quads_at_nodes();
    std::map<std::pair<int, int>, int> on_boundary;  // only the boundary's intervals: few
    std::vector<char> boundary_node(mesh_.nodes.size(), 0);
    const auto add = [&](Vec2 p, const NodePlace& place) {
      mesh_.nodes.push_back(p);
      mesh_.places.push_back(place);
      return static_cast<int>(mesh_.nodes.size()) - 1;
    };
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k) {
        const double t = middle_param(edge_of(s), param_on_curve(s, static_cast<int>(k)),
                                      param_on_curve(s, static_cast<int>(k + 1)));
        NodePlace place;
        place.loop = s.loop;
        place.edge = s.edge;
        place.t = t;
        const int a = s.nodes[k], b = s.nodes[k + 1];
        const int middle = add(edge_point(edge_of(s), t).p, place);
        on_boundary[{std::min(a, b), std::max(a, b)}] = middle;
        if (s.shared) shared_midside_.push_back(middle);
        boundary_node[a] = boundary_node[b] = 1;
      }
    }
    mesh_.midside.resize(mesh_.quads.size());
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
      for (int i = 0; i < 4; ++i) {
        const int a = mesh_.quads[e][i];
        const int b = mesh_.quads[e][(i + 1) % 4];
        int middle = -1;
        if (boundary_node[a] && boundary_node[b]) {
          const auto found = on_boundary.find({std::min(a, b), std::max(a, b)});
          if (found != on_boundary.end()) middle = found->second;
        }
        // An inner side's node comes from the first quad along it.
        for (int k = at.first[a]; k < at.first[a + 1] && middle < 0; ++k) {
          const int other = at.quads[k];
          if (other >= static_cast<int>(e)) continue;
          for (int j = 0; j < 4; ++j) {
            const int c = mesh_.quads[other][j], d = mesh_.quads[other][(j + 1) % 4];
            if ((c == a && d == b) || (c == b && d == a)) middle = mesh_.midside[other][j];
          }
        }
        if (middle < 0) middle = add(0.5 * (mesh_.nodes[a] + mesh_.nodes[b]), NodePlace{});
        mesh_.midside[e][i] = middle;
      }
    }
  }

  // The least Jacobian determinant of an 8-node element over the 3 x 3 Gauss
  // points, where a solver evaluates it (corners counter-clockwise, mid-side
  // node i on the side from corner i to i + 1).
  double least_quadratic_jacobian(std::size_t e) const {
    static const double kCorner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    static const double kGauss[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    Vec2 x[8];
    for (int i = 0; i < 4; ++i) {
      x[i] = mesh_.nodes[mesh_.quads[e][i]];
      x[4 + i] = mesh_.nodes[mesh_.midside[e][i]];
    }
    double least = std::numeric_limits<double>::infinity();
    for (double xi : kGauss) {
      for (double eta : kGauss) {
        Vec2 d_xi, d_eta;
        for (int i = 0; i < 4; ++i) {
          const double a = kCorner[i][0], b = kCorner[i][1];
          d_xi = d_xi + 0.25 * a * (1 + eta * b) * (2 * xi * a + eta * b) * x[i];
          d_eta = d_eta + 0.25 * b * (1 + xi * a) * (xi * a + 2 * eta * b) * x[i];
        }
        for (int i : {0, 2}) {  // mid-sides at eta = -1 and +1
          const double b = i == 0 ? -1.0 : 1.0;
          d_xi = d_xi + (-xi * (1 + eta * b)) * x[4 + i];
          d_eta = d_eta + (0.5 * b * (1 - xi * xi)) * x[4 + i];
        }
        for (int i : {1, 3}) {  // mid-sides at xi = +1 and -1
          const double a = i == 1 ? 1.0 : -1.0;
          d_xi = d_xi + (0.5 * a * (1 - eta * eta)) * x[4 + i];
          d_eta = d_eta + (-eta * (1 + xi * a)) * x[4 + i];
        }
        least = std::min(least, cross(d_xi, d_eta));
      }
    }
    return least;
  }

  // A thin element along a curve that bends into it (a layer along a
  // concave arc) can fold once its boundary side follows the curve: its
  // boundary mid-side nodes move back towards their chords' middles, by
  // halves, until the element is valid (the node keeps its place on the
  // edge for boundary conditions). Returns how many sides were bent less.
  int straighten_folding_curved_sides() {
    int straightened = 0;
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
      if (least_quadratic_jacobian(e) > 0.0) continue;
      std::vector<std::pair<int, Vec2>> sides;  // mid-side node, its chord's middle
      for (int i = 0; i < 4; ++i) {
        const int m = mesh_.midside[e][i];
        // A side shared with another face keeps the node both faces have.
        if (mesh_.places[m].loop < 0 ||
            std::find(shared_midside_.begin(), shared_midside_.end(), m) != shared_midside_.end())
          continue;
        const Vec2 chord_middle = 0.5 * (mesh_.nodes[mesh_.quads[e][i]] + mesh_.nodes[mesh_.quads[e][(i + 1) % 4]]);
        sides.emplace_back(m, chord_middle);
      }
      if (sides.empty()) continue;  // an inner fold: the check below names it
      std::vector<Vec2> on_curve;
      for (const auto& [m, middle] : sides) on_curve.push_back(mesh_.nodes[m]);
      for (double bend : {0.5, 0.25, 0.125, 0.0625, 0.0}) {
        for (std::size_t j = 0; j < sides.size(); ++j)
          mesh_.nodes[sides[j].first] = sides[j].second + bend * (on_curve[j] - sides[j].second);
        if (least_quadratic_jacobian(e) > 0.0) break;
      }
      straightened += static_cast<int>(sides.size());
    }
    return straightened;
  }

  // An interior node in only two elements (a doublet) has them share both
  // its sides, so one of them is flat there however the node is placed:
  // blocks give one when their corners at a split's bend add up to two
  // elements. The two elements (n, b, c, a) and (n, a, d, b) become one,
  // (b, c, a, d), and the node goes; every side but the two inner ones
  // stays, so the mesh stays conforming. Repeated while joining makes new
  // ones. Returns the number of nodes removed.
  int collapse_doublets() {
    int removed = 0;
    for (;;) {
      const QuadsAtNodes at = quads_at_nodes();
      std::vector<char> quad_gone(mesh_.quads.size(), 0), node_gone(mesh_.nodes.size(), 0);
      bool changed = false;
      for (std::size_t n = 0; n < mesh_.nodes.size(); ++n) {
        if (mesh_.places[n].loop >= 0 || at.first[n + 1] - at.first[n] != 2) continue;
        const int e1 = at.quads[at.first[n]], e2 = at.quads[at.first[n] + 1];
        if (quad_gone[e1] || quad_gone[e2]) continue;
        const auto from_node = [&](int e) {
          std::array<int, 4> q = mesh_.quads[e];
          std::rotate(q.begin(), std::find(q.begin(), q.end(), static_cast<int>(n)), q.end());
          return q;
        };
        const std::array<int, 4> q1 = from_node(e1), q2 = from_node(e2);
        if (q2[1] != q1[3] || q2[3] != q1[1] || q1[2] == q2[2]) continue;
        mesh_.quads[e1] = {q1[1], q1[2], q1[3], q2[2]};
        quad_gone[e2] = 1;
        node_gone[n] = 1;
        changed = true;
        ++removed;
      }
      if (!changed) break;
      std::vector<int> new_index(mesh_.nodes.size(), -1);
      int kept = 0;
      for (std::size_t n = 0; n < mesh_.nodes.size(); ++n) {
        if (node_gone[n]) continue;
        new_index[n] = kept;
        mesh_.nodes[kept] = mesh_.nodes[n];
        mesh_.places[kept] = mesh_.places[n];
        ++kept;
      }
      mesh_.nodes.resize(kept);
      mesh_.places.resize(kept);
      std::size_t quads = 0;
      for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
        if (quad_gone[e]) continue;
        for (int& v : mesh_.quads[e]) v = new_index[v];
        mesh_.quads[quads] = mesh_.quads[e];
        if (!mesh_.block_of_quad.empty()) mesh_.block_of_quad[quads] = mesh_.block_of_quad[e];
        ++quads;
      }
      mesh_.quads.resize(quads);
      if (!mesh_.block_of_quad.empty()) mesh_.block_of_quad.resize(quads);
      for (Segment& s : segments_) {
        for (int& v : s.nodes) v = new_index[v];
        s.nodes.erase(std::remove(s.nodes.begin(), s.nodes.end(), -1), s.nodes.end());
      }
      for (int& v : vertex_of_end_) v = v < 0 ? v : new_index[v];
      if (renumbered_.empty()) {
        renumbered_ = std::move(new_index);
      } else {
        for (int& v : renumbered_) v = v < 0 ? v : new_index[v];
      }
    }
    return removed;
  }

  // The mesh's own checks: conformity, orientation, area.
  void check_mesh() const {
    const std::size_t nodes = mesh_.nodes.size();
    const QuadsAtNodes quads_at = quads_at_nodes();
    // Each node's corners, gathered once: the corners after and before it.
    std::vector<int> corners_first(nodes + 1, 0);
    std::vector<std::pair<int, int>> corners;
    for (std::size_t a = 0; a < nodes; ++a) {
      for (int k = quads_at.first[a]; k < quads_at.first[a + 1]; ++k) {
        const auto& q = mesh_.quads[quads_at.quads[k]];
        for (int i = 0; i < 4; ++i)
          if (q[i] == static_cast<int>(a)) corners.emplace_back(q[(i + 1) % 4], q[(i + 3) % 4]);
      }
      corners_first[a + 1] = static_cast<int>(corners.size());
    }
    const auto quads_on_side = [&](int a, int b) {
      return static_cast<int>(std::count_if(corners.begin() + corners_first[a], corners.begin() + corners_first[a + 1],
                                            [b](const auto& c) { return c.first == b || c.second == b; }));
    };
    // The outer sides are exactly the boundary's intervals, each once: with
    // every element turning counter-clockwise, the elements then cover the
    // face once (the mapping's degree is the boundary's winding number).
    std::vector<std::pair<int, int>> boundary_intervals;
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k)
        boundary_intervals.emplace_back(std::min(s.nodes[k], s.nodes[k + 1]), std::max(s.nodes[k], s.nodes[k + 1]));
    }
    std::sort(boundary_intervals.begin(), boundary_intervals.end());
    std::vector<char> interval_used(boundary_intervals.size(), 0), on_boundary_interval(nodes, 0);
    for (const auto& [a, b] : boundary_intervals) on_boundary_interval[a] = on_boundary_interval[b] = 1;
    for (const auto& q : mesh_.quads) {
      for (int i = 0; i < 4; ++i) {
        const int a = q[i];
        const int b = q[(i + 1) % 4];
        // A side a ten-millionth of the face long is a collapsed element to a
        // solver (not the face's CAD tolerance: loose on some real parts).
        if (a == b || distance(mesh_.nodes[a], mesh_.nodes[b]) <= 1e-7 * face_.size)
          fail("an element has a collapsed side (" + std::to_string(distance(mesh_.nodes[a], mesh_.nodes[b])) +
               " long) at " + at(mesh_.nodes[a]));
        const int count = quads_on_side(a, b);
        const Vec2 p = 0.5 * (mesh_.nodes[a] + mesh_.nodes[b]);
        if (count > 2) fail("an element side at " + at(p) + " is shared by " + std::to_string(count) + " elements");
        const std::pair<int, int> side{std::min(a, b), std::max(a, b)};
        const auto interval = on_boundary_interval[a] && on_boundary_interval[b]
                                  ? std::lower_bound(boundary_intervals.begin(), boundary_intervals.end(), side)
                                  : boundary_intervals.end();
        const bool on_boundary = interval != boundary_intervals.end() && *interval == side;
        if ((count == 1) != on_boundary)
          fail("an element side at " + at(p) +
               (count == 1 ? " is open but not on the boundary" : " is on the boundary but closed"));
        if (on_boundary) interval_used[interval - boundary_intervals.begin()] = 1;
      }
    }
    for (std::size_t k = 0; k < boundary_intervals.size(); ++k) {
      if (!interval_used[k])
        fail("no element lies along the boundary at " + at(mesh_.nodes[boundary_intervals[k].first]));
    }
    // What the straight boundary sides cut off the face (or add to it): the
    // area between each interval's curve and its chord, exactly (Green's
    // theorem along the curve; the short connectors from a vertex node to
    // the other edge's curve end included). The elements must cover the
    // face less that: the polygon of the boundary nodes, once.
    double cut_off = 0.0;
    double worst_sagitta = 0.0;
    Vec2 worst_side;
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k) {
        const Vec2 a = mesh_.nodes[s.nodes[k]];
        const Vec2 b = mesh_.nodes[s.nodes[k + 1]];
        const double ta = current_param(s, static_cast<int>(k)), tb = current_param(s, static_cast<int>(k + 1));
        const Vec2 curve_b = edge_point(edge_of(s), tb).p;
        // Between the nodes where they lie on the curve now (a split's end slides along it).
        const double off = edge_sagitta(edge_of(s), param_on_curve(s, static_cast<int>(k)),
                                        param_on_curve(s, static_cast<int>(k + 1)));
        if (off > worst_sagitta) worst_sagitta = off, worst_side = 0.5 * (a + b);
        // The closed path a -> curve -> b -> a seen from a (the chord and the
        // step from a onto the curve sweep nothing from there).
        cut_off += edge_area_integral(edge_of(s), ta, tb, a) + 0.5 * cross(curve_b - a, b - curve_b);
      }
    }
    if (worst_sagitta > options_.max_sagitta * options_.size) {
      std::ostringstream s;
      s << "the boundary side at " << at(worst_side) << " lies " << worst_sagitta << " off its curve, "
        << worst_sagitta / options_.size << " of the size (at most " << options_.max_sagitta
        << "): the mesh leaves the face or misses part of it there";
      fail(s.str());
    }
    double area = 0.0;
    int worst = -1;
    double worst_value = 2.0;
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
      area += quad_area(mesh_, mesh_.quads[e]);
      const double value = worst_corner_jacobian(mesh_, mesh_.quads[e]);
      if (value < worst_value) {
        worst_value = value;
        worst = static_cast<int>(e);
      }
    }
    if (worst >= 0 && worst_value <= 0.0) {
      Vec2 centre;
      for (int n : mesh_.quads[worst]) centre = centre + 0.25 * mesh_.nodes[n];
      std::ostringstream s;
      s << "element " << worst + 1 << " at " << at(centre) << " is inverted (scaled Jacobian " << worst_value << ")";
      fail(s.str());
    }
    for (std::size_t e = 0; e < mesh_.midside.size(); ++e) {
      if (least_quadratic_jacobian(e) > 0.0) continue;
      Vec2 centre;
      for (int n : mesh_.quads[e]) centre = centre + 0.25 * mesh_.nodes[n];
      fail("8-node element " + std::to_string(e + 1) + " at " + at(centre) +
           " has a Jacobian of the wrong sign at a Gauss point");
    }
    // The face's area runs its connectors through the snapped vertices, the
    // cut-off ones through the vertex nodes (within tolerance_ of them): a
    // sliver of at most tolerance_^2 at each end of each edge.
    int edges = 0;
    for (const Loop& loop : face_.loops) edges += static_cast<int>(loop.edges.size());
    const double allowed = 1e-9 * face_.area + 2.0 * edges * tolerance_ * tolerance_;
    if (std::abs(area - (face_.area - cut_off)) > allowed) {
      std::ostringstream s;
      s.precision(10);
      s << "the elements cover " << area << ", the polygon of the boundary nodes " << face_.area - cut_off
        << " (the face " << face_.area << ")";
      fail(s.str());
    }
  }

  const FaceModel& face_;
  const Decomposition& d_;
  const MeshingOptions& options_;
  EdgeCuts cuts_;
  double tolerance_;
  std::vector<int> counts_;  // intervals per segment, as placed
  // facing_goals' distances, by the two sides' segments
  mutable std::map<std::pair<std::vector<int>, std::vector<int>>, double> facing_distances_;
  std::vector<Segment> segments_;
  std::vector<int> shared_midside_;                       // order 2: mid-side nodes on sides shared with another face
  std::vector<std::vector<std::vector<PieceUse>>> uses_;  // per block, per side
  std::vector<BlockShape> shapes_;
  std::vector<int> vertex_of_end_;  // per segment end (2 s + 0 start, 2 s + 1 end)
  std::vector<int> renumbered_;     // old node -> new after collapse_doublets (-1: removed), empty if none
  QuadMesh mesh_;
};

using Point3 = std::array<double, 3>;

double distance3(const Point3& a, const Point3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// A 3-D point in a face's frame: its coordinates in the plane, and its distance from the plane.
Vec2 in_plane(const Frame& f, const Point3& p) {
  const Point3 d{p[0] - f.origin[0], p[1] - f.origin[1], p[2] - f.origin[2]};
  return {d[0] * f.x_dir[0] + d[1] * f.x_dir[1] + d[2] * f.x_dir[2],
          d[0] * f.y_dir[0] + d[1] * f.y_dir[1] + d[2] * f.y_dir[2]};
}

double off_plane(const Frame& f, const Point3& p) {
  return std::abs((p[0] - f.origin[0]) * f.normal[0] + (p[1] - f.origin[1]) * f.normal[1] +
                  (p[2] - f.origin[2]) * f.normal[2]);
}

// Where a 3-D point lies on an edge of a face: the parameter and the
// distance from the curve (infinite off the face's plane).
std::pair<double, double> locate_on_edge(const FaceModel& face, const BoundaryEdge& edge, double ta, double tb,
                                         const Point3& p, double tolerance) {
  if (off_plane(face.frame, p) > tolerance) return {ta, std::numeric_limits<double>::infinity()};
  return closest_param(edge, ta, tb, in_plane(face.frame, p));
}

void check_options(const MeshingOptions& options) {
  if (!(options.size > 0.0) || !std::isfinite(options.size))
    throw InputError("mesh size must be a positive number, got " + std::to_string(options.size));
  if (options.order != 1 && options.order != 2)
    throw InputError("element order must be 1 or 2, got " + std::to_string(options.order));
}

// A face's box in 3-D, grown by `margin`: faces whose boxes miss each other
// share nothing, which spares the pairwise searches on many faces.
struct Box3 {
  Point3 low{};
  Point3 high{};
  bool meets(const Box3& o) const {
    for (int k = 0; k < 3; ++k)
      if (low[k] > o.high[k] || o.low[k] > high[k]) return false;
    return true;
  }
};

Box3 face_box(const FaceModel& face, double margin) {
  // The samples lie on the curves within the chord tolerance of them.
  const double chord = 1e-3 * face.size;
  Box3 box{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (const Loop& loop : face.loops) {
    for (const Vec2& p : sample_loop(loop, chord)) {
      const Point3 q = to_3d(face.frame, p);
      for (int k = 0; k < 3; ++k) {
        box.low[k] = std::min(box.low[k], q[k] - chord - margin);
        box.high[k] = std::max(box.high[k], q[k] + chord + margin);
      }
    }
  }
  return box;
}

// The break points every face's edges get from the others: their loop
// vertices, wherever these lie inside one of its edges (a T-junction, or
// where two faces' edges overlap only in part).
std::vector<EdgeCuts> edge_cuts(const std::vector<FaceModel>& faces, const std::vector<Box3>& boxes, double tolerance) {
  std::vector<std::vector<Point3>> marks(faces.size());
  for (std::size_t g = 0; g < faces.size(); ++g) {
    for (const Loop& loop : faces[g].loops) {
      for (const BoundaryEdge& edge : loop.edges) marks[g].push_back(to_3d(faces[g].frame, edge.start));
    }
  }
  std::vector<EdgeCuts> cuts(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceModel& face = faces[f];
    for (const Loop& loop : face.loops) cuts[f].emplace_back(loop.edges.size());
    for (std::size_t g = 0; g < faces.size(); ++g) {
      if (g == f || !boxes[f].meets(boxes[g])) continue;
      for (const Point3& p : marks[g]) {
        if (off_plane(face.frame, p) > tolerance) continue;
        const Vec2 q = in_plane(face.frame, p);
        for (std::size_t l = 0; l < face.loops.size(); ++l) {
          for (std::size_t e = 0; e < face.loops[l].edges.size(); ++e) {
            const BoundaryEdge& edge = face.loops[l].edges[e];
            if (distance(q, edge.start) <= tolerance || distance(q, edge.end) <= tolerance) continue;
            const auto [t, gap] = closest_param(edge, edge.t_start, edge.t_end, q);
            if (gap <= tolerance) cuts[f][l][e].push_back(t);
          }
        }
      }
    }
  }
  return cuts;
}

// A face's boundary segments grouped into stretches: by edge and by the
// break points (cuts) between them, in order along the edge.
std::vector<Stretch> face_stretches(const BlockMesher& m, const EdgeCuts& cuts) {
  std::map<std::array<int, 3>, Stretch> found;
  const std::vector<Segment>& segments = m.segments();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    if (s.split >= 0) continue;
    const BoundaryEdge& edge = m.edge_of(s);
    const double span = edge.t_end - edge.t_start;
    const auto position = [&](double t) { return (t - edge.t_start) / span; };
    const double middle = position(0.5 * (s.t_from + s.t_to));
    int index = 0;
    if (s.loop < static_cast<int>(cuts.size()) && s.edge < static_cast<int>(cuts[s.loop].size())) {
      for (double c : cuts[s.loop][s.edge]) index += position(c) < middle ? 1 : 0;
    }
    Stretch& st = found[{s.loop, s.edge, index}];
    st.loop = s.loop;
    st.edge = s.edge;
    st.segments.push_back(static_cast<int>(i));
  }
  std::vector<Stretch> stretches;
  for (auto& [key, st] : found) {
    const BoundaryEdge& edge = m.edge_of(segments[st.segments.front()]);
    const double sign = edge.t_end > edge.t_start ? 1.0 : -1.0;
    const auto low_end = [&](const Segment& s) { return sign * s.t_from < sign * s.t_to ? s.t_from : s.t_to; };
    std::sort(st.segments.begin(), st.segments.end(),
              [&](int a, int b) { return sign * low_end(segments[a]) < sign * low_end(segments[b]); });
    st.low = low_end(segments[st.segments.front()]);
    const Segment& last = segments[st.segments.back()];
    st.high = low_end(last) == last.t_from ? last.t_to : last.t_from;
    for (int i : st.segments) {
      st.length += segments[i].length;
      st.forward.push_back((segments[i].t_to - segments[i].t_from) * (st.high - st.low) > 0.0);
    }
    stretches.push_back(std::move(st));
  }
  return stretches;
}

std::string face_names(const std::vector<FaceModel>& faces) {
  std::string names;
  for (const FaceModel& f : faces) names += (names.empty() ? "" : ", ") + f.name;
  return names;
}

}  // namespace

BlockMesh mesh_blocks(const FaceModel& face, const Decomposition& decomposition, const MeshingOptions& options) {
  check_options(options);
  return BlockMesher(face, decomposition, options).run();
}

int shared_edge_count(const std::vector<SharedPiece>& shared) {
  std::set<std::array<int, 6>> edges;
  for (const SharedPiece& p : shared)
    edges.insert({p.face_a, p.loop_edge_a[0], p.loop_edge_a[1], p.face_b, p.loop_edge_b[0], p.loop_edge_b[1]});
  return static_cast<int>(edges.size());
}

FaceSetBlockMesh mesh_blocks_together(const std::vector<FaceModel>& faces,
                                      const std::vector<Decomposition>& decompositions, const MeshingOptions& options) {
  check_options(options);
  if (faces.size() != decompositions.size())
    throw std::invalid_argument("mesh_blocks_together: " + std::to_string(faces.size()) + " faces but " +
                                std::to_string(decompositions.size()) + " decompositions");
  FaceSetBlockMesh result;
  // Ten times the file's own tolerance, but never a sizeable part of an
  // element: some files carry edge tolerances of a millimetre on parts of
  // a few centimetres (OCCT's mal_tige.brep: 1.57 on a 180 mm rod), and
  // nodes of one element that far apart are not one point.
  for (const FaceModel& f : faces)
    result.tolerance =
        std::max({result.tolerance, 1e-5 * f.size, std::min(10.0 * f.tolerance, kMostTolerance * options.size)});
  const double tolerance = result.tolerance;
  std::vector<Box3> boxes;
  for (const FaceModel& f : faces) boxes.push_back(face_box(f, tolerance));
  const std::vector<EdgeCuts> cuts = edge_cuts(faces, boxes, tolerance);
  std::vector<std::unique_ptr<BlockMesher>> meshers;
  std::vector<int> offset{0};
  std::vector<Stretch> stretches;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    meshers.push_back(std::make_unique<BlockMesher>(faces[f], decompositions[f], options, cuts[f], tolerance));
    meshers.back()->prepare();
    offset.push_back(offset.back() + static_cast<int>(meshers.back()->segments().size()));
    for (Stretch& st : face_stretches(*meshers.back(), cuts[f])) {
      st.face = static_cast<int>(f);
      stretches.push_back(std::move(st));
    }
  }

  // Shared stretches: classes, the lowest (the first face's) placing the nodes.
  std::vector<int> parent(stretches.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> reversed(stretches.size(), false);  // against the representative's direction
  const auto point3 = [&](const Stretch& st, bool last) {
    const BoundaryEdge& edge = meshers[st.face]->edge_of(meshers[st.face]->segments()[st.segments.front()]);
    return to_3d(faces[st.face].frame, edge_point(edge, last ? st.high : st.low).p);
  };
  // Every segment's middle of one stretch lies on the other's curve. (Lengths,
  // summed from chords, are only a quick first test: within 1e-3 on curves.)
  const auto lies_on = [&](const Stretch& a, const Stretch& b) {
    const BlockMesher& m = *meshers[a.face];
    const BoundaryEdge& other = meshers[b.face]->edge_of(meshers[b.face]->segments()[b.segments.front()]);
    for (int i : a.segments) {
      const Segment& s = m.segments()[i];
      const Point3 mid = to_3d(faces[a.face].frame, edge_point(m.edge_of(s), 0.5 * (s.t_from + s.t_to)).p);
      if (locate_on_edge(faces[b.face], other, b.low, b.high, mid, tolerance).second > tolerance) return false;
    }
    return true;
  };
  for (std::size_t a = 0; a < stretches.size(); ++a) {
    for (std::size_t b = a + 1; b < stretches.size(); ++b) {
      const Stretch& sa = stretches[a];
      const Stretch& sb = stretches[b];
      if (sa.face == sb.face || !boxes[sa.face].meets(boxes[sb.face]) ||
          find_root(parent, static_cast<int>(b)) != static_cast<int>(b) ||
          std::abs(sa.length - sb.length) > 2.0 * tolerance + 1e-3 * std::max(sa.length, sb.length))
        continue;
      const Point3 a0 = point3(sa, false), a1 = point3(sa, true), b0 = point3(sb, false), b1 = point3(sb, true);
      const bool forward = distance3(a0, b0) <= tolerance && distance3(a1, b1) <= tolerance;
      const bool backward = distance3(a0, b1) <= tolerance && distance3(a1, b0) <= tolerance;
      if ((!forward && !backward) || !lies_on(sa, sb) || !lies_on(sb, sa)) continue;
      bool against = !forward;
      if (forward && backward) {
        // A closed stretch (a whole circle): its direction from the tangents.
        const auto tangent = [&](const Stretch& st) {
          const BoundaryEdge& edge = meshers[st.face]->edge_of(meshers[st.face]->segments()[st.segments.front()]);
          const Vec2 t = edge_tangent(edge, st.low);
          const Point3 tip = to_3d(faces[st.face].frame, t), base = to_3d(faces[st.face].frame, {});
          return Point3{tip[0] - base[0], tip[1] - base[1], tip[2] - base[2]};
        };
        const Point3 ta = tangent(sa), tb = tangent(sb);
        against = ta[0] * tb[0] + ta[1] * tb[1] + ta[2] * tb[2] < 0.0;
      }
      parent[b] = find_root(parent, static_cast<int>(a));
      reversed[b] = reversed[a] != against;
    }
  }

  // The stretch of each class that places its nodes: the one cut into the
  // most segments (most split ends on it), whose joints then stay where its
  // decomposition put them; the others move their fewer joints to its nodes.
  std::vector<int> placer(stretches.size());
  for (std::size_t i = 0; i < stretches.size(); ++i) placer[i] = find_root(parent, static_cast<int>(i));
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    int& p = placer[find_root(parent, static_cast<int>(i))];
    if (stretches[i].segments.size() > stretches[p].segments.size()) p = static_cast<int>(i);
  }
  for (std::size_t i = 0; i < stretches.size(); ++i) placer[i] = placer[find_root(parent, static_cast<int>(i))];

  // One interval assignment: a count per segment, a shared stretch's
  // segments in every face summing alike.
  const auto global = [&](const Stretch& st) {
    std::vector<int> ids;
    for (int i : st.segments) ids.push_back(offset[st.face] + i);
    return ids;
  };
  std::vector<EqualSums> equal_sums;
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const int root = find_root(parent, static_cast<int>(i));
    if (root == static_cast<int>(i)) continue;
    equal_sums.push_back({global(stretches[root]), global(stretches[i])});
    for (int k : {root, static_cast<int>(i)})
      for (int seg : stretches[k].segments) meshers[stretches[k].face]->segment(seg).shared = true;
  }
  const auto problem = [&]() {
    IntervalProblem p;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      IntervalProblem own = meshers[f]->interval_problem();
      p.segments.insert(p.segments.end(), own.segments.begin(), own.segments.end());
      for (BlockShape& shape : own.blocks) {
        for (auto& side : shape.side_segments)
          for (int& id : side) id += offset[f];
        p.blocks.push_back(std::move(shape));
      }
    }
    p.equal_sums = equal_sums;
    return p;
  };
  start_stage(options.progress, "interval counts");
  const auto t0 = std::chrono::steady_clock::now();
  IntervalAssignment intervals;
  std::vector<std::vector<std::string>> relaxed(faces.size());
  try {
    intervals = assign_or_relax(
        problem,
        [&] {
          bool any = false;
          for (std::size_t f = 0; f < faces.size(); ++f) {
            relaxed[f] = meshers[f]->flatten_three_element_corners();
            any = any || !relaxed[f].empty();
          }
          return any;
        },
        [&](std::size_t b, const FoldedSides& folded) {
          for (const auto& m : meshers) {
            if (b < m->shapes().size()) return m->separate(b, folded);
            b -= m->shapes().size();
          }
          return false;
        });
  } catch (const std::exception& e) {
    throw SelfCheckError(face_names(faces),
                         std::string("mesh: the faces' blocks cannot be given interval counts together: ") + e.what());
  }
  const auto t1 = std::chrono::steady_clock::now();

  // Placement face by face. The placing stretch's nodes are known from the
  // counts alone; every other face moves its own segment ends on the
  // stretch (where its splits meet it) to the nodes its counts reach, and
  // puts its nodes there.
  std::vector<std::vector<Point3>> placed_points(stretches.size());
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const Stretch& st = stretches[i];
    if (placer[i] != static_cast<int>(i) || !meshers[st.face]->segments()[st.segments.front()].shared) continue;
    const std::vector<int> counts(intervals.counts.begin() + offset[st.face],
                                  intervals.counts.begin() + offset[st.face + 1]);
    for (const Vec2& p : meshers[st.face]->stretch_points(st, counts))
      placed_points[i].push_back(to_3d(faces[st.face].frame, p));
  }
  std::vector<std::vector<int>> run_nodes(stretches.size());
  const auto collect_run = [&](std::size_t i) {
    const Stretch& st = stretches[i];
    const BlockMesher& m = *meshers[st.face];
    std::vector<int>& run = run_nodes[i];
    for (std::size_t j = 0; j < st.segments.size(); ++j) {
      std::vector<int> nodes = m.segments()[st.segments[j]].nodes;
      if (!st.along(j)) std::reverse(nodes.begin(), nodes.end());
      run.insert(run.end(), nodes.begin() + (run.empty() ? 0 : 1), nodes.end());
    }
  };
  std::size_t block_count = 0;
  for (const auto& m : meshers) block_count += m->shapes().size();
  start_stage(options.progress, "blocks", static_cast<int>(block_count));
  std::size_t first_block = 0;
  std::size_t next_stretch = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    BlockMesher& m = *meshers[f];
    const std::vector<int> counts(intervals.counts.begin() + offset[f], intervals.counts.begin() + offset[f + 1]);
    const std::size_t first_stretch = next_stretch;
    for (; next_stretch < stretches.size() && stretches[next_stretch].face == static_cast<int>(f); ++next_stretch) {
      const int source = placer[next_stretch];
      if (source == static_cast<int>(next_stretch)) continue;
      const Stretch& st = stretches[next_stretch];
      std::vector<Point3> run = placed_points[source];
      if (reversed[next_stretch] != reversed[source]) std::reverse(run.begin(), run.end());
      std::size_t at = 0;
      for (std::size_t j = 0; j < st.segments.size(); ++j) {
        Segment& s = m.segment(st.segments[j]);
        const std::size_t n = static_cast<std::size_t>(counts[st.segments[j]]);
        if (at + n >= run.size()) throw SelfCheckError(face_names(faces), "mesh: a shared stretch's counts differ");
        if (j + 1 < st.segments.size()) m.move_joint(st, j, in_plane(faces[f].frame, run[at + n]));
        s.targets.clear();
        for (std::size_t k = 1; k < n; ++k) s.targets.push_back(in_plane(faces[f].frame, run[at + k]));
        if (!st.along(j)) std::reverse(s.targets.begin(), s.targets.end());
        at += n;
      }
    }
    const std::size_t blocks = m.shapes().size();
    const std::vector<std::vector<int>> params(intervals.params.begin() + first_block,
                                               intervals.params.begin() + first_block + blocks);
    first_block += blocks;
    m.place(counts, params);
    for (std::size_t i = first_stretch; i < next_stretch; ++i) collect_run(i);
  }
  const auto t2 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const int source = placer[i];
    if (source == static_cast<int>(i)) continue;
    const Stretch& a = stretches[source];
    const Stretch& b = stretches[i];
    SharedPiece piece;
    piece.face_a = a.face;
    piece.face_b = b.face;
    piece.edge_a = faces[a.face].loops[a.loop].edges[a.edge].source_index;
    piece.edge_b = faces[b.face].loops[b.loop].edges[b.edge].source_index;
    piece.loop_edge_a = {a.loop, a.edge};
    piece.loop_edge_b = {b.loop, b.edge};
    piece.nodes_a = run_nodes[source];
    piece.nodes_b = run_nodes[i];
    if (reversed[i] != reversed[source]) std::reverse(piece.nodes_b.begin(), piece.nodes_b.end());
    result.shared.push_back(std::move(piece));
  }
  const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  start_stage(options.progress, options.smooth ? "smoothing" : "checks", static_cast<int>(faces.size()));
  for (std::size_t f = 0; f < faces.size(); ++f) {
    BlockMesh mesh = meshers[f]->finish();
    step(options.progress);
    // The assignment and placement were done for all faces at once.
    mesh.stage_seconds.insert(mesh.stage_seconds.begin(), {{"intervals", f == 0 ? seconds(t0, t1) : 0.0},
                                                           {"placement", f == 0 ? seconds(t1, t2) : 0.0}});
    mesh.notes.insert(mesh.notes.begin(), relaxed[f].begin(), relaxed[f].end());
    if (f == 0) mesh.notes.insert(mesh.notes.end(), intervals.notes.begin(), intervals.notes.end());
    meshers[f]->flag_if_coarse(mesh);
    result.faces.push_back(std::move(mesh));
  }
  // Only interior nodes are ever removed: the shared boundary nodes stay, renumbered.
  for (SharedPiece& piece : result.shared) {
    for (int& n : piece.nodes_a) n = meshers[piece.face_a]->renumbered(n);
    for (int& n : piece.nodes_b) n = meshers[piece.face_b]->renumbered(n);
  }
  return result;
}

}  // namespace mm
