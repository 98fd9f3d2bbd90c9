#include "report/mesh_report.hpp"

namespace mm {

namespace {
nlohmann::json node_list(const std::vector<IrregularNode>& nodes) {
  nlohmann::json list = nlohmann::json::array();
  for (const IrregularNode& n : nodes) {
    list.push_back({{"x", n.p.x}, {"y", n.p.y}, {"elements", n.elements}, {"expected", n.expected}});
  }
  return list;
}
nlohmann::json measures_json(const QualityReport& quality) {
  nlohmann::json measures = nlohmann::json::object();
  for (int k = 0; k < kMeasureCount; ++k) {
    const MeasureSummary& m = quality.measures[k];
    measures[measure_info(static_cast<Measure>(k)).name] = {{"min", m.min},
                                                            {"mean", m.mean},
                                                            {"max", m.max},
                                                            {"worst_element", m.worst_element + 1},
                                                            {"worst_x", m.worst_at.x},
                                                            {"worst_y", m.worst_at.y}};
  }
  return measures;
}

nlohmann::json worst_json(const QualityReport& quality) {
  nlohmann::json list = nlohmann::json::array();
  for (const WorstElement& w : quality.worst_elements) {
    list.push_back({{"element", w.element + 1},
                    {"x", w.at.x},
                    {"y", w.at.y},
                    {"shape", w.measures.shape},
                    {"edge_ratio", w.measures.edge_ratio},
                    {"scaled_jacobian", w.measures.scaled_jacobian}});
  }
  return list;
}

nlohmann::json sizes_json(const QualityReport& quality) {
  if (quality.size <= 0.0) return nullptr;
  return {{"requested", quality.size},
          {"min", quality.min_relative_size},
          {"mean", quality.mean_relative_size},
          {"max", quality.max_relative_size},
          {"in_half_to_one_and_a_half", quality.sizes_in_range}};
}
}  // namespace

nlohmann::json mesh_report_json(const QualityReport& quality, int order) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, seconds] : quality.stage_seconds) stages[name] = seconds;
  return {{"nodes", quality.nodes},
          {"quads", quality.quads},
          {"order", order},
          {"triangles", quality.triangles},
          {"inverted", quality.inverted},
          {"min_scaled_jacobian", quality.min_scaled_jacobian},
          {"mean_scaled_jacobian", quality.mean_scaled_jacobian},
          {"min_angle", quality.min_angle},
          {"max_angle", quality.max_angle},
          {"worst_element", quality.worst_element + 1},
          {"irregular_interior", quality.irregular_interior.size()},
          {"irregular_boundary", quality.irregular_boundary.size()},
          {"irregular_interior_nodes", node_list(quality.irregular_interior)},
          {"irregular_boundary_nodes", node_list(quality.irregular_boundary)},
          {"measures", measures_json(quality)},
          {"counts",
           {{"shape_below_0.3", quality.poor_shape},
            {"edge_ratio_above_10", quality.needles},
            {"edge_ratio_above_5", quality.stretched},
            {"scaled_jacobian_below_0.3", quality.poor_scaled_jacobian}}},
          {"worst_elements", worst_json(quality)},
          {"min_jacobian_ratio", quality.min_jacobian_ratio},
          {"relative_sizes", sizes_json(quality)},
          {"area", quality.area},
          {"seconds", quality.seconds},
          {"stages", stages}};
}

nlohmann::json merged_mesh_report_json(const QualityReport& quality, const MergedMesh& mesh, int shared_edges) {
  nlohmann::json report = mesh_report_json(quality, mesh.order());
  const auto placed = [&](const std::vector<IrregularNode>& nodes) {
    nlohmann::json list = nlohmann::json::array();
    for (const IrregularNode& n : nodes) {
      const auto& p = mesh.nodes.at(n.node);
      list.push_back({{"node", n.node + 1},
                      {"x", p[0]},
                      {"y", p[1]},
                      {"z", p[2]},
                      {"elements", n.elements},
                      {"expected", n.expected}});
    }
    return list;
  };
  report["irregular_interior_nodes"] = placed(quality.irregular_interior);
  report["irregular_boundary_nodes"] = placed(quality.irregular_boundary);
  report["shared_edges"] = shared_edges;
  return report;
}

}  // namespace mm
