#include "medial/voronoi_graph.hpp"

#include <algorithm>
#include <boost/polygon/point_data.hpp>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>
#include <cmath>
#include <unordered_map>

#include "medial/nearest.hpp"

namespace mm {
namespace {

namespace bp = boost::polygon;

// Largest nudge of a discretisation point off its curve, relative to the face size.
using IntPoint = bp::point_data<int>;
using IntSegment = bp::segment_data<int>;

// Boost.Polygon wants integer coordinates: the face is scaled so its extent
// spans about 2^29 units, far finer than any tolerance we work to.
struct IntegerGrid {
  Vec2 origin;
  double scale = 1.0;
  IntPoint to_int(Vec2 p) const {
    return IntPoint(static_cast<int>(std::lround((p.x - origin.x) * scale)),
                    static_cast<int>(std::lround((p.y - origin.y) * scale)));
  }
  Vec2 to_face(double x, double y) const { return {origin.x + x / scale, origin.y + y / scale}; }
};

Site site_of(const bp::voronoi_cell<double>& cell) {
  Site site;
  site.segment = static_cast<int>(cell.source_index());
  switch (cell.source_category()) {
    case bp::SOURCE_CATEGORY_SEGMENT_START_POINT: site.part = Site::kStart; break;
    case bp::SOURCE_CATEGORY_SEGMENT_END_POINT: site.part = Site::kEnd; break;
    default: site.part = Site::kSegment; break;
  }
  return site;
}

// Is point q (not on the boundary) on the material side of the site? For a
// segment: left of its line. For a vertex of the discretisation: left of both
// segments meeting there at a convex vertex, left of either at a reflex one,
// within rounding (a vertex's Voronoi cell lies in the material only where
// the boundary turns right, and is a sliver there when the turn is slight).
bool material_side(const VoronoiGraph& g, const Site& site, Vec2 q) {
  const BoundarySegment& s = g.segments[site.segment];
  if (site.part == Site::kSegment) return cross(s.p1 - s.p0, q - s.p0) > 0.0;
  const BoundarySegment& in = site.part == Site::kStart ? g.segments[s.previous] : s;
  const BoundarySegment& out = site.part == Site::kStart ? s : g.segments[s.next];
  const Vec2 v = site.part == Site::kStart ? s.p0 : s.p1;
  const Vec2 a = normalized(in.p1 - in.p0), b = normalized(out.p1 - out.p0), d = q - v;
  const double slack = -1e-9 * norm(d);
  if (cross(a, b) < 0.0) return cross(a, d) >= slack || cross(b, d) >= slack;
  return cross(a, d) >= slack && cross(b, d) >= slack;
}

// Chord parameters of an edge for the diagram. At a corner the end chords
// are cut short until they follow the curve's tangent to within a quarter of
// the corner's deviation from a straight angle, so that a nearly flat convex
// corner stays convex in the polygon (and keeps its flare) and a nearly flat
// reflex one stays reflex.
std::vector<double> chord_parameters(const FaceModel& face, int loop, int edge, const std::vector<double>& corner_slack,
                                     double chord_tolerance, double max_turn) {
  const BoundaryEdge& e = face.loops[loop].edges[edge];
  // A hole bounded by one closed curve curving away from the material (a
  // round bore) gives the diagram a plain fan of bisectors with no join where
  // the pairing could flip, so it can do with coarser chords (five times the
  // chord tolerance, twice the turning): fewer chords, a faster diagram. Holes
  // with fillets and joins keep the fine chords; the axis's self-check
  // rebuilds from finer chords should a coarse one mislead it.
  const bool closed_hole = loop > 0 && face.loops[loop].edges.size() == 1;
  const bool concave = closed_hole && curvature(e, 0.5 * (e.t_start + e.t_end)) < 0;
  std::vector<double> params = concave ? sample_edge_parameters(e, 5 * chord_tolerance, 2 * max_turn)
                                       : sample_edge_parameters(e, chord_tolerance, max_turn);
  if (curve_type(e.curve) == CurveType::Line) return params;
  const int count = static_cast<int>(face.loops[loop].edges.size());
  const auto chord_angle = [&](double t_end, double t_other) {
    const Vec2 tangent = edge_tangent(e, t_end);
    const Vec2 chord = evaluate_point(e.curve, t_other) - evaluate_point(e.curve, t_end);
    return std::abs(signed_angle(t_end == e.t_start ? tangent : -1.0 * tangent, chord));
  };
  const double start_limit = corner_slack[edge], end_limit = corner_slack[(edge + 1) % count];
  for (int i = 0; i < 40 && start_limit > 0 && chord_angle(params[0], params[1]) > start_limit; ++i) {
    params.insert(params.begin() + 1, 0.5 * (params[0] + params[1]));
  }
  for (int i = 0; i < 40 && end_limit > 0; ++i) {
    const std::size_t n = params.size();
    if (chord_angle(params[n - 1], params[n - 2]) <= end_limit) break;
    params.insert(params.end() - 1, 0.5 * (params[n - 2] + params[n - 1]));
  }
  return params;
}

}  // namespace

Vec2 site_point(const VoronoiGraph& graph, const Site& site, Vec2 near) {
  const BoundarySegment& s = graph.segments[site.segment];
  if (site.part == Site::kStart) return s.p0;
  if (site.part == Site::kEnd) return s.p1;
  const Vec2 d = s.p1 - s.p0;
  const double u = std::clamp(dot(near - s.p0, d) / dot(d, d), 0.0, 1.0);
  return s.p0 + u * d;
}

VoronoiGraph interior_voronoi_graph(const FaceModel& face, double chord_tolerance, double max_turn) {
  VoronoiGraph graph;
  const Box box = bounding_box(face);
  IntegerGrid grid{box.min, std::ldexp(1.0, 29) / std::max(box.max.x - box.min.x, box.max.y - box.min.y)};

  // Per loop vertex: how far a chord there may stray from the tangent (0: no limit).
  std::vector<std::vector<double>> corner_slack;
  for (const Loop& loop : face.loops) corner_slack.emplace_back(loop.edges.size(), 0.0);
  for (const Corner& c : face.corners) corner_slack[c.loop][c.vertex] = 0.25 * std::abs(kPi - c.angle);

  std::vector<IntSegment> input;
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    const std::size_t first = graph.segments.size();
    const auto& edges = face.loops[li].edges;
    for (std::size_t ei = 0; ei < edges.size(); ++ei) {
      const std::vector<double> params = chord_parameters(face, static_cast<int>(li), static_cast<int>(ei),
                                                          corner_slack[li], chord_tolerance, max_turn);
      const std::vector<Vec2> pts = edge_points(edges[ei], params);
      for (std::size_t k = 0; k + 1 < params.size(); ++k) {
        // Chords share their rounded end points, so a chord shorter than the
        // grid can be dropped without opening the loop.
        const IntPoint a = grid.to_int(pts[k]), b = grid.to_int(pts[k + 1]);
        if (a == b) continue;
        input.emplace_back(a, b);
        graph.segments.push_back({static_cast<int>(li), static_cast<int>(ei), params[k], params[k + 1],
                                  grid.to_face(a.x(), a.y()), grid.to_face(b.x(), b.y()), 0, 0});
      }
    }
    const std::size_t count = graph.segments.size() - first;
    for (std::size_t k = 0; k < count; ++k) {
      graph.segments[first + k].previous = static_cast<int>(first + (k + count - 1) % count);
      graph.segments[first + k].next = static_cast<int>(first + (k + 1) % count);
    }
  }

