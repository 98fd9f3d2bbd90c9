#include "medial/medial_axis.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>

#include "medial/voronoi_graph.hpp"

namespace mm {
namespace {

// The discretisation only has to get the topology right: chords within this
// fraction of the face size (and 15 degrees of turning) of the curves.
constexpr double kChordTolerance = 1e-3;
// Two touching points closer than this (relative to the face size) are one:
// an edge whose two exact touching points coincide is an artefact of the
// discretisation (the bisector of two chords of one smooth curve).
constexpr double kSamePlace = 1e-6;
// A branch ending inside the face whose medial angle never reaches this is
// the trace of a curvature ripple: flow type 2 all along, no critical point.
constexpr double kRippleAngle = kPi / 4;
// Medial polylines get a point at least every this fraction of the face size.
constexpr double kPointSpacing = 1e-2;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

class Builder {
 public:
  explicit Builder(const FaceModel& face)
      : face_(face), index_(face), graph_(interior_voronoi_graph(face, kChordTolerance * face.size)) {}

  MedialAxis build() {
    keep_genuine_edges();
    build_nodes();
    add_finite_contacts();
    prune_ripple_branches();
    classify_nodes();
    trace_chains();
    return std::move(axis_);
  }

 private:
  struct Node {
    std::vector<int> edges;  // kept Voronoi edges
    int vertex = -1;         // medial vertex made of this node, if any
  };

  double size() const { return face_.size; }

  // The exact boundary place a site stands for, nearest to m.
  BoundaryPlace place_of(const Site& site, Vec2 m) const {
    const BoundarySegment& s = graph_.segments[site.segment];
    double t = s.t0;
    if (site.part == Site::kEnd) {
      t = s.t1;
    } else if (site.part == Site::kSegment) {
      const Vec2 d = s.p1 - s.p0;
      t = s.t0 + std::clamp(dot(m - s.p0, d) / dot(d, d), 0.0, 1.0) * (s.t1 - s.t0);
    }
    return nearest_on_run(index_, index_.place(s.loop, s.edge, t), m);
  }

  void keep_genuine_edges() {
    for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
      const VoronoiEdge& e = graph_.edges[i];
      const Vec2 m = 0.5 * (graph_.vertices[e.from].p + graph_.vertices[e.to].p);
      if (!same_place(place_of(e.left, m), place_of(e.right, m), kSamePlace * size())) kept_.push_back(i);
    }
  }

  // Voronoi vertices joined by kept edges; coincident ones (degenerate
  // diagrams put several vertices at one point, e.g. a square's centre) merged.
  void build_nodes() {
    UnionFind sets(graph_.vertices.size());
    for (int i : kept_) {
      const VoronoiEdge& e = graph_.edges[i];
      if (distance(graph_.vertices[e.from].p, graph_.vertices[e.to].p) <= 1e-9 * size()) sets.unite(e.from, e.to);
    }
    node_of_.assign(graph_.vertices.size(), -1);
    for (int i : kept_) {
      const VoronoiEdge& e = graph_.edges[i];
      const int a = node_id(sets.find(e.from)), b = node_id(sets.find(e.to));
      if (a == b) continue;
      edge_nodes_[i] = {a, b};
      nodes_[a].edges.push_back(i);
      nodes_[b].edges.push_back(i);
    }
  }

  int node_id(int voronoi_vertex) {
    if (node_of_[voronoi_vertex] < 0) {
      node_of_[voronoi_vertex] = static_cast<int>(nodes_.size());
      nodes_.emplace_back();
      node_vertex_.push_back(voronoi_vertex);
    }
    return node_of_[voronoi_vertex];
  }

  Vec2 node_point(int node) const { return graph_.vertices[node_vertex_[node]].p; }

