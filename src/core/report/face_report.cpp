#include "report/face_report.hpp"

#include <cstdio>
#include <sstream>

namespace mm {

nlohmann::json face_report_json(const FaceModel& face) {
  nlohmann::json edges = nlohmann::json::array();
  for (const Loop& loop : face.loops) {
    for (const BoundaryEdge& edge : loop.edges) {
      edges.push_back({{"type", curve_type_name(curve_type(edge.curve))}, {"length", edge_length(edge)}});
    }
  }
  nlohmann::json corners = nlohmann::json::array();
  for (const Corner& c : face.corners) {
    corners.push_back({{"x", c.position.x}, {"y", c.position.y}, {"angle_deg", c.angle * 180.0 / kPi}, {"nc", c.nc}});
  }
  return {{"face", face.name},     {"area", face.area},
          {"diagonal", face.size}, {"holes", face.holes()},
          {"euler", face.euler()}, {"edges", edges},
          {"corners", corners},    {"predicted_sum_k", predicted_sum_k(face)}};
}

std::string face_report_table(const FaceModel& face) {
  std::ostringstream out;
  char line[256];
  out << face.name << "\n";
  std::snprintf(line, sizeof line, "  area %.10g   holes %d   euler %d   predicted sum of k %d\n", face.area,
                face.holes(), face.euler(), predicted_sum_k(face));
  out << line;
  out << "  edges\n      #  loop  type       length\n";
  int number = 0;
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    for (const BoundaryEdge& edge : face.loops[li].edges) {
      std::snprintf(line, sizeof line, "  %5d  %4zu  %-8s %12.6g\n", ++number, li + 1,
                    curve_type_name(curve_type(edge.curve)), edge_length(edge));
      out << line;
    }
  }
  out << "  corners\n      #  loop            x             y   angle (deg)  nc\n";
  number = 0;
  for (const Corner& c : face.corners) {
    std::snprintf(line, sizeof line, "  %5d  %4d  %12.6g  %12.6g  %12.4f  %2d\n", ++number, c.loop + 1, c.position.x,
                  c.position.y, c.angle * 180.0 / kPi, c.nc);
    out << line;
  }
  return out.str();
}

nlohmann::json frame_json(const Frame& frame) {
  return {{"origin", frame.origin}, {"x_dir", frame.x_dir}, {"y_dir", frame.y_dir}, {"normal", frame.normal}};
}

}  // namespace mm
