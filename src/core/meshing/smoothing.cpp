#include "meshing/smoothing.hpp"

#include <lbfgs.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>

namespace mm {
namespace {

// A node whose move is below this fraction of its mean edge length does not
// wake its neighbours: the sweeps stop once nothing moves noticeably.
constexpr double kStillFraction = 2e-2;
// Boundary nodes keep this fraction of their parameter interval away from
// its ends, so they never reach a neighbour.
constexpr double kIntervalMargin = 1e-2;
constexpr int kUntanglePasses = 200;
constexpr int kUntangleStall = 3;  // passes without fewer inverted quads before reaching further
constexpr int kRelaxSweeps = 50;
// Quads at least this good are left alone: moving their nodes costs time
// and cannot help the worst element.
constexpr double kGoodEnough = 0.9;
constexpr int kWorstPasses = 5;
// The direct search is spared when the worst element is within this of the
// best that the mesh's irregular interior nodes allow (see
// irregular_node_bound): it could lift the minimum by no more.
constexpr double kBoundSlack = 1e-3;
// Quads within this much of the minimum shape count as the worst:
// their nodes' room lifts it. Once the minimum is good enough, the band
// shrinks to this fraction of its distance from 1, or it would hold nearly
// every quad and the search would cost far more than it gains.
constexpr double kWorstBand = 0.1;
// At most this many of the worst quads get the direct search per pass, so a
// large mesh with a wide band of poor quads stays cheap.
constexpr std::size_t kWorstQuads = 256;
constexpr double kStepFractions[] = {1.0, 0.5, 0.25};
// A boundary interval keeps at least this fraction of the length it had
// before smoothing, with or without a turning bound.
constexpr double kShortestChord = 0.25;
// A side at a moved node keeps at least this fraction of the quad's side
// opposite it (or its length, if already shorter): a thin strip's node
// otherwise slides onto its neighbour.
constexpr double kShortestSide = 0.01;
// The joint search round the worst quads (spread_worst): only when the
// minimum is below kSpreadBelow (a poor element: Gmsh's minimum on the
// shared faces is at most 0.72); on the kSpreadSeeds worst quads within
// kSpreadBand of it and kSpreadRings rings round them; the soft maximum of
// 1 / shape over their corners with this power (large: near the
// maximum itself, smooth enough for quasi-Newton steps); at most this many
// L-BFGS steps.
constexpr double kSpreadBelow = 0.75;
constexpr double kSpreadBand = 0.1;
constexpr std::size_t kSpreadSeeds = 32;
constexpr int kSpreadRings = 8;
constexpr int kSpreadPower = 16;  // a power of two: squarings
constexpr int kSpreadSteps = 200;
// The search stops once its least corner has not risen by kSpreadGain in
// kSpreadPatience steps.
constexpr double kSpreadGain = 1e-3;
constexpr int kSpreadPatience = 10;
// Halvings towards where a boundary node was when it breaks a bound.
constexpr int kSlideBisections = 8;
// Halvings of a step before the search gives up (it then has met a bound or
// its quasi-Newton model no longer fits).
constexpr int kSpreadLineSearch = 12;
// A corner below this shape during the search is out of bounds.
constexpr double kSpreadFloor = 1e-3;

// Signed quality of corner i of a quad: its Verdict shape, 2 x the corner
// area over the sum of its two sides' squares (1 for a right angle between
// equal sides; it falls with the angle and with the sides' ratio, so a
// needle or a collapsed side scores near 0 however square its corners), or
// the unnormalised corner area (cross product) when untangling. The scaled
// Jacobian, which smoothing used to raise, sees angles only: raising its
// minimum bought slightly better corners with needles.
template <bool kShape>
double corner_measure(const Vec2 (&v)[4], int i) {
  // From the edge to the next corner to the reversed edge from the previous one.
  const Vec2 next = v[(i + 1) % 4] - v[i], prev = -(v[i] - v[(i + 3) % 4]);
  double value = cross(next, prev);
  if (kShape) {
    const double squares = dot(next, next) + dot(prev, prev);
    value = squares > 0.0 ? 2.0 * value / squares : -1.0;  // a collapsed side is as bad as it gets
  }
  return value;
}

// The quad's quality at its worst corner.
template <bool kShape>
double quad_measure(const Vec2 (&v)[4]) {
  double worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) worst = std::min(worst, corner_measure<kShape>(v, i));
  return worst;
}

// The quality around one node: the least and the mean of its quads' values.
struct LocalQuality {
  double min = 0.0;
  double mean = 0.0;
};

// Accepts a move only if the worst quad around the node is no worse and
// either the worst or the mean got better.
bool better(const LocalQuality& candidate, const LocalQuality& current) {
  return candidate.min >= current.min && (candidate.min > current.min || candidate.mean > current.mean);
}

class Smoother {
 public:
  Smoother(const FaceModel& face, QuadMesh& mesh, const SmoothingOptions& options)
      : face_(face), mesh_(mesh), options_(options) {
    validate();
    quad_shape_.resize(mesh_.quads.size());
    for (std::size_t q = 0; q < mesh_.quads.size(); ++q) quad_shape_[q] = quad_value<true>(static_cast<int>(q), -1, {});
  }

  SmoothingResult run() {
    SmoothingResult result;
    if (mesh_.quads.empty()) return result;
    result.min_shape_before = *std::min_element(quad_shape_.begin(), quad_shape_.end());
    result.inverted_before = count_inverted();
    if (options_.joint_search_only) {
      // A mesh already good enough is left before its adjacency is even
      // built: this runs after every smoothing, most often on such a mesh.
      if (result.min_shape_before < kSpreadBelow) {
        build_adjacency();
        find_movable_nodes();
        if (spread_worst()) improve_worst();
      }
      result.min_shape_after = *std::min_element(quad_shape_.begin(), quad_shape_.end());
      result.inverted_after = count_inverted();
      return result;
    }
    build_adjacency();
    find_movable_nodes();
    if (result.inverted_before > 0) result.sweeps += untangle();
    // Some folds need a side to shrink on the way out (a high-lift slot,
    // fuzz aerofoil_3_217): untangled once more without the side floor.
    if (count_inverted() > 0) {
      floor_untangling_ = false;
      result.sweeps += untangle();
      floor_untangling_ = true;
    }
    result.sweeps += laplacian_sweeps();
    if (*std::min_element(quad_shape_.begin(), quad_shape_.end()) < irregular_node_bound() - kBoundSlack)
      improve_worst();
    result.min_shape_after = *std::min_element(quad_shape_.begin(), quad_shape_.end());
    result.inverted_after = count_inverted();
    return result;
  }

