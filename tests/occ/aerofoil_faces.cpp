#include "aerofoil_faces.hpp"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeSegment.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <cmath>
#include <stdexcept>

namespace mm::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kPerSide = 161;  // points per surface: 321 round a section

struct P2 {
  double x = 0.0, y = 0.0;
};

P2 operator+(P2 a, P2 b) {
  return {a.x + b.x, a.y + b.y};
}
P2 operator*(double s, P2 a) {
  return {s * a.x, s * a.y};
}

P2 turned(P2 p, double degrees) {
  const double a = degrees * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  return {c * p.x - s * p.y, s * p.x + c * p.y};
}

gp_Pnt point(P2 p, double scale) {
  return gp_Pnt(scale * p.x, scale * p.y, 0.0);
}

// Half thickness of the NACA form for thickness t (of the chord) at x; the
// original form leaves the trailing edge 0.0021 t / 0.2 open, the closed one
// (last coefficient -0.1036) shuts it.
double naca_thickness(double t, double x, bool closed) {
  return t / 0.2 *
         (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x -
          (closed ? 0.1036 : 0.1015) * x * x * x * x);
}

// Camber line height and slope at x of a 4- or 5-digit designation.
struct Camber {
  double y = 0.0, slope = 0.0;
};

Camber naca_camber(const std::string& digits, double x) {
  if (digits.size() == 4) {
    const double m = (digits[0] - '0') / 100.0, p = (digits[1] - '0') / 10.0;
    if (m == 0.0 || p == 0.0) return {};
    if (x < p) return {m / (p * p) * (2 * p * x - x * x), 2 * m / (p * p) * (p - x)};
    const double q = 1 - p;
    return {m / (q * q) * (1 - 2 * p + 2 * p * x - x * x), 2 * m / (q * q) * (p - x)};
  }
  // Standard (not reflexed) 5-digit camber lines for design lift 0.3, by the
  // camber position digit (Abbott & von Doenhoff, section 6.5): r and k1.
  static const double r_of[5] = {0.0580, 0.1260, 0.2025, 0.2900, 0.3910};
  static const double k1_of[5] = {361.4, 51.64, 15.957, 6.643, 3.230};
  const int position = digits[1] - '0';
  const double lift = (digits[0] - '0') / 2.0;  // design lift 0.15 L against the table's 0.3
  const double r = r_of[position - 1], k1 = k1_of[position - 1];
  if (x < r)
    return {lift * k1 / 6 * (x * x * x - 3 * r * x * x + r * r * (3 - r) * x),
            lift * k1 / 6 * (3 * x * x - 6 * r * x + r * r * (3 - r))};
  return {lift * k1 * r * r * r / 6 * (1 - x), -lift * k1 * r * r * r / 6};
}

void check_designation(const std::string& d) {
  bool digits = d.size() == 4 || d.size() == 5;
  for (char c : d) digits = digits && c >= '0' && c <= '9';
  const bool five_ok = d.size() != 5 || (d[1] >= '1' && d[1] <= '5' && d[2] == '0');
  if (!digits || !five_ok || std::stoi(d.substr(d.size() - 2)) < 1)
    throw std::invalid_argument("unknown NACA designation " + d);
}

Handle(Geom_BSplineCurve) interpolate(const std::vector<gp_Pnt>& points) {
  Handle(TColgp_HArray1OfPnt) array = new TColgp_HArray1OfPnt(1, static_cast<int>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) array->SetValue(static_cast<int>(i) + 1, points[i]);
  GeomAPI_Interpolate interpolation(array, false, 1e-12);
  interpolation.Perform();
  if (!interpolation.IsDone()) throw Standard_Failure("B-spline interpolation failed");
  return interpolation.Curve();
}

TopoDS_Wire wire_of(const std::vector<TopoDS_Edge>& edges) {
  BRepBuilderAPI_MakeWire wire;
  for (const TopoDS_Edge& e : edges) wire.Add(e);
  return wire.Wire();
}

