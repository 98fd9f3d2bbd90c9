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
