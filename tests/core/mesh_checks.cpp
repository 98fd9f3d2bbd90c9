#include "mesh_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "medial_checks.hpp"

namespace mm::test {

namespace {
std::string where(Vec2 p) {
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

struct EdgePiece {
  int loop = -1;
  int edge = -1;
  double ta = 0.0;
  double tb = 0.0;
};

// The edge a boundary side a -> b runs along, with the curve parameters of
// its ends, from the nodes' places. A node at a vertex has the place of one
// of the edges meeting there: on any edge, a node may stand for that edge's
// ends within the mesher's tolerance, or for its own place on its own edge.
// Of the edges where the side then runs forwards, the shortest piece of
// curve (a tiny edge between two corners is also the end of its neighbours;
// a closed edge starts and ends at its one vertex; an edge shorter than the
// tolerance, a blunt trailing edge, has both its ends at either node, as
// has the curve it closes). lengths: each edge's, per loop.
std::optional<EdgePiece> boundary_piece(const FaceModel& face, const QuadMesh& mesh,
                                        const std::vector<std::vector<double>>& lengths, int a, int b) {
  const NodePlace& pa = mesh.places[a];
  const NodePlace& pb = mesh.places[b];
  if (pa.loop < 0 || pa.loop != pb.loop) return std::nullopt;
  const Loop& loop = face.loops[pa.loop];
  const double close = std::max(10.0 * face.tolerance, 1e-5 * face.size);
  const auto params = [&](int edge, int n) {
    const NodePlace& place = mesh.places[n];
    const BoundaryEdge& e = loop.edges[edge];
    std::vector<double> ts;
    if (place.edge == edge) ts.push_back(place.t);
    if (place.face_corner)
      for (double t : {e.t_start, e.t_end})
        if (distance(edge_point(e, t).p, mesh.nodes[n]) <= close) ts.push_back(t);
    return ts;
  };
  std::optional<EdgePiece> best;
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < loop.edges.size(); ++k) {
    const BoundaryEdge& e = loop.edges[k];
    const double span = e.t_end - e.t_start;
    for (double ta : params(static_cast<int>(k), a))
      for (double tb : params(static_cast<int>(k), b)) {
        const double share = (tb - ta) / span;
        const double piece = share * lengths[pa.loop][k];
        if (share > 0.0 && piece < least) least = piece, best = EdgePiece{pa.loop, static_cast<int>(k), ta, tb};
      }
  }
  return best;
}
}  // namespace

std::vector<std::string> mesh_validity_problems(const FaceModel& face, const QuadMesh& mesh) {
  std::vector<std::string> problems;
  const auto problem = [&](const std::string& text) {
    if (problems.size() < 20) problems.push_back(text);
  };
  if (mesh.quads.empty()) problem("no elements");
  if (mesh.places.size() != mesh.nodes.size()) problem("nodes and places differ in number");
  std::map<std::pair<int, int>, int> sides;
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.quads.size(); ++e) {
    const auto& q = mesh.quads[e];
    for (int i = 0; i < 4; ++i) {
      const Vec2 p = mesh.nodes[q[i]];
      const double turn = cross(mesh.nodes[q[(i + 1) % 4]] - p, mesh.nodes[q[(i + 3) % 4]] - p);
      if (!(turn > 0.0)) problem("element " + std::to_string(e) + " is inverted at " + where(p));
      area += 0.5 * cross(p, mesh.nodes[q[(i + 1) % 4]]);
      ++sides[{std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}];
    }
  }
  // Two nodes on one point: a solver sees a crack or a collapsed element.
  // Sorted by x, only neighbours in x need comparing.
  std::vector<int> by_x(mesh.nodes.size());
  for (std::size_t n = 0; n < by_x.size(); ++n) by_x[n] = static_cast<int>(n);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return mesh.nodes[a].x < mesh.nodes[b].x; });
  const double same_point = 1e-7 * face.size;
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    for (std::size_t j = i + 1; j < by_x.size() && mesh.nodes[by_x[j]].x - mesh.nodes[by_x[i]].x <= same_point; ++j) {
      if (distance(mesh.nodes[by_x[i]], mesh.nodes[by_x[j]]) <= same_point)
        problem("nodes " + std::to_string(by_x[i]) + " and " + std::to_string(by_x[j]) + " are both at " +
                where(mesh.nodes[by_x[i]]));
    }
  }
  const BoundaryProbe probe(face);
  const double on_curve = 1e-7 * face.size;
  std::vector<bool> on_boundary(mesh.nodes.size(), false);
  double boundary_length = 0.0;
  for (const auto& [side, count] : sides) {
    const Vec2 a = mesh.nodes[side.first], b = mesh.nodes[side.second];
    if (count > 2) problem("a side at " + where(0.5 * (a + b)) + " is in " + std::to_string(count) + " elements");
    if (count == 1) {
      on_boundary[side.first] = on_boundary[side.second] = true;
      boundary_length += distance(a, b);
    }
  }
  // Straight sides cut chords off curved boundary: an element may reach
  // outside the exact face by at most the largest sagitta of its chords.
  double sagitta = 0.0;
  for (const auto& [side, count] : sides) {
    if (count == 1)
      sagitta = std::max(sagitta, probe.distance_to_boundary(0.5 * (mesh.nodes[side.first] + mesh.nodes[side.second])));
  }
  for (std::size_t e = 0; e < mesh.quads.size(); ++e) {
    Vec2 centre;
    for (int n : mesh.quads[e]) centre = centre + 0.25 * mesh.nodes[n];
    if (!probe.inside(centre) && probe.distance_to_boundary(centre) > sagitta + on_curve)
      problem("element " + std::to_string(e) + " has its centre outside the face at " + where(centre));
  }
  // An interior node in two elements has them share both its sides: one is flat there.
  std::vector<int> valence(mesh.nodes.size(), 0);
  for (const auto& q : mesh.quads)
    for (int n : q) ++valence[n];
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (!on_boundary[n] && valence[n] > 0 && valence[n] < 3)
      problem("interior node " + std::to_string(n) + " at " + where(mesh.nodes[n]) + " is in only " +
              std::to_string(valence[n]) + " elements");
  }
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (!on_boundary[n]) continue;
    const double off = probe.distance_to_boundary(mesh.nodes[n]);
    // A face's corner joins its edges' ends within the tolerance the face was read with.
    const bool at_corner = n < mesh.places.size() && mesh.places[n].face_corner;
    if (off > (at_corner ? std::max(on_curve, face.tolerance) : on_curve))
      problem("boundary node " + std::to_string(n) + " is " + std::to_string(off) + " off the boundary");
    if (mesh.places[n].loop < 0) problem("boundary node " + std::to_string(n) + " is not marked as on a curve");
  }
  // The boundary sides' chords cut off (or add) the area between each one
  // and its curve: computed exactly from where the nodes say they are on
  // their edges, the elements must cover the face less that.
  // Each boundary side in the direction of its quad (material on the left: the loop's direction).
  std::set<std::pair<int, int>> outer;
  for (const auto& [side, count] : sides)
    if (count == 1) outer.insert(side);
  std::vector<std::pair<int, int>> directed;
  for (const auto& q : mesh.quads)
    for (int i = 0; i < 4; ++i)
      if (outer.count({std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}))
        directed.emplace_back(q[i], q[(i + 1) % 4]);
  std::vector<std::vector<double>> lengths;
  for (const Loop& loop : face.loops) {
    lengths.emplace_back();
    for (const BoundaryEdge& e : loop.edges) lengths.back().push_back(edge_length(e));
  }
  double cut_off = 0.0;
  for (const auto& [a, b] : directed) {
    const auto piece = boundary_piece(face, mesh, lengths, a, b);
    if (!piece) {
      problem("the boundary side from " + where(mesh.nodes[a]) + " to " + where(mesh.nodes[b]) +
              " does not run along one edge");
      continue;
    }
    const BoundaryEdge& edge = face.loops[piece->loop].edges[piece->edge];
    const Vec2 pa = mesh.nodes[a], curve_b = edge_point(edge, piece->tb).p;
    cut_off += edge_area_integral(edge, piece->ta, piece->tb, pa) + 0.5 * cross(curve_b - pa, mesh.nodes[b] - curve_b);
  }
  // Vertex nodes sit within the face's tolerance of the snapped vertices its area runs through.
  int edges = 0;
  for (const Loop& loop : face.loops) edges += static_cast<int>(loop.edges.size());
  const double slack = std::max(10.0 * face.tolerance, 1e-5 * face.size);
  if (std::abs(area - (face.area - cut_off)) > 1e-9 * face.area + 2.0 * edges * slack * slack) {
    problem("the elements cover " + std::to_string(area) + ", the polygon of the boundary nodes " +
            std::to_string(face.area - cut_off) + " (the face " + std::to_string(face.area) + ")");
  }
  // Every boundary loop is covered: the mesh's boundary is as long as the face's, to the chordal error.
  double face_length = 0.0;
  for (const auto& loop : lengths)
    for (double length : loop) face_length += length;
  if (boundary_length > face_length * (1.0 + 1e-9) || boundary_length < 0.9 * face_length) {
    problem("the mesh's boundary is " + std::to_string(boundary_length) + " long, the face's " +
            std::to_string(face_length));
  }
  return problems;
}