 private:
  void validate() const {
    if (!mesh_.midside.empty())
      throw std::invalid_argument("smooth_mesh: only order-1 meshes are smoothed; add mid-side nodes afterwards");
    const int nodes = static_cast<int>(mesh_.nodes.size());
    if (static_cast<int>(mesh_.places.size()) != nodes)
      throw std::invalid_argument("smooth_mesh: " + std::to_string(mesh_.places.size()) + " node places for " +
                                  std::to_string(nodes) + " nodes");
    for (std::size_t q = 0; q < mesh_.quads.size(); ++q)
      for (int n : mesh_.quads[q])
        if (n < 0 || n >= nodes)
          throw std::invalid_argument("smooth_mesh: quad " + std::to_string(q) + " refers to node " +
                                      std::to_string(n) + " of " + std::to_string(nodes));
    for (int n = 0; n < nodes; ++n) {
      const NodePlace& place = mesh_.places[n];
      if (place.loop < 0) continue;
      if (place.loop >= static_cast<int>(face_.loops.size()) || place.edge < 0 ||
          place.edge >= static_cast<int>(face_.loops[place.loop].edges.size()))
        throw std::invalid_argument("smooth_mesh: node " + std::to_string(n) + " lies on loop " +
                                    std::to_string(place.loop) + " edge " + std::to_string(place.edge) +
                                    ", which the face does not have");
    }
  }

  // Node -> (quad, corner) pairs in flat arrays.
  void build_adjacency() {
    const std::size_t nodes = mesh_.nodes.size();
    offsets_.assign(nodes + 1, 0);
    for (const auto& quad : mesh_.quads)
      for (int n : quad) ++offsets_[n + 1];
    for (std::size_t n = 0; n < nodes; ++n) offsets_[n + 1] += offsets_[n];
    corners_.resize(offsets_[nodes]);
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t q = 0; q < mesh_.quads.size(); ++q)
      for (int i = 0; i < 4; ++i) corners_[fill[mesh_.quads[q][i]]++] = static_cast<int>(q) * 4 + i;
  }

