#include "singularity/mesh_flow.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "medial/nearest.hpp"

// The bookkeeping behind the flux balance; docs/flux_balance.md proves each
// rule. Walk a medial point's path from its left touching point L to the
// point and on to its right touching point R. With the directions at L and R
// adjusted onto the boundary's cross (the inward normal on a smooth edge, the
// nearest arm of the corner's cross at a concave corner), the path turns by
// psi, and the cross turns by the least amount it can: psi - q pi/2 with
// q = round(psi / (pi/2)), the signed flow type (|q| = n, q > 0 where the
// disc shrinks towards the edge's end). Along the boundary the cross follows
// the tangent except at corners, where it turns (2 - nc) quarter turns less:
// a potential phi counts those quarter turns along each loop (part of them at
// a concave corner, by the arm in use). Balancing the cross's turning round
// any region cut out by radii gives its k from the q of the radii and the
// phi of the boundary between them:
//   sliver between two medial points a, b of an edge (section 2),
//   k = (q_a - q_b) + phi(b.L -> a.L) + phi(a.R -> b.R),
// whether the touches move continuously or jump past a pruned branch
// (section 3); round a medial vertex with d edge ends (section 4),
//   k = 2 d - 4 - sum of the ends' q pointing away
//       + sum of phi over the boundary between neighbouring ends' touches,
// which gives flares, curvature-contact ends and finite contacts (section 5).
// Summed over the face this telescopes to sum(2 - nc) - 4 chi, so the
// Poincare-Hopf invariant holds whenever every piece is counted once.
namespace mm {

namespace {

constexpr double kHalfPi = 0.5 * kPi;

// The cross seen from one touching point.
struct Side {
  Vec2 radius;      // true direction from the boundary into the face
  Vec2 inward;      // adjusted direction from the boundary into the face
  int corner = -1;  // index into face.corners of a concave corner touched
  int arm = 0;      // the arm of that corner's cross in use
  int loop = 0;     // the place touched
  int edge = 0;
  double t = 0.0;
  double s = 0.0;  // arc length along the loop from its vertex 0
  int phi = 0;     // quarter turns the cross lags the tangent by since vertex 0 (section 2)
};

struct State {
  Vec2 p;
  double r = 0.0;
  BoundaryPlace left, right;
  Side l, r_side;
  double psi_actual = 0.0;  // turning of the path along the true radii, in (-pi, pi]
  double psi = 0.0;         // turning of the adjusted path L -> p -> R, lifted
  int q = 0;
  bool degenerate = false;  // both radii vanish or coincide: take the neighbour's flow
  bool end = false;         // an end made from its vertex: its places do not span a bisector
};

// The boundary between two touches, followed forwards along the loop.
struct Piece {
  double length = 0.0;  // negative for a hair's breadth backwards
  int phi = 0;          // quarter turns the cross lags the tangent by along it
};

class FlowBuilder {
 public:
  FlowBuilder(const FaceModel& face, const MedialAxis& axis)
      : face_(face), axis_(axis), index_(face), tolerance_(1e-7 * face.size) {
    for (std::size_t i = 0; i < face.corners.size(); ++i) {
      corner_of_[{face.corners[i].loop, face.corners[i].vertex}] = static_cast<int>(i);
    }
    // Length along the loop and phi at the start of each edge; phi steps by
    // 2 - nc at each corner (section 2). Lengths only order touches and tell
    // near from far, so a coarse polyline serves (a B-spline's exact length
    // is an integral, far dearer than the rest of the stage).
    for (std::size_t l = 0; l < face.loops.size(); ++l) {
      LoopMeasure m;
      double s = 0.0;
      int phi = 0;
      for (std::size_t e = 0; e < face.loops[l].edges.size(); ++e) {
        const BoundaryEdge& edge = face.loops[l].edges[e];
        const auto it = corner_of_.find({static_cast<int>(l), static_cast<int>(e)});
        const int weight = it == corner_of_.end() ? 0 : 2 - face.corners[it->second].nc;
        if (e > 0) phi += weight;
        m.total_phi += weight;
        m.start.push_back(s);
        m.phi.push_back(phi);
        EdgeMeasure em;
        em.t = measure_parameters(edge);
        const std::vector<Vec2> points = edge_points(edge, em.t);
        em.s.push_back(0.0);
        for (std::size_t i = 1; i < points.size(); ++i)
          em.s.push_back(em.s.back() + distance(points[i - 1], points[i]));
        s += em.s.back();
        m.edges.push_back(std::move(em));
      }
      m.length = s;
      loops_.push_back(std::move(m));
    }
  }

