#include "medial/medial_axis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "medial/nearest_boundary.hpp"
#include "medial/voronoi_graph.hpp"

namespace mm {
namespace {

// The discretisation only has to get the topology right (the exact curves
// give the geometry), and Boost.Polygon's time grows with the number of
// chords: chords within this fraction of the face size of the curves,
// turning by at most kMaxChordTurn. Where the result fails its own check,
// the axis is built again with chords finer by kChordRefinement, at most twice.
constexpr double kChordTolerance = 1e-3;
constexpr double kMaxChordTurn = 30.0 * kPi / 180.0;
constexpr int kMaxRefinements = 2;
// Two touching points closer than this (relative to the face size) are one:
// an edge whose two exact touching points coincide is an artefact of the
// discretisation (the bisector of two chords of one smooth curve).
constexpr double kSamePlace = 1e-6;
// A branch ending inside the face whose medial angle never reaches this is
// the trace of a curvature ripple: flow type 2 all along, no critical point.
constexpr double kRippleAngle = kPi / 4;
// A convex corner at least this wide is nearly flat: the chords' diagram may
// lose the end of its flare (see cut_short_flare).
constexpr double kNearlyFlat = 5 * kPi / 6;
// Medial polylines get a point at least every this fraction of the face size.
constexpr double kPointSpacing = 1e-2;

// Adds b unless a place within tolerance of it is there already.
void add_distinct(const BoundaryIndex& index, std::vector<BoundaryPlace>& places, const BoundaryPlace& b,
                  double tolerance) {
  for (const auto& q : places)
    if (same_place(index, q, b, tolerance)) return;
  places.push_back(b);
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

class Builder {
 public:
  // fineness 1 for the normal chords, larger for finer ones.
  Builder(const FaceModel& face, double fineness)
      : face_(face),
        index_(face),
        chord_tolerance_(kChordTolerance * face.size / fineness),
        graph_(interior_voronoi_graph(face, chord_tolerance_, kMaxChordTurn / fineness)) {}

  MedialAxis build() {
    index_voronoi_edges();
    add_finite_contacts();
    keep_genuine_edges();
    build_nodes();
    prune_ripple_branches();
    join_isolated_finite_contacts();
    keep_connected_axis();
    classify_nodes();
    separate_coincident_junctions();
    repair_flipped_junction_pairs();
    trace_chains();
    return std::move(axis_);
  }

 private:
  struct Node {
    std::vector<int> edges;  // kept Voronoi edges
    int vertex = -1;         // medial vertex made of this node, if any
  };

  double size() const { return face_.size; }

  // The exact boundary place a site stands for, nearest to m. Asked again
  // and again for one site and point (a node's sites once per edge there
  // and once more for its medial point, a junction's once per nearby
  // Voronoi vertex): the last few answers are kept.
  BoundaryPlace place_of(const Site& site, Vec2 m) const {
    for (const PlaceMemo& memo : place_memo_) {
      if (memo.segment == site.segment && memo.part == site.part && std::memcmp(&memo.m, &m, sizeof m) == 0)
        return memo.place;
    }
    const BoundaryPlace place = search_place_of(site, m);
    place_memo_[place_memo_next_] = {site.segment, site.part, m, place};
    place_memo_next_ = (place_memo_next_ + 1) % place_memo_.size();
    return place;
  }

  // The parameter of the point of a segment site's chord nearest to m.
  static double chord_parameter(const BoundarySegment& s, Vec2 m) {
    const Vec2 d = s.p1 - s.p0;
    return s.t0 + std::clamp(dot(m - s.p0, d) / dot(d, d), 0.0, 1.0) * (s.t1 - s.t0);
  }

  BoundaryPlace search_place_of(const Site& site, Vec2 m) const {
    const BoundarySegment& s = graph_.segments[site.segment];
    const double t = site.part == Site::kEnd ? s.t1 : site.part == Site::kSegment ? chord_parameter(s, m) : s.t0;
    BoundaryPlace place = index_.place(s.loop, s.edge, t);
    place.corner_itself = site.part != Site::kSegment && place.corner >= 0;
    return nearest_on_run(index_, place, m);
  }

  // An edge is genuine if the exact bisector of its two sites' places exists
  // near its midpoint with two distinct touching points. Bisectors of two
  // chords of one smooth curve, or of an edge and a corner at its own end,
  // collapse onto a single touching point instead.
  void keep_genuine_edges() {
    const double same = kSamePlace * size();
    for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
      const VoronoiEdge& e = graph_.edges[i];
      const Vec2 m = 0.5 * (graph_.vertices[e.from].p + graph_.vertices[e.to].p);
      const BoundaryPlace a = place_of(e.left, m), b = place_of(e.right, m);
      if (same_place(index_, a, b, same)) continue;
      const Bisected exact = bisect(index_, m, a, b);
      if (exact.converged && !same_place(index_, exact.a, exact.b, same)) kept_.push_back(static_cast<int>(i));
    }
  }

  // Which interior Voronoi edges meet at each Voronoi vertex.
  void index_voronoi_edges() {
    voronoi_neighbours_.assign(graph_.vertices.size(), {});
    for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
      voronoi_neighbours_[graph_.edges[i].from].push_back(static_cast<int>(i));
      voronoi_neighbours_[graph_.edges[i].to].push_back(static_cast<int>(i));
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
      // The curve strays from its chord by up to the chord tolerance (either
      // side): near enough, ask the exact curve.
      if (distance(c, s.p0 + u * d) < r + 2 * chord_tolerance_) {
        const BoundaryPlace near = nearest_on_run(index_, index_.place(s.loop, s.edge, s.t0 + u * (s.t1 - s.t0)), c);
        if (distance(c, near.point) < r * (1 - 1e-9)) return false;
      }
    }
    return true;
  }

  double medial_angle_at(int voronoi_edge, Vec2 p) const {
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    return medial_angle({p, 0.0, place_of(e.left, p), place_of(e.right, p)});
  }

  // The finite-contact vertex the axis ending at this node runs into, or -1:
  // the nearest one whose centre lies on the exact bisector of the places the
  // end's edge touches (both at the arc's radius from it). The discretised
  // axis stops short of the centre, by up to a few radii where a notch is deep.
  int finite_contact_for(int node) const {
    const VoronoiEdge& e = graph_.edges[nodes_[node].edges.front()];
    const Vec2 p = node_point(node);
    // The places the end touches, seen from the centre: a corner stays that
    // corner (searching on from it could slide onto another arc's range).
    const BoundaryPlace left_here = place_of(e.left, p), right_here = place_of(e.right, p);
    const auto seen_from = [&](const BoundaryPlace& here, Vec2 c) {
      return here.corner >= 0 ? here : nearest_on_run(index_, here, c);
    };
    int best = -1;
    for (std::size_t i = 0; i < axis_.vertices.size(); ++i) {
      const MedialVertex& v = axis_.vertices[i];
      if (v.kind != MedialVertexKind::FiniteContact || distance(v.p, p) > 3 * v.r) continue;
      if (best >= 0 && distance(v.p, p) >= distance(axis_.vertices[best].p, p)) continue;
      const double tolerance = 1e-9 * size();
      const double left = distance(v.p, seen_from(left_here, v.p).point);
      const double right = distance(v.p, seen_from(right_here, v.p).point);
      if (std::abs(left - v.r) <= tolerance && std::abs(right - v.r) <= tolerance) best = static_cast<int>(i);
    }
    return best;
  }

  // The branch from end node n up to the first node that is not a plain
  // point of an edge: its Voronoi edges, that node, and the largest medial
  // angle along it.
  struct Branch {
    std::vector<int> edges;
    int far = -1;
    double largest = 0.0;
  };
  Branch branch_from(int n) const {
    Branch branch;
    int node = n, e = nodes_[n].edges.front();
    while (true) {
      branch.edges.push_back(e);
      const auto [a, b] = edge_nodes_.at(e);
      node = a == node ? b : a;
      branch.largest = std::max(branch.largest, medial_angle_at(e, node_point(node)));
      if (nodes_[node].edges.size() != 2) break;
      e = nodes_[node].edges[0] == e ? nodes_[node].edges[1] : nodes_[node].edges[0];
    }
    branch.far = node;
    return branch;
  }