  // Interior nodes move freely; boundary nodes slide between their two
  // boundary neighbours (along the loop: quads are counter-clockwise with the
  // material on the left, so a quad's boundary side runs with the loop).
  void find_movable_nodes() {
    const int nodes = static_cast<int>(mesh_.nodes.size());
    movable_.assign(nodes, 0);
    behind_.assign(nodes, -1);
    ahead_.assign(nodes, -1);
    first_chord_behind_.assign(nodes, 0.0);
    first_chord_ahead_.assign(nodes, 0.0);
    std::vector<char> fixed(nodes, 0);
    for (int n : options_.fixed)
      if (n >= 0 && n < nodes) fixed[n] = 1;
    std::vector<int> nexts, prevs;  // the nodes after and before n in its quads
    for (int n = 0; n < nodes; ++n) {
      const NodePlace& place = mesh_.places[n];
      if (offsets_[n] == offsets_[n + 1] || place.face_corner || fixed[n]) continue;
      // A side n -> next is on the mesh boundary when no quad runs it
      // next -> n, that is when next is no quad's corner before n; and
      // prev -> n when prev is no quad's corner after n.
      nexts.clear(), prevs.clear();
      for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
        const auto& quad = mesh_.quads[corners_[k] / 4];
        nexts.push_back(quad[(corners_[k] % 4 + 1) % 4]);
        prevs.push_back(quad[(corners_[k] % 4 + 3) % 4]);
      }
      const auto among = [](int node, const std::vector<int>& nodes) {
        return std::find(nodes.begin(), nodes.end(), node) != nodes.end();
      };
      int behind_count = 0, ahead_count = 0;
      for (std::size_t k = 0; k < nexts.size(); ++k) {
        if (!among(nexts[k], prevs)) ahead_[n] = nexts[k], ++ahead_count;
        if (!among(prevs[k], nexts)) behind_[n] = prevs[k], ++behind_count;
      }
      if (place.loop < 0) {
        if (ahead_count > 0)
          throw std::invalid_argument("smooth_mesh: node " + std::to_string(n) +
                                      " is marked interior but lies on the mesh boundary");
        movable_[n] = 1;
        continue;
      }
      if (ahead_count == 0)
        throw std::invalid_argument("smooth_mesh: node " + std::to_string(n) + " is marked on loop " +
                                    std::to_string(place.loop) + " but lies inside the mesh");
      // A node where the boundary touches itself stays put: sliding it has no single interval.
      if (ahead_count != 1 || behind_count != 1) continue;
      if (mesh_.places[ahead_[n]].loop != place.loop || mesh_.places[behind_[n]].loop != place.loop)
        throw std::invalid_argument("smooth_mesh: boundary node " + std::to_string(n) +
                                    " has a boundary neighbour on another loop");
      movable_[n] = 1;
      first_chord_behind_[n] = distance(mesh_.nodes[n], mesh_.nodes[behind_[n]]);
      first_chord_ahead_[n] = distance(mesh_.nodes[n], mesh_.nodes[ahead_[n]]);
    }
  }

  // The quad's value with node `moved` put at p (moved = -1: as it is).
  template <bool kShape>
  double quad_value(int q, int moved, Vec2 p) const {
    const auto& quad = mesh_.quads[q];
    Vec2 v[4];
    for (int i = 0; i < 4; ++i) v[i] = quad[i] == moved ? p : mesh_.nodes[quad[i]];
    return quad_measure<kShape>(v);
  }

  template <bool kShape>
  LocalQuality local_quality(int n, Vec2 p) const {
    LocalQuality local{std::numeric_limits<double>::infinity(), 0.0};
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
      const double value = quad_value<kShape>(corners_[k] / 4, n, p);
      local.min = std::min(local.min, value);
      local.mean += value;
    }
    local.mean /= offsets_[n + 1] - offsets_[n];
    return local;
  }

  // The quads around a node, the node's corner first: the corner opposite
  // it does not move with it, so it is valued once per search. The floors
  // are the least squared lengths of the sides from the node to v[1], v[3].
  struct StarQuad {
    Vec2 v[4];
    double opposite;
    double floor_next, floor_prev;
  };

  template <bool kShape>
  void gather_star(int n, std::vector<StarQuad>& star) const {
    star.resize(offsets_[n + 1] - offsets_[n]);
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
      const auto& quad = mesh_.quads[corners_[k] / 4];
      const int at = corners_[k] % 4;
      StarQuad& s = star[k - offsets_[n]];
      for (int i = 0; i < 4; ++i) s.v[i] = mesh_.nodes[quad[(at + i) % 4]];
      s.opposite = corner_measure<kShape>(s.v, 2);
      const auto floor = [&](Vec2 side, Vec2 opposite_side) {
        return std::min(dot(side, side), kShortestSide * kShortestSide * dot(opposite_side, opposite_side));
      };
      s.floor_next = floor(s.v[1] - s.v[0], s.v[2] - s.v[3]);
      s.floor_prev = floor(s.v[3] - s.v[0], s.v[2] - s.v[1]);
    }
  }

  // Whether putting the star's node at p is better() than `current`: the
  // same values as local_quality, without going on once one corner falls
  // below current.min (then it is not). Most candidates of the searches fail
  // so, most often at the moved corner itself, which is valued first.
  template <bool kShape>
  bool improves(std::vector<StarQuad>& star, Vec2 p, const LocalQuality& current, LocalQuality& candidate) const {
    candidate = LocalQuality{std::numeric_limits<double>::infinity(), 0.0};
    for (StarQuad& s : star) {
      s.v[0] = p;
      const Vec2 next_side = s.v[1] - p, prev_side = s.v[3] - p;
      if ((kShape || floor_untangling_) &&
          (dot(next_side, next_side) < s.floor_next || dot(prev_side, prev_side) < s.floor_prev))
        return false;
      const double at = corner_measure<kShape>(s.v, 0);
      if (at < current.min) return false;
      const double next = corner_measure<kShape>(s.v, 1);
      if (next < current.min) return false;
      const double prev = corner_measure<kShape>(s.v, 3);
      const double value = std::min(std::min(s.opposite, at), std::min(next, prev));
      if (value < current.min) return false;
      candidate.min = std::min(candidate.min, value);
      candidate.mean += value;
    }
    candidate.mean /= static_cast<double>(star.size());
    return better(candidate, current);
  }

  LocalQuality cached_quality(int n) const {
    LocalQuality local{std::numeric_limits<double>::infinity(), 0.0};
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
      local.min = std::min(local.min, quad_shape_[corners_[k] / 4]);
      local.mean += quad_shape_[corners_[k] / 4];
    }
    local.mean /= offsets_[n + 1] - offsets_[n];
    return local;
  }

  int count_inverted() const {
    return static_cast<int>(std::count_if(quad_shape_.begin(), quad_shape_.end(), [](double sj) { return sj <= 0.0; }));
  }

  double mean_squared_side(int n) const {
    double sum = 0.0;
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
      const auto& quad = mesh_.quads[corners_[k] / 4];
      const Vec2 side = mesh_.nodes[quad[(corners_[k] % 4 + 1) % 4]] - mesh_.nodes[n];
      sum += dot(side, side);
    }
    return sum / (offsets_[n + 1] - offsets_[n]);
  }

  // Two smoothing targets: the mean of the points that would make each quad a
  // parallelogram (keeps graded and regular grids as they are), and the mean
  // of the side neighbours (plain Laplacian, better at irregular nodes).
  void targets(int n, Vec2& parallelogram, Vec2& centroid) const {
    parallelogram = centroid = Vec2{};
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) {
      const auto& quad = mesh_.quads[corners_[k] / 4];
      const int i = corners_[k] % 4;
      const Vec2 next = mesh_.nodes[quad[(i + 1) % 4]], prev = mesh_.nodes[quad[(i + 3) % 4]];
      parallelogram = parallelogram + (next + prev - mesh_.nodes[quad[(i + 2) % 4]]);
      centroid = centroid + 0.5 * (next + prev);
    }
    const double count = offsets_[n + 1] - offsets_[n];
    parallelogram = parallelogram / count;
    centroid = centroid / count;
  }

  const BoundaryEdge& edge_of(int n) const {
    const NodePlace& place = mesh_.places[n];
    return face_.loops[place.loop].edges[place.edge];
  }

  // The parameters a boundary node may slide between: its boundary
  // neighbours' when they lie on the same edge and on the right side, else
  // the edge's own ends (the neighbour is a vertex, or across a closed
  // curve's seam).
  void slide_interval(int n, double& behind, double& ahead) const {
    const NodePlace& place = mesh_.places[n];
    const BoundaryEdge& edge = edge_of(n);
    const double direction = edge.t_end >= edge.t_start ? 1.0 : -1.0;
    behind = edge.t_start;
    ahead = edge.t_end;
    const NodePlace& back = mesh_.places[behind_[n]];
    const NodePlace& front = mesh_.places[ahead_[n]];
    if (back.edge == place.edge && (place.t - back.t) * direction > 0.0) behind = back.t;
    if (front.edge == place.edge && (front.t - place.t) * direction > 0.0) ahead = front.t;
  }

  // How much the edge's tangent turns between two parameters (sampled).
  double turning(const BoundaryEdge& edge, double from, double to) const {
    if (std::holds_alternative<LineCurve>(edge.curve)) return 0.0;  // what the sampling gives a line, exactly
    // A circle's parameter is its tangent's angle: the sampling's answer to
    // rounding (its steps never reach pi), without a sine, cosine or atan2.
    if (std::holds_alternative<CircleCurve>(edge.curve)) return std::abs(to - from);
    constexpr int kSteps = 8;
    double total = 0.0;
    Vec2 last = edge_point(edge, from).d1;
    for (int k = 1; k <= kSteps; ++k) {
      const Vec2 d = edge_point(edge, from + (to - from) * k / kSteps).d1;
      if (norm(d) > 0.0 && norm(last) > 0.0) total += std::abs(signed_angle(last, d));
      last = d;
    }
    return total;
  }

  // Where boundary node n may go: with a turning bound, its two intervals
  // (to the slide interval's ends) turn by no more than the bound or than
  // they do now, and with a sagitta bound stray from their chords no
  // further than it or than they do now; without, only the shortest-chord
  // bound below holds.
  struct SlideBound {
    const BoundaryEdge* edge = nullptr;
    int node = -1;
    double behind = 0.0, ahead = 0.0;  // the slide interval
    double behind_limit = 0.0, ahead_limit = 0.0;
    double behind_sagitta = 0.0, ahead_sagitta = 0.0;
  };

  SlideBound slide_bound(int n, double behind, double ahead) const {
    SlideBound bound;
    bound.edge = &edge_of(n);
    bound.node = n;
    bound.behind = behind, bound.ahead = ahead;
    bound.behind_limit = bound.ahead_limit = std::numeric_limits<double>::infinity();
    bound.behind_sagitta = bound.ahead_sagitta = std::numeric_limits<double>::infinity();
    const double now = mesh_.places[n].t;
    if (options_.max_boundary_sagitta > 0.0) {
      bound.behind_sagitta = std::max(options_.max_boundary_sagitta, edge_sagitta(*bound.edge, behind, now));
      bound.ahead_sagitta = std::max(options_.max_boundary_sagitta, edge_sagitta(*bound.edge, now, ahead));
    }
    if (!(options_.max_boundary_turn > 0.0)) return bound;  // the shortest-chord bound alone
    bound.behind_limit = std::max(options_.max_boundary_turn, turning(*bound.edge, behind, now));
    bound.ahead_limit = std::max(options_.max_boundary_turn, turning(*bound.edge, now, ahead));
    return bound;
  }

  // Whether boundary node n may go to parameter t: no interval shrinks
  // below kShortestChord of its length before smoothing (the shape of the
  // quads alone would let a boundary interval shrink well below the size
  // asked for), nor turns past its limit.
  bool may_slide_to(const SlideBound& bound, double t) const {
    if (!bound.edge) return true;  // an interior node
    const int n = bound.node;
    const Vec2 p = edge_point(*bound.edge, t).p;
    return distance(p, mesh_.nodes[behind_[n]]) >= kShortestChord * first_chord_behind_[n] &&
           distance(p, mesh_.nodes[ahead_[n]]) >= kShortestChord * first_chord_ahead_[n] &&
           (std::isinf(bound.behind_limit) || turning(*bound.edge, bound.behind, t) <= bound.behind_limit) &&
           (std::isinf(bound.ahead_limit) || turning(*bound.edge, t, bound.ahead) <= bound.ahead_limit) &&
           (std::isinf(bound.behind_sagitta) || edge_sagitta(*bound.edge, bound.behind, t) <= bound.behind_sagitta) &&
           (std::isinf(bound.ahead_sagitta) || edge_sagitta(*bound.edge, t, bound.ahead) <= bound.ahead_sagitta);
  }

  double clamp_to_interval(double t, double behind, double ahead) const {
    const double s = std::clamp((t - behind) / (ahead - behind), kIntervalMargin, 1.0 - kIntervalMargin);
    return behind + s * (ahead - behind);
  }

  // The parameter in the interval whose curve point is nearest the target:
  // Newton on (P(t) - target) . P'(t) from the current parameter.
  double nearest_parameter(const BoundaryEdge& edge, double t, Vec2 target, double behind, double ahead) const {
    for (int iteration = 0; iteration < 6; ++iteration) {
      const CurvePoint cp = edge_point(edge, t);
      const Vec2 offset = cp.p - target;
      const double slope = dot(offset, cp.d1), speed2 = dot(cp.d1, cp.d1);
      double curvature = speed2 + dot(offset, cp.d2);
      if (curvature <= 0.0) curvature = speed2;  // away from a minimum: a Gauss-Newton step
      if (curvature <= 0.0) break;
      const double next = clamp_to_interval(t - slope / curvature, behind, ahead);
      if (next == t) break;
      t = next;
    }
    return t;
  }

  void commit(int n, Vec2 p, double t) {
    mesh_.nodes[n] = p;
    if (mesh_.places[n].loop >= 0) mesh_.places[n].t = t;
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k)
      quad_shape_[corners_[k] / 4] = quad_value<true>(corners_[k] / 4, -1, {});
  }

  // Node n moved: the movable nodes of its quads are flagged to be handled again.
  void wake_neighbours(int n, std::vector<char>& awake) const {
    for (int k = offsets_[n]; k < offsets_[n + 1]; ++k)
      for (int m : mesh_.quads[corners_[k] / 4])
        if (movable_[m]) awake[m] = 1;
  }

  // One Laplacian step of one node; true if it moved noticeably.
  bool smooth_node(int n) {
    const LocalQuality current = cached_quality(n);
    if (current.min >= kGoodEnough) return false;
    const Vec2 x = mesh_.nodes[n];
    gather_star<true>(n, star_);
    const double still2 = kStillFraction * kStillFraction * mean_squared_side(n);
    Vec2 parallelogram, centroid;
    targets(n, parallelogram, centroid);
    if (mesh_.places[n].loop < 0) {
      for (Vec2 target : {parallelogram, centroid}) {
        const Vec2 step = target - x;
        if (dot(step, step) < still2) continue;
        for (double fraction : kStepFractions) {
          const Vec2 p = x + fraction * step;
          LocalQuality candidate;
          if (!improves<true>(star_, p, current, candidate)) continue;
          commit(n, p, 0.0);
          return fraction * fraction * dot(step, step) >= still2;
        }
      }
      return false;
    }
    const BoundaryEdge& edge = edge_of(n);
    const double t = mesh_.places[n].t;
    double behind, ahead;
    slide_interval(n, behind, ahead);
    if (behind == ahead) return false;
    const SlideBound bound = slide_bound(n, behind, ahead);
    // The third target spaces the node evenly in parameter between its neighbours.
    const double candidates[] = {nearest_parameter(edge, t, parallelogram, behind, ahead),
                                 nearest_parameter(edge, t, centroid, behind, ahead), 0.5 * (behind + ahead)};
    for (double target : candidates) {
      for (double fraction : kStepFractions) {
        const double tc = t + fraction * (target - t);
        const Vec2 p = edge_point(edge, tc).p;
        const Vec2 step = p - x;
        if (dot(step, step) < still2) break;
        LocalQuality candidate;
        if (!improves<true>(star_, p, current, candidate) || !may_slide_to(bound, tc)) continue;
        commit(n, p, tc);
        return true;
      }
    }
    return false;
  }

  int laplacian_sweeps() {
    active_ = movable_;
    int sweeps = 0;
    bool any_active = true;
    while (any_active && sweeps < options_.max_sweeps) {
      ++sweeps;
      any_active = false;
      // Gauss-Seidel: a node woken further on in this sweep is handled in it.
      for (std::size_t n = 0; n < active_.size(); ++n) {
        if (!active_[n]) continue;
        active_[n] = 0;
        if (smooth_node(static_cast<int>(n))) wake_neighbours(static_cast<int>(n), active_);
      }
      any_active = std::find(active_.begin(), active_.end(), 1) != active_.end();
    }
    return sweeps;
  }

  // Direct search for the position (or parameter) that best improves the
  // quality around the node: the Laplacian targets first, then compass
  // steps that halve when none helps. True if the node moved.
  template <bool kShape>
  bool optimise_node(int n) {
    const Vec2 x0 = mesh_.nodes[n];
    const bool on_boundary = mesh_.places[n].loop >= 0;
    const double t0 = on_boundary ? mesh_.places[n].t : 0.0;
    double behind = 0.0, ahead = 0.0;
    SlideBound bound;
    if (on_boundary) {
      slide_interval(n, behind, ahead);
      if (behind == ahead) return false;
      bound = slide_bound(n, behind, ahead);
    }
    Vec2 best_p = x0;
    double best_t = t0;
    LocalQuality best = local_quality<kShape>(n, x0);
    gather_star<kShape>(n, star_);
    const auto consider = [&](Vec2 p, double t) {
      LocalQuality q;
      if (!improves<kShape>(star_, p, best, q) || !may_slide_to(bound, t)) return false;
      best = q, best_p = p, best_t = t;
      return true;
    };
    Vec2 parallelogram, centroid;
    targets(n, parallelogram, centroid);
    const BoundaryEdge* edge = on_boundary ? &edge_of(n) : nullptr;
    for (Vec2 target : {parallelogram, centroid}) {
      if (on_boundary) {
        const double t = nearest_parameter(*edge, t0, target, behind, ahead);
        consider(edge_point(*edge, t).p, t);
      } else {
        consider(target, 0.0);
      }
    }
    double step = on_boundary ? 0.25 * (ahead - behind) : 0.5 * std::sqrt(mean_squared_side(n));
    static const Vec2 kCompass[] = {
        {1, 0},  {0.7071067811865476, 0.7071067811865476},   {0, 1},  {-0.7071067811865476, 0.7071067811865476},
        {-1, 0}, {-0.7071067811865476, -0.7071067811865476}, {0, -1}, {0.7071067811865476, -0.7071067811865476}};
    for (int iteration = 0, halvings = 0; iteration < 40 && halvings < 10; ++iteration) {
      bool improved = false;
      if (on_boundary) {
        for (double sign : {1.0, -1.0}) {
          const double t = best_t + sign * step;
          if (clamp_to_interval(t, behind, ahead) != t) continue;
          improved |= consider(edge_point(*edge, t).p, t);
        }
      } else {
        const Vec2 from = best_p;
        for (Vec2 direction : kCompass) improved |= consider(from + step * direction, 0.0);
      }
      if (!improved) step *= 0.5, ++halvings;
    }
    if (best_p.x == x0.x && best_p.y == x0.y) return false;
    commit(n, best_p, best_t);
    return true;
  }

  // The nodes of the given quads and `rings` rings of quads around them, in index order.
  void region(const std::vector<int>& quads, int rings, std::vector<int>& nodes) {
    picked_.resize(mesh_.nodes.size(), 0);
    nodes.clear();
    for (int q : quads)
      for (int n : mesh_.quads[q])
        if (!picked_[n]) picked_[n] = 1, nodes.push_back(n);
    for (int ring = 0, from = 0; ring < rings; ++ring) {
      const int to = static_cast<int>(nodes.size());
      for (int k = from; k < to; ++k)
        for (int c = offsets_[nodes[k]]; c < offsets_[nodes[k] + 1]; ++c)
          for (int n : mesh_.quads[corners_[c] / 4])
            if (!picked_[n]) picked_[n] = 1, nodes.push_back(n);
      from = to;
    }
    for (int n : nodes) picked_[n] = 0;
    std::sort(nodes.begin(), nodes.end());
  }

  // Plain Laplacian relaxation of the region's interior nodes, with no
  // quality check: it unfolds what node-by-node search cannot reach. Kept
  // only if fewer quads around the region end up inverted.
  void relax_region(const std::vector<int>& nodes) {
    std::vector<int> quads;
    for (int n : nodes)
      for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) quads.push_back(corners_[k] / 4);
    std::sort(quads.begin(), quads.end());
    quads.erase(std::unique(quads.begin(), quads.end()), quads.end());
    const auto count = [&] {
      return std::count_if(quads.begin(), quads.end(), [&](int q) { return quad_shape_[q] <= 0.0; });
    };
    const auto before = count();
    std::vector<Vec2> saved;
    for (int n : nodes) saved.push_back(mesh_.nodes[n]);
    for (int sweep = 0; sweep < kRelaxSweeps; ++sweep)
      for (int n : nodes)
        if (movable_[n] && mesh_.places[n].loop < 0) {
          Vec2 parallelogram, centroid;
          targets(n, parallelogram, centroid);
          mesh_.nodes[n] = centroid;
        }
    for (int q : quads) quad_shape_[q] = quad_value<true>(q, -1, {});
    if (count() < before) return;
    for (std::size_t k = 0; k < nodes.size(); ++k) mesh_.nodes[nodes[k]] = saved[k];
    for (int q : quads) quad_shape_[q] = quad_value<true>(q, -1, {});
  }

  // Lifts the least signed corner area around the nodes of inverted quads
  // until none is inverted or nothing moves. A fold larger than one node's
  // reach needs room from further away: while the count of inverted quads
  // stalls, the worked nodes grow by rings, and at the widest a plain
  // Laplacian relaxation of the region is tried once. Returns the passes.
  int untangle() {
    std::vector<int> inverted;
    for (std::size_t q = 0; q < quad_shape_.size(); ++q)
      if (quad_shape_[q] <= 0.0) inverted.push_back(static_cast<int>(q));
    std::vector<char> listed(mesh_.quads.size(), 0);
    std::vector<int> nodes;
    std::size_t fewest = inverted.size();
    int passes = 0, rings = 0, stalled = 0;
    bool relaxed = false;
    while (!inverted.empty() && passes < kUntanglePasses) {
      ++passes;
      region(inverted, rings, nodes);
      bool progress = false;
      for (int n : nodes)
        if (movable_[n]) progress |= optimise_node<false>(n);
      // Only quads around the nodes just handled can have changed.
      std::vector<int> still;
      const auto keep = [&](int q) {
        if (quad_shape_[q] <= 0.0 && !listed[q]) listed[q] = 1, still.push_back(q);
      };
      for (int q : inverted) keep(q);
      for (int n : nodes)
        for (int k = offsets_[n]; k < offsets_[n + 1]; ++k) keep(corners_[k] / 4);
      for (int q : still) listed[q] = 0;
      inverted.swap(still);
      if (inverted.size() < fewest) {
        fewest = inverted.size(), stalled = 0;
      } else if (++stalled >= kUntangleStall || !progress) {
        if (rings < options_.untangle_rings) {
          ++rings, stalled = 0;
        } else if (!relaxed) {
          relaxed = true;
          region(inverted, 2 * options_.untangle_rings, nodes);
          relax_region(nodes);
          inverted.clear();
          for (std::size_t q = 0; q < quad_shape_.size(); ++q)
            if (quad_shape_[q] <= 0.0) inverted.push_back(static_cast<int>(q));
          fewest = inverted.size(), rings = 0, stalled = 0;
        } else {
          break;
        }
      }
    }
    return passes;
  }

  // The highest minimum shape any placement of the nodes could reach for
  // the mesh's irregular interior nodes (shape is at most the scaled
  // Jacobian, whose bound this is): v corners round a node add up to 360 degrees, so the least of them is at most 360 /
  // v degrees, or at least that for v < 4 (a valence-3 node has a corner of 120 degrees or more): sin(360 / v degrees)
  // either way.
  double irregular_node_bound() const {
    double bound = 1.0;
    for (std::size_t n = 0; n < mesh_.nodes.size(); ++n) {
      const int valence = offsets_[n + 1] - offsets_[n];
      if (mesh_.places[n].loop >= 0 || valence == 4 || valence == 0) continue;
      bound = std::min(bound, std::max(0.0, std::sin(2.0 * kPi / valence)));
    }
    return bound;
  }

  // Direct search on the nodes of the worst quads: the Laplacian steps
  // spread quality, this lifts the minimum itself. A node's search depends
  // only on where it and the nodes of its quads are, so a node that found no
  // better place is not searched again until one of those moves.
  void improve_worst() {
    std::vector<int> worst_quads, nodes;
    std::vector<char> awake(mesh_.nodes.size(), 1);
    for (int pass = 0; pass < kWorstPasses; ++pass) {
      const double worst = *std::min_element(quad_shape_.begin(), quad_shape_.end());
      const double band = worst < kGoodEnough ? kWorstBand : kWorstBand * (1.0 - worst);
      worst_quads.clear();
      for (std::size_t q = 0; q < quad_shape_.size(); ++q)
        if (quad_shape_[q] < worst + band) worst_quads.push_back(static_cast<int>(q));
      if (worst_quads.size() > kWorstQuads)
        std::nth_element(worst_quads.begin(), worst_quads.begin() + kWorstQuads, worst_quads.end(),
                         [&](int a, int b) { return quad_shape_[a] < quad_shape_[b]; });
      nodes.clear();
      for (std::size_t k = 0; k < std::min(worst_quads.size(), kWorstQuads); ++k)
        for (int n : mesh_.quads[worst_quads[k]])
          if (movable_[n]) nodes.push_back(n);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      bool moved = false;
      for (int n : nodes) {
        if (!awake[n]) continue;
        awake[n] = 0;
        if (optimise_node<true>(n)) moved = true, wake_neighbours(n, awake);
      }
      if (!moved) break;
    }
  }

  // The nodes round the worst quads moved together (boundary nodes along
  // their curves), by L-BFGS on a soft maximum of 1 / shape over
  // the corners of their quads. Node by node search stalls where a lattice
  // shears over several rows (each node's best move spoils a neighbour's
  // quad); moving them together spreads the shear over the region. Kept only
  // if the minimum rises, with every node within the bounds of the node
  // searches (sides, slide intervals, chords, turning). True if kept.
  bool spread_worst() {
    const double worst = *std::min_element(quad_shape_.begin(), quad_shape_.end());
    if (!(worst > 0.0) || worst >= kSpreadBelow) return false;
    std::vector<int> seeds, nodes;
    for (std::size_t q = 0; q < quad_shape_.size(); ++q)
      if (quad_shape_[q] < worst + kSpreadBand) seeds.push_back(static_cast<int>(q));
    if (seeds.size() > kSpreadSeeds) {
      std::nth_element(seeds.begin(), seeds.begin() + kSpreadSeeds, seeds.end(),
                       [&](int a, int b) { return quad_shape_[a] < quad_shape_[b]; });
      seeds.resize(kSpreadSeeds);
    }
    region(seeds, kSpreadRings, nodes);
    Spread spread(*this, worst);
    for (int n : nodes) {
      if (!movable_[n]) continue;
      Spread::Free node;
      node.node = n;
      node.start = mesh_.nodes[n];
      if (mesh_.places[n].loop >= 0) {
        double behind, ahead;
        slide_interval(n, behind, ahead);
        if (behind == ahead) continue;
        node.bound = slide_bound(n, behind, ahead);
        node.t_start = mesh_.places[n].t;
        if (!may_slide_to(node.bound, node.t_start)) continue;
      }
      spread.free.push_back(node);
    }
    if (spread.free.empty()) return false;
    spread.finish_setup();
    std::vector<double> x(spread.variables, 0.0);
    lbfgs_parameter_t parameters;
    lbfgs_parameter_init(&parameters);
    parameters.max_iterations = kSpreadSteps;
    parameters.linesearch = LBFGS_LINESEARCH_BACKTRACKING;
    parameters.max_linesearch = kSpreadLineSearch;
    double value = 0.0;
    lbfgs(static_cast<int>(x.size()), x.data(), &value, &Spread::evaluate, &Spread::progress, &spread, &parameters);
    bool kept = spread.put(x.data());
    if (kept) {
      for (int q : spread.quads) quad_shape_[q] = quad_value<true>(q, -1, {});
      kept = *std::min_element(quad_shape_.begin(), quad_shape_.end()) > worst;
    }
    if (!kept) {
      spread.put_back();
      for (int q : spread.quads) quad_shape_[q] = quad_value<true>(q, -1, {});
    }
    return kept;
  }

  // spread_worst's search: its nodes, variables and objective (liblbfgs's callbacks).
  struct Spread {
    struct Free {
      int node = -1;
      Vec2 start;
      SlideBound bound;      // boundary nodes: where they may slide (bound.edge set)
      double t_start = 0.0;  // and their parameter before
      double t_unit = 0.0;   // the parameter step of one variable unit
      int first = 0;         // its variable: x, y; or the parameter's
    };
    Smoother& smoother;
    std::vector<Free> free;
    std::vector<int> quads;           // the quads round the free nodes
    std::vector<double> side_floors;  // per quad side: the least squared length allowed
    std::vector<Vec2> gradient;       // per node, scratch (only the free nodes' entries are read)
    std::vector<Vec2> tangent;        // per node: a boundary node's curve derivative where it is
    int variables = 0;
    double scale;       // the minimum before: keeps the powers in range
    double length = 1;  // the unit of the variables: the mean side round the free nodes
    double least = 0;   // the least corner of the last evaluation
    double best;        // the highest least corner of the steps so far
    int best_step = 0;  // and its step

    Spread(Smoother& s, double worst) : smoother(s), scale(worst), best(worst) {}

    // The quads, their sides' floors and the variables' units.
    void finish_setup() {
      const QuadMesh& mesh = smoother.mesh_;
      double sides = 0.0;
      for (const Free& f : free) {
        sides += std::sqrt(smoother.mean_squared_side(f.node));
        for (int k = smoother.offsets_[f.node]; k < smoother.offsets_[f.node + 1]; ++k)
          quads.push_back(smoother.corners_[k] / 4);
      }
      length = sides / static_cast<double>(free.size());
      std::sort(quads.begin(), quads.end());
      quads.erase(std::unique(quads.begin(), quads.end()), quads.end());
      for (int q : quads) {
        const auto& quad = mesh.quads[q];
        for (int i = 0; i < 4; ++i) {
          const Vec2 side = mesh.nodes[quad[(i + 1) % 4]] - mesh.nodes[quad[i]];
          const Vec2 facing = mesh.nodes[quad[(i + 2) % 4]] - mesh.nodes[quad[(i + 3) % 4]];
          side_floors.push_back(std::min(dot(side, side), kShortestSide * kShortestSide * dot(facing, facing)));
        }
      }
      // Each node's move from where it was, in mean sides (a boundary node's
      // parameter step of that length), so that the search's scales and
      // liblbfgs's tolerances fit any face.
      for (Free& f : free) {
        f.first = variables;
        if (!f.bound.edge) {
          variables += 2;
          continue;
        }
        const double speed = norm(edge_point(*f.bound.edge, f.t_start).d1);
        f.t_unit = speed > 0.0 ? length / speed : 0.0;
        variables += 1;
      }
      gradient.assign(mesh.nodes.size(), Vec2{});
      tangent.assign(mesh.nodes.size(), Vec2{});
    }

    // Puts the nodes where x says; a boundary node within its slide interval,
    // and drawn back towards where it was as far as its chord and turning
    // bounds need (bisection: they hold where it was). False if a side
    // falls below its floor.
    bool put(const double* x) {
      QuadMesh& mesh = smoother.mesh_;
      const auto place = [&](const Free& f, double t) {
        const CurvePoint point = edge_point(*f.bound.edge, t);
        mesh.nodes[f.node] = point.p;
        mesh.places[f.node].t = t;
        tangent[f.node] = point.d1;
      };
      for (const Free& f : free) {
        if (!f.bound.edge) {
          mesh.nodes[f.node] = f.start + length * Vec2{x[f.first], x[f.first + 1]};
          continue;
        }
        place(f, smoother.clamp_to_interval(f.t_start + f.t_unit * x[f.first], f.bound.behind, f.bound.ahead));
      }
      for (const Free& f : free) {
        if (!f.bound.edge || smoother.may_slide_to(f.bound, mesh.places[f.node].t)) continue;
        double allowed = f.t_start, beyond = mesh.places[f.node].t;
        for (int k = 0; k < kSlideBisections; ++k) {
          const double middle = 0.5 * (allowed + beyond);
          (smoother.may_slide_to(f.bound, middle) ? allowed : beyond) = middle;
        }
        place(f, allowed);
      }
      for (std::size_t j = 0; j < quads.size(); ++j) {
        const auto& quad = mesh.quads[quads[j]];
        for (int i = 0; i < 4; ++i) {
          const Vec2 side = mesh.nodes[quad[(i + 1) % 4]] - mesh.nodes[quad[i]];
          if (dot(side, side) < side_floors[4 * j + i]) return false;
        }
      }
      return true;
    }

    void put_back() {
      for (const Free& f : free) {
        smoother.mesh_.nodes[f.node] = f.start;
        if (f.bound.edge) smoother.mesh_.places[f.node].t = f.t_start;
      }
    }

    // Stops the search (non-zero) once its least corner stalls.
    static int progress(void* instance, const double*, const double*, double, double, double, double, int, int k, int) {
      Spread& self = *static_cast<Spread*>(instance);
      if (self.least > self.best + kSpreadGain) self.best = self.least, self.best_step = k;
      return k - self.best_step >= kSpreadPatience ? 1 : 0;
    }

    // (1 / p) log sum (scale / s)^p over the corners, s their shapes, and
    // its gradient; out of bounds, a value no step accepts.
    static double evaluate(void* instance, const double* x, double* g, int n, double /*step*/) {
      Spread& self = *static_cast<Spread*>(instance);
      std::fill(g, g + n, 0.0);
      constexpr double kOut = std::numeric_limits<double>::max();
      if (!self.put(x)) return kOut;
      const QuadMesh& mesh = self.smoother.mesh_;
      double sum = 0.0, least = std::numeric_limits<double>::infinity();
      for (const Free& f : self.free) self.gradient[f.node] = Vec2{};
      for (int q : self.quads) {
        const auto& quad = mesh.quads[q];
        // Each side's length once: the two corners at its ends see it either way round.
        double side_length[4];
        for (int i = 0; i < 4; ++i) side_length[i] = norm(mesh.nodes[quad[(i + 1) % 4]] - mesh.nodes[quad[i]]);
        for (int i = 0; i < 4; ++i) {
          const int at = quad[i], next = quad[(i + 1) % 4], prev = quad[(i + 3) % 4];
          const Vec2 a = mesh.nodes[next] - mesh.nodes[at], b = mesh.nodes[prev] - mesh.nodes[at];
          const double la = side_length[i], lb = side_length[(i + 3) % 4];
          const double squares = la * la + lb * lb;
          const double s = 2.0 * cross(a, b) / squares;
          if (!(s > kSpreadFloor)) return kOut;
          least = std::min(least, s);
          double w = self.scale / s;
          for (int power = 1; power < kSpreadPower; power *= 2) w *= w;
          sum += w;
          // dw / ds = -p w / s; the log's 1 / (p sum) is applied below.
          const double dw = -kSpreadPower * w / s;
          const Vec2 ds_da = (2.0 / squares) * (Vec2{b.y, -b.x} - s * a);
          const Vec2 ds_db = (2.0 / squares) * (Vec2{-a.y, a.x} - s * b);
          self.gradient[next] = self.gradient[next] + dw * ds_da;
          self.gradient[prev] = self.gradient[prev] + dw * ds_db;
          self.gradient[at] = self.gradient[at] - dw * (ds_da + ds_db);
        }
      }
      self.least = least;
      const double factor = 1.0 / (kSpreadPower * sum);
      for (const Free& f : self.free) {
        const Vec2 d = factor * self.gradient[f.node];
        if (!f.bound.edge) {
          g[f.first] = self.length * d.x;
          g[f.first + 1] = self.length * d.y;
        } else {
          g[f.first] = f.t_unit * dot(d, self.tangent[f.node]);
        }
      }
      return std::log(sum) / kSpreadPower;
    }
  };

  const FaceModel& face_;
  QuadMesh& mesh_;
  const SmoothingOptions& options_;
  std::vector<int> offsets_;  // node n's quads are corners_[offsets_[n] .. offsets_[n + 1])
  std::vector<int> corners_;  // quad * 4 + corner index
  std::vector<char> movable_;
  std::vector<char> active_;
  std::vector<int> behind_;  // boundary neighbours against and along the loop
  std::vector<int> ahead_;
  std::vector<double> first_chord_behind_;  // boundary nodes' chords to those neighbours before smoothing
  std::vector<double> first_chord_ahead_;
  std::vector<double> quad_shape_;
  bool floor_untangling_ = true;  // the side floor holds while untangling
  std::vector<char> picked_;      // scratch flags of region()
  std::vector<StarQuad> star_;    // scratch of the node being moved
};

}  // namespace

SmoothingResult smooth_mesh(const FaceModel& face, QuadMesh& mesh, const SmoothingOptions& options) {
  return Smoother(face, mesh, options).run();
}

}  // namespace mm
