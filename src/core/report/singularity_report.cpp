#include "report/singularity_report.hpp"

namespace mm {

namespace {

nlohmann::json singularity_list(const std::vector<Singularity>& singularities) {
  nlohmann::json list = nlohmann::json::array();
  for (const Singularity& s : singularities) {
    list.push_back({{"x", s.p.x}, {"y", s.p.y}, {"k", s.k}, {"at", singularity_source_name(s.at)}, {"r", s.r}});
  }
  return list;
}

}  // namespace

nlohmann::json singularity_report_json(const FaceModel& face, const MeshFlow& flow,
                                       const std::vector<SingularityGroup>* merged) {
  nlohmann::json runs = nlohmann::json::array();
  for (const FlowRun& run : flow.runs) {
    nlohmann::json polyline = nlohmann::json::array();
    for (Vec2 p : run.points) polyline.push_back({p.x, p.y});
    runs.push_back({{"edge", run.edge}, {"n", run.n}, {"polyline", polyline}});
  }
  nlohmann::json report = {{"predicted_sum_k", predicted_sum_k(face)}, {"flow", runs}};
  if (!merged) {
    report["singularities"] = singularity_list(flow.singularities);
    report["sum_k"] = flow.sum_k();
    return report;
  }
  nlohmann::json groups = nlohmann::json::array();
  int sum = 0;
  for (const SingularityGroup& g : *merged) {
    const char* at = g.members.size() == 1 ? singularity_source_name(flow.singularities[g.members[0]].at) : "merged";
    groups.push_back({{"x", g.p.x}, {"y", g.p.y}, {"k", g.k}, {"at", at}, {"members", g.members}});
    sum += g.k;
  }
  report["singularities"] = groups;
  report["sum_k"] = sum;
  report["unmerged"] = singularity_list(flow.singularities);
  return report;
}

}  // namespace mm
