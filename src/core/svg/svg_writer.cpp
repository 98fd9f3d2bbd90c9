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

void SvgCanvas::text(Vec2 p, const std::string& label, double size_px, const std::string& style) {
  const Vec2 q = map(p);
  body_ << "<text x=\"" << q.x << "\" y=\"" << q.y << "\" font-family=\"sans-serif\" font-size=\"" << size_px
        << "\" style=\"" << style << "\">" << label << "</text>\n";
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

void draw_face(SvgCanvas& canvas, const FaceModel& face) {
  std::vector<std::vector<Vec2>> loops;
  for (const Loop& loop : face.loops) loops.push_back(sample_loop(loop, 0.5 / canvas.pixels_per_unit()));
  canvas.region(loops, "fill:#e8eef7;stroke:#333;stroke-width:1.5");
  for (const Corner& c : face.corners) {
    canvas.dot(c.position, 5, std::string("fill:") + kCornerColours[c.nc] + ";stroke:black;stroke-width:0.5");
  }
  // Legend under the picture, in face coordinates just below the bounding box.
  const Box box = bounding_box(face);
  const double step = 70.0 / canvas.pixels_per_unit();
  const Vec2 origin{box.min.x, box.min.y - 22.0 / canvas.pixels_per_unit()};
  for (int nc = 0; nc <= 4; ++nc) {
    const Vec2 at{origin.x + nc * step, origin.y};
    canvas.dot(at, 5, std::string("fill:") + kCornerColours[nc] + ";stroke:black;stroke-width:0.5");
    canvas.text({at.x + 8.0 / canvas.pixels_per_unit(), at.y - 4.0 / canvas.pixels_per_unit()},
                "nc=" + std::to_string(nc), 12, "fill:#333");
  }
}

}  // namespace mm
