#include "report/decomposition_report.hpp"

namespace mm {

namespace {

nlohmann::json point_list(const std::vector<Vec2>& points) {
  nlohmann::json list = nlohmann::json::array();
  for (const Vec2& p : points) list.push_back({p.x, p.y});
  return list;
}

nlohmann::json singularity_json(const DecomposedSingularity& s) {
  return {{"x", s.p.x}, {"y", s.p.y}, {"k", s.k}, {"fixed", s.fixed}, {"members", s.members}};
}

}  // namespace

nlohmann::json decomposition_report_json(const FaceModel& face, const Decomposition& d) {
  nlohmann::json blocks = nlohmann::json::array();
  for (const Block& b : d.blocks) {
    nlohmann::json corners = nlohmann::json::array();
    for (const BlockCorner& c : b.corners) corners.push_back({{"x", c.p.x}, {"y", c.p.y}, {"type", c.type}});
    nlohmann::json sides = nlohmann::json::array();
    for (const BlockSide& side : b.sides) {
      nlohmann::json pieces = nlohmann::json::array();
      for (const OutlinePiece& piece : side.pieces) {
        if (piece.split >= 0) {
          pieces.push_back({{"split", piece.split}, {"reversed", piece.reversed}});
        } else {
          pieces.push_back(
              {{"loop", piece.loop}, {"edge", piece.edge}, {"t_from", piece.t_from}, {"t_to", piece.t_to}});
        }
      }
      sides.push_back(pieces);
    }
    nlohmann::json singularity = nullptr;
    if (b.singularity >= 0) {
      const DecomposedSingularity& s = d.singularities[b.singularity];
      singularity = {{"x", s.p.x}, {"y", s.p.y}, {"k", s.k}};
    }
    blocks.push_back({{"kind", b.kind == BlockKind::Polygon ? "polygon" : "submap"},
                      {"sides", static_cast<int>(b.corners.size())},
                      {"boundary", point_list(b.outline)},
                      {"area", b.area},
                      {"singularity", singularity},
                      {"corners", corners},
                      {"side_pieces", sides}});
  }
  nlohmann::json splits = nlohmann::json::array();
  for (const Split& s : d.splits)
    splits.push_back({{"polyline", point_list(s.polyline)}, {"reason", split_reason_name(s.reason)}});
  nlohmann::json fixed = nlohmann::json::array(), all = nlohmann::json::array();
  for (const DecomposedSingularity& s : d.singularities) {
    all.push_back(singularity_json(s));
    if (s.fixed) fixed.push_back(singularity_json(s));
  }
  return {{"face", face.name},      {"face_area", face.area}, {"blocks", blocks},
          {"splits", splits},       {"fixed", fixed},         {"singularities", all},
          {"fallback", d.fallback}, {"notes", d.notes},       {"wrapped_holes", d.wrapped_holes}};
}

}  // namespace mm
