#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
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

namespace {
using Point3 = std::array<double, 3>;

Point3 unit(const Point3& v) {
  const double n = std::hypot(v[0], v[1], v[2]);
  return n > 0.0 ? Point3{v[0] / n, v[1] / n, v[2] / n} : v;
}

double dot3(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Point3 cross3(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
}  // namespace

SvgCanvas draw_merged_mesh(const MergedMesh& mesh, const std::vector<std::vector<int>>& shared_chains,
                           const QualityReport& quality, double width) {
  // The view that sees the most edge-on face best: the mean normal (face on
  // for coplanar faces) or a diagonal of the octants (faces at right angles,
  // closed surfaces, whose normals cancel); ties go to the mean's side.
  Point3 mean{0, 0, 0};
  for (const Point3& n : mesh.normals)
    for (int k = 0; k < 3; ++k) mean[k] += n[k];
  std::vector<Point3> candidates;
  if (std::hypot(mean[0], mean[1], mean[2]) > 1e-6 * static_cast<double>(mesh.normals.size())) {
    mean = unit(mean);
    candidates.push_back(mean);
  }
  for (double x : {1.0, -1.0})
    for (double y : {-1.0, 1.0})
      for (double z : {1.0, -1.0}) candidates.push_back(unit({x, y, z}));
  Point3 view = candidates.front();
  double best = -1.0;
  for (const Point3& v : candidates) {
    double worst = 1.0;
    for (const Point3& n : mesh.normals) worst = std::min(worst, std::abs(dot3(n, v)));
    const double score = worst + 1e-3 * dot3(v, mean);
    if (score > best + 1e-9) {
      best = score;
      view = v;
    }
  }
  // Screen x: world X across the view (world Y when looking along X).
  Point3 across = std::abs(view[0]) < 0.99 ? Point3{1, 0, 0} : Point3{0, 1, 0};
  const double along = dot3(across, view);
  across = unit({across[0] - along * view[0], across[1] - along * view[1], across[2] - along * view[2]});
  const Point3 up = cross3(view, across);
  std::vector<Vec2> at;
  for (const Point3& p : mesh.nodes) at.push_back({dot3(p, across), dot3(p, up)});
  const Box box = at.empty() ? Box{{0, 0}, {1, 1}} : bounding_box(at);
  SvgCanvas canvas(box, width);
  // The elements furthest from the viewer first, so nearer faces cover them.
  std::vector<double> depth;
  for (const auto& quad : mesh.quads) {
    double d = 0.0;
    for (int n : quad) d += dot3(mesh.nodes[n], view);
    depth.push_back(d);
  }
  std::vector<std::size_t> order(mesh.quads.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  for (std::size_t e : order) {
    std::vector<Vec2> outline;
    for (int i = 0; i < 4; ++i) {
      outline.push_back(at[mesh.quads[e][i]]);
      if (mesh.order() == 2) outline.push_back(at[mesh.midside[e][i]]);
    }
    const int face = e < mesh.face_of_quad.size() ? mesh.face_of_quad[e] : 0;
    canvas.region({outline}, std::string("fill:") + kBlockFills[face % 8] + ";stroke:#555;stroke-width:0.6");
  }
  for (const auto& chain : shared_chains) {
    std::vector<Vec2> line;
    for (int n : chain) line.push_back(at[n]);
    canvas.polyline(line, false, "fill:none;stroke:#9467bd;stroke-width:2.5");
  }
  for (const IrregularNode& n : quality.irregular_boundary)
    canvas.dot(at[n.node], 3.5, "fill:#ff7f0e;stroke:black;stroke-width:0.5");
  for (const IrregularNode& n : quality.irregular_interior)
    canvas.dot(at[n.node], 5, std::string("fill:") + valence_colour(n.elements) + ";stroke:black;stroke-width:0.5");
  const double unit_px = 1.0 / canvas.pixels_per_unit();
  double x = box.min.x;
  for (const auto& [colour, label] : std::vector<std::pair<std::string, std::string>>{
           {valence_colour(3), "valence 3"}, {valence_colour(5), "valence 5"}, {"#9467bd", "shared pieces"}}) {
    canvas.dot({x, box.min.y - 22.0 * unit_px}, 5, "fill:" + colour + ";stroke:black;stroke-width:0.5");
    canvas.text({x + 8.0 * unit_px, box.min.y - 26.0 * unit_px}, label, 12, "fill:#333");
    x += (24.0 + 8.0 * label.size()) * unit_px;
  }
  return canvas;
}

}  // namespace mm