  bp::voronoi_diagram<double> diagram;
  bp::construct_voronoi(input.begin(), input.end(), &diagram);

  std::unordered_map<const bp::voronoi_vertex<double>*, int> vertex_ids;
  const auto vertex_id = [&](const bp::voronoi_vertex<double>* v) {
    const auto found = vertex_ids.find(v);
    if (found != vertex_ids.end()) return found->second;
    VoronoiVertex vertex;
    vertex.p = grid.to_face(v->x(), v->y());
    const auto* e = v->incident_edge();
    do {
      vertex.sites.push_back(site_of(*e->cell()));
      e = e->rot_next();
    } while (e != v->incident_edge());
    vertex.r = distance(vertex.p, site_point(graph, vertex.sites.front(), vertex.p));
    graph.vertices.push_back(vertex);
    vertex_ids.emplace(v, static_cast<int>(graph.vertices.size()) - 1);
    return static_cast<int>(graph.vertices.size()) - 1;
  };

  for (const auto& edge : diagram.edges()) {
    // Each edge appears twice (once per side); keep one, primary and finite.
    if (&edge > edge.twin() || !edge.is_primary() || !edge.is_finite()) continue;
    const Site left = site_of(*edge.cell()), right = site_of(*edge.twin()->cell());
    const Vec2 a = grid.to_face(edge.vertex0()->x(), edge.vertex0()->y());
    const Vec2 b = grid.to_face(edge.vertex1()->x(), edge.vertex1()->y());
    // Test the end farther from the boundary against a segment site if there
    // is one; between two points, the edge is inside if either's cell is.
    bool inside = false;
    if (left.part == Site::kSegment || right.part == Site::kSegment) {
      const Site& judge = left.part == Site::kSegment ? left : right;
      const double da = distance(a, site_point(graph, judge, a)), db = distance(b, site_point(graph, judge, b));
      inside = material_side(graph, judge, da > db ? a : b);
    } else {
      inside = material_side(graph, left, 0.5 * (a + b)) || material_side(graph, right, 0.5 * (a + b));
    }
    if (!inside) continue;
    graph.edges.push_back({vertex_id(edge.vertex0()), vertex_id(edge.vertex1()), left, right});
  }
  return graph;
}

}  // namespace mm
