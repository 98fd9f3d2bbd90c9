#include "quality/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "boundary/face_model.hpp"

namespace mm {
namespace {

// Corner i of a quad: the edge to the next corner and the edge back to the
// previous one. Counter-clockwise, cross(next, prev) > 0 at a convex corner.
struct CornerEdges {
  Vec2 next;
  Vec2 prev;
};

CornerEdges corner_edges(const std::array<Vec2, 4>& p, int i) {
  return {p[(i + 1) % 4] - p[i], p[(i + 3) % 4] - p[i]};
}

double corner_scaled_jacobian(const CornerEdges& e) {
  const double lengths = norm(e.next) * norm(e.prev);
  // A collapsed edge leaves no area at the corner: as bad as inverted.
  return lengths > 0.0 ? cross(e.next, e.prev) / lengths : 0.0;
}

// Interior angle of a counter-clockwise quad, degrees in [0, 360): turning
// from the next edge to the previous one counter-clockwise. A clockwise
// (inverted) element shows reflex angles.
double corner_angle_degrees(const CornerEdges& e) {
  double a = std::atan2(cross(e.next, e.prev), dot(e.next, e.prev));
  if (a < 0.0) a += 2.0 * kPi;
  return a * 180.0 / kPi;
}

// A number that grows with corner_angle_degrees (a pseudo-angle in [0, 4)):
// the extreme angles of a large mesh are found without an atan2 per corner.
double angle_order(const CornerEdges& e) {
  const double x = dot(e.next, e.prev), y = cross(e.next, e.prev);
  const double size = std::abs(x) + std::abs(y);
  if (size == 0.0) return 0.0;
  return y >= 0.0 ? 1.0 - x / size : 3.0 + x / size;
}

double quad_scaled_jacobian(const std::array<Vec2, 4>& p) {
  double worst = 1.0;
  for (int i = 0; i < 4; ++i) worst = std::min(worst, corner_scaled_jacobian(corner_edges(p, i)));
  return worst;
}

double shoelace_area(const std::array<Vec2, 4>& p) {
  return 0.5 * (cross(p[0], p[1]) + cross(p[1], p[2]) + cross(p[2], p[3]) + cross(p[3], p[0]));
}

void check_mesh(const QuadMesh& mesh) {
  const int n = static_cast<int>(mesh.nodes.size());
  if (mesh.places.size() != mesh.nodes.size())
    throw InputError("quality: mesh has " + std::to_string(n) + " nodes but " + std::to_string(mesh.places.size()) +
                     " node places");
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    for (int v : mesh.quads[q]) {
      if (v < 0 || v >= n)
        throw InputError("quality: quad " + std::to_string(q) + " refers to node " + std::to_string(v) + " of " +
                         std::to_string(n));
    }
  }
}

}  // namespace

double scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return quad_scaled_jacobian({a, b, c, d});
}