  MeshFlow build() {
    std::vector<std::vector<State>> ends(axis_.edges.size());
    flow_.points.resize(axis_.edges.size());
    // Junctions joined by an edge of no length are one point where more
    // than three edges meet, its disc touching four or more places: the
    // edge between them has no touches of its own to balance, so the group
    // is balanced as one vertex (section 4).
    group_.resize(axis_.vertices.size());
    for (std::size_t v = 0; v < group_.size(); ++v) group_[v] = static_cast<int>(v);
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      if (!is_point(static_cast<int>(e))) continue;
      const int a = root(axis_.edges[e].from), b = root(axis_.edges[e].to);
      group_[std::max(a, b)] = std::min(a, b);
    }
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const std::vector<State> states = edge_states(static_cast<int>(e));
      if (is_point(static_cast<int>(e))) {
        flow_.runs.push_back({static_cast<int>(e), std::abs(states.front().q), {states.front().p, states.back().p}});
      } else {
        trace_edge(static_cast<int>(e), states);
      }
      ends[e] = {states.front(), states.back()};
      for (const State& s : states) {
        flow_.points[e].push_back(
            {s.q, std::abs(s.psi - s.q * kHalfPi), s.l.corner, s.l.arm, s.r_side.corner, s.r_side.arm});
      }
    }
    for (std::size_t v = 0; v < axis_.vertices.size(); ++v) {
      if (root(static_cast<int>(v)) == static_cast<int>(v)) add_vertex(static_cast<int>(v), ends);
    }
    return std::move(flow_);
  }

 private:
  // Lengths along one edge: its sample parameters from t_start to t_end and
  // the polyline's length from the start to each.
  struct EdgeMeasure {
    std::vector<double> t, s;
    double at(double parameter) const {
      const bool rising = t.back() >= t.front();
      const auto after = rising ? std::upper_bound(t.begin(), t.end(), parameter)
                                : std::upper_bound(t.begin(), t.end(), parameter, std::greater<>());
      if (after == t.begin()) return 0.0;
      if (after == t.end()) return s.back();
      const std::size_t i = static_cast<std::size_t>(after - t.begin());
      return s[i - 1] + (s[i] - s[i - 1]) * (parameter - t[i - 1]) / (t[i] - t[i - 1]);
    }
  };