// The section's outline, counter-clockwise: trailing edge, upper surface,
// leading edge, lower surface, back to the trailing edge; one B-spline,
// closed at the sharp trailing edge or closed by a straight edge there.
TopoDS_Wire section_wire(const AerofoilSection& s, double scale) {
  check_designation(s.digits);
  const double t = std::stoi(s.digits.substr(s.digits.size() - 2)) / 100.0;
  std::vector<P2> upper, lower;  // from the leading edge to the trailing edge
  for (int i = 0; i < kPerSide; ++i) {
    // Clustered at the leading edge only: points crowded at a sharp
    // trailing edge, where the surfaces meet at a few degrees, make the
    // interpolating B-spline overshoot and cross itself there.
    const double x = 1 - std::cos(0.5 * kPi * i / (kPerSide - 1));
    const Camber c = naca_camber(s.digits, x);
    const double h = naca_thickness(t, x, !s.blunt), theta = std::atan(c.slope);
    upper.push_back({x - h * std::sin(theta), c.y + h * std::cos(theta)});
    lower.push_back({x + h * std::sin(theta), c.y - h * std::cos(theta)});
  }
  std::vector<gp_Pnt> points;
  const auto add = [&](P2 p) {
    const P2 q = P2{s.x, s.y} + turned(s.chord * p, -s.angle);
    points.push_back(point(q, scale));
  };
  for (int i = kPerSide - 1; i >= 0; --i) add(upper[i]);
  for (int i = 1; i < kPerSide; ++i) add(lower[i]);
  if (!s.blunt) points.back() = points.front();
  const Handle(Geom_BSplineCurve) curve = interpolate(points);
  std::vector<TopoDS_Edge> edges{BRepBuilderAPI_MakeEdge(curve).Edge()};
  if (s.blunt) edges.push_back(BRepBuilderAPI_MakeEdge(GC_MakeSegment(points.back(), points.front()).Value()).Edge());
  return wire_of(edges);
}

TopoDS_Face face_with_holes(const TopoDS_Wire& outer, const std::vector<TopoDS_Wire>& holes) {
  BRepBuilderAPI_MakeFace face(outer, true);
  for (const TopoDS_Wire& hole : holes) face.Add(TopoDS::Wire(hole.Reversed()));
  return face.Face();
}

TopoDS_Wire far_field(double scale) {
  BRepBuilderAPI_MakePolygon box;
  for (P2 p : {P2{-4.5, -2}, P2{5.5, -2}, P2{5.5, 2}, P2{-4.5, 2}}) box.Add(point(p, scale));
  box.Close();
  return box.Wire();
}

double gap_between(const TopoDS_Wire& a, const TopoDS_Wire& b) {
  BRepExtrema_DistShapeShape distance(a, b);
  if (!distance.IsDone()) throw Standard_Failure("no distance between the elements");
  return distance.Value();
}

// The element moved from `from` along `direction` until its narrowest gap to
// `fixed` is `gap` (all in chords): bisection, the gap growing with the move
// once the two have come apart.
AerofoilSection placed_at_gap(AerofoilSection element, P2 direction, const TopoDS_Wire& fixed, double gap,
                              double scale) {
  const P2 from{element.x, element.y};
  const auto gap_at = [&](double move) {
    element.x = from.x + move * direction.x, element.y = from.y + move * direction.y;
    return gap_between(section_wire(element, scale), fixed) / scale;
  };
  double lo = 0.0, hi = 0.2;
  if (gap_at(lo) >= gap) throw std::invalid_argument("the element starts farther out than its gap");
  while (gap_at(hi) < gap) hi *= 2;
  for (int i = 0; i < 30 && hi - lo > 1e-4 * gap; ++i) (gap_at(0.5 * (lo + hi)) < gap ? lo : hi) = 0.5 * (lo + hi);
  gap_at(0.5 * (lo + hi));
  return element;
}

// Half thickness along a cascade blade, s from 0 (leading edge) to 1: the
// closed NACA form (sharp), or that form plus a quadratic and a cubic term
// that make it end at te_radius with zero slope, so that the arc round the
// trailing edge meets both sides tangentially.
double blade_thickness(const Cascade& c, double s) {
  const double base = naca_thickness(c.thickness, s, true);
  if (!c.rounded) return base;
  const double at_end = naca_thickness(c.thickness, 1.0, true);
  const double slope_at_end = c.thickness / 0.2 * (0.2969 * 0.5 - 0.1260 - 2 * 0.3516 + 3 * 0.2843 - 4 * 0.1036);
  const double rest = c.te_radius - at_end, d = -slope_at_end;
  const double alpha = 3 * rest - d, beta = d - 2 * rest;  // alpha + beta = rest, 2 alpha + 3 beta = d
  return base + alpha * s * s + beta * s * s * s;
}

}  // namespace

TopoDS_Face section_face(const AerofoilSection& section, double scale) {
  return face_with_holes(section_wire(section, scale), {});
}

TopoDS_Face far_field_face(const std::vector<AerofoilSection>& sections, double scale) {
  std::vector<TopoDS_Wire> holes;
  for (const AerofoilSection& s : sections) holes.push_back(section_wire(s, scale));
  return face_with_holes(far_field(scale), holes);
}