QualityReport measure_quality(const QuadMesh& mesh) {
  check_mesh(mesh);
  QualityReport report;
  report.nodes = static_cast<int>(mesh.nodes.size());
  report.quads = static_cast<int>(mesh.quads.size());
  std::vector<int> elements_at(mesh.nodes.size(), 0);

  double sum_jacobian = 0.0;
  double min_jacobian = std::numeric_limits<double>::infinity();
  double min_order = std::numeric_limits<double>::infinity();
  double max_order = -std::numeric_limits<double>::infinity();
  CornerEdges min_corner{}, max_corner{};
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    const auto& quad = mesh.quads[q];
    const std::array<Vec2, 4> p{mesh.nodes[quad[0]], mesh.nodes[quad[1]], mesh.nodes[quad[2]], mesh.nodes[quad[3]]};
    double element_jacobian = 1.0;
    for (int i = 0; i < 4; ++i) {
      const CornerEdges e = corner_edges(p, i);
      element_jacobian = std::min(element_jacobian, corner_scaled_jacobian(e));
      const double order = angle_order(e);
      if (order < min_order) min_order = order, min_corner = e;
      if (order > max_order) max_order = order, max_corner = e;
      ++elements_at[quad[i]];
    }
    if (element_jacobian <= 0.0) ++report.inverted;
    if (element_jacobian < min_jacobian) {
      min_jacobian = element_jacobian;
      report.worst_element = static_cast<int>(q);
    }
    sum_jacobian += element_jacobian;
    report.area += shoelace_area(p);
  }
  if (!mesh.quads.empty()) {
    report.min_scaled_jacobian = min_jacobian;
    report.mean_scaled_jacobian = sum_jacobian / static_cast<double>(mesh.quads.size());
    report.min_angle = corner_angle_degrees(min_corner);
    report.max_angle = corner_angle_degrees(max_corner);
  }

  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const int elements = elements_at[n];
    if (elements == 0) continue;  // an order-2 mid-side node has no valence
    const NodePlace& place = mesh.places[n];
    const int expected = place.loop < 0 ? 4 : place.corner_elements;
    if (elements == expected) continue;
    const IrregularNode node{static_cast<int>(n), mesh.nodes[n], elements, expected};
    (place.loop < 0 ? report.irregular_interior : report.irregular_boundary).push_back(node);
  }
  return report;
}

QualityReport combine_quality(const std::vector<QualityReport>& faces, const std::vector<const QuadMesh*>& meshes,
                              const MergedMesh& merged) {
  if (faces.size() != meshes.size() || merged.node_of.size() != meshes.size())
    throw InputError("quality: " + std::to_string(faces.size()) + " face reports for " + std::to_string(meshes.size()) +
                     " meshes");
  QualityReport report;
  report.nodes = static_cast<int>(merged.nodes.size());
  report.quads = static_cast<int>(merged.quads.size());
  double sum_jacobian = 0.0;
  int first_quad = 0;
  bool any = false;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const QualityReport& q = faces[f];
    report.inverted += q.inverted;
    report.area += q.area;
    if (q.quads > 0) {
      if (!any || q.min_scaled_jacobian < report.min_scaled_jacobian) {
        report.min_scaled_jacobian = q.min_scaled_jacobian;
        report.worst_element = first_quad + q.worst_element;
      }
      report.min_angle = any ? std::min(report.min_angle, q.min_angle) : q.min_angle;
      report.max_angle = any ? std::max(report.max_angle, q.max_angle) : q.max_angle;
      sum_jacobian += q.mean_scaled_jacobian * q.quads;
      any = true;
    }
    first_quad += q.quads;
  }
  if (report.quads > 0) report.mean_scaled_jacobian = sum_jacobian / report.quads;

  std::vector<int> elements(merged.nodes.size(), 0);
  for (const auto& quad : merged.quads)
    for (int n : quad) ++elements[n];
  std::vector<int> expected(merged.nodes.size(), 0);
  std::vector<IrregularNode> first(merged.nodes.size());
  for (std::size_t f = 0; f < meshes.size(); ++f) {
    const QuadMesh& mesh = *meshes[f];
    std::vector<bool> corner(mesh.nodes.size(), false);
    for (const auto& quad : mesh.quads)
      for (int n : quad) corner[n] = true;
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
      if (!corner[n]) continue;  // order-2 mid-side nodes have no valence
      const int m = merged.node_of[f][n];
      const NodePlace& place = mesh.places[n];
      if (expected[m] == 0) first[m] = IrregularNode{m, mesh.nodes[n], 0, 0};
      expected[m] += place.loop < 0 ? 4 : place.corner_elements;
    }
  }
  for (std::size_t m = 0; m < merged.nodes.size(); ++m) {
    if (elements[m] == 0 || elements[m] == expected[m]) continue;
    IrregularNode node = first[m];
    node.elements = elements[m];
    node.expected = expected[m];
    (merged.on_boundary[m] ? report.irregular_boundary : report.irregular_interior).push_back(node);
  }
  return report;
}

}  // namespace mm