  // Parameters from t_start to t_end for a coarse polyline along an edge:
  // two per B-spline knot span, a sixteenth of a turn of a circle or an
  // ellipse, 32 along any other curve.
  static std::vector<double> measure_parameters(const BoundaryEdge& edge) {
    const double lo = std::min(edge.t_start, edge.t_end), hi = std::max(edge.t_start, edge.t_end);
    const CurveType type = curve_type(edge.curve);
    std::vector<double> cuts{lo};
    if (type != CurveType::Line) {
      for (const double b : breakpoints(edge.curve, lo, hi)) cuts.push_back(b);
    }
    cuts.push_back(hi);
    const int per_piece = type == CurveType::Line      ? 1
                          : type == CurveType::BSpline ? 2
                          : type == CurveType::Other   ? 32
                                                       : 0;
    std::vector<double> t;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const int n =
          per_piece > 0 ? per_piece : std::max(1, static_cast<int>(std::ceil((cuts[i + 1] - cuts[i]) / (kPi / 8))));
      for (int k = 0; k < n; ++k) t.push_back(cuts[i] + (cuts[i + 1] - cuts[i]) * k / n);
    }
    t.push_back(hi);
    if (edge.t_end < edge.t_start) std::reverse(t.begin(), t.end());
    return t;
  }

  struct LoopMeasure {
    std::vector<double> start;  // length along the loop at the start of each edge
    std::vector<EdgeMeasure> edges;
    std::vector<int> phi;  // phi along each edge
    double length = 0.0;
    int total_phi = 0;  // sum of 2 - nc over the loop's corners
  };

  // An edge of no length between two junctions.
  bool is_point(int e) const {
    const MedialEdge& edge = axis_.edges[e];
    if (edge.from < 0 || edge.to < 0 || edge.from == edge.to) return false;
    const auto junction = [&](int v) { return axis_.vertices[v].kind == MedialVertexKind::Junction; };
    if (!junction(edge.from) || !junction(edge.to)) return false;
    for (const MedialPoint& m : edge.points) {
      if (distance(m.p, edge.points.front().p) > 1e-9 * face_.size) return false;
    }
    return true;
  }

  int root(int v) const {
    while (group_[v] != v) v = group_[v];
    return v;
  }

  bool is_concave(int corner) const {
    return corner >= 0 && index_.is_reflex(face_.corners[corner].loop, face_.corners[corner].vertex);
  }

  int corner_at(const BoundaryPlace& place) const {
    if (place.corner < 0) return -1;
    const auto it = corner_of_.find({place.loop, place.corner});
    return it == corner_of_.end() ? -1 : it->second;
  }

  // Direction of the corner's outgoing edge: arm 0 of its cross; arm j lies
  // j * angle / nc further round into the face.
  Vec2 outgoing(int corner) const {
    const Corner& c = face_.corners[corner];
    const BoundaryEdge& e = face_.loops[c.loop].edges[c.vertex];
    return edge_tangent(e, e.t_start);
  }

  Side side_at(const BoundaryPlace& place, Vec2 p) const {
    Side s;
    s.loop = place.loop;
    s.edge = place.edge;
    s.t = place.t;
    const LoopMeasure& m = loops_[place.loop];
    const int corner = corner_at(place);
    if (is_concave(corner) && distance(p, place.point) > 0.0) {
      const Corner& c = face_.corners[corner];
      const Vec2 out = outgoing(corner);
      double polar = signed_angle(out, p - place.point);
      if (polar < 0) polar += 2 * kPi;
      const double spacing = c.angle / c.nc;
      s.corner = corner;
      s.arm = std::clamp(static_cast<int>(std::lround(polar / spacing)), 0, c.nc);
      s.radius = normalized(p - place.point);
      s.inward = rotated(out, s.arm * spacing);
      // Arm nc - 1 stands for the incoming edge, arm 1 for the outgoing one.
      s.s = m.start[c.vertex];
      s.phi = m.phi[c.vertex] + s.arm - 1;
    } else {
      s.radius = s.inward = perp(edge_tangent(face_.loops[place.loop].edges[place.edge], place.t));
      s.s = m.start[place.edge] + m.edges[place.edge].at(place.t);
      s.phi = m.phi[place.edge];
    }
    // The end of the loop is its start: one phi for one place.
    if (s.s > m.length - tolerance_) {
      s.s -= m.length;
      s.phi -= m.total_phi;
    }
    return s;
  }

  // The boundary from a to b the shorter way round the loop (a negative
  // length runs backwards). Along an edge touches move on continuously or
  // jump past a pruned branch, far less than half a loop; the shorter way
  // also absorbs the small back-and-forth of touches where the medial
  // points' places along the axis are ill-conditioned (sides nearly
  // parallel), so phi differences telescope whatever the points.
  std::optional<Piece> piece(const Side& a, const Side& b) const {
    if (a.loop != b.loop) return std::nullopt;
    const LoopMeasure& m = loops_[a.loop];
    Piece p{b.s - a.s, b.phi - a.phi};
    if (p.length < -0.5 * m.length) {
      p.length += m.length;
      p.phi += m.total_phi;
    } else if (p.length > 0.5 * m.length) {
      p.length -= m.length;
      p.phi -= m.total_phi;
    }
    return p;
  }

  // The boundary from a forwards to b, a touch a hair's breadth behind
  // taken as the same place.
  std::optional<Piece> ahead(const Side& a, const Side& b) const {
    if (a.loop != b.loop) return std::nullopt;
    const LoopMeasure& m = loops_[a.loop];
    Piece p{b.s - a.s, b.phi - a.phi};
    if (p.length < -tolerance_) {
      p.length += m.length;
      p.phi += m.total_phi;
    }
    return p;
  }

  // The boundary pieces of the sliver between states a and b (a first along
  // the edge): on the left from b's touch forwards to a's, on the right from
  // a's to b's (section 2).
  std::pair<std::optional<Piece>, std::optional<Piece>> sliver_pieces(const State& a, const State& b) const {
    return {piece(b.l, a.l), piece(a.r_side, b.r_side)};
  }

  int sliver_k(const State& a, const State& b) const {
    const auto [left, right] = sliver_pieces(a, b);
    return (a.q - b.q) + (left ? left->phi : 0) + (right ? right->phi : 0);
  }

  bool same_flow(const State& a, const State& b) const {
    const auto [left, right] = sliver_pieces(a, b);
    return a.q == b.q && left && right && left->phi == 0 && right->phi == 0;
  }

  State state_at(const MedialPoint& m) const {
    State s;
    s.p = m.p;
    s.r = m.r;
    s.left = m.left;
    s.right = m.right;
    s.degenerate = distance(m.left.point, m.right.point) <= 1e-9 * face_.size;
    s.l = side_at(m.left, m.p);
    s.r_side = side_at(m.right, m.p);
    s.psi_actual = signed_angle(s.l.radius, -s.r_side.radius);
    s.psi = signed_angle(s.l.inward, -s.r_side.inward);
    return s;
  }

  // The adjusted turning is known up to 2 pi. Each adjustment is under 60
  // degrees, so it lies within pi of the true turning, which says which way
  // the disc shrinks; only where the radii (nearly) coincide is the true
  // turning itself ambiguous, and a neighbour's value decides.
  static void unwrap(State& s, double neighbour) {
    const double reference = std::abs(s.psi_actual) < kPi - 1e-3 ? s.psi_actual : neighbour;
    s.psi += 2 * kPi * std::round((reference - s.psi) / (2 * kPi));
    s.q = static_cast<int>(std::lround(s.psi / kHalfPi));
  }

  // The state an edge has where it ends at a flare, from the corner itself
  // rather than from the neighbouring point, which may lie past a switch
  // (section 5). Moving away from a flare the disc touches the corner's
  // incoming edge on its left and its outgoing edge on its right.
  std::optional<State> vertex_end(int v, bool at_start) const {
    if (v < 0) return std::nullopt;
    const MedialVertex& vertex = axis_.vertices[v];
    if (vertex.touches.empty()) return std::nullopt;
    if (vertex.kind == MedialVertexKind::Flare) {
      const int corner = corner_at(vertex.touches.front());
      if (corner < 0 || is_concave(corner)) return std::nullopt;
      const Corner& c = face_.corners[corner];
      const int count = index_.edge_count(c.loop);
      const int in = (c.vertex + count - 1) % count;
      const BoundaryPlace incoming = index_.place(c.loop, in, index_.edge(c.loop, in).t_end);
      const BoundaryPlace outgoing = index_.place(c.loop, c.vertex, index_.edge(c.loop, c.vertex).t_start);
      State s =
          at_start ? state_at({vertex.p, 0.0, incoming, outgoing}) : state_at({vertex.p, 0.0, outgoing, incoming});
      s.degenerate = false;
      s.end = true;
      unwrap(s, 0.0);  // |psi| is the corner's angle, under pi
      return s;
    }
    return std::nullopt;
  }

  std::vector<State> edge_states(int e) const {
    const MedialEdge& edge = axis_.edges[e];
    std::vector<State> states;
    for (const MedialPoint& m : edge.points) states.push_back(state_at(m));
    // A point whose touches match both its neighbours' better the other way
    // round has them swapped.
    const auto gap = [](const BoundaryPlace& a, const BoundaryPlace& b) { return distance(a.point, b.point); };
    for (std::size_t i = 1; i + 1 < states.size(); ++i) {
      const auto swapped_better = [&](const State& n) {
        return gap(states[i].left, n.right) + gap(states[i].right, n.left) <
               0.5 * (gap(states[i].left, n.left) + gap(states[i].right, n.right));
      };
      if (swapped_better(states[i - 1]) && swapped_better(states[i + 1])) {
        const MedialPoint& m = edge.points[i];
        states[i] = state_at({m.p, m.r, m.right, m.left});
      }
    }
    // A point inside the edge whose two feet (nearly) meet while its
    // neighbours' are apart had one foot carried to the wrong end of a curve
    // (the seam of a closed curve): find its feet again from its neighbour's.
    for (std::size_t i = 1; i + 1 < states.size(); ++i) {
      const double least = std::min(spread(states[i - 1]), spread(states[i + 1]));
      if (spread(states[i]) >= 0.1 * least) continue;
      const State& prev = states[i - 1];
      const MedialPoint& m = edge.points[i];
      const BoundaryPlace l = nearest_on_run(index_, prev.left, m.p), r = nearest_on_run(index_, prev.right, m.p);
      const double off = std::max(std::abs(distance(l.point, m.p) - m.r), std::abs(distance(r.point, m.p) - m.r));
      if (off <= 1e-6 * face_.size) states[i] = state_at({m.p, m.r, l, r});
    }
    // Flares make their ends' states themselves.
    const std::optional<State> first = states.size() > 1 ? vertex_end(edge.from, true) : std::nullopt;
    const std::optional<State> last = states.size() > 1 ? vertex_end(edge.to, false) : std::nullopt;
    const std::vector<State> original = states;
    const auto neighbour = [&](bool at_last) -> const State& {
      if (at_last) return original.size() == 2 && first ? *first : original[original.size() - 2];
      return original.size() == 2 && last ? *last : original[1];
    };
    for (const bool at_last : {false, true}) {
      const int v = at_last ? edge.to : edge.from;
      if (v < 0 || states.size() < 2) continue;
      const MedialVertex& vertex = axis_.vertices[v];
      State& end = at_last ? states.back() : states.front();
      if (states.size() < (at_last ? 2u : 3u)) continue;  // a two-point edge follows its first point
      const State& next = neighbour(at_last);
      if (vertex.kind == MedialVertexKind::Flare || vertex.kind == MedialVertexKind::CurvatureContact) continue;
      // The vertex's touches may not continue the neighbour's (several
      // places nearly on one circle, or a touch the vertex lacks): follow the
      // neighbour's touches on to the vertex instead, so that each end's
      // touches are those its edge's slivers reach (section 4).
      if (end.degenerate) continue;
      const auto [left, right] = at_last ? sliver_pieces(next, end) : sliver_pieces(end, next);
      const double jump = std::max(10 * distance(end.p, next.p), 1e-6 * face_.size);
      if (left && right && std::abs(left->length) <= jump && std::abs(right->length) <= jump) continue;
      end =
          state_at({end.p, end.r, nearest_on_run(index_, next.left, end.p), nearest_on_run(index_, next.right, end.p)});
    }
    // Start where psi is least ambiguous (farthest from +-pi), then carry on
    // both ways; degenerate points take their neighbour's flow and cross.
    std::size_t start = 0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (!states[i].degenerate &&
          (states[start].degenerate || std::abs(states[i].psi_actual) < std::abs(states[start].psi_actual)))
        start = i;
    }
    unwrap(states[start], 0.0);
    const auto follow = [&](std::size_t i, std::size_t from) {
      if (states[i].degenerate) {
        const State& n = states[from];
        states[i].l = n.l;
        states[i].r_side = n.r_side;
        states[i].psi = n.psi;
        states[i].psi_actual = n.psi_actual;
      }
      unwrap(states[i], states[from].psi);
    };
    for (std::size_t i = start + 1; i < states.size(); ++i) follow(i, i - 1);
    for (std::size_t i = start; i-- > 0;) follow(i, i + 1);
    if (first) states.front() = *first;
    if (last) states.back() = *last;
    return states;
  }

  // Whether a point bisected from one state's places is a medial point: no
  // boundary nearer than its radius. Between two neighbouring states only
  // the boundary the other state touches can be (past a touch jump the
  // bisector of one state's places runs on into it), so the runs through
  // the other state's places are checked, not the whole boundary.
  bool is_medial(const Bisected& mid, const State& other) const {
    if (!mid.converged) return false;
    for (const BoundaryPlace* place : {&other.left, &other.right}) {
      if (distance(nearest_on_run(index_, *place, mid.p).point, mid.p) < mid.r - 1e-9 * face_.size) return false;
    }
    return true;
  }

  static double spread(const State& s) { return distance(s.left.point, s.right.point); }

  // Whether c's touches lie on the boundary between a's and b's, as the
  // touches of a medial point between them do (section 2).
  bool touches_between(const State& a, const State& c, const State& b) const {
    const auto within = [&](const Side& from, const Side& via, const Side& to) {
      const auto whole = piece(from, to), first = piece(from, via), second = piece(via, to);
      return whole && first && second &&
             std::abs(first->length) + std::abs(second->length) <= std::abs(whole->length) + 1e-3 * face_.size;
    };
    return within(b.l, c.l, a.l) && within(a.r_side, c.r_side, b.r_side);
  }

  // A state between two nearby ones on the exact axis, or nothing. Past a
  // touch jump the bisector of one state's places is no longer medial: try
  // the other's. Near a curvature contact, or the seam of a closed curve, a
  // foot may run to the wrong end of the curve from the middle: try nearer
  // either state.
  std::optional<State> between(const State& a, const State& b) const {
    for (const double f : {0.5, 0.25, 0.75, 0.1, 0.9}) {
      const Vec2 m = a.p + f * (b.p - a.p);
      for (const State* from : {&a, &b}) {
        if (from->end || from->degenerate) continue;
        const Bisected mid = bisect(index_, m, from->left, from->right);
        if (!is_medial(mid, from == &a ? b : a) || distance(mid.p, m) > distance(a.p, b.p)) continue;
        State s = state_at({mid.p, mid.r, mid.a, mid.b});
        if (s.degenerate || !touches_between(a, s, b)) continue;
        unwrap(s, from->psi);
        return s;
      }
    }
    return std::nullopt;
  }

  struct Switch {
    Vec2 p;
    double r = 0.0;
    int k = 0;
    bool flow_changed = false;
    bool jump = false;  // the touches jump: a pruned branch left the edge here
    int n_after = 0;
  };

  // The switches between two states, found by bisection down to 1e-10 of
  // the face size. Where the flow changes but the sliver's k is 0 (q and a
  // concave corner's arm change together, or a +1 and a -1 lie close), only
  // the runs' split is wanted, and 1e-7 of the face places it well enough.
  void locate(const State& a, const State& b, int depth, std::vector<Switch>& out) const {
    if (same_flow(a, b)) return;
    const double finest = (sliver_k(a, b) == 0 ? 1e-7 : 1e-10) * face_.size;
    if (depth < 60 && distance(a.p, b.p) > finest) {
      if (const auto mid = between(a, b)) {
        locate(a, *mid, depth + 1, out);
        locate(*mid, b, depth + 1, out);
        return;
      }
    }
    // As fine as it gets. The touches move on continuously (a flow or
    // corner switch), or one of them jumps the way touches move, past a
    // pruned branch (section 3). Otherwise the axis's points are out of
    // order there: a unit k is still where the flow switches (the pieces
    // telescope), a larger one is an axis that folds back on itself.
    const auto [left, right] = sliver_pieces(a, b);
    const int k = (a.q - b.q) + (left ? left->phi : 0) + (right ? right->phi : 0);
    const double jump = std::max(1e3 * distance(a.p, b.p), 1e-6 * face_.size);
    const auto steady = [&](const std::optional<Piece>& p) { return p && std::abs(p->length) <= jump; };
    const auto onwards = [&](const std::optional<Piece>& p) { return p && p->length > jump; };
    const bool jumps = (onwards(left) && steady(right)) || (steady(left) && onwards(right));
    if (std::abs(k) > 1 && !jumps && !(steady(left) && steady(right))) {
      std::ostringstream message;
      message << "mesh flow: the medial axis folds back at (" << a.p.x << ", " << a.p.y
              << "): its touching points run backwards or jump on both sides";
      throw SelfCheckError(face_.name, message.str());
    }
    out.push_back({0.5 * (a.p + b.p), 0.5 * (a.r + b.r), k, a.q != b.q, jumps, std::abs(b.q)});
  }

  // The end vertex of edge e that p coincides with, or -1.
  int vertex_at(int e, Vec2 p) const {
    for (int v : {axis_.edges[e].from, axis_.edges[e].to}) {
      if (v >= 0 && distance(axis_.vertices[v].p, p) <= 1e-7 * face_.size) return v;
    }
    return -1;
  }

  void trace_edge(int e, const std::vector<State>& states) {
    FlowRun run{e, std::abs(states.front().q), {states.front().p}};
    const bool closed = axis_.edges[e].from < 0;
    for (std::size_t i = 1; i < states.size(); ++i) {
      std::vector<Switch> switches;
      locate(states[i - 1], states[i], 0, switches);
      // A switch between a flare and the edge's first point beside it, no
      // further from the corner than the axis's points resolve, is the flare's.
      const int flare = i == 1 && states.front().end                  ? axis_.edges[e].from
                        : i + 1 == states.size() && states.back().end ? axis_.edges[e].to
                                                                      : -1;
      for (const Switch& s : switches) {
        if (const int v = flare >= 0 ? flare : vertex_at(e, s.p); v >= 0) {
          at_vertex_[v] += s.k;  // a switch right at a vertex belongs to the vertex's balance
        } else if (s.k != 0) {
          // A jump stands for the junction of the branch pruned there.
          const SingularitySource source = s.jump           ? SingularitySource::Junction
                                           : s.flow_changed ? SingularitySource::FlowSwitch
                                                            : SingularitySource::CornerSwitch;
          flow_.singularities.push_back({s.p, s.r, s.k, source, e, -1});
        }
        if (s.n_after != run.n) {
          run.points.push_back(s.p);
          flow_.runs.push_back(run);
          run = {e, s.n_after, {s.p}};
        }
      }
      run.points.push_back(states[i].p);
    }
    flow_.runs.push_back(run);
    if (closed && states.size() > 1) {
      // A loop with no vertex closes on itself: balance its last and first points.
      State first = states.front();
      unwrap(first, states.back().psi);
      const int k = sliver_k(states.back(), first);
      if (k != 0) flow_.singularities.push_back({first.p, first.r, k, SingularitySource::FlowSwitch, e, -1});
    }
  }

  // An edge's end at a vertex, seen travelling away from the vertex.
  struct End {
    Side left, right;
    int q = 0;
    double direction = 0.0;  // the angle at which the edge leaves the vertex
  };

  // The angle at which edge e leaves its first (or last) vertex.
  double leaving(int e, bool at_start) const {
    const std::vector<MedialPoint>& points = axis_.edges[e].points;
    const Vec2 end = at_start ? points.front().p : points.back().p;
    for (std::size_t i = 1; i < points.size(); ++i) {
      const Vec2 d = (at_start ? points[i].p : points[points.size() - 1 - i].p) - end;
      if (norm(d) > 1e-9 * face_.size) return std::atan2(d.y, d.x);
    }
    return 0.0;
  }

  // The phi of the boundary between neighbouring ends round a vertex
  // (section 4). Going round the vertex anticlockwise, each end's left touch
  // comes just before the next end's right touch: the gap runs forwards from
  // the one to the other, a point at a junction (the shorter way round takes
  // up a hair's breadth either way), an arc of the circle at a finite contact.
  int gaps_phi(std::vector<End> away, bool finite_contact) const {
    std::sort(away.begin(), away.end(), [](const End& a, const End& b) { return a.direction < b.direction; });
    int phi = 0;
    for (std::size_t i = 0; i < away.size(); ++i) {
      const Side& left = away[i].left;
      const Side& right = away[(i + 1) % away.size()].right;
      // Touches on two loops have no boundary between them and add nothing;
      // were that wrong, the face's sum of k would not balance.
      const auto p = finite_contact ? ahead(left, right) : piece(left, right);
      if (p) phi += p->phi;
    }
    return phi;
  }

  void add_vertex(int v, const std::vector<std::vector<State>>& ends) {
    const MedialVertex& vertex = axis_.vertices[v];
    std::vector<End> away;
    int k = 0;
    for (std::size_t u = 0; u < axis_.vertices.size(); ++u) {
      if (root(static_cast<int>(u)) != v) continue;
      k += at_vertex_[static_cast<int>(u)];
      for (int e : axis_.vertices[u].edges) {  // listed once even when both ends are here
        const MedialEdge& edge = axis_.edges[e];
        if (is_point(e)) continue;
        if (edge.from == int(u))
          away.push_back({ends[e].front().l, ends[e].front().r_side, ends[e].front().q, leaving(e, true)});
        if (edge.to == int(u))
          away.push_back({ends[e].back().r_side, ends[e].back().l, -ends[e].back().q, leaving(e, false)});
      }
    }
    k += 2 * static_cast<int>(away.size()) - 4;
    for (const End& end : away) k -= end.q;
    k += gaps_phi(away, vertex.kind == MedialVertexKind::FiniteContact);
    if (k == 0) return;
    const SingularitySource source = vertex.kind == MedialVertexKind::Junction ? SingularitySource::Junction
                                     : vertex.kind == MedialVertexKind::Flare  ? SingularitySource::Flare
                                     : vertex.kind == MedialVertexKind::FiniteContact
                                         ? SingularitySource::FiniteContact
                                         : SingularitySource::CurvatureContact;
    flow_.singularities.push_back({vertex.p, vertex.r, k, source, -1, v});
  }

  const FaceModel& face_;
  const MedialAxis& axis_;
  BoundaryIndex index_;
  double tolerance_;
  std::map<std::pair<int, int>, int> corner_of_;
  std::vector<LoopMeasure> loops_;
  std::map<int, int> at_vertex_;  // k of switches found right at a vertex
  std::vector<int> group_;        // the junction a junction is balanced with, by edges of no length
  MeshFlow flow_;
};

}  // namespace

