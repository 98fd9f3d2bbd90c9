#include "singularity/mesh_flow.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "medial/nearest.hpp"

// The bookkeeping behind the flux balance. Walk a medial point's path from
// its left touching point L to the point and on to its right touching point
// R. With the directions at L and R adjusted onto the boundary's cross (the
// inward normal on a smooth edge, the nearest arm of the corner's cross at a
// concave corner), the path turns by psi, and the cross turns by the least
// amount it can: psi - q pi/2 with q = round(psi / (pi/2)), the signed flow
// type (|q| = n, q > 0 where the disc shrinks towards the edge's end).
// Balancing the cross's turning round the sliver between two nearby medial
// points gives
//   k = (q1 - q2) + (J_L1 - J_L2) + (J_R2 - J_R1),
// where J numbers the corner arm in use (only at concave corners). Round a
// medial vertex the slivers meet in a star of radii, which gives
//   k = 2 deg - 4 - sum over its edges of their q pointing away from it
//       (+ 2 - nc at a flare; - the arm step at a concave corner touched).
// Summed over the face this telescopes to sum(2 - nc) - 4 chi, whatever the
// axis looks like, so the Poincare-Hopf invariant holds by construction.
namespace mm {

namespace {

constexpr double kHalfPi = 0.5 * kPi;

Vec2 rotated(Vec2 v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// The cross seen from one touching point.
struct Side {
  Vec2 radius;      // true direction from the boundary into the face
  Vec2 inward;      // adjusted direction from the boundary into the face
  int corner = -1;  // index into face.corners of a concave corner touched
  int arm = 0;      // the arm of that corner's cross in use
  int loop = 0;     // the place touched (smooth places)
  int edge = 0;
  double t = 0.0;
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
};

class FlowBuilder {
 public:
  FlowBuilder(const FaceModel& face, const MedialAxis& axis) : face_(face), axis_(axis), index_(face) {
    for (std::size_t i = 0; i < face.corners.size(); ++i) {
      corner_of_[{face.corners[i].loop, face.corners[i].vertex}] = static_cast<int>(i);
    }
  }

  MeshFlow build() {
    std::vector<std::vector<State>> ends(axis_.edges.size());
    flow_.points.resize(axis_.edges.size());
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const std::vector<State> states = edge_states(static_cast<int>(e));
      trace_edge(static_cast<int>(e), states);
      ends[e] = {states.front(), states.back()};
      for (const State& s : states) {
        flow_.points[e].push_back(
            {s.q, std::abs(s.psi - s.q * kHalfPi), s.l.corner, s.l.arm, s.r_side.corner, s.r_side.arm});
      }
    }
    for (std::size_t v = 0; v < axis_.vertices.size(); ++v) add_vertex(static_cast<int>(v), ends);
    return std::move(flow_);
  }

 private:
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
    } else {
      s.radius = s.inward = perp(edge_tangent(face_.loops[place.loop].edges[place.edge], place.t));
    }
    return s;
  }

  // The arm number a side stands for at the given concave corner: its own arm
  // there, or, on a smooth edge next to the corner, the arm along that edge's
  // normal (1 on the outgoing edge, nc - 1 on the incoming one).
  std::optional<int> arm_at(const Side& s, int corner) const {
    if (s.corner == corner) return s.arm;
    if (s.corner >= 0) return std::nullopt;
    const Corner& c = face_.corners[corner];
    const int count = static_cast<int>(face_.loops[c.loop].edges.size());
    if (s.loop != c.loop) return std::nullopt;
    const bool outgoing = s.edge == c.vertex, incoming = (s.edge + 1) % count == c.vertex;
    if (outgoing && incoming) {  // a loop of one edge: the nearer end decides
      const BoundaryEdge& e = face_.loops[c.loop].edges[s.edge];
      return std::abs(s.t - e.t_start) < std::abs(s.t - e.t_end) ? 1 : c.nc - 1;
    }
    if (outgoing) return 1;
    if (incoming) return c.nc - 1;
    return std::nullopt;
  }

  // The concave corner between two smooth sides on neighbouring edges, or -1.
  int concave_between(const Side& a, const Side& b) const {
    if (a.loop != b.loop || a.edge == b.edge) return -1;
    const int count = static_cast<int>(face_.loops[a.loop].edges.size());
    const int vertex = b.edge == (a.edge + 1) % count ? b.edge : a.edge == (b.edge + 1) % count ? a.edge : -1;
    if (vertex < 0) return -1;
    const auto it = corner_of_.find({a.loop, vertex});
    return it != corner_of_.end() && is_concave(it->second) ? it->second : -1;
  }

  // The concave corner whose arms a pair of sides is measured by, or -1.
  int corner_of_pair(const Side& a, const Side& b) const {
    return a.corner >= 0 ? a.corner : b.corner >= 0 ? b.corner : concave_between(a, b);
  }

  // Whether two sides touch places that meet (so one arm numbering serves both).
  bool comparable(const Side& a, const Side& b) const {
    const int corner = corner_of_pair(a, b);
    return corner < 0 ? a.corner < 0 && b.corner < 0 : arm_at(a, corner) && arm_at(b, corner);
  }

  // J2 - J1 for one side. A side sweeps a corner's arms upwards on the left
  // of the edge and downwards on the right. Where the touch jumps between
  // places that do not meet (a pruned branch left the edge there and took
  // the rest of a corner's sweep with it), the corner left is swept to its
  // last arm and the corner reached from its first.
  int arm_step(const Side& a, const Side& b, bool left) const {
    const int corner = corner_of_pair(a, b);
    if (corner < 0) return 0;
    const auto ja = arm_at(a, corner), jb = arm_at(b, corner);
    if (ja && jb) return *jb - *ja;
    const auto first_arm = [&](int c) { return left ? 1 : face_.corners[c].nc - 1; };
    const auto last_arm = [&](int c) { return left ? face_.corners[c].nc - 1 : 1; };
    int step = 0;
    if (a.corner >= 0) step += last_arm(a.corner) - a.arm;
    if (b.corner >= 0) step += b.arm - first_arm(b.corner);
    return step;
  }

