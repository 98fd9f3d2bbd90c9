#include "medial_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace mm::test {

BoundaryProbe::BoundaryProbe(const FaceModel& face) : index_(face), chord_tolerance_(1e-4 * face.size) {
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    loops_.emplace_back();
    for (std::size_t ei = 0; ei < face.loops[li].edges.size(); ++ei) {
      const BoundaryEdge& e = face.loops[li].edges[ei];
      for (double t : sample_edge_parameters(e, chord_tolerance_)) {
        loops_.back().push_back({index_.place(static_cast<int>(li), static_cast<int>(ei), t), evaluate(e.curve, t).p});
      }
    }
  }
}

BoundaryPlace BoundaryProbe::nearest(Vec2 p) const {
  // Refine from every sample nearer than its neighbours on its edge: a long
  // straight edge has few samples, so a per-loop shortlist could miss it, and
  // one edge may pass p several times (a loop that is one closed curve), each
  // time with a nearest point of its own, only one of which the nearest
  // sample leads to.
  BoundaryPlace best;
  double best_distance = 1e300;
  const auto consider = [&](const BoundaryPlace& candidate) {
    if (distance(candidate.point, p) < best_distance) best = candidate, best_distance = distance(candidate.point, p);
  };
  for (const auto& loop : loops_) {
    for (std::size_t i = 0; i < loop.size();) {
      std::size_t j = i;
      while (j < loop.size() && loop[j].first.edge == loop[i].first.edge) ++j;
      for (std::size_t k = i; k < j; ++k) {
        const double d = distance(loop[k].second, p);
        if ((k > i && distance(loop[k - 1].second, p) < d) || (k + 1 < j && distance(loop[k + 1].second, p) < d))
          continue;
        consider(loop[k].first);
        consider(nearest_on_run(index_, loop[k].first, p));
      }
      i = j;
    }
  }
  return best;
}

bool BoundaryProbe::inside(Vec2 p) const {
  bool in = false;  // even-odd rule on the fine polylines
  double to_chords = std::numeric_limits<double>::infinity();
  for (const auto& loop : loops_) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 a = loop[i].second, b = loop[(i + 1) % loop.size()].second;
      if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
      const Vec2 d = b - a;
      const double u = dot(d, d) > 0.0 ? std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0) : 0.0;
      to_chords = std::min(to_chords, distance(p, a + u * d));
    }
  }
  if (to_chords > 2 * chord_tolerance_) return in;
  // Within the chords' sagitta of a curve they may put p on the wrong side
  // (a fine mesh has element centres that near): away from an edge's ends
  // the side of the exact nearest point decides, the material lying on the
  // left of every loop.
  const BoundaryPlace b = nearest(p);
  const BoundaryEdge& e = index_.edge(b.loop, b.edge);
  const double from_ends = std::min(std::abs(b.t - e.t_start), std::abs(b.t - e.t_end));
  if (from_ends > 1e-9 * std::abs(e.t_end - e.t_start)) return cross(edge_tangent(e, b.t), p - b.point) > 0.0;
  return in;
}

std::vector<const MedialVertex*> of_kind(const MedialAxis& axis, MedialVertexKind kind) {
  std::vector<const MedialVertex*> result;
  for (const auto& v : axis.vertices)
    if (v.kind == kind) result.push_back(&v);
  return result;
}

::testing::AssertionResult medial_axis_is_valid(const FaceModel& face, const MedialAxis& axis, double tolerance) {
  // No point can be more exact than the boundary: add the file's own tolerance
  // (a real part may leave gaps of that size between its edges).
  const double tol = tolerance * face.size + face.tolerance;
  const BoundaryProbe probe(face);
  std::ostringstream problems;
  int count = 0;
  const auto name = [](const BoundaryPlace& b) {
    return "loop " + std::to_string(b.loop) + " edge " + std::to_string(b.edge) + " t " + std::to_string(b.t);
  };
  const auto check_point = [&](Vec2 p, double r, const std::vector<BoundaryPlace>& places, const std::string& what) {
    if (count > 5) return;
    std::vector<Vec2> touches;
    for (const BoundaryPlace& b : places) touches.push_back(b.point);
    const BoundaryPlace nearest = probe.nearest(p);
    const double d = distance(nearest.point, p);
    if (std::abs(d - r) > tol) {
      problems << what << " at (" << p.x << ", " << p.y << "): r = " << r << " but the boundary is " << d << " away at "
               << name(nearest) << "; touches:";
      for (const BoundaryPlace& b : places) problems << " [" << name(b) << "]";
      problems << "\n";
      ++count;
    }
    if (r > tol && !probe.inside(p)) {
      problems << what << " at (" << p.x << ", " << p.y << ") is outside the face\n";
      ++count;
    }
    for (const Vec2& t : touches) {
      if (std::abs(distance(t, p) - r) > tol) {
        problems << what << " at (" << p.x << ", " << p.y << "): touching point (" << t.x << ", " << t.y << ") is "
                 << distance(t, p) << " away, r = " << r << "\n";
        ++count;
      }
    }
  };
  for (const MedialVertex& v : axis.vertices) {
    check_point(v.p, v.r, v.touches, medial_vertex_kind_name(v.kind));
    if (v.kind == MedialVertexKind::Flare) {
      bool at_convex_corner = false;
      for (const Corner& c : face.corners) at_convex_corner |= distance(c.position, v.p) <= tol && c.angle < kPi;
      if (!at_convex_corner) problems << "flare at (" << v.p.x << ", " << v.p.y << ") is not at a convex corner\n";
    }
  }
  for (const MedialEdge& e : axis.edges) {
    for (const MedialPoint& p : e.points) check_point(p.p, p.r, {p.left, p.right}, "edge point");
  }
  // Topology: one component, cycle rank = holes (a loop with no vertex counts as one vertex).
  std::vector<int> parent(axis.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  int vertices = static_cast<int>(axis.vertices.size()), components = vertices;
  for (const MedialEdge& e : axis.edges) {
    if (e.from < 0) {
      ++vertices, ++components;
      continue;
    }
    if (find(e.from) != find(e.to)) parent[find(e.from)] = find(e.to), --components;
  }
  const int rank = static_cast<int>(axis.edges.size()) - vertices + components;
  if (components != 1) problems << "the axis has " << components << " components\n";
  if (rank != face.holes()) problems << "the axis has " << rank << " cycles for " << face.holes() << " holes\n";
  const std::string text = problems.str();
  if (text.empty()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << face.name << ":\n" << text;
}

}  // namespace mm::test