const char* singularity_source_name(SingularitySource source) {
  switch (source) {
    case SingularitySource::FlowSwitch: return "flow_switch";
    case SingularitySource::CornerSwitch: return "corner_switch";
    case SingularitySource::Junction: return "junction";
    case SingularitySource::Flare: return "flare";
    case SingularitySource::FiniteContact: return "finite_contact";
    case SingularitySource::CurvatureContact: return "curvature_contact";
  }
  return "unknown";
}

int MeshFlow::sum_k() const {
  int sum = 0;
  for (const Singularity& s : singularities) sum += s.k;
  return sum;
}

MeshFlow compute_mesh_flow(const FaceModel& face, const MedialAxis& axis) {
  MeshFlow flow = FlowBuilder(face, axis).build();
  // A flow switch, where the touches move on smoothly, changes q by one
  // (section 2); a larger jump is a critical point the bisection missed.
  for (const Singularity& s : flow.singularities) {
    if ((s.at == SingularitySource::FlowSwitch || s.at == SingularitySource::CornerSwitch) && std::abs(s.k) > 1) {
      std::ostringstream check;
      check << "mesh flow: a flow switch of k = " << s.k << " at (" << s.p.x << ", " << s.p.y << ")";
      throw SelfCheckError(face.name, check.str());
    }
  }
  if (flow.sum_k() != predicted_sum_k(face)) {
    throw SelfCheckError(face.name, "mesh flow: sum of k " + std::to_string(flow.sum_k()) +
                                        " is not the Poincare-Hopf total " + std::to_string(predicted_sum_k(face)));
  }
  return flow;
}

}  // namespace mm