  // Curvature contacts of end nodes already found, by node, with the edge
  // the node ended then (pruning may leave a junction as an end).
  using ContactMemo = std::map<int, std::pair<int, std::optional<MedialVertex>>>;

  // A branch from a curvature peak is medial only if the disc at the centre of
  // curvature holds no boundary (else another edge cuts it off first), and
  // only one branch ends at a peak: a stub of the diagram between two chords
  // of one curve, beside the branch into a peak, finds that peak too (a lobe
  // beside a nearly flat reflex corner, fuzz bspline_23_682). The end nearer
  // the peak's centre is its branch, unless that end's branch is a ripple,
  // pruned itself (fuzz bspline_26_602: a ripple's stub at a lobe's peak
  // took the lobe's whole branch with it). Only ends nearer than this one
  // are asked.
  bool curvature_end_is_medial(int node, ContactMemo& memo) const {
    const auto contact = [&](int n) -> const std::optional<MedialVertex>& {
      auto it = memo.find(n);
      if (it == memo.end() || it->second.first != nodes_[n].edges.front())
        it = memo.insert_or_assign(n, std::make_pair(nodes_[n].edges.front(), curvature_contact(n))).first;
      return it->second.second;
    };
    const std::optional<MedialVertex> v = contact(node);
    if (!v || !disc_is_empty(v->p, v->r)) return false;
    const double gap = distance(node_point(node), v->p);
    for (std::size_t other = 0; other < nodes_.size(); ++other) {
      if (static_cast<int>(other) == node || nodes_[other].edges.size() != 1) continue;
      if (distance(node_point(static_cast<int>(other)), v->p) >= gap) continue;
      if (branch_from(static_cast<int>(other)).largest < kRippleAngle) continue;
      const std::optional<MedialVertex>& w = contact(static_cast<int>(other));
      if (w && distance(w->p, v->p) <= kSamePlace * size()) return false;
    }
    return true;
  }

  // A branch into a nearly flat convex corner (its flare) whose last
  // Voronoi edges, beside the corner, were dropped with the chords'
  // artefacts: its end lies where the flare's bisector is at the end's
  // radius from both sides, r / sin(angle / 2) from the corner along the
  // corner's inward bisector, and its sites' places lie on the corner's two
  // edges within a quarter of the radius of it. The corner's index, or -1.
  int cut_short_flare(int node) const {
    const Vec2 p = node_point(node);
    const double r = graph_.vertices[node_vertex_[node]].r;
    const VoronoiEdge& e = graph_.edges[nodes_[node].edges.front()];
    const BoundaryPlace left = place_of(e.left, p), right = place_of(e.right, p);
    for (std::size_t i = 0; i < face_.corners.size(); ++i) {
      const Corner& c = face_.corners[i];
      if (c.angle >= kPi || c.angle < kNearlyFlat) continue;
      if (distance(left.point, c.position) > 0.25 * r || distance(right.point, c.position) > 0.25 * r) continue;
      const int count = index_.edge_count(c.loop);
      const BoundaryEdge& in = index_.edge(c.loop, (c.vertex + count - 1) % count);
      const BoundaryEdge& out = index_.edge(c.loop, c.vertex);
      const Vec2 inward = normalized(edge_tangent(out, out.t_start) - edge_tangent(in, in.t_end));
      const double along = r / std::sin(0.5 * c.angle);
      if (distance(p, c.position + along * inward) <= 0.05 * along) return static_cast<int>(i);
    }
    return -1;
  }

