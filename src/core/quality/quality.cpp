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

constexpr MeasureInfo kMeasures[kMeasureCount] = {
    {"scaled_jacobian", true, &QuadMeasures::scaled_jacobian},
    {"shape", true, &QuadMeasures::shape},
    {"edge_ratio", false, &QuadMeasures::edge_ratio},
    {"aspect_ratio", false, &QuadMeasures::aspect_ratio},
    {"skew", false, &QuadMeasures::skew},
    {"taper", false, &QuadMeasures::taper},
    {"stretch", true, &QuadMeasures::stretch},
    {"condition", false, &QuadMeasures::condition},
};

Vec2 centroid(const std::array<Vec2, 4>& p) {
  return 0.25 * (p[0] + p[1] + p[2] + p[3]);
}

// Whether value a is worse than b by measure m.
bool worse(const MeasureInfo& m, double a, double b) {
  return m.higher_is_better ? a < b : a > b;
}

// Keeps the kWorstListed elements of least shape, worst first.
void keep_worst(std::vector<WorstElement>& worst, const WorstElement& candidate) {
  const auto by_shape = [](const WorstElement& a, const WorstElement& b) {
    return a.measures.shape < b.measures.shape;
  };
  if (static_cast<int>(worst.size()) == kWorstListed && !by_shape(candidate, worst.back())) return;
  worst.insert(std::upper_bound(worst.begin(), worst.end(), candidate, by_shape), candidate);
  if (static_cast<int>(worst.size()) > kWorstListed) worst.pop_back();
}

// Adds one element's measures to the report's summaries and counts (means
// are sums until finish_measures).
void add_measures(QualityReport& report, int element, Vec2 at, const QuadMeasures& m) {
  for (int k = 0; k < kMeasureCount; ++k) {
    const MeasureInfo& info = kMeasures[k];
    MeasureSummary& summary = report.measures[k];
    const double value = m.*info.value;
    if (summary.worst_element < 0) {
      summary.min = summary.max = value;
      summary.worst_element = element, summary.worst_at = at;
    } else {
      const bool worst = worse(info, value, info.higher_is_better ? summary.min : summary.max);
      summary.min = std::min(summary.min, value);
      summary.max = std::max(summary.max, value);
      if (worst) summary.worst_element = element, summary.worst_at = at;
    }
    summary.mean += value;
  }
  if (m.shape < kPoorShape) ++report.poor_shape;
  if (m.edge_ratio > kNeedleEdgeRatio) ++report.needles;
  if (m.edge_ratio > kStretchedEdgeRatio) ++report.stretched;
  if (m.scaled_jacobian < kPoorScaledJacobian) ++report.poor_scaled_jacobian;
  keep_worst(report.worst_elements, WorstElement{element, at, m});
}

void finish_measures(QualityReport& report) {
  if (report.quads == 0) return;
  for (MeasureSummary& summary : report.measures) summary.mean /= report.quads;
}

}  // namespace

const MeasureInfo& measure_info(Measure m) {
  return kMeasures[static_cast<int>(m)];
}

double scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return quad_scaled_jacobian({a, b, c, d});
}

QualityReport measure_quality(const QuadMesh& mesh, double size) {
  check_mesh(mesh);
  QualityReport report;
  report.size = size > 0.0 ? size : 0.0;
  int sizes_in_range = 0;
  report.min_relative_size = std::numeric_limits<double>::infinity();
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
    const QuadMeasures measures = measure_quad(p);
    report.area += measures.area;
    add_measures(report, static_cast<int>(q), centroid(p), measures);
    if (mesh.order() == 2) {
      const auto& mid = mesh.midside[q];
      const std::array<Vec2, 8> p8{
          p[0], p[1], p[2], p[3], mesh.nodes[mid[0]], mesh.nodes[mid[1]], mesh.nodes[mid[2]], mesh.nodes[mid[3]]};
      report.min_jacobian_ratio = std::min(report.min_jacobian_ratio, jacobian_ratio(p8));
    }
    if (report.size > 0.0) {
      const double relative = std::sqrt(std::max(0.0, measures.area)) / report.size;
      report.min_relative_size = std::min(report.min_relative_size, relative);
      report.max_relative_size = std::max(report.max_relative_size, relative);
      report.mean_relative_size += relative;
      if (relative >= 0.5 && relative <= 1.5) ++sizes_in_range;
    }
  }
  finish_measures(report);
  if (report.size > 0.0 && report.quads > 0) {
    report.mean_relative_size /= report.quads;
    report.sizes_in_range = static_cast<double>(sizes_in_range) / report.quads;
  } else {
    report.min_relative_size = 0.0;
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
  int sized_quads = 0;
  bool any = false;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const QualityReport& q = faces[f];
    report.inverted += q.inverted;
    report.area += q.area;
    report.poor_shape += q.poor_shape;
    report.needles += q.needles;
    report.stretched += q.stretched;
    report.poor_scaled_jacobian += q.poor_scaled_jacobian;
    report.min_jacobian_ratio = std::min(report.min_jacobian_ratio, q.min_jacobian_ratio);
    for (WorstElement w : q.worst_elements) {
      w.element += first_quad;
      keep_worst(report.worst_elements, w);
    }
    if (q.quads > 0) {
      for (int k = 0; k < kMeasureCount; ++k) {
        const MeasureSummary& from = q.measures[k];
        MeasureSummary& to = report.measures[k];
        const MeasureInfo& info = kMeasures[k];
        const bool first = to.worst_element < 0;
        if (first ||
            worse(info, info.higher_is_better ? from.min : from.max, info.higher_is_better ? to.min : to.max)) {
          to.worst_element = first_quad + from.worst_element;
          to.worst_at = from.worst_at;
        }
        to.min = first ? from.min : std::min(to.min, from.min);
        to.max = first ? from.max : std::max(to.max, from.max);
        to.mean += from.mean * q.quads;
      }
      if (q.size > 0.0) {
        const bool first = sized_quads == 0;
        report.size = first ? q.size : std::min(report.size, q.size);
        report.min_relative_size =
            first ? q.min_relative_size : std::min(report.min_relative_size, q.min_relative_size);
        report.max_relative_size = std::max(report.max_relative_size, q.max_relative_size);
        report.mean_relative_size += q.mean_relative_size * q.quads;
        report.sizes_in_range += q.sizes_in_range * q.quads;
        sized_quads += q.quads;
      }
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
  finish_measures(report);
  if (sized_quads > 0) {
    report.mean_relative_size /= sized_quads;
    report.sizes_in_range /= sized_quads;
  }

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
