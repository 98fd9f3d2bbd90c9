#include "report/medial_report.hpp"

namespace mm {

nlohmann::json medial_report_json(const MedialAxis& axis) {
  nlohmann::json vertices = nlohmann::json::array();
  for (const MedialVertex& v : axis.vertices) {
    vertices.push_back({{"x", v.p.x}, {"y", v.p.y}, {"r", v.r}, {"kind", medial_vertex_kind_name(v.kind)}});
  }
  nlohmann::json edges = nlohmann::json::array();
  for (const MedialEdge& e : axis.edges) {
    nlohmann::json polyline = nlohmann::json::array();
    for (const MedialPoint& p : e.points) polyline.push_back({p.p.x, p.p.y, p.r});
    edges.push_back({{"from", e.from}, {"to", e.to}, {"polyline", polyline}});
  }
  return {{"vertices", vertices}, {"edges", edges}};
}

}  // namespace mm