  // Removes branches from an end inside the face (not a corner, not a finite
  // contact) to the next junction whose medial angle stays below kRippleAngle
  // or whose end is no medial point, until none is left.
  void prune_ripple_branches() {
    ContactMemo contacts;
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::size_t n = 0; n < nodes_.size(); ++n) {
        if (nodes_[n].edges.size() != 1) continue;
        if (graph_.vertices[node_vertex_[n]].r <= 1e-6 * size() || finite_contact_for(static_cast<int>(n)) >= 0)
          continue;
        const Branch branch = branch_from(static_cast<int>(n));
        if (nodes_[branch.far].edges.size() == 1) continue;
        const double largest = branch.largest;
        if (largest >= kRippleAngle && curvature_end_is_medial(static_cast<int>(n), contacts)) continue;
        // A cut-short flare keeps its branch if the branch is more than a
        // stub beside a junction (there the junction touches the corner).
        double length = 0.0;
        for (int f : branch.edges)
          length += distance(node_point(edge_nodes_.at(f).first), node_point(edge_nodes_.at(f).second));
        if (largest >= kRippleAngle && length > 0.25 * graph_.vertices[node_vertex_[n]].r) {
          if (const int corner = cut_short_flare(static_cast<int>(n)); corner >= 0) {
            flare_of_node_[static_cast<int>(n)] = corner;
            continue;
          }
        }
        for (int f : branch.edges) {
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

  // A fillet of large radius turning little (a nearly flat convex corner)
  // has the finite contact at its centre, and from there a branch along the
  // bisector of the two sides it joins, to a junction with the rest of the
  // axis. A single chord (or a few) standing for such an arc puts the apex
  // of its Voronoi cell about twice the radius out, not at the centre, and
  // when the junction is nearer than that the diagram has no such branch:
  // the finite contact stays alone. The branch is added here, as a Voronoi
  // edge between the chords beside the arc, from the centre to the end of
  // the first kept Voronoi edge it meets going away from the arc; that node
  // becomes a junction, placed exactly by make_junction.
  void join_isolated_finite_contacts() {
    for (std::size_t vi = 0; vi < axis_.vertices.size(); ++vi) {
      const MedialVertex& v = axis_.vertices[vi];
      if (v.kind != MedialVertexKind::FiniteContact || v.contact_angle >= 2 * kPi - 1e-9) continue;
      bool joined = false;
      for (std::size_t n = 0; n < nodes_.size() && !joined; ++n)
        joined = nodes_[n].edges.size() == 1 && finite_contact_for(static_cast<int>(n)) == static_cast<int>(vi);
      if (joined) continue;
      const BoundaryPlace& arc_start = v.touches.front();
      int first = -1, last = -1;  // the arc's chords
      for (std::size_t k = 0; k < graph_.segments.size(); ++k) {
        const BoundarySegment& seg = graph_.segments[k];
        if (seg.loop != arc_start.loop || seg.edge != arc_start.edge) continue;
        if (first < 0) first = static_cast<int>(k);
        last = static_cast<int>(k);
      }
      if (first < 0) continue;
      const int before = graph_.segments[first].previous, after = graph_.segments[last].next;
      if (graph_.segments[before].edge == arc_start.edge || graph_.segments[after].edge == arc_start.edge) continue;
      const BoundaryEdge& arc = index_.edge(arc_start.loop, arc_start.edge);
      const Vec2 away = normalized(v.p - evaluate(arc.curve, 0.5 * (arc.t_start + arc.t_end)).p);
      // The first kept Voronoi edge the ray from the centre crosses, split there.
      int crossed = -1;
      double nearest = 1e300;
      for (const auto& [e, ends] : edge_nodes_) {
        const Vec2 a = node_point(ends.first), b = node_point(ends.second);
        const double denominator = cross(away, b - a);
        if (std::abs(denominator) < 1e-300) continue;
        const double u = cross(away, v.p - a) / denominator;   // along a -> b
        const double s = cross(a - v.p, b - a) / denominator;  // along the ray
        if (u < 0 || u > 1 || s <= 0 || s >= nearest) continue;
        nearest = s;
        crossed = e;
      }
      if (crossed < 0) continue;
      const int meet = split_voronoi_edge(crossed, v.p + nearest * away);
      VoronoiVertex centre;
      centre.p = v.p;
      centre.r = v.r;
      centre.sites = {Site{before, Site::kSegment}, Site{after, Site::kSegment}};
      add_voronoi_edge(add_voronoi_vertex(centre), node_vertex_[meet], centre.sites[0], centre.sites[1]);
    }
  }

  int add_voronoi_vertex(const VoronoiVertex& vertex) {
    graph_.vertices.push_back(vertex);
    voronoi_neighbours_.emplace_back();
    node_of_.push_back(-1);
    return static_cast<int>(graph_.vertices.size()) - 1;
  }

  // A kept Voronoi edge between two Voronoi vertices, with its nodes.
  void add_voronoi_edge(int from, int to, const Site& left, const Site& right) {
    graph_.edges.push_back({from, to, left, right});
    const int edge = static_cast<int>(graph_.edges.size()) - 1;
    voronoi_neighbours_[from].push_back(edge);
    voronoi_neighbours_[to].push_back(edge);
    const int a = node_id(from), b = node_id(to);
    edge_nodes_[edge] = {a, b};
    nodes_[a].edges.push_back(edge);
    nodes_[b].edges.push_back(edge);
  }

  // Splits a kept Voronoi edge at the point p on its chord; the node there.
  int split_voronoi_edge(int edge, Vec2 p) {
    const VoronoiEdge old = graph_.edges[edge];
    const auto [a, b] = edge_nodes_.at(edge);
    VoronoiVertex middle;
    middle.p = p;
    middle.r = distance(p, site_point(graph_, old.left, p));
    middle.sites = {old.left, old.right};
    const int vertex = add_voronoi_vertex(middle);
    // The old edge now ends at the new vertex; a second one goes on from it
    // to the far node (whose Voronoi vertex may stand for several merged).
    graph_.edges[edge].to = vertex;
    auto& far_end = voronoi_neighbours_[old.to];
    far_end.erase(std::remove(far_end.begin(), far_end.end(), edge), far_end.end());
    voronoi_neighbours_[vertex].push_back(edge);
    auto& far_node = nodes_[b].edges;
    far_node.erase(std::remove(far_node.begin(), far_node.end(), edge), far_node.end());
    const int node = node_id(vertex);
    edge_nodes_[edge] = {a, node};
    nodes_[node].edges.push_back(edge);
    add_voronoi_edge(vertex, node_vertex_[b], old.left, old.right);
    return node;
  }

  // The medial axis is connected, its pieces of Voronoi edges joined directly
  // or through the centre of an arc they run into. Near a curvature contact on
  // a nearly round cap the two feet stay within kSamePlace of each other over
  // a long stretch, so the test of keep_genuine_edges flips back and forth
  // there and leaves fragments beyond a gap: keep only the longest connected
  // set of edges (pieces that reach the same finite contact counting as one).
  void keep_connected_axis() {
    const std::size_t n = nodes_.size();
    UnionFind sets(n + axis_.vertices.size());
    for (const auto& [e, ends] : edge_nodes_) sets.unite(ends.first, ends.second);
    for (std::size_t i = 0; i < n; ++i) {
      if (nodes_[i].edges.size() != 1) continue;
      const int contact = finite_contact_for(static_cast<int>(i));
      if (contact >= 0) sets.unite(static_cast<int>(i), static_cast<int>(n) + contact);
    }
    std::map<int, double> length;
    for (const auto& [e, ends] : edge_nodes_)
      length[sets.find(ends.first)] += distance(node_point(ends.first), node_point(ends.second));
    if (length.size() < 2) return;
    const int keep = std::max_element(length.begin(), length.end(), [](const auto& a, const auto& b) {
                       return a.second < b.second;
                     })->first;
    for (auto it = edge_nodes_.begin(); it != edge_nodes_.end();) {
      const auto [a, b] = it->second;
      if (sets.find(a) == keep) {
        ++it;
        continue;
      }
      for (int end : {a, b}) {
        auto& list = nodes_[end].edges;
        list.erase(std::remove(list.begin(), list.end(), it->first), list.end());
      }
      it = edge_nodes_.erase(it);
    }
  }

  // Distinct exact places touched around a node, from the sites of its edges.
  std::vector<BoundaryPlace> touches_at(int node, Vec2 p) const {
    std::vector<BoundaryPlace> places;
    for (int e : nodes_[node].edges) {
      add_distinct(index_, places, place_of(graph_.edges[e].left, p), kSamePlace * size());
      add_distinct(index_, places, place_of(graph_.edges[e].right, p), kSamePlace * size());
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

  // Candidate places for a junction: the sites of every Voronoi cell around
  // the node and around Voronoi vertices close by (near-degenerate
  // junctions, where several places are almost on one circle, come as close
  // pairs of Voronoi vertices that may pair the places up wrongly).
  std::vector<BoundaryPlace> junction_candidates(int node, Vec2 p) const {
    std::vector<BoundaryPlace> places;
    for (const Site& site : junction_sites(node, p))
      add_distinct(index_, places, place_of(site, p), kSamePlace * size());
    // The sites of the node's own edges (a branch joined to a finite contact
    // brings sites no Voronoi vertex here has).
    for (int e : nodes_[node].edges) {
      add_distinct(index_, places, place_of(graph_.edges[e].left, p), kSamePlace * size());
      add_distinct(index_, places, place_of(graph_.edges[e].right, p), kSamePlace * size());
    }
    return places;
  }

  // The sites of the Voronoi vertices within reach of the node over any
  // interior Voronoi edge, kept or not.
  std::vector<Site> junction_sites(int node, Vec2 p) const {
    std::vector<int> nearby{node_vertex_[node]};
    for (std::size_t k = 0; k < nearby.size() && nearby.size() < 64; ++k) {
      for (int e : voronoi_neighbours_[nearby[k]]) {
        const VoronoiEdge& edge = graph_.edges[e];
        const int other = edge.from == nearby[k] ? edge.to : edge.from;
        if (distance(graph_.vertices[other].p, p) <= kPointSpacing * size() &&
            std::find(nearby.begin(), nearby.end(), other) == nearby.end())
          nearby.push_back(other);
      }
    }
    std::vector<Site> sites;
    for (int v : nearby) {
      for (const Site& site : graph_.vertices[v].sites) {
        if (std::none_of(sites.begin(), sites.end(),
                         [&](const Site& s) { return s.segment == site.segment && s.part == site.part; }))
          sites.push_back(site);
      }
    }
    return sites;
  }

  // The exact junction: the point equally far from three candidate places
  // with no candidate nearer, touching both places of as many of the node's
  // own edges as can be (near a point where four places are almost on one
  // circle, two nodes close together would otherwise both take the junction
  // nearer to them, and edges would meet a junction that does not touch
  // their places), then closest to where the Voronoi diagram put it.
  void make_junction(int node, Vec2 p) {
    std::optional<MedialVertex> v = exact_junction(node, p, nullptr);
    if (!v) {  // no exact solution: keep the discretised one
      v = MedialVertex{};
      v->kind = MedialVertexKind::Junction;
      v->p = p;
      v->touches = junction_candidates(node, p);
      v->r = v->touches.empty() ? 0.0 : distance(p, v->touches.front().point);
    }
    nodes_[node].vertex = static_cast<int>(axis_.vertices.size());
    axis_.vertices.push_back(*v);
  }

  // The exact junction of a node, or, given `avoid`, another one than that
  // (not at avoid's point); none if there is none.
  std::optional<MedialVertex> exact_junction(int node, Vec2 p, const MedialVertex* avoid) const {
    MedialVertex v;
    v.kind = MedialVertexKind::Junction;
    v.p = p;
    const std::vector<BoundaryPlace> candidates = junction_candidates(node, p);
    std::pair<int, double> best{1, 1e300};  // (minus own edges touched, distance)
    const auto consider = [&](const Equidistant& exact, bool held) {
      if (!exact.converged) return;
      // Two of the places slid into one (from a place on a thin face's
      // far side, the search can run round an end onto the near side):
      // then any point of the other two's bisector solves the equations,
      // and the point found is an ordinary point of that edge. A reflex
      // corner reached along both its edges is left alone: the chords'
      // diagram splits the corner's normal wedge between the two edges'
      // ends, and this has long stood for the junction there.
      const auto& e = exact.places;
      const auto one = [&](const BoundaryPlace& a, const BoundaryPlace& b) {
        return same_place(index_, a, b, kSamePlace * size()) && !at_reflex_corner(a);
      };
      if (one(e[0], e[1]) || one(e[0], e[2]) || one(e[1], e[2])) return;
      if (avoid && distance(exact.p, avoid->p) <= 1e-9 * size()) return;
      const std::pair<int, double> score{-own_edges_touched(node, exact.p, exact.r), distance(exact.p, p)};
      if (!(score < best)) return;
      std::vector<BoundaryPlace> touches;
      for (const BoundaryPlace& c : candidates) {
        const BoundaryPlace at = nearest_on_run(index_, c, exact.p);
        const double d = distance(at.point, exact.p);
        if (d < exact.r * (1 - 1e-9)) return;  // boundary inside the disc
        if (d <= exact.r * (1 + 1e-9)) touches.push_back(at);
      }
      // A foot held in its window is a place no candidate's search reaches.
      if (held) {
        for (const BoundaryPlace& at : exact.places) add_distinct(index_, touches, at, kSamePlace * size());
      }
      best = score;
      v.p = exact.p;
      v.r = exact.r;
      v.touches = touches;
    };
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      for (std::size_t j = i + 1; j < candidates.size(); ++j) {
        for (std::size_t k = j + 1; k < candidates.size(); ++k)
          consider(equidistant(index_, p, {candidates[i], candidates[j], candidates[k]}), false);
      }
    }
    if (v.touches.empty() && candidates.size() < 3) {
      // Near a curvature contact the distance from the discretised junction
      // to a run curving nearly round it may have no local minimum where the
      // exact junction's foot is, and the searches slide past it (two sites'
      // places become one, leaving two): search again with each foot held
      // near its chord. (With three places or more and no junction among
      // them, held feet found junctions that turned blocks inside out,
      // fuzz bspline_5_1347.)
      const auto [starts, windows] = chord_windows(node, p);
      for (std::size_t i = 0; i < starts.size(); ++i) {
        for (std::size_t j = i + 1; j < starts.size(); ++j) {
          for (std::size_t k = j + 1; k < starts.size(); ++k)
            consider(
                equidistant_within(index_, p, {starts[i], starts[j], starts[k]}, {windows[i], windows[j], windows[k]}),
                true);
        }
      }
    }
    if (v.touches.empty()) return std::nullopt;
    return v;
  }

  // Where five places lie almost on one circle, two neighbouring junction
  // nodes can both take the one exact junction that touches most of their
  // own edges, leaving two vertices at one point with the same touches and
  // none for the pairing between them (filleted_14_1695, filleted_9_1070:
  // an edge beside them then touched one place at one end and another at
  // the other, and a block outline ran clockwise or missed itself). The
  // node whose own edges that junction touches less takes the best other
  // junction, if there is one.
  void separate_coincident_junctions() {
    for (const auto& [s, ends] : edge_nodes_) {
      const auto [a, b] = ends;
      if (!junction_node(a) || !junction_node(b)) continue;
      const MedialVertex &va = axis_.vertices[nodes_[a].vertex], &vb = axis_.vertices[nodes_[b].vertex];
      if (distance(va.p, vb.p) > 1e-9 * size()) continue;
      const int redo = own_edges_touched(a, va.p, va.r) < own_edges_touched(b, va.p, va.r) ? a : b;
      const MedialVertex& keep = redo == a ? vb : va;
      if (const std::optional<MedialVertex> other = exact_junction(redo, node_point(redo), &keep))
        axis_.vertices[nodes_[redo].vertex] = *other;
    }
  }

  // The segment sites around a junction node, each as the place of its chord
  // nearest to p and a parameter window of its edge: the chord's range and
  // twice its length on either side.
  std::pair<std::vector<BoundaryPlace>, std::vector<std::array<double, 2>>> chord_windows(int node, Vec2 p) const {
    std::vector<Site> sites = junction_sites(node, p);
    for (int e : nodes_[node].edges) sites.insert(sites.end(), {graph_.edges[e].left, graph_.edges[e].right});
    std::vector<BoundaryPlace> starts;
    std::vector<std::array<double, 2>> windows;
    std::vector<int> seen;
    for (const Site& site : sites) {
      if (site.part != Site::kSegment || std::find(seen.begin(), seen.end(), site.segment) != seen.end()) continue;
      seen.push_back(site.segment);
      const BoundarySegment& s = graph_.segments[site.segment];
      const BoundaryEdge& edge = index_.edge(s.loop, s.edge);
      const double reach = 2 * std::abs(s.t1 - s.t0);
      starts.push_back(index_.place(s.loop, s.edge, chord_parameter(s, p)));
      windows.push_back({std::max(std::min(s.t0, s.t1) - reach, std::min(edge.t_start, edge.t_end)),
                         std::min(std::max(s.t0, s.t1) + reach, std::max(edge.t_start, edge.t_end))});
    }
    return {starts, windows};
  }

  bool at_reflex_corner(const BoundaryPlace& place) const {
    return std::any_of(face_.corners.begin(), face_.corners.end(), [&](const Corner& c) {
      return c.loop == place.loop && index_.is_reflex(c.loop, c.vertex) &&
             distance(c.position, place.point) <= kSamePlace * size();
    });
  }

  // Where four places lie almost on one circle the axis has two junctions
  // joined by a short edge, and the discretised diagram may pair the places
  // the other way round from the exact junctions (a flip): an edge then meets
  // the junction that does not touch its two places, and the short edge is
  // the bisector of the wrong two. Such edges are moved to the junction that
  // touches both their places, and the short edge becomes the bisector of
  // the two places both junctions touch.
  void repair_flipped_junction_pairs() {
    for (std::size_t a = 0; a < nodes_.size(); ++a) {
      if (!junction_node(static_cast<int>(a))) continue;
      for (const int s : std::vector<int>(nodes_[a].edges)) {
        const auto [x, y] = edge_nodes_.at(s);
        const int b = x == static_cast<int>(a) ? y : x;
        if (b > static_cast<int>(a) && junction_node(b)) repair_pair(static_cast<int>(a), b, s);
      }
    }
  }

  bool junction_node(int node) const {
    return nodes_[node].vertex >= 0 && axis_.vertices[nodes_[node].vertex].kind == MedialVertexKind::Junction;
  }

  // Whether the disc at p of radius r touches the site's place; both of the
  // Voronoi edge's sites.
  bool touches_site(Vec2 p, double r, const Site& site) const {
    return std::abs(distance(place_of(site, p).point, p) - r) <= 1e-9 * size();
  }
  bool touches_edge(Vec2 p, double r, int voronoi_edge) const {
    return touches_site(p, r, graph_.edges[voronoi_edge].left) && touches_site(p, r, graph_.edges[voronoi_edge].right);
  }

  // How many of the node's own Voronoi edges the disc at p of radius r
  // touches both places of.
  int own_edges_touched(int node, Vec2 p, double r) const {
    return static_cast<int>(std::count_if(nodes_[node].edges.begin(), nodes_[node].edges.end(),
                                          [&](int e) { return touches_edge(p, r, e); }));
  }

  void repair_pair(int a, int b, int s) {
    const MedialVertex &va = axis_.vertices[nodes_[a].vertex], &vb = axis_.vertices[nodes_[b].vertex];
    if (distance(va.p, vb.p) > kPointSpacing * size() || (touches_edge(va.p, va.r, s) && touches_edge(vb.p, vb.r, s)))
      return;
    std::vector<int> to_b, to_a;
    for (int f : nodes_[a].edges)
      if (f != s && !touches_edge(va.p, va.r, f) && touches_edge(vb.p, vb.r, f)) to_b.push_back(f);
    for (int f : nodes_[b].edges)
      if (f != s && !touches_edge(vb.p, vb.r, f) && touches_edge(va.p, va.r, f)) to_a.push_back(f);
    if (to_a.empty() && to_b.empty()) return;
    const int degree_a = static_cast<int>(nodes_[a].edges.size() - to_b.size() + to_a.size());
    const int degree_b = static_cast<int>(nodes_[b].edges.size() - to_a.size() + to_b.size());
    if (degree_a < 3 || degree_b < 3) return;
    // The places both junctions touch, from the sites of the edges there.
    std::vector<Site> shared;
    std::vector<BoundaryPlace> shared_places;
    for (const int node : {a, b}) {
      for (int f : nodes_[node].edges) {
        if (f == s) continue;
        for (const Site& site : {graph_.edges[f].left, graph_.edges[f].right}) {
          if (!touches_site(va.p, va.r, site) || !touches_site(vb.p, vb.r, site)) continue;
          const BoundaryPlace place = place_of(site, va.p);
          if (std::any_of(shared_places.begin(), shared_places.end(),
                          [&](const BoundaryPlace& q) { return same_place(index_, q, place, kSamePlace * size()); }))
            continue;
          shared.push_back(site);
          shared_places.push_back(place);
        }
      }
    }
    if (shared.size() != 2) return;
    const auto move = [&](int f, int from, int to) {
      auto& ends = edge_nodes_.at(f);
      (ends.first == from ? ends.first : ends.second) = to;
      auto& list = nodes_[from].edges;
      list.erase(std::remove(list.begin(), list.end(), f), list.end());
      nodes_[to].edges.push_back(f);
    };
    for (int f : to_b) move(f, a, b);
    for (int f : to_a) move(f, b, a);
    graph_.edges[s].left = shared[0];
    graph_.edges[s].right = shared[1];
  }

  void make_end(int node, Vec2 p) {
    const double r = graph_.vertices[node_vertex_[node]].r;
    // Flare: the axis runs into a convex corner (or ran into it before its
    // last stretch was lost: cut_short_flare).
    const auto flare = [&](const Corner& c) {
      MedialVertex v;
      v.kind = MedialVertexKind::Flare;
      v.p = c.position;
      v.touches.push_back(index_.place(c.loop, c.vertex, face_.loops[c.loop].edges[c.vertex].t_start));
      nodes_[node].vertex = add_vertex(v);
    };
    if (r <= 1e-6 * size()) {
      for (const Corner& c : face_.corners) {
        if (distance(c.position, p) <= 1e-6 * size()) return flare(c);
      }
    }
    if (const auto cut_short = flare_of_node_.find(node); cut_short != flare_of_node_.end())
      return flare(face_.corners[cut_short->second]);
    // The round end of a slot: joins the finite-contact vertex of its arc.
    const int finite_contact = finite_contact_for(node);
    if (finite_contact >= 0) {
      nodes_[node].vertex = finite_contact;
      return;
    }
    // A curvature contact, snapped to its exact place when there is one.
    const std::vector<BoundaryPlace> touches = touches_at(node, p);
    MedialVertex fallback;
    fallback.kind = MedialVertexKind::CurvatureContact;
    fallback.p = p;
    fallback.r = r;
    fallback.touches = touches;
    nodes_[node].vertex = add_vertex(curvature_contact(node).value_or(fallback));
  }

  int add_vertex(const MedialVertex& v) {
    axis_.vertices.push_back(v);
    return static_cast<int>(axis_.vertices.size()) - 1;
  }

  // A place on a loop moved by arc length ds along the loop's order (way +1)
  // or against it (-1), across tangent joins (a closed curve's seam is one)
  // and, if past_reflex, reflex corners, past which the boundary a disc
  // touches goes on (crossed says one was passed); false at any other
  // corner (at a convex one the axis ends in the corner's flare and no
  // curvature contact can lie beyond).
  bool advance(BoundaryPlace& q, int way, double ds, bool past_reflex, bool& crossed) const {
    crossed = false;
    const BoundaryEdge& edge = index_.edge(q.loop, q.edge);
    const double sense = (edge.t_end >= edge.t_start ? 1.0 : -1.0) * way;
    const double t = q.t + sense * ds / std::max(norm(evaluate(edge.curve, q.t).d1), 1e-300);
    const double end = way > 0 ? edge.t_end : edge.t_start;
    if ((end - t) * sense > 0) {
      q = index_.place(q.loop, q.edge, t);
      return true;
    }
    const int count = index_.edge_count(q.loop);
    const int vertex = way > 0 ? (q.edge + 1) % count : q.edge;
    if (index_.is_corner(q.loop, vertex)) {
      if (!past_reflex || !index_.is_reflex(q.loop, vertex)) return false;
      crossed = true;
    }
    const int next = way > 0 ? (q.edge + 1) % count : (q.edge + count - 1) % count;
    const BoundaryEdge& following = index_.edge(q.loop, next);
    q = index_.place(q.loop, next, way > 0 ? following.t_start : following.t_end);
    return true;
  }

  // Places along the boundary about ds apart, in order. cut[i] says a reflex
  // corner lies between places i and i + 1, cut_front and cut_back that a
  // corner cut the run short: a curvature peak is a peak among its
  // neighbours on its side of a corner, and may lie at a corner.
  struct Run {
    std::vector<BoundaryPlace> places;
    std::vector<bool> cut;
    bool cut_front = false, cut_back = false;
  };

  struct Walk {
    std::vector<BoundaryPlace> places;  // from nearest the start on, the start left out
    std::vector<bool> crossed;          // a reflex corner was passed on the way to the place
    bool stopped = false;               // at a corner
  };

  Walk walk(const BoundaryPlace& from, int way, double ds, int steps, bool past_reflex) const {
    Walk w;
    BoundaryPlace q = from;
    for (int k = 0; k < steps; ++k) {
      bool crossed = false;
      if (!advance(q, way, ds, past_reflex, crossed)) {
        w.stopped = true;
        break;
      }
      w.places.push_back(q);
      w.crossed.push_back(crossed);
    }
    return w;
  }

  // The run from the far end of `behind` through `foot` to the far end of
  // the first `count` places of `ahead`.
  static Run join(const Walk& behind, const BoundaryPlace& foot, const Walk& ahead, std::size_t count) {
    Run run;
    for (std::size_t k = behind.places.size(); k-- > 0;) {
      run.places.push_back(behind.places[k]);
      run.cut.push_back(behind.crossed[k]);
    }
    run.places.push_back(foot);
    count = std::min(count, ahead.places.size());
    for (std::size_t k = 0; k < count; ++k) {
      run.cut.push_back(ahead.crossed[k]);
      run.places.push_back(ahead.places[k]);
    }
    run.cut_front = behind.stopped;
    run.cut_back = ahead.stopped && count == ahead.places.size();
    return run;
  }

  // The end of the axis at a node of one edge, between two places of one
  // smooth curve: the centre of curvature at a curvature peak (an ellipse's
  // is at x = +-(a^2 - b^2)/a on its major axis), or nothing if no true local
  // maximum of curvature lies near. Every disc of a branch ending there holds
  // the boundary from its right foot forwards to its left one (travelling
  // into the end, the face on the boundary's left), the end's touching point
  // among it: so where the end's two feet are apart, the peaks on that
  // stretch (past reflex corners) are the candidates, the one nearest the
  // node among those whose disc is empty. A wavy cap has peaks close
  // together whose centres are all near the node, and the branch the Voronoi
  // diagram kept runs into one of them; the nearest either way may be its
  // neighbour's, and an edge hung on that one folds back. Where the feet
  // have met, or passed each other (the discretised end lies a few chords
  // beyond the true one), the feet of the nearest node back along the
  // branch whose feet are apart stand in for them: of a lobe's two peaks
  // the one nearer the end node may lie outside those (fuzz
  // bspline_10_172). Where no node within r has such feet, or no peak
  // between them has an empty disc, the peaks within the node's radius r
  // along the boundary either way from each foot are the candidates: an
  // empty disc first, then the nearest to the node. Each foot's own run
  // then, up to any corner (beside a reflex corner the feet may lie on
  // either side of it, and the peak on the other side's), but past reflex
  // corners where the feet have met in one place (the node's two touches
  // may also meet there, seen from it): a nearly flat one at the seam of a
  // closed B-spline may hide the peak just beyond.
  static constexpr int kSamples = 64;  // per radius along the boundary
  static constexpr int kFeetBack = 8;  // nodes back along the branch
  std::optional<MedialVertex> curvature_contact(int node) const {
    const Vec2 p = node_point(node);
    const double r = graph_.vertices[node_vertex_[node]].r;
    const std::vector<BoundaryPlace> touches = touches_at(node, p);
    if (touches.empty() || r <= 0) return std::nullopt;
    const double ds = r / kSamples;
    std::vector<BoundaryPlace> feet;
    for (BoundaryPlace foot : touches) {
      foot.corner_itself = false;
      add_distinct(index_, feet, nearest_on_run(index_, foot, p), kSamePlace * size());
    }
    std::optional<MedialVertex> best;
    bool best_empty = false;
    int from = node, e = nodes_[node].edges.front();
    for (int step = 0; step < kFeetBack; ++step) {
      const auto [a, b] = edge_nodes_.at(e);
      const int back = a == from ? b : a;
      const Vec2 q = node_point(from);
      if (distance(q, p) > r) break;
      std::vector<BoundaryPlace> apart = feet;
      if (from != node) {
        apart.clear();
        add_distinct(index_, apart, place_of(graph_.edges[e].left, q), kSamePlace * size());
        add_distinct(index_, apart, place_of(graph_.edges[e].right, q), kSamePlace * size());
      }
      if (apart.size() == 2 && apart[0].loop == apart[1].loop) {
        const Vec2 in = q - node_point(back);
        const bool first_right = cross(in, apart[0].point - q) < cross(in, apart[1].point - q);
        if (peaks_between(apart[first_right ? 0 : 1], apart[first_right ? 1 : 0], p, ds, best, best_empty)) {
          if (best_empty) return best;
          best.reset();
          break;
        }
      }
      if (nodes_[back].edges.size() != 2) break;
      from = back;
      e = nodes_[back].edges[0] == e ? nodes_[back].edges[1] : nodes_[back].edges[0];
    }
    const bool met = feet.size() == 1;
    for (const BoundaryPlace& foot : feet)
      peaks_on(join(walk(foot, -1, ds, kSamples, met), foot, walk(foot, 1, ds, kSamples, met), kSamples), p, ds, best,
               best_empty);
    return best;
  }

  // The peaks on the boundary from the right foot forwards to the left one,
  // as candidates for curvature_contact; false if the left foot lies more
  // than a circle's length of the disc of radius kSamples * ds ahead (the
  // feet have passed each other). A few places more either side on the
  // feet's own runs (the feet are the discretised end's, a chord off).
  bool peaks_between(const BoundaryPlace& right, const BoundaryPlace& left, Vec2 p, double ds,
                     std::optional<MedialVertex>& best, bool& best_empty) const {
    constexpr int kMargin = kSamples / 8;
    const int reach = static_cast<int>(std::ceil(2 * kPi * kSamples));
    const Walk ahead = walk(right, 1, ds, reach + kMargin, true);
    for (std::size_t k = 0; k < ahead.places.size() && k < static_cast<std::size_t>(reach); ++k) {
      if (distance(ahead.places[k].point, left.point) > ds) continue;
      std::size_t count = k + 1;
      while (count < ahead.places.size() && count < k + 1 + kMargin && !ahead.crossed[count]) ++count;
      peaks_on(join(walk(right, -1, ds, kMargin, false), right, ahead, count), p, ds, best, best_empty);
      return true;
    }
    return false;
  }

  // The curvature peaks of a run, as candidates for curvature_contact: best
  // is the nearest to p whose disc is empty, else the nearest.
  void peaks_on(const Run& run, Vec2 p, double ds, std::optional<MedialVertex>& best, bool& best_empty) const {
    const std::size_t n = run.places.size();
    std::vector<double> kappa(n);
    for (std::size_t i = 0; i < n; ++i)
      kappa[i] = curvature(index_.edge(run.places[i].loop, run.places[i].edge), run.places[i].t);
    for (std::size_t i = 0; i < n; ++i) {
      // Neighbours on this place's side of any corner; at a run's end, a
      // place may be a peak only where a corner cut it short (the curvature
      // may rise all the way to a corner).
      const bool before = i > 0 && !run.cut[i - 1], after = i + 1 < n && !run.cut[i];
      if ((i == 0 && !run.cut_front) || (i + 1 == n && !run.cut_back)) continue;
      const double k = kappa[i];
      if (k <= 0 || (before && k < kappa[i - 1]) || (after && k < kappa[i + 1])) continue;
      // Golden-section refinement within a sample step either side, on the
      // sample's edge (a closed curve's seam may lie between the samples).
      const BoundaryPlace& at_sample = run.places[i];
      const BoundaryEdge& edge = index_.edge(at_sample.loop, at_sample.edge);
      const double dt = ds / std::max(norm(evaluate(edge.curve, at_sample.t).d1), 1e-300);
      double a = std::max(std::min(edge.t_start, edge.t_end), at_sample.t - dt);
      double b = std::min(std::max(edge.t_start, edge.t_end), at_sample.t + dt);
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = b - g * (b - a), x2 = a + g * (b - a);
      double f1 = curvature(edge, x1), f2 = curvature(edge, x2);
      for (int it = 0; it < 200 && b - a > 1e-15 * (1 + std::abs(a)); ++it) {
        if (f1 < f2) {
          a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = curvature(edge, x2);
        } else {
          b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = curvature(edge, x1);
        }
      }
      const double t = 0.5 * (a + b);
      const BoundaryPlace at = index_.place(at_sample.loop, at_sample.edge, t);
      // A peak at a convex corner is the corner's flare, no contact. At a
      // reflex corner the disc touching the corner with the curvature of
      // this side there is the end (the other side turns away from it).
      if (at.corner >= 0 && !index_.is_reflex(at.loop, at.corner)) continue;
      MedialVertex v;
      v.kind = MedialVertexKind::CurvatureContact;
      v.r = 1.0 / curvature(edge, t);
      v.p = at.point + v.r * perp(edge_tangent(edge, t));
      v.touches = {at};
      // Every place of a circular arc is a peak, all with one centre: judged once.
      if (best && distance(v.p, best->p) <= 1e-9 * size() && std::abs(v.r - best->r) <= 1e-9 * size()) continue;
      // A peak whose disc holds boundary is no contact (a ripple beside the
      // true one, when the end stopped short of it): an empty disc wins.
      const bool empty = disc_is_empty(v.p, v.r);
      if (!best || empty > best_empty || (empty == best_empty && distance(v.p, p) < distance(best->p, p)))
        best = v, best_empty = empty;
    }
  }

  // The medial point on the bisector of an edge's two sites nearest to m.
  MedialPoint medial_point(int voronoi_edge, Vec2 m) const {
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    const Bisected b = bisect(index_, m, place_of(e.left, m), place_of(e.right, m));
    return {b.p, b.r, b.a, b.b};
  }

  // A node inside a medial edge where one touching place gives way to another
  // (after a ripple branch was pruned there) lies equally far from all three
  // places; elsewhere it is an ordinary point of the edge's bisector.
  MedialPoint transition_point(int node, int voronoi_edge) const {
    const Vec2 p = node_point(node);
    // Three distinct places, not three boundary edges: on a closed B-spline
    // that is one edge every place lies on edge 0.
    const std::vector<BoundaryPlace> places = touches_at(node, p);
    if (places.size() == 3) {
      const Equidistant exact = equidistant(index_, p, places);
      if (exact.converged && distance(exact.p, p) <= kPointSpacing * size()) {
        const VoronoiEdge& e = graph_.edges[voronoi_edge];
        return {exact.p, exact.r, place_of(e.left, exact.p), place_of(e.right, exact.p)};
      }
    }
    return medial_point(voronoi_edge, p);
  }

  // A vertex as the end point of an edge: its exact place, with the feet of the
  // edge's two sites seen from there.
  MedialPoint end_point(int vertex, int voronoi_edge) const {
    const MedialVertex& v = axis_.vertices[vertex];
    const VoronoiEdge& e = graph_.edges[voronoi_edge];
    if (v.kind == MedialVertexKind::Flare || v.kind == MedialVertexKind::CurvatureContact) {
      return {v.p, v.r, v.touches.front(), v.touches.front()};
    }
    // At a junction, the touching places of the vertex nearest to the sites'.
    const auto touch = [&](const Site& site) {
      const BoundaryPlace own = place_of(site, v.p);
      if (v.kind != MedialVertexKind::Junction || std::abs(distance(own.point, v.p) - v.r) <= 1e-9 * size()) return own;
      return *std::min_element(v.touches.begin(), v.touches.end(), [&](const auto& a, const auto& b) {
        return distance(a.point, own.point) < distance(b.point, own.point);
      });
    };
    return {v.p, v.r, touch(e.left), touch(e.right)};
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
    trim_past_junction(edge, edge.from, false);
    trim_past_junction(edge, edge.to, true);
    drop_overshoot(edge, edge.from, false);
    drop_overshoot(edge, edge.to, true);
    touch_from_neighbour(edge, edge.from, false);
    touch_from_neighbour(edge, edge.to, true);
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
    if (nodes_[to].vertex >= 0) {
      edge.points.push_back(end_point(nodes_[to].vertex, e));
      return;
    }
    // The exact transition may lie short of points placed before it (the
    // discretised node lies a little past it): those touch the place beyond
    // the jump already, and kept they would put the edge's points out of
    // order (its touches jumping to and fro, fuzz bspline_10_182).
    const MedialPoint transition = transition_point(to, e);
    while (edge.points.size() > 1 && dot(edge.points.back().p - transition.p, b - a) > 0) edge.points.pop_back();
    edge.points.push_back(transition);
  }

  // The discretised junction lies a little off the exact one, so the first
  // points of an edge may lie just beyond it, where a third place of the
  // junction is nearer than their two: those points are not medial, drop them.
  void trim_past_junction(MedialEdge& edge, int vertex, bool at_end) const {
    if (vertex < 0 || axis_.vertices[vertex].kind != MedialVertexKind::Junction) return;
    const MedialVertex& junction = axis_.vertices[vertex];
    auto& pts = edge.points;
    while (pts.size() > 2) {
      const MedialPoint& q = at_end ? pts[pts.size() - 2] : pts[1];
      bool beyond = false;
      for (const BoundaryPlace& t : junction.touches) {
        beyond |= distance(nearest_on_run(index_, t, q.p).point, q.p) < q.r * (1 - 1e-12);
      }
      if (!beyond) break;
      pts.erase(at_end ? pts.end() - 2 : pts.begin() + 1);
    }
  }

  // Near a junction where the nearest-point searches of an edge's sites can
  // slide round a fillet onto the neighbouring edge's side, the edge's first
  // points may lie on that neighbour: the edge runs past its vertex along
  // it, turns right back and passes the vertex again. Those points belong to
  // the neighbour (their touches are its two sides), and a medial edge never
  // turns back, so they are dropped: the edge leaves its vertex from the
  // nearest point to it after the turn. Only a turn within the junction's
  // radius of it is such an overshoot. A branch whose curvature-contact end
  // was put on the peak it runs into may likewise keep a point or two of
  // the pruned ripple beyond it, near its end (within a tenth of its radius).
  void drop_overshoot(MedialEdge& edge, int vertex, bool at_end) const {
    if (vertex < 0) return;
    const MedialVertex& v = axis_.vertices[vertex];
    const double reach = v.kind == MedialVertexKind::Junction           ? v.r
                         : v.kind == MedialVertexKind::CurvatureContact ? 0.1 * v.r
                                                                        : 0.0;
    while (drop_one_overshoot(edge.points, at_end, reach)) continue;
    // Along a branch the radius falls to the contact's at a curvature-contact
    // end: points beside the end with a smaller one lie past the exact end
    // (bspline_15_1532: the last point 8 beyond its contact of radius 649,
    // at radius 643.5, and the branch turned back 150 degrees onto it).
    if (v.kind != MedialVertexKind::CurvatureContact) return;
    auto& pts = edge.points;
    while (pts.size() > 2) {
      const std::size_t k = at_end ? pts.size() - 2 : 1;
      if (!(pts[k].r < v.r * (1 - 1e-9) && distance(pts[k].p, v.p) <= reach)) break;
      pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(k));
    }
  }

  static bool drop_one_overshoot(std::vector<MedialPoint>& pts, bool at_end, double reach) {
    const int n = static_cast<int>(pts.size());
    const auto index = [&](int k) { return at_end ? n - 1 - k : k; };
    const auto at = [&](int k) { return pts[index(k)].p; };
    for (int k = 1; k + 1 < n / 2 && distance(at(k), at(0)) <= reach; ++k) {
      const Vec2 in = at(k) - at(k - 1), out = at(k + 1) - at(k);
      if (!(dot(in, out) < -0.9 * norm(in) * norm(out))) continue;
      int nearest = k + 1;
      for (int j = k + 2; j <= n / 2; ++j) {
        if (distance(at(j), at(0)) < distance(at(nearest), at(0))) nearest = j;
      }
      if (at_end) {
        pts.erase(pts.begin() + index(nearest - 1), pts.begin() + index(0));
      } else {
        pts.erase(pts.begin() + 1, pts.begin() + nearest);
      }
      return true;
    }
    return false;
  }

  // At an arc's centre every point of the arc is equally near, so a finite
  // contact end touches what its neighbouring point touches, seen from there.
  void touch_from_neighbour(MedialEdge& edge, int vertex, bool at_end) const {
    if (vertex < 0 || axis_.vertices[vertex].kind != MedialVertexKind::FiniteContact || edge.points.size() < 2) return;
    MedialPoint& end = at_end ? edge.points.back() : edge.points.front();
    const MedialPoint& next = at_end ? edge.points[edge.points.size() - 2] : edge.points[1];
    end.left = nearest_on_run(index_, next.left, end.p);
    end.right = nearest_on_run(index_, next.right, end.p);
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

  struct PlaceMemo {
    int segment = -1;  // none yet
    Site::Part part = Site::kSegment;
    Vec2 m;
    BoundaryPlace place;
  };

  const FaceModel& face_;
  mutable std::array<PlaceMemo, 8> place_memo_;
  mutable std::size_t place_memo_next_ = 0;
  BoundaryIndex index_;
  double chord_tolerance_;
  VoronoiGraph graph_;
  std::vector<int> kept_;
  std::vector<int> node_of_;
  std::vector<int> node_vertex_;
  std::vector<std::vector<int>> voronoi_neighbours_;
  std::vector<Node> nodes_;
  std::map<int, std::pair<int, int>> edge_nodes_;
  std::map<int, int> flare_of_node_;  // end node -> corner, for cut-short flares
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

namespace {

// The axis of a face with h holes is one connected graph with h independent
// cycles (a loop with no vertex counts as a vertex of its own); "" if so.
std::string topology_problem(const MedialAxis& axis, const FaceModel& face) {
  const int holes = face.holes();
  UnionFind sets(axis.vertices.size());
  int vertices = static_cast<int>(axis.vertices.size()), components = vertices;
  for (const MedialEdge& e : axis.edges) {
    if (e.from < 0) {
      ++vertices, ++components;
    } else if (sets.find(e.from) != sets.find(e.to)) {
      sets.unite(e.from, e.to);
      --components;
    }
  }
  const int cycles = static_cast<int>(axis.edges.size()) - vertices + components;
  if (components != 1) return "the axis falls into " + std::to_string(components) + " pieces";
  if (cycles != holes)
    return "the axis has " + std::to_string(cycles) + " cycles for " + std::to_string(holes) + " holes";
  // Every convex corner ends a branch of the axis: one connected graph that
  // misses a corner's flare misses the part of the face round it.
  for (const Corner& c : face.corners) {
    if (c.angle >= kPi) continue;
    const bool flare = std::any_of(axis.vertices.begin(), axis.vertices.end(), [&](const MedialVertex& v) {
      return v.kind == MedialVertexKind::Flare && distance(v.p, c.position) <= 1e-6 * face.size + face.tolerance;
    });
    if (!flare) {
      std::ostringstream where;
      where << "no branch of the axis ends in the convex corner at (" << c.position.x << ", " << c.position.y << ")";
      return where.str();
    }
  }
  return "";
}

// The nearest boundary point to every medial point: the vertices, then the
// edges' points in order. Both checks below need them, and each costs a
// nearest-point search on the exact curves.
std::vector<Vec2> nearest_points(const NearestBoundary& boundary, const MedialAxis& axis) {
  std::vector<Vec2> nearest;
  for (const MedialVertex& v : axis.vertices) nearest.push_back(boundary.nearest(v.p).point);
  for (const MedialEdge& e : axis.edges) {
    for (const MedialPoint& p : e.points) nearest.push_back(boundary.nearest(p.p).point);
  }
  return nearest;
}

// The largest difference between a medial point's radius and its distance to
// the boundary or to the places it touches.
double radius_error(const std::vector<Vec2>& nearest, const MedialAxis& axis) {
  double worst = 0.0;
  const auto off = [&](Vec2 p, double r, Vec2 q) { worst = std::max(worst, std::abs(r - distance(q, p))); };
  std::size_t i = 0;
  for (const MedialVertex& v : axis.vertices) {
    off(v.p, v.r, nearest[i++]);
    for (const BoundaryPlace& t : v.touches) off(v.p, v.r, t.point);
  }
  for (const MedialEdge& e : axis.edges) {
    for (const MedialPoint& p : e.points) {
      off(p.p, p.r, nearest[i++]);
      off(p.p, p.r, p.left.point);
      off(p.p, p.r, p.right.point);
    }
  }
  return worst;
}

double violation(const std::vector<Vec2>& nearest, const MedialAxis& axis) {
  double worst = 0.0;
  std::size_t i = 0;
  const auto check = [&](Vec2 p, double r) { worst = std::max(worst, r - distance(nearest[i++], p)); };
  for (const MedialVertex& v : axis.vertices) check(v.p, v.r);
  for (const MedialEdge& e : axis.edges) {
    for (const MedialPoint& p : e.points) check(p.p, p.r);
  }
  return worst;
}

// An edge point's feet come from nearest-point searches started at its
// Voronoi sites' chords, which on a long wavy curve may settle in a local
// minimum of the distance (a foot on a bump while the disc reaches into the
// next one, or both feet on one bump): then the global nearest place is
// nearer than the radius. Such a point is placed again on the bisector of
// the global nearest place and one of its feet. The global place stands in
// for the foot on its side, the nearer one, so the farther foot is kept
// first: the point's two touches stay one on each side of its edge. Kept
// the other way (the foot beside the global place), a point beside a pruned
// ripple branch becomes the ripple's own bisector point, touching two places
// on one side, and the edge's touches fold back there. Only where that
// leaves the disc off the boundary (both feet were on one bump) is the
// other foot kept instead. nearest is updated.
void repair_edge_points(const BoundaryIndex& index, const NearestBoundary& boundary, double tolerance, MedialAxis& axis,
                        std::vector<Vec2>& nearest) {
  const double same = kSamePlace * index.face().size;
  const auto error = [](const MedialPoint& q, Vec2 near) {
    return std::max({std::abs(q.r - distance(near, q.p)), std::abs(q.r - distance(q.left.point, q.p)),
                     std::abs(q.r - distance(q.right.point, q.p))});
  };
  std::size_t i = axis.vertices.size();
  for (MedialEdge& e : axis.edges) {
    for (std::size_t k = 0; k < e.points.size(); ++k, ++i) {
      MedialPoint& q = e.points[k];
      double worst = error(q, nearest[i]);
      if (worst <= tolerance) continue;
      const BoundaryPlace global = boundary.nearest(q.p);
      const bool left_nearer = distance(q.left.point, global.point) < distance(q.right.point, global.point);
      for (const BoundaryPlace& foot : {left_nearer ? q.right : q.left, left_nearer ? q.left : q.right}) {
        if (worst <= tolerance) break;
        if (same_place(index, foot, global, same)) continue;
        const Bisected b = bisect(index, q.p, global, foot);
        if (!b.converged || same_place(index, b.a, b.b, same) || distance(b.p, q.p) > kPointSpacing * index.face().size)
          continue;
        const BoundaryPlace at = boundary.nearest(b.p);
        MedialPoint moved{b.p, b.r, b.a, b.b};
        const double moved_error = error(moved, at.point);
        if (moved_error >= worst) continue;
        // Left and right of the direction of travel, as orient_touches names them.
        const Vec2 dir = e.points[std::min(k + 1, e.points.size() - 1)].p - e.points[k > 0 ? k - 1 : 0].p;
        if (cross(dir, moved.left.point - moved.p) < cross(dir, moved.right.point - moved.p))
          std::swap(moved.left, moved.right);
        q = moved, nearest[i] = at.point, worst = moved_error;
      }
    }
  }
}

// One build of the axis from chords `fineness` times finer than the
// default, with its edge points repaired, and what the checks make of it.
struct CheckedAxis {
  MedialAxis axis;
  double violation = 0.0;  // before repair: how far boundary reaches into a disc
  std::string problem;     // empty: the right topology
  double error = 0.0;      // after repair: the largest radius error (radius_error)
};

CheckedAxis checked_axis(const FaceModel& face, double fineness, const BoundaryIndex& index,
                         const NearestBoundary& boundary, double tolerance) {
  CheckedAxis checked;
  checked.axis = Builder(face, fineness).build();
  std::vector<Vec2> nearest = nearest_points(boundary, checked.axis);
  checked.violation = violation(nearest, checked.axis);
  checked.problem = topology_problem(checked.axis, face);
  repair_edge_points(index, boundary, tolerance, checked.axis, nearest);
  checked.error = radius_error(nearest, checked.axis);
  return checked;
}

}  // namespace

double medial_axis_violation(const FaceModel& face, const MedialAxis& axis) {
  const BoundaryIndex index(face);
  return violation(nearest_points(NearestBoundary(index), axis), axis);
}

MedialAxis compute_medial_axis(const FaceModel& face, double fineness) {
  const double tolerance = 1e-7 * face.size + face.tolerance;
  // The accuracy the axis promises (1e-6 of the diagonal, as the tests ask),
  // both ways: no boundary inside a disc, and every disc touching it.
  const double allowed = 1e-6 * face.size + face.tolerance;
  const BoundaryIndex index(face);
  const NearestBoundary boundary(index);  // built once for every check below
  CheckedAxis best = checked_axis(face, fineness, index, boundary, tolerance);
  // Finer chords where a point is off, a disc misses its touching places
  // (a junction the chords put beside a spurious ripple branch:
  // bspline_29_1052) or the axis has a cycle or a piece too many. An axis of
  // the right topology outranks one within the allowed radius error, which
  // outranks a more exact one.
  const auto rank = [&](const CheckedAxis& a) { return std::make_pair(a.problem.empty(), a.error <= allowed); };
  for (int i = 0; i < kMaxRefinements && (best.violation > tolerance || best.error > allowed || !best.problem.empty());
       ++i) {
    fineness *= kChordRefinement;
    CheckedAxis finer = checked_axis(face, fineness, index, boundary, tolerance);
    if (rank(finer) > rank(best) || (rank(finer) == rank(best) && finer.violation < best.violation))
      best = std::move(finer);
  }
  if (best.error > allowed) {
    std::ostringstream check;
    check << "medial axis: a medial point's distance to the boundary or to a place it touches is " << best.error
          << " off its radius (allowed " << allowed << ")";
    throw SelfCheckError(face.name, check.str());
  }
  // Repairing moves edge points only: the topology is the one found above.
  if (!best.problem.empty()) throw SelfCheckError(face.name, "medial axis: " + best.problem);
  return std::move(best.axis);
}

FaceAxis compute_face_medial_axis(const FaceModel& face) {
  try {
    return {face, compute_medial_axis(face), {}};
  } catch (const SelfCheckError& first) {
    // A kink taken as smooth has no flare of its own on the axis, yet its
    // neighbour may dip into a disc the axis ends in (a line into an arc's
    // centre disc): with the kinks as corners the axis is the exact one.
    FaceModel kinked = with_kinks_as_corners(face);
    const std::size_t kinks = kinked.corners.size() - face.corners.size();
    if (kinks == 0) throw;
    try {
      MedialAxis axis = compute_medial_axis(kinked);
      return {std::move(kinked), std::move(axis), kinks_as_corners_note("the medial axis", first.check(), kinks), true};
    } catch (const SelfCheckError&) {
      throw first;
    }
  }
}

}  // namespace mm