  // k of the sliver between two states.
  int sliver_k(const State& a, const State& b) const {
    return (a.q - b.q) - arm_step(a.l, b.l, true) + arm_step(a.r_side, b.r_side, false);
  }

  bool same_flow(const State& a, const State& b) const {
    return a.q == b.q && comparable(a.l, b.l) && comparable(a.r_side, b.r_side) && arm_step(a.l, b.l, true) == 0 &&
           arm_step(a.r_side, b.r_side, false) == 0;
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

  std::vector<State> edge_states(int e) const {
    const auto& points = axis_.edges[e].points;
    std::vector<State> states;
    for (const MedialPoint& m : points) states.push_back(state_at(m));
    // At a vertex an end point takes its touches from the vertex's, which may
    // not continue its neighbour's (several places nearly on one circle):
    // follow the neighbour's touches on to the vertex instead, so the edge's
    // own sweep of a corner's arms stays continuous.
    for (const bool last : {false, true}) {
      if (states.size() < (last ? 2u : 3u)) continue;  // a two-point edge follows its first point
      State& end = last ? states.back() : states.front();
      const State& next = last ? states[states.size() - 2] : states[1];
      if (end.degenerate || (comparable(end.l, next.l) && comparable(end.r_side, next.r_side))) continue;
      end =
          state_at({end.p, end.r, nearest_on_run(index_, next.left, end.p), nearest_on_run(index_, next.right, end.p)});
    }
    // Start where psi is least ambiguous (farthest from +-pi), then carry on
    // both ways; degenerate points (flare and curvature-contact ends) take
    // their neighbour's flow and cross.
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
    return states;
  }

  // A state between two nearby ones on the exact axis, or nothing.
  std::optional<State> between(const State& a, const State& b) const {
    const Bisected mid = bisect(index_, 0.5 * (a.p + b.p), a.left, a.right);
    if (!mid.converged || distance(mid.p, 0.5 * (a.p + b.p)) > distance(a.p, b.p)) return std::nullopt;
    State s = state_at({mid.p, mid.r, mid.a, mid.b});
    if (s.degenerate) return std::nullopt;
    unwrap(s, a.psi);
    return s;
  }

  struct Switch {
    Vec2 p;
    double r = 0.0;
    int k = 0;
    bool flow_changed = false;
    int n_after = 0;
  };

  // The switches between two states, found by bisection down to 1e-10 of the face size.
  void locate(const State& a, const State& b, int depth, std::vector<Switch>& out) const {
    if (same_flow(a, b)) return;
    if (depth < 60 && distance(a.p, b.p) > 1e-10 * face_.size) {
      if (const auto mid = between(a, b)) {
        locate(a, *mid, depth + 1, out);
        locate(*mid, b, depth + 1, out);
        return;
      }
    }
    const int k = sliver_k(a, b);  // as fine as it gets
    out.push_back({0.5 * (a.p + b.p), 0.5 * (a.r + b.r), k, a.q != b.q, std::abs(b.q)});
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
      for (const Switch& s : switches) {
        if (const int v = vertex_at(e, s.p); v >= 0) {
          at_vertex_[v] += s.k;  // a switch right at a vertex belongs to the vertex's balance
        } else if (s.k != 0) {
          flow_.singularities.push_back(
              {s.p, s.r, s.k, s.flow_changed ? SingularitySource::FlowSwitch : SingularitySource::CornerSwitch, e, -1});
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

  void add_vertex(int v, const std::vector<std::vector<State>>& ends) {
    const MedialVertex& vertex = axis_.vertices[v];
    int degree = 0, away = 0;
    std::map<int, std::pair<int, int>> arms;  // concave corner -> lowest and highest arm used here
    const auto note_arm = [&](const Side& s) {
      if (s.corner < 0) return;
      const auto it = arms.emplace(s.corner, std::make_pair(s.arm, s.arm)).first;
      it->second = {std::min(it->second.first, s.arm), std::max(it->second.second, s.arm)};
    };
    for (int e : vertex.edges) {  // listed once even when both ends are here
      const MedialEdge& edge = axis_.edges[e];
      if (edge.from == v) {
        ++degree;
        away += ends[e].front().q;
        note_arm(ends[e].front().l);
        note_arm(ends[e].front().r_side);
      }
      if (edge.to == v) {
        ++degree;
        away -= ends[e].back().q;
        note_arm(ends[e].back().l);
        note_arm(ends[e].back().r_side);
      }
    }
    int k = 2 * degree - 4 - away + at_vertex_[v];
    for (const auto& [corner, range] : arms) k -= range.second - range.first;
    if (vertex.kind == MedialVertexKind::Flare && !vertex.touches.empty()) {
      const int corner = corner_at(vertex.touches.front());
      if (corner >= 0) k += 2 - face_.corners[corner].nc;
    }
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
  std::map<std::pair<int, int>, int> corner_of_;
  std::map<int, int> at_vertex_;  // k of switches found right at a vertex
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
  // A flow switch changes n by one; a larger jump is a critical point the
  // bisection missed.
  for (const Singularity& s : flow.singularities) {
    if (s.at == SingularitySource::FlowSwitch && std::abs(s.k) > 1) {
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