  // Every convex circular arc whose centre's disc of the arc's radius is empty
  // is touched all along by that disc: a finite-contact vertex at the centre.
  void add_finite_contacts() {
    for (std::size_t li = 0; li < face_.loops.size(); ++li) {
      const auto& edges = face_.loops[li].edges;
      for (std::size_t ei = 0; ei < edges.size(); ++ei) {
        const auto* arc = std::get_if<CircleCurve>(&edges[ei].curve);
        if (!arc || curvature(edges[ei], edges[ei].t_start) <= 0) continue;
        const int existing = finite_contact_at(arc->center, arc->radius);
        if (existing >= 0) {
          add_arc_contact(axis_.vertices[existing], static_cast<int>(li), static_cast<int>(ei));
          continue;
        }
        if (!disc_is_empty(arc->center, arc->radius)) continue;
        MedialVertex v;
        v.p = arc->center;
        v.r = arc->radius;
        v.kind = MedialVertexKind::FiniteContact;
        add_arc_contact(v, static_cast<int>(li), static_cast<int>(ei));
        axis_.vertices.push_back(v);
      }
    }
  }

  int finite_contact_at(Vec2 center, double radius) const {
    for (std::size_t i = 0; i < axis_.vertices.size(); ++i) {
      const MedialVertex& v = axis_.vertices[i];
      if (v.kind == MedialVertexKind::FiniteContact && distance(v.p, center) <= 1e-9 * size() &&
          std::abs(v.r - radius) <= 1e-9 * size())
        return static_cast<int>(i);
    }
    return -1;
  }

  void add_arc_contact(MedialVertex& v, int loop, int edge) {
    const BoundaryEdge& e = face_.loops[loop].edges[edge];
    v.contact_angle = std::min(2 * kPi, v.contact_angle + std::abs(e.t_end - e.t_start));
    v.touches.push_back(index_.place(loop, edge, e.t_start));
    v.touches.push_back(index_.place(loop, edge, e.t_end));
  }

  // No boundary closer to c than r, apart from arcs of that very circle.
  bool disc_is_empty(Vec2 c, double r) const {
    for (const BoundarySegment& s : graph_.segments) {
      const BoundaryEdge& e = face_.loops[s.loop].edges[s.edge];
      if (const auto* arc = std::get_if<CircleCurve>(&e.curve)) {
        if (distance(arc->center, c) <= 1e-9 * size() && std::abs(arc->radius - r) <= 1e-9 * size()) continue;
      }
      const Vec2 d = s.p1 - s.p0;
      const double u = std::clamp(dot(c - s.p0, d) / dot(d, d), 0.0, 1.0);
      if (distance(c, s.p0 + u * d) < r * (1 - 1e-6)) {
        // A chord may cut inside a convex curve by its sag: ask the exact curve.
        const BoundaryPlace near = nearest_on_run(index_, index_.place(s.loop, s.edge, s.t0 + u * (s.t1 - s.t0)), c);
        if (distance(c, near.point) < r * (1 - 1e-9)) return false;
      }
    }
    return true;
  }

  double medial_angle_at(int voronoi_edge, Vec2 p) const {
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    const Vec2 a = place_of(e.left, p).point - p, b = place_of(e.right, p).point - p;
    return norm(a) > 0 && norm(b) > 0 ? std::abs(signed_angle(a, b)) : 0.0;
  }

  // The finite-contact vertex an axis ending at p runs into, or -1: the
  // discretised axis stops short of the arc's centre by a fraction of its radius.
  int finite_contact_near(Vec2 p) const {
    for (std::size_t i = 0; i < axis_.vertices.size(); ++i) {
      const MedialVertex& v = axis_.vertices[i];
      if (v.kind == MedialVertexKind::FiniteContact && distance(v.p, p) <= 0.25 * v.r) return static_cast<int>(i);
    }
    return -1;
  }

