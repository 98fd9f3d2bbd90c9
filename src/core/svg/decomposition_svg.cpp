#include <algorithm>

#include "geometry/polygon.hpp"
#include "svg/svg_writer.hpp"

namespace mm {

namespace {

// Pale fills that tell neighbouring blocks apart.
const char* const kBlockFills[8] = {"#c6dbef", "#c7e9c0", "#fdd0a2", "#dadaeb",
                                    "#fcbba1", "#d9f0a3", "#fde0ef", "#e5f5f9"};

// A point well inside the outline for the label: the best of a grid.
Vec2 label_point(const std::vector<Vec2>& outline) {
  const Box box = bounding_box(outline);
  Vec2 best = outline.front();
  double clearance = -1.0;
  const int n = 24;
  for (int i = 1; i < n; ++i) {
    for (int j = 1; j < n; ++j) {
      const Vec2 p{box.min.x + (box.max.x - box.min.x) * i / n, box.min.y + (box.max.y - box.min.y) * j / n};
      if (!inside_polygon(outline, p)) continue;
      const double c = distance_to_polygon(outline, p);
      if (c > clearance) clearance = c, best = p;
    }
  }
  return best;
}

}  // namespace

void draw_decomposition(SvgCanvas& canvas, const FaceModel& face, const MedialAxis& axis, const Decomposition& d) {
  const double unit = 1.0 / canvas.pixels_per_unit();
  for (std::size_t i = 0; i < d.blocks.size(); ++i) {
    canvas.polyline(d.blocks[i].outline, true,
                    std::string("fill:") + kBlockFills[i % 8] + ";stroke:none;fill-opacity:0.9");
  }
  for (const MedialEdge& e : axis.edges) {
    std::vector<Vec2> pts;
    for (const MedialPoint& p : e.points) pts.push_back(p.p);
    canvas.polyline(pts, false, "fill:none;stroke:#999;stroke-width:1;stroke-dasharray:4 3");
  }
  std::vector<std::vector<Vec2>> loops;
  for (const Loop& loop : face.loops) loops.push_back(sample_loop(loop, 0.5 * unit));
  canvas.region(loops, "fill:none;stroke:#333;stroke-width:1.5");
  for (const Split& s : d.splits) canvas.polyline(s.polyline, false, "fill:none;stroke:#111;stroke-width:2.2");
  for (const Block& b : d.blocks) {
    if (b.outline.size() < 3) continue;
    for (const BlockCorner& c : b.corners) {
      if (c.type != 1) canvas.dot(c.p, 2.5, "fill:#555");
    }
    const std::string label = b.kind == BlockKind::Polygon ? std::to_string(b.corners.size()) : "submap";
    const Vec2 at = label_point(b.outline);
    canvas.text(at - Vec2{3.5 * unit * label.size(), -5 * unit}, label, 14, "fill:#222");
  }
  for (const DecomposedSingularity& s : d.singularities) {
    const std::string colour = s.k > 0 ? "#d62728" : "#1f4fd6";
    canvas.dot(s.p, 5.5, "fill:" + colour + ";stroke:black;stroke-width:0.8");
    if (s.fixed) canvas.dot(s.p, 9, "fill:none;stroke:" + colour + ";stroke-width:1.5");
    canvas.text(s.p + Vec2{8 * unit, 6 * unit}, (s.k > 0 ? "+" : "") + std::to_string(s.k), 13,
                "fill:" + colour + ";font-weight:bold");
  }
  draw_legend(canvas, face, {{"#111", "split"}, {"#d62728", "k>0"}, {"#1f4fd6", "k<0"}, {"#ffffff", "ringed: fixed"}});
}

}  // namespace mm