TopoDS_Face high_lift_face(const HighLift& layout, double scale) {
  AerofoilSection main{layout.main, layout.blunt, 0.8, 0.0, 0.0, 0.0};
  const TopoDS_Wire main_wire = section_wire(main, scale);
  // The slat starts with its trailing edge inside the main element's nose
  // and moves out forwards and up; the flap starts with its nose under the
  // main element's trailing edge and moves out backwards and down.
  AerofoilSection slat{layout.slat, layout.blunt, 0.15, 0.0, 0.0, -layout.slat_angle};
  const P2 slat_te = turned({0.15, 0.0}, layout.slat_angle);
  slat.x = 0.03 - slat_te.x, slat.y = 0.0 - slat_te.y;
  slat = placed_at_gap(slat, turned({-1.0, 0.0}, -50.0), main_wire, layout.gap, scale);
  AerofoilSection flap{layout.flap, layout.blunt, 0.3, 0.72, -0.01, layout.flap_angle};
  flap = placed_at_gap(flap, turned({1.0, 0.0}, -60.0), main_wire, layout.gap, scale);
  return face_with_holes(far_field(scale), {section_wire(slat, scale), main_wire, section_wire(flap, scale)});
}

TopoDS_Face cascade_face(const Cascade& c, double scale) {
  const double a = std::tan(c.inlet * kPi / 180.0), b = -std::tan(c.outlet * kPi / 180.0) - a;
  // The camber line in blade coordinates (chord along x), then in the passage.
  const auto camber = [&](double x) { return P2{x, x * (1 - x) * (a + b * x)}; };
  const auto camber_slope = [&](double x) { return a * (1 - 2 * x) + b * (2 * x - 3 * x * x); };
  const auto in_passage = [&](P2 p) { return turned(p, c.stagger); };
  const double x_end = c.rounded ? 1.0 - c.te_radius : 1.0;  // the trailing edge arc's centre
  std::vector<P2> upper, lower;
  for (int i = 0; i < kPerSide; ++i) {
    const double s = 1 - std::cos(0.5 * kPi * i / (kPerSide - 1)), x = s * x_end;  // as for the sections
    const double slope = camber_slope(x), h = blade_thickness(c, s);
    if (i > 0 && i + 1 < kPerSide && !(h > 0))
      throw std::invalid_argument("the blade's thickness vanishes before its trailing edge");
    const P2 normal = (1.0 / std::hypot(1.0, slope)) * P2{-slope, 1.0};
    upper.push_back(in_passage(camber(x) + h * normal));
    lower.push_back(in_passage(camber(x) + (-h) * normal));
  }
  std::vector<gp_Pnt> points;
  for (int i = kPerSide - 1; i >= 0; --i) points.push_back(point(upper[i], scale));
  for (int i = 1; i < kPerSide; ++i) points.push_back(point(lower[i], scale));
  if (!c.rounded) points.back() = points.front();
  std::vector<TopoDS_Edge> blade{BRepBuilderAPI_MakeEdge(interpolate(points)).Edge()};
  if (c.rounded) {
    const double slope = camber_slope(x_end);
    const P2 tangent = (1.0 / std::hypot(1.0, slope)) * P2{1.0, slope};
    const P2 tip = in_passage(camber(x_end) + c.te_radius * tangent);
    blade.push_back(
        BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(points.back(), point(tip, scale), points.front()).Value()).Edge());
  }
  // Periodic sides: the camber line carried on straight along its end
  // tangents to half a chord (axially) before and after the blade.
  const P2 lead = in_passage(camber(0.0)), trail = in_passage(camber(1.0));
  const P2 lead_dir = in_passage({1.0, camber_slope(0.0)}), trail_dir = in_passage({1.0, camber_slope(1.0)});
  if (lead_dir.x <= 0.3 * std::hypot(lead_dir.x, lead_dir.y) ||
      trail_dir.x <= 0.3 * std::hypot(trail_dir.x, trail_dir.y))
    throw std::invalid_argument("cascade metal angles too steep for an axial passage");
  std::vector<P2> side;
  constexpr int kStraight = 16, kCurved = 120;
  for (int i = 0; i < kStraight; ++i)
    side.push_back(lead + (-0.5 * (kStraight - i) / kStraight / lead_dir.x) * lead_dir);
  for (int i = 0; i <= kCurved; ++i) side.push_back(in_passage(camber(static_cast<double>(i) / kCurved)));
  for (int i = 1; i <= kStraight; ++i) side.push_back(trail + (0.5 * i / kStraight / trail_dir.x) * trail_dir);
  std::vector<gp_Pnt> below, above;
  for (const P2& p : side) {
    below.push_back(point(p + P2{0.0, -0.5 * c.pitch}, scale));
    above.push_back(point(p + P2{0.0, 0.5 * c.pitch}, scale));
  }
  std::vector<gp_Pnt> above_back(above.rbegin(), above.rend());
  const TopoDS_Wire outer =
      wire_of({BRepBuilderAPI_MakeEdge(interpolate(below)).Edge(),
               BRepBuilderAPI_MakeEdge(GC_MakeSegment(below.back(), above.back()).Value()).Edge(),
               BRepBuilderAPI_MakeEdge(interpolate(above_back)).Edge(),
               BRepBuilderAPI_MakeEdge(GC_MakeSegment(above.front(), below.front()).Value()).Edge()});
  return face_with_holes(outer, {wire_of(blade)});
}

}  // namespace mm::test
