#include <string>

#include "svg/svg_writer.hpp"

namespace mm {

namespace {
const char* const kBlockFills[8] = {"#deebf7", "#e5f5e0", "#fee6ce", "#efedf5",
                                    "#fde0dd", "#f7fcb9", "#fde0ef", "#e0f3f8"};

const char* valence_colour(int valence) {
  if (valence <= 2) return "#08306b";
  if (valence == 3) return "#2171b5";
  if (valence == 5) return "#d62728";
  return "#7f0000";
}
}  // namespace

void draw_quad_mesh(SvgCanvas& canvas, const FaceModel& face, const Decomposition& decomposition, const QuadMesh& mesh,
                    const QualityReport& quality) {
  draw_face(canvas, face);
  const double width = canvas.pixels_per_unit() * face.size < 4000.0 ? 0.6 : 0.3;
  for (std::size_t e = 0; e < mesh.quads.size(); ++e) {
    std::vector<Vec2> outline;
    for (int i = 0; i < 4; ++i) {
      outline.push_back(mesh.nodes[mesh.quads[e][i]]);
      if (mesh.order() == 2) outline.push_back(mesh.nodes[mesh.midside[e][i]]);
    }
    const int block = e < mesh.block_of_quad.size() ? mesh.block_of_quad[e] : 0;
    canvas.region({outline},
                  std::string("fill:") + kBlockFills[block % 8] + ";stroke:#555;stroke-width:" + std::to_string(width));
  }
  for (const Split& s : decomposition.splits)
    canvas.polyline(s.polyline, false, "fill:none;stroke:#000;stroke-width:2");
  for (const Loop& loop : face.loops) {
    canvas.polyline(sample_loop(loop, 0.5 / canvas.pixels_per_unit()), true, "fill:none;stroke:#000;stroke-width:2");
  }
  for (const IrregularNode& n : quality.irregular_boundary) {
    canvas.dot(n.p, 3.5, "fill:#ff7f0e;stroke:black;stroke-width:0.5");
  }
  for (const IrregularNode& n : quality.irregular_interior) {
    canvas.dot(n.p, 5, std::string("fill:") + valence_colour(n.elements) + ";stroke:black;stroke-width:0.5");
  }
  draw_legend(canvas, face,
              {{valence_colour(3), "valence 3"},
               {valence_colour(5), "valence 5"},
               {valence_colour(6), "valence 6+"},
               {"#ff7f0e", "boundary node off its nc"},
               {"#000", "splits"}});
}

}  // namespace mm