  // Removes branches from an end inside the face (not a corner, not a finite
  // contact) to the next junction whose medial angle stays below kRippleAngle,
  // until none is left.
  void prune_ripple_branches() {
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::size_t n = 0; n < nodes_.size(); ++n) {
        if (nodes_[n].edges.size() != 1) continue;
        const Vec2 p = node_point(static_cast<int>(n));
        if (graph_.vertices[node_vertex_[n]].r <= 1e-6 * size() || finite_contact_near(p) >= 0) continue;
        std::vector<int> branch;
        int node = static_cast<int>(n), e = nodes_[n].edges.front();
        double largest = 0.0;
        while (true) {
          branch.push_back(e);
          const auto [a, b] = edge_nodes_.at(e);
          node = a == node ? b : a;
          largest = std::max(largest, medial_angle_at(e, node_point(node)));
          if (nodes_[node].edges.size() != 2) break;
          e = nodes_[node].edges[0] == e ? nodes_[node].edges[1] : nodes_[node].edges[0];
        }
        if (largest >= kRippleAngle || nodes_[node].edges.size() == 1) continue;
        for (int f : branch) {
          const auto [a, b] = edge_nodes_.at(f);
          for (int end : {a, b}) {
            auto& list = nodes_[end].edges;
            list.erase(std::remove(list.begin(), list.end(), f), list.end());
          }
          edge_nodes_.erase(f);
        }
        changed = true;
      }
    }
  }

  // Distinct exact places touched around a node, from the sites of its edges.
  std::vector<BoundaryPlace> touches_at(int node, Vec2 p) const {
    std::vector<BoundaryPlace> places;
    const auto add = [&](const BoundaryPlace& b) {
      for (const auto& q : places)
        if (same_place(q, b, kSamePlace * size())) return;
      places.push_back(b);
    };
    for (int e : nodes_[node].edges) {
      add(place_of(graph_.edges[e].left, p));
      add(place_of(graph_.edges[e].right, p));
    }
    return places;
  }

  void classify_nodes() {
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const int degree = static_cast<int>(nodes_[n].edges.size());
      if (degree == 2) continue;
      const Vec2 p = node_point(static_cast<int>(n));
      if (degree >= 3) {
        make_junction(static_cast<int>(n), p);
      } else if (degree == 1) {
        make_end(static_cast<int>(n), p);
      }
    }
  }

  void make_junction(int node, Vec2 p) {
    MedialVertex v;
    v.kind = MedialVertexKind::Junction;
    v.touches = touches_at(node, p);
    v.p = p;
    v.r = v.touches.empty() ? 0.0 : distance(p, v.touches.front().point);
    if (v.touches.size() >= 3) {
      const Equidistant exact = equidistant(index_, p, {v.touches[0], v.touches[1], v.touches[2]});
      if (exact.converged) {
        v.p = exact.p;
        v.r = exact.r;
        for (auto& t : v.touches) t = nearest_on_run(index_, t, v.p);
      }
    }
    nodes_[node].vertex = static_cast<int>(axis_.vertices.size());
    axis_.vertices.push_back(v);
  }

  void make_end(int node, Vec2 p) {
    const std::vector<BoundaryPlace> touches = touches_at(node, p);
    const double r = graph_.vertices[node_vertex_[node]].r;
    // Flare: the axis runs into a convex corner.
    if (r <= 1e-6 * size()) {
      for (const Corner& c : face_.corners) {
        if (distance(c.position, p) <= 1e-6 * size()) {
          MedialVertex v;
          v.kind = MedialVertexKind::Flare;
          v.p = c.position;
          v.touches.push_back(index_.place(c.loop, c.vertex, face_.loops[c.loop].edges[c.vertex].t_start));
          nodes_[node].vertex = add_vertex(v);
          return;
        }
      }
    }
    // The round end of a slot: joins the finite-contact vertex of its arc.
    const int finite_contact = finite_contact_near(p);
    if (finite_contact >= 0) {
      nodes_[node].vertex = finite_contact;
      return;
    }
    nodes_[node].vertex = add_vertex(curvature_contact(touches, p, r));
  }

  int add_vertex(const MedialVertex& v) {
    axis_.vertices.push_back(v);
    return static_cast<int>(axis_.vertices.size()) - 1;
  }

  // A stretch of one edge, from parameter t0 to t1.
  struct Stretch {
    int loop, edge;
    double t0, t1;
  };

  // The boundary between places a and b along their smooth run, the shorter
  // way round (a closed curve's seam is crossed like any tangent join).
  // Empty if a corner lies between them both ways.
  std::vector<Stretch> run_between(const BoundaryPlace& a, const BoundaryPlace& b) const {
    std::vector<Stretch> best;
    double best_length = 1e300;
    const int count = index_.edge_count(a.loop);
    for (int way : {1, -1}) {
      std::vector<Stretch> path;
      int e = a.edge;
      double t = a.t;
      bool reached = false;
      for (int step = 0; step <= count && !reached; ++step) {
        const BoundaryEdge& edge = index_.edge(a.loop, e);
        const double forward = (edge.t_end - edge.t_start) * way;  // > 0: parameter grows along `way`
        const double end = way > 0 ? edge.t_end : edge.t_start;
        if (e == b.edge && b.loop == a.loop && (b.t - t) * forward >= 0) {
          path.push_back({a.loop, e, t, b.t});
          reached = true;
          break;
        }
        path.push_back({a.loop, e, t, end});
        const int vertex = way > 0 ? (e + 1) % count : e;
        if (index_.is_corner(a.loop, vertex)) break;
        e = way > 0 ? (e + 1) % count : (e + count - 1) % count;
        const BoundaryEdge& next = index_.edge(a.loop, e);
        t = way > 0 ? next.t_start : next.t_end;
      }
      if (!reached) continue;
      double length = 0.0;
      for (const Stretch& s : path) {
        const BoundaryEdge& edge = index_.edge(s.loop, s.edge);
        for (int k = 0; k < 16; ++k) {
          length += distance(evaluate(edge.curve, s.t0 + (s.t1 - s.t0) * k / 16).p,
                             evaluate(edge.curve, s.t0 + (s.t1 - s.t0) * (k + 1) / 16).p);
        }
      }
      if (length < best_length) best_length = length, best = path;
    }
    return best;
  }

  // The end of an axis between two places of one smooth curve: the centre of
  // curvature where the curvature between them peaks (an ellipse's is at
  // x = +-(a^2 - b^2)/a on its major axis).
  MedialVertex curvature_contact(const std::vector<BoundaryPlace>& touches, Vec2 p, double r) const {
    MedialVertex v;
    v.kind = MedialVertexKind::CurvatureContact;
    v.p = p;
    v.r = r;
    v.touches = touches;
    if (touches.size() < 2 || touches[0].loop != touches[1].loop) return v;
    // Coarse search along the stretch between the feet, then golden-section refinement.
    const Stretch* best = nullptr;
    double best_t = 0.0, best_k = -1e300, step = 0.0;
    const std::vector<Stretch> stretches = run_between(touches[0], touches[1]);
    for (const Stretch& s : stretches) {
      const BoundaryEdge& edge = index_.edge(s.loop, s.edge);
      for (int k = 0; k <= 32; ++k) {
        const double t = s.t0 + (s.t1 - s.t0) * k / 32;
        const double kappa = curvature(edge, t);
        if (kappa > best_k) best = &s, best_t = t, best_k = kappa, step = std::abs(s.t1 - s.t0) / 32;
      }
    }
    if (!best || best_k <= 0) return v;
    const BoundaryEdge& edge = index_.edge(best->loop, best->edge);
    const double lo = std::min(best->t0, best->t1), hi = std::max(best->t0, best->t1);
    double a = std::max(lo, best_t - step), b = std::min(hi, best_t + step);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = curvature(edge, x1), f2 = curvature(edge, x2);
    for (int i = 0; i < 200 && b - a > 1e-15 * (1 + std::abs(a)); ++i) {
      if (f1 < f2) {
        a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = curvature(edge, x2);
      } else {
        b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = curvature(edge, x1);
      }
    }
    const double t = 0.5 * (a + b);
    const BoundaryPlace at = index_.place(best->loop, best->edge, t);
    v.r = 1.0 / curvature(edge, t);
    v.p = at.point + v.r * perp(edge_tangent(edge, t));
    v.touches = {at};
    return v;
  }

  // The medial point on the bisector of an edge's two sites nearest to m.
  MedialPoint medial_point(int voronoi_edge, Vec2 m) const {
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    const Bisected b = bisect(index_, m, place_of(e.left, m), place_of(e.right, m));
    return {b.p, b.r, b.a, b.b};
  }

  // A vertex as the end point of an edge: its exact place, with the feet of the
  // edge's two sites seen from there.
  MedialPoint end_point(int vertex, int voronoi_edge) const {
    const MedialVertex& v = axis_.vertices[vertex];
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    if (v.kind == MedialVertexKind::Flare || v.kind == MedialVertexKind::CurvatureContact) {
      return {v.p, v.r, v.touches.front(), v.touches.front()};
    }
    return {v.p, v.r, place_of(e.left, v.p), place_of(e.right, v.p)};
  }

  void trace_chains() {
    std::vector<bool> used(graph_.edges.size(), false);
    // Chains start at nodes that are medial vertices; what is left are closed loops.
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (nodes_[n].vertex < 0) continue;
      for (int e : nodes_[n].edges) {
        if (!used[e]) trace(static_cast<int>(n), e, used);
      }
    }
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      for (int e : nodes_[n].edges) {
        if (!used[e]) trace(static_cast<int>(n), e, used);
      }
    }
  }

  void trace(int start, int first_edge, std::vector<bool>& used) {
    MedialEdge edge;
    edge.from = nodes_[start].vertex;
    int node = start, e = first_edge;
    while (true) {
      used[e] = true;
      const auto [a, b] = edge_nodes_.at(e);
      const int next = a == node ? b : a;
      append_voronoi_edge(edge, node, next, e);
      node = next;
      if (nodes_[node].vertex >= 0 || node == start) break;
      int following = -1;
      for (int f : nodes_[node].edges)
        if (!used[f]) following = f;
      if (following < 0) break;
      e = following;
    }
    edge.to = nodes_[node].vertex;
    if (edge.from < 0) edge.to = -1;  // a closed loop with no vertex
    orient_touches(edge);
    const int id = static_cast<int>(axis_.edges.size());
    if (edge.from >= 0) axis_.vertices[edge.from].edges.push_back(id);
    if (edge.to >= 0 && edge.to != edge.from) axis_.vertices[edge.to].edges.push_back(id);
    axis_.edges.push_back(std::move(edge));
  }

  // Points along one Voronoi edge from node `from` to node `to`, placed on the
  // exact bisector; the end node is added only where the chain ends.
  void append_voronoi_edge(MedialEdge& edge, int from, int to, int e) {
    const Vec2 a = node_point(from), b = node_point(to);
    const int pieces = std::max(1, static_cast<int>(std::ceil(distance(a, b) / (kPointSpacing * size()))));
    if (edge.points.empty()) {
      edge.points.push_back(nodes_[from].vertex >= 0 ? end_point(nodes_[from].vertex, e) : medial_point(e, a));
    }
    for (int k = 1; k < pieces; ++k) edge.points.push_back(medial_point(e, a + (double(k) / pieces) * (b - a)));
    edge.points.push_back(nodes_[to].vertex >= 0 ? end_point(nodes_[to].vertex, e) : medial_point(e, b));
  }

  // Names each point's touching places left and right of the direction of travel.
  static void orient_touches(MedialEdge& edge) {
    const auto& pts = edge.points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec2 dir = pts[std::min(i + 1, pts.size() - 1)].p - pts[i > 0 ? i - 1 : 0].p;
      MedialPoint& q = edge.points[i];
      if (cross(dir, q.left.point - q.p) < cross(dir, q.right.point - q.p)) std::swap(q.left, q.right);
    }
  }

  const FaceModel& face_;
  BoundaryIndex index_;
  VoronoiGraph graph_;
  std::vector<int> kept_;
  std::vector<int> node_of_;
  std::vector<int> node_vertex_;
  std::vector<Node> nodes_;
  std::map<int, std::pair<int, int>> edge_nodes_;
  MedialAxis axis_;
};

}  // namespace

double medial_angle(const MedialPoint& point) {
  const Vec2 a = point.left.point - point.p, b = point.right.point - point.p;
  if (norm(a) == 0.0 || norm(b) == 0.0) return 0.0;
  return std::abs(signed_angle(a, b));
}

const char* medial_vertex_kind_name(MedialVertexKind kind) {
  switch (kind) {
    case MedialVertexKind::Junction: return "junction";
    case MedialVertexKind::Flare: return "flare";
    case MedialVertexKind::FiniteContact: return "finite_contact";
    case MedialVertexKind::CurvatureContact: return "curvature_contact";
  }
  return "junction";
}

MedialAxis compute_medial_axis(const FaceModel& face) {
  return Builder(face).build();
}

}  // namespace mm