std::string element_count_problem(const FaceModel& face, const QuadMesh& mesh, double size) {
  std::map<std::pair<int, int>, int> sides;
  for (const auto& q : mesh.quads) {
    for (int i = 0; i < 4; ++i) ++sides[{std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}];
  }
  const double expected = face.area / (size * size);
  const double quads = static_cast<double>(mesh.quads.size());
  // The boundary's own intervals (at least one per edge, at most 45 degrees
  // of turning each on curves) also set a count: a mapped square with b
  // boundary intervals has (b / 4)^2 quads, where small holes or thin arms
  // need more than area / H^2.
  int boundary_sides = 0;
  for (const auto& entry : sides) boundary_sides += entry.second == 1 ? 1 : 0;
  const double from_boundary = 0.0625 * boundary_sides * boundary_sides;
  if (expected > 20 && (quads < 0.4 * expected || quads > 4.0 * std::max(expected, from_boundary))) {
    return std::to_string(mesh.quads.size()) + " elements for area / H^2 = " + std::to_string(expected) + " and " +
           std::to_string(boundary_sides) + " boundary intervals";
  }
  return "";
}

std::vector<std::string> mesh_problems(const FaceModel& face, const QuadMesh& mesh, double size) {
  std::vector<std::string> problems = mesh_validity_problems(face, mesh);
  const std::string count = element_count_problem(face, mesh, size);
  if (!count.empty() && problems.size() < 20) problems.push_back(count);
  return problems;
}

int interior_irregularity(const QuadMesh& mesh) {
  std::vector<int> valence(mesh.nodes.size(), 0);
  for (const auto& q : mesh.quads)
    for (int n : q) ++valence[n];
  int sum = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    if (mesh.places[n].loop < 0 && valence[n] > 0) sum += std::abs(4 - valence[n]);
  }
  return sum;
}

}  // namespace mm::test
