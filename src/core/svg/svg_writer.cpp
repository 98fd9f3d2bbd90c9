#include "svg/svg_writer.hpp"

#include <algorithm>
#include <fstream>

namespace mm {

SvgCanvas::SvgCanvas(Box box, double width) : box_(box), width_(width), margin_(0.05 * width) {
  const double w = std::max(box.max.x - box.min.x, 1e-300);
  const double h = std::max(box.max.y - box.min.y, 1e-300);
  scale_ = (width - 2 * margin_) / w;
  height_ = h * scale_ + 2 * margin_ + 30;  // room for a legend line
}

Vec2 SvgCanvas::map(Vec2 p) const {
  return {margin_ + (p.x - box_.min.x) * scale_, margin_ + (box_.max.y - p.y) * scale_};
}

void SvgCanvas::polyline(const std::vector<Vec2>& points, bool closed, const std::string& style) {
  body_ << "<path d=\"";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 q = map(points[i]);
    body_ << (i == 0 ? "M" : "L") << q.x << ' ' << q.y << ' ';
  }
  body_ << (closed ? "Z" : "") << "\" style=\"" << style << "\"/>\n";
}

void SvgCanvas::region(const std::vector<std::vector<Vec2>>& loops, const std::string& style) {
  body_ << "<path fill-rule=\"evenodd\" d=\"";
  for (const auto& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 q = map(loop[i]);
      body_ << (i == 0 ? "M" : "L") << q.x << ' ' << q.y << ' ';
    }
    body_ << "Z ";
  }
  body_ << "\" style=\"" << style << "\"/>\n";
}

void SvgCanvas::dot(Vec2 p, double radius_px, const std::string& style) {
  const Vec2 q = map(p);
  body_ << "<circle cx=\"" << q.x << "\" cy=\"" << q.y << "\" r=\"" << radius_px << "\" style=\"" << style << "\"/>\n";
}

namespace {
std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}
}  // namespace

void SvgCanvas::text(Vec2 p, const std::string& label, double size_px, const std::string& style) {
  const Vec2 q = map(p);
  body_ << "<text x=\"" << q.x << "\" y=\"" << q.y << "\" font-family=\"sans-serif\" font-size=\"" << size_px
        << "\" style=\"" << style << "\">" << escaped(label) << "</text>\n";
}

std::string SvgCanvas::str() const {
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_ << "\" height=\"" << height_
      << "\" viewBox=\"0 0 " << width_ << ' ' << height_ << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << body_.str() << "</svg>\n";
  return out.str();
}

void SvgCanvas::save(const std::string& path) const {
  std::ofstream file(path);
  file << str();
  if (!file) throw InputError(path + ": cannot write the SVG file");
}

namespace {
// One colour per corner type nc = 0..4.
const char* const kCornerColours[5] = {"#d62728", "#ff7f0e", "#2ca02c", "#1f77b4", "#9467bd"};
}  // namespace

void draw_legend(SvgCanvas& canvas, const FaceModel& face,
                 const std::vector<std::pair<std::string, std::string>>& items) {
  const Box box = bounding_box(face);
  const double unit = 1.0 / canvas.pixels_per_unit();
  double x = box.min.x;
  const double y = box.min.y - 22.0 * unit;
  for (const auto& [colour, label] : items) {
    canvas.dot({x, y}, 5, "fill:" + colour + ";stroke:black;stroke-width:0.5");
    canvas.text({x + 8.0 * unit, y - 4.0 * unit}, label, 12, "fill:#333");
    x += (24.0 + 8.0 * label.size()) * unit;
  }
}

void draw_face(SvgCanvas& canvas, const FaceModel& face) {
  std::vector<std::vector<Vec2>> loops;
  for (const Loop& loop : face.loops) loops.push_back(sample_loop(loop, 0.5 / canvas.pixels_per_unit()));
  canvas.region(loops, "fill:#e8eef7;stroke:#333;stroke-width:1.5");
}

void draw_corners(SvgCanvas& canvas, const FaceModel& face) {
  for (const Corner& c : face.corners) {
    canvas.dot(c.position, 5, std::string("fill:") + kCornerColours[c.nc] + ";stroke:black;stroke-width:0.5");
  }
  std::vector<std::pair<std::string, std::string>> legend;
  for (int nc = 0; nc <= 4; ++nc) legend.emplace_back(kCornerColours[nc], "nc=" + std::to_string(nc));
  draw_legend(canvas, face, legend);
}

namespace {
const char* vertex_colour(MedialVertexKind kind) {
  switch (kind) {
    case MedialVertexKind::Junction: return "#d62728";
    case MedialVertexKind::Flare: return "#2ca02c";
    case MedialVertexKind::FiniteContact: return "#1f77b4";
    case MedialVertexKind::CurvatureContact: return "#ff7f0e";
  }
  return "black";
}
}  // namespace

void draw_medial_axis(SvgCanvas& canvas, const FaceModel& face, const MedialAxis& axis) {
  for (const MedialEdge& e : axis.edges) {
    std::vector<Vec2> pts;
    for (const MedialPoint& p : e.points) pts.push_back(p.p);
    canvas.polyline(pts, false, "fill:none;stroke:#444;stroke-width:1.5");
  }
  for (const MedialVertex& v : axis.vertices) {
    canvas.dot(v.p, 4.5, std::string("fill:") + vertex_colour(v.kind) + ";stroke:black;stroke-width:0.5");
  }
  std::vector<std::pair<std::string, std::string>> legend;
  for (MedialVertexKind kind : {MedialVertexKind::Junction, MedialVertexKind::Flare, MedialVertexKind::FiniteContact,
                                MedialVertexKind::CurvatureContact}) {
    legend.emplace_back(vertex_colour(kind), medial_vertex_kind_name(kind));
  }
  draw_legend(canvas, face, legend);
}

namespace {
// Flow types n = 0, 1, 2 and anything beyond (possible only next to cusps).
const char* const kFlowColours[4] = {"#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd"};
}  // namespace

void draw_mesh_flow(SvgCanvas& canvas, const FaceModel& face, const MeshFlow& flow,
                    const std::vector<SingularityMark>& marks) {
  for (const FlowRun& run : flow.runs) {
    canvas.polyline(run.points, false,
                    std::string("fill:none;stroke-width:2.5;stroke:") + kFlowColours[std::min(run.n, 3)]);
  }
  const double unit = 1.0 / canvas.pixels_per_unit();
  for (const SingularityMark& m : marks) {
    const std::string colour = m.k > 0 ? "#d62728" : "#1f4fd6";
    canvas.dot(m.p, 6, "fill:" + colour + ";stroke:black;stroke-width:0.8");
    canvas.text(m.p + Vec2{8 * unit, 6 * unit}, (m.k > 0 ? "+" : "") + std::to_string(m.k), 14,
                "fill:" + colour + ";font-weight:bold");
  }
  draw_legend(canvas, face,
              {{kFlowColours[0], "n=0"},
               {kFlowColours[1], "n=1"},
               {kFlowColours[2], "n=2"},
               {"#d62728", "k>0"},
               {"#1f4fd6", "k<0"}});
}

}  // namespace mm
