// medialmesh_fuzz: random faces through every stage that exists.
//
//   medialmesh_fuzz --seed S --count N --out DIR [--time-limit SECONDS] [--families F,G...] [--from I]
//                   [--size F]
//
// Builds N random OCC faces of eleven families (filleted polygons with holes,
// plates with notches and slots, closed B-spline outlines, thin strips with
// tiny edges, faces bounded by elliptic arcs, NACA sections and high-lift
// arrangements in a far field, turbine cascade passages: tests/occ/
// aerofoil_faces.hpp; circles and fillets written as several B-spline arcs,
// faces converted whole to NURBS, cambered slat sections with a concave side
// and a cusp, faces through OCC's STEP writer and reader), each placed
// anywhere in 3-D at
// a scale of 1e-3 to 1e4, and runs each in a child process of its own, under
// a time limit: BREP text -> boundary model -> medial axis -> mesh flow ->
// decomposition -> the face cut into block faces by OCC -> the block mesh
// (mesh_face, order 1, elements 0.05 of the face's diagonal, or F of it
// with --size F), with checks
// that do not trust the stages (OCC's area, the number of holes, the test
// suite's medial axis checks, Poincare-Hopf, the test suite's decomposition
// and mesh checks, OCC's validity and area of the block faces). Counts ok,
// clean errors (InputError), failed self-checks, internal errors, crashes,
// hangs and broken invariants per family and the stage each face stopped in,
// writes every face that is not ok as DIR/<family>_<seed>_<i>.brep with a
// line in DIR/fuzz.log, and exits with 1 if any face crashed, hung, broke an
// invariant or hit an internal error. --families runs only the faces of
// those families among the N (each the face a full run makes), to compare
// one stage's families before and after a change. --from I skips the
// faces before the I-th (counted from 0 over all families): face
// <family>_<seed>_<n> is the I-th for I = 11 (n div 5) + n mod 5 in the first
// five families and I = 11 n + f for the later ones (f = 5 aerofoils, 6
// cascades, 7 arcs, 8 nurbs, 9 slats, 10 step), so --from I --count I+1
// remakes that one face.
#include <sys/wait.h>
#include <unistd.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepFilletAPI_MakeFillet2d.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeArcOfEllipse.hxx>
#include <GC_MakeSegment.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gp_Elips.hxx>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "aerofoil_faces.hpp"
#include "decomposition_checks.hpp"
#include "medial/medial_axis.hpp"
#include "medial_checks.hpp"
#include "mesh_checks.hpp"
#include "occ/occ_reader.hpp"
#include "occ/occ_split.hpp"
#include "pipeline/pipeline.hpp"
#include "singularity/mesh_flow.hpp"

namespace {

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
int integer(Rng& rng, int lo, int hi) {  // lo..hi inclusive
  return std::uniform_int_distribution<int>(lo, hi)(rng);
}

gp_Pnt point(double x, double y) {
  return gp_Pnt(x, y, 0);
}

TopoDS_Wire polygon_wire(const std::vector<gp_Pnt>& points) {
  BRepBuilderAPI_MakePolygon polygon;
  for (const gp_Pnt& p : points) polygon.Add(p);
  polygon.Close();
  return polygon.Wire();
}

TopoDS_Wire circle_wire(double x, double y, double r) {
  return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(new Geom_Circle(gp_Ax2(point(x, y), gp::DZ()), r)).Edge())
      .Wire();
}

// A face from an outer wire and holes (each turned clockwise).
TopoDS_Face with_holes(const TopoDS_Face& outer, const std::vector<TopoDS_Wire>& holes) {
  if (holes.empty()) return outer;
  BRepBuilderAPI_MakeFace face(outer);
  for (const TopoDS_Wire& hole : holes) face.Add(TopoDS::Wire(hole.Reversed()));
  return face.Face();
}

// Star-shaped polygon, corners filleted at random radii, up to two round holes.
TopoDS_Face filleted_polygon(Rng& rng) {
  const int sides = integer(rng, 3, 10);
  std::vector<gp_Pnt> points;
  for (int i = 0; i < sides; ++i) {
    const double a = (i + uniform(rng, 0.15, 0.85)) * 2 * M_PI / sides, r = uniform(rng, 0.6, 1.0);
    points.push_back(point(r * std::cos(a), r * std::sin(a)));
  }
  TopoDS_Face face = BRepBuilderAPI_MakeFace(polygon_wire(points)).Face();
  BRepFilletAPI_MakeFillet2d fillets(face);
  TopTools_IndexedMapOfShape vertices;
  TopExp::MapShapes(face, TopAbs_VERTEX, vertices);
  double shortest = 1e300;
  for (int i = 0; i < sides; ++i) shortest = std::min(shortest, points[i].Distance(points[(i + 1) % sides]));
  for (int i = 1; i <= vertices.Extent(); ++i) {
    if (uniform(rng, 0, 1) < 0.8) fillets.AddFillet(TopoDS::Vertex(vertices(i)), shortest * uniform(rng, 0.02, 0.3));
  }
  fillets.Build();
  if (fillets.IsDone()) face = TopoDS::Face(fillets.Shape());
  std::vector<TopoDS_Wire> holes;
  // From five sides on the inscribed radius exceeds 0.48: holes reaching 0.3 fit.
  const int count = sides >= 5 ? integer(rng, 0, 2) : 0;
  for (int h = 0; h < count; ++h) {
    holes.push_back(circle_wire((h == 0 ? -0.2 : 0.2) + uniform(rng, -0.02, 0.02), uniform(rng, -0.05, 0.05),
                                uniform(rng, 0.02, 0.1)));
  }
  return with_holes(face, holes);
}

// A slot (two half circles joined by straight sides) along x.
TopoDS_Wire slot_wire(double cx, double cy, double length, double radius) {
  const double x0 = cx - length / 2, x1 = cx + length / 2;
  BRepBuilderAPI_MakeWire wire;
  wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(point(x0, cy - radius), point(x1, cy - radius)).Value()).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(
               GC_MakeArcOfCircle(point(x1, cy - radius), point(x1 + radius, cy), point(x1, cy + radius)).Value())
               .Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(point(x1, cy + radius), point(x0, cy + radius)).Value()).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(
               GC_MakeArcOfCircle(point(x0, cy + radius), point(x0 - radius, cy), point(x0, cy - radius)).Value())
               .Edge());
  return wire.Wire();
}

// A rectangle with rectangular notches in its long sides and slots in between.
TopoDS_Face notched_plate(Rng& rng) {
  const double width = uniform(rng, 2, 4), height = uniform(rng, 1, 2);
  const auto notches = [&](bool top) {
    std::vector<gp_Pnt> pts;
    const int count = integer(rng, 0, 3);
    for (int i = 0; i < count; ++i) {
      const double slot = width / count, x1 = slot * (i + uniform(rng, 0.1, 0.4)),
                   x2 = slot * (i + uniform(rng, 0.5, 0.9)), depth = uniform(rng, 0.05, 0.3) * height;
      const double y0 = top ? height : 0.0, y1 = top ? height - depth : depth;
      for (const gp_Pnt& p : {point(x1, y0), point(x1, y1), point(x2, y1), point(x2, y0)}) pts.push_back(p);
    }
    if (top) std::reverse(pts.begin(), pts.end());
    return pts;
  };
  std::vector<gp_Pnt> outline{point(0, 0)};
  for (const gp_Pnt& p : notches(false)) outline.push_back(p);
  outline.push_back(point(width, 0));
  outline.push_back(point(width, height));
  for (const gp_Pnt& p : notches(true)) outline.push_back(p);
  outline.push_back(point(0, height));
  std::vector<TopoDS_Wire> holes;
  const int slots = integer(rng, 0, 2);
  for (int s = 0; s < slots; ++s) {
    const double third = width / 3, radius = uniform(rng, 0.02, 0.08) * height;
    holes.push_back(
        slot_wire(third * (s + 1), height * uniform(rng, 0.45, 0.55), third * uniform(rng, 0.1, 0.6), radius));
  }
  return with_holes(BRepBuilderAPI_MakeFace(polygon_wire(outline)).Face(), holes);
}

// A smooth outline through points of a random star, periodic or closed at
// one point (a corner there), its knots maybe moved; maybe a round hole.
TopoDS_Face bspline_outline(Rng& rng) {
  const int n = integer(rng, 8, 30);
  std::array<double, 4> amplitude{}, phase{};
  for (int h = 0; h < 4; ++h) amplitude[h] = uniform(rng, 0, 0.07), phase[h] = uniform(rng, 0, 2 * M_PI);
  const double stretch = uniform(rng, 0.5, 1.0);
  const bool periodic = uniform(rng, 0, 1) < 0.6;
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, periodic ? n : n + 1);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    double r = 1;
    for (int h = 0; h < 4; ++h) r += amplitude[h] * std::cos((h + 2) * a + phase[h]);
    points->SetValue(i + 1, point(r * std::cos(a), stretch * r * std::sin(a)));
  }
  if (!periodic) points->SetValue(n + 1, points->Value(1));
  GeomAPI_Interpolate interpolate(points, periodic, 1e-9);
  interpolate.Perform();
  if (!interpolate.IsDone()) throw Standard_Failure("interpolation failed");
  Handle(Geom_BSplineCurve) curve = interpolate.Curve();
  if (uniform(rng, 0, 1) < 0.5) {
    TColStd_Array1OfReal knots(1, curve->NbKnots());
    curve->Knots(knots);
    const double shift = uniform(rng, -10, 10);
    for (double& k : knots) k += shift;
    curve->SetKnots(knots);
  }
  const TopoDS_Face face =
      BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(curve).Edge()).Wire()).Face();
  std::vector<TopoDS_Wire> holes;
  if (uniform(rng, 0, 1) < 0.4) holes.push_back(circle_wire(uniform(rng, -0.1, 0.1), 0, 0.2 * stretch));
  return with_holes(face, holes);
}

// A long thin strip with tiny steps and notches along one side and maybe a
// tiny chamfer at a corner.
TopoDS_Face thin_strip(Rng& rng) {
  const double length = 1, height = length / uniform(rng, 20, 200);
  std::vector<gp_Pnt> outline{point(0, 0)};
  const int notches = integer(rng, 1, 4);
  for (int i = 0; i < notches; ++i) {
    const double x = length * (i + uniform(rng, 0.2, 0.7)) / notches, w = length * std::pow(10, uniform(rng, -3, -2)),
                 depth = height * uniform(rng, 0.05, 0.3);
    for (const gp_Pnt& p : {point(x, 0), point(x, depth), point(x + w, depth), point(x + w, 0)}) outline.push_back(p);
  }
  if (uniform(rng, 0, 1) < 0.5) {
    const double cut = height * 1e-2;
    outline.push_back(point(length - cut, 0));
    outline.push_back(point(length, cut));
  } else {
    outline.push_back(point(length, 0));
  }
  outline.push_back(point(length, height));
  outline.push_back(point(0, height));
  return BRepBuilderAPI_MakeFace(polygon_wire(outline)).Face();
}

// Faces bounded by elliptic arcs: an ellipse with an elliptic hole, a half
// ellipse on its chord, or a rectangle with an elliptic top.
TopoDS_Face elliptic(Rng& rng) {
  const double a = uniform(rng, 1, 3), b = uniform(rng, 0.3, 1);
  const gp_Elips ellipse(gp_Ax2(point(0, 0), gp::DZ(), gp::DX()), a, b);
  const int kind = integer(rng, 0, 2);
  if (kind == 0) {
    const TopoDS_Face outer =
        BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(ellipse).Edge()).Wire()).Face();
    if (uniform(rng, 0, 1) < 0.3) return outer;
    const double f = uniform(rng, 0.2, 0.6), turn = uniform(rng, 0, M_PI);
    const double ha = std::max(f * a, f * b * 1.0001), hb = f * b;
    const gp_Elips hole(gp_Ax2(point(0, 0), gp::DZ(), gp_Dir(std::cos(turn), std::sin(turn), 0)), ha, hb);
    if (ha > b * 0.9) return outer;  // a turned hole must stay inside
    return with_holes(outer, {BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(hole).Edge()).Wire()});
  }
  BRepBuilderAPI_MakeWire wire;
  if (kind == 1) {
    const double from = uniform(rng, 0, M_PI), to = from + uniform(rng, 0.5, 1.5) * M_PI;
    Handle(Geom_TrimmedCurve) arc = GC_MakeArcOfEllipse(ellipse, from, to, true).Value();
    wire.Add(BRepBuilderAPI_MakeEdge(arc).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(arc->EndPoint(), arc->StartPoint()).Value()).Edge());
  } else {
    const double h = uniform(rng, 0.2, 1.5);
    const gp_Elips top(gp_Ax2(point(0, h), gp::DZ(), gp::DX()), a, b);
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(point(-a, h), point(-a, 0)).Value()).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(point(-a, 0), point(a, 0)).Value()).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(point(a, 0), point(a, h)).Value()).Edge());
    wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfEllipse(top, 0.0, M_PI, true).Value()).Edge());
  }
  return BRepBuilderAPI_MakeFace(wire.Wire()).Face();
}

// A random NACA designation: 4-digit (camber 0-6 %, at 0.2-0.6 of the
// chord) or 5-digit standard (design lift 0.15-0.45, camber position 1-5),
// thickness 6-24 %.
std::string naca_digits(Rng& rng) {
  const int thickness = integer(rng, 6, 24);
  std::string t = (thickness < 10 ? "0" : "") + std::to_string(thickness);
  if (uniform(rng, 0, 1) < 0.5) {
    const int camber = integer(rng, 0, 6);
    return std::to_string(camber) + std::to_string(camber == 0 ? 0 : integer(rng, 2, 6)) + t;
  }
  return std::to_string(integer(rng, 1, 3)) + std::to_string(integer(rng, 1, 5)) + "0" + t;
}

// One or two NACA sections in the far field, or a slat, main element and
// flap with slot gaps of 0.3 % to 3 % of the chord.
TopoDS_Face aerofoil(Rng& rng) {
  const bool blunt = uniform(rng, 0, 1) < 0.5;
  if (uniform(rng, 0, 1) < 0.5) {
    mm::test::HighLift layout;
    layout.gap = std::pow(10.0, uniform(rng, std::log10(0.003), std::log10(0.03)));
    layout.slat_angle = uniform(rng, 10, 35);
    layout.flap_angle = uniform(rng, 10, 45);
    layout.slat = naca_digits(rng), layout.main = naca_digits(rng), layout.flap = naca_digits(rng);
    layout.blunt = blunt;
    return mm::test::high_lift_face(layout, 1.0);
  }
  std::vector<mm::test::AerofoilSection> sections{{naca_digits(rng), blunt, 1.0, 0.0, 0.0, uniform(rng, -10, 15)}};
  if (uniform(rng, 0, 1) < 0.3)  // a tandem: a second section behind and above or below
    sections.push_back({naca_digits(rng), blunt, uniform(rng, 0.3, 1.0), uniform(rng, 1.3, 2.5),
                        uniform(rng, -0.6, 0.6), uniform(rng, -10, 15)});
  return mm::test::far_field_face(sections, 1.0);
}

// A turbine cascade passage of random stagger, turning, pitch and thickness,
// its trailing edge sharp or rounded.
TopoDS_Face cascade(Rng& rng) {
  mm::test::Cascade c;
  c.stagger = uniform(rng, -10, 20);
  c.inlet = uniform(rng, 15, 50);
  c.outlet = uniform(rng, -60, -20);
  c.pitch = uniform(rng, 0.7, 1.1);
  c.thickness = uniform(rng, 0.08, 0.2);
  c.rounded = uniform(rng, 0, 1) < 0.5;
  c.te_radius = uniform(rng, 0.005, 0.02);
  return mm::test::cascade_face(c, 1.0);
}

// Points of the circle (x, y, r) from angle a0 to a1, n of them, ends exact.
std::vector<gp_Pnt> arc_points(double x, double y, double r, double a0, double a1, int n) {
  std::vector<gp_Pnt> points;
  for (int i = 0; i < n; ++i) {
    const double a = a0 + (a1 - a0) * i / (n - 1);
    points.push_back(point(x + r * std::cos(a), y + r * std::sin(a)));
  }
  return points;
}

// An arc of the circle (x, y, r) from a0 to a1 as one B-spline: rational
// (an exact conversion, as CAD writes it) or interpolated through points
// (as some exporters write it, a circle within their tolerance).
TopoDS_Edge spline_arc(double x, double y, double r, double a0, double a1, bool rational) {
  if (rational) {
    Handle(Geom_Circle) circle = new Geom_Circle(gp_Ax2(point(x, y), gp::DZ()), r);
    return BRepBuilderAPI_MakeEdge(GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(circle, a0, a1))).Edge();
  }
  const std::vector<gp_Pnt> points = arc_points(x, y, r, a0, a1, 9 + static_cast<int>(8 * (a1 - a0)));
  Handle(TColgp_HArray1OfPnt) array = new TColgp_HArray1OfPnt(1, static_cast<int>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) array->SetValue(static_cast<int>(i) + 1, points[i]);
  GeomAPI_Interpolate interpolate(array, false, 1e-12);
  interpolate.Perform();
  if (!interpolate.IsDone()) throw Standard_Failure("interpolation failed");
  return BRepBuilderAPI_MakeEdge(interpolate.Curve()).Edge();
}

// A whole circle as 2 to 4 B-spline arcs from a random angle on.
TopoDS_Wire circle_in_pieces(Rng& rng, double x, double y, double r) {
  const int pieces = integer(rng, 2, 4);
  const bool rational = uniform(rng, 0, 1) < 0.5;
  const double start = uniform(rng, 0, 2 * M_PI);
  BRepBuilderAPI_MakeWire wire;
  for (int k = 0; k < pieces; ++k)
    wire.Add(spline_arc(x, y, r, start + 2 * M_PI * k / pieces, start + 2 * M_PI * (k + 1) / pieces, rational));
  return wire.Wire();
}

// Circles and fillets written as several B-spline arcs, as several STEP
// exporters write them: a disc, a washer, a plate with holes, a rectangle
// with rounded corners (each a B-spline quarter circle).
TopoDS_Face arcs_in_pieces(Rng& rng) {
  const int kind = integer(rng, 0, 3);
  if (kind <= 1) {
    const TopoDS_Face disc = BRepBuilderAPI_MakeFace(circle_in_pieces(rng, 0, 0, 1)).Face();
    if (kind == 0) return disc;
    const double r = uniform(rng, 0.2, 0.8);
    return with_holes(disc, {circle_in_pieces(rng, uniform(rng, -0.1, 0.1) * (1 - r), 0, r)});
  }
  const double width = uniform(rng, 1.5, 3), height = uniform(rng, 0.8, 1.5);
  if (kind == 2) {
    std::vector<TopoDS_Wire> holes;
    const int count = integer(rng, 1, 3);
    for (int h = 0; h < count; ++h)
      holes.push_back(circle_in_pieces(rng, width * (h + 0.5) / count, height / 2,
                                       uniform(rng, 0.1, 0.35) * std::min(width / count, height)));
    return with_holes(
        BRepBuilderAPI_MakeFace(polygon_wire({point(0, 0), point(width, 0), point(width, height), point(0, height)}))
            .Face(),
        holes);
  }
  const double r = uniform(rng, 0.05, 0.45) * height;
  const bool rational = uniform(rng, 0, 1) < 0.5;
  const std::array<gp_Pnt, 4> centres{point(width - r, r), point(width - r, height - r), point(r, height - r),
                                      point(r, r)};
  BRepBuilderAPI_MakeWire wire;
  for (int c = 0; c < 4; ++c) {
    const double a0 = -M_PI / 2 + c * M_PI / 2;
    const gp_Pnt& o = centres[c];
    wire.Add(spline_arc(o.X(), o.Y(), r, a0, a0 + M_PI / 2, rational));
    const gp_Pnt& next = centres[(c + 1) % 4];
    const double a1 = a0 + M_PI / 2;
    wire.Add(BRepBuilderAPI_MakeEdge(point(o.X() + r * std::cos(a1), o.Y() + r * std::sin(a1)),
                                     point(next.X() + r * std::cos(a1), next.Y() + r * std::sin(a1)))
                 .Edge());
  }
  return BRepBuilderAPI_MakeFace(wire.Wire()).Face();
}

// A face of another family converted whole to NURBS, as some exporters
// write every face: a planar B-spline surface with B-spline edges.
TopoDS_Face nurbs(Rng& rng) {
  const int kind = integer(rng, 0, 3);
  const TopoDS_Face face = kind == 0   ? filleted_polygon(rng)
                           : kind == 1 ? notched_plate(rng)
                           : kind == 2 ? elliptic(rng)
                                       : arcs_in_pieces(rng);
  return TopoDS::Face(BRepBuilderAPI_NurbsConvert(face, true).Shape());
}

// A cambered section alone, as the end face of a slat or flap: camber 4 to
// 9 % (a concave lower side), thickness 4 to 12 % and a sharp trailing edge
// (a cusp of some 4 to 15 degrees), or a blunt one.
TopoDS_Face slat(Rng& rng) {
  mm::test::AerofoilSection section;
  const int thickness = integer(rng, 4, 12);
  section.digits = std::to_string(integer(rng, 4, 9)) + std::to_string(integer(rng, 2, 5)) +
                   (thickness < 10 ? "0" : "") + std::to_string(thickness);
  section.blunt = uniform(rng, 0, 1) < 0.2;
  return mm::test::section_face(section, 1.0);
}

// A face of another family written to STEP by OCC's writer and read back
// by its reader, as a user's file comes.
TopoDS_Face step_round_trip(Rng& rng) {
  const int kind = integer(rng, 0, 4);
  const TopoDS_Face face = kind == 0   ? filleted_polygon(rng)
                           : kind == 1 ? notched_plate(rng)
                           : kind == 2 ? bspline_outline(rng)
                           : kind == 3 ? elliptic(rng)
                                       : arcs_in_pieces(rng);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("medialmesh_fuzz_" + std::to_string(getpid()) + "_" + std::to_string(integer(rng, 0, 1 << 30)) + ".step");
  STEPControl_Writer writer;
  if (writer.Transfer(face, STEPControl_AsIs) != IFSelect_RetDone || writer.Write(path.c_str()) != IFSelect_RetDone)
    throw Standard_Failure("STEP writing failed");
  STEPControl_Reader reader;
  const bool read = reader.ReadFile(path.c_str()) == IFSelect_RetDone && reader.TransferRoots() > 0;
  std::filesystem::remove(path);
  if (!read) throw Standard_Failure("STEP reading failed");
  TopExp_Explorer faces(reader.OneShape(), TopAbs_FACE);
  if (!faces.More()) throw Standard_Failure("no face read back from STEP");
  return TopoDS::Face(faces.Current());
}

// New families go at the end, so that the faces of the old ones keep their
// numbers and seeds (see generate).
const std::vector<std::pair<std::string, TopoDS_Face (*)(Rng&)>> kFamilies = {{"filleted", filleted_polygon},
                                                                              {"plate", notched_plate},
                                                                              {"bspline", bspline_outline},
                                                                              {"strip", thin_strip},
                                                                              {"elliptic", elliptic},
                                                                              {"aerofoil", aerofoil},
                                                                              {"cascade", cascade},
                                                                              {"arcs", arcs_in_pieces},
                                                                              {"nurbs", nurbs},
                                                                              {"slat", slat},
                                                                              {"step", step_round_trip}};
// The families there were when the fuzzer first ran 10 000 faces.
constexpr std::size_t kFirstFamilies = 5;

// Turned about a random axis, scaled by 1e-3 to 1e4, moved up to 100 times that.
TopoDS_Face placed(const TopoDS_Face& face, Rng& rng) {
  const double scale = std::pow(10.0, uniform(rng, -3, 4));
  gp_Dir axis(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1) + 1e-3);
  gp_Trsf turn, grow, move;
  turn.SetRotation(gp_Ax1(gp::Origin(), axis), uniform(rng, 0, 2 * M_PI));
  grow.SetScale(gp::Origin(), scale);
  const double reach = scale * std::pow(10.0, uniform(rng, -2, 2));
  move.SetTranslation(gp_Vec(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)) * reach);
  return TopoDS::Face(BRepBuilderAPI_Transform(face, move * grow * turn, true).Shape());
}

// kCoarse: a right mesh whose element count is far from area / H^2 (the
// tests' element_count_problem): poor, not wrong, so kept but no failure.
enum Outcome { kOk, kCoarse, kInputError, kSelfCheck, kBroken, kInternal, kCrash, kHang, kNotBuilt, kOutcomes };
const char* const kOutcomeNames[kOutcomes] = {"ok",
                                              "ok, element count off area / H^2",
                                              "clean error (InputError)",
                                              "self-check error",
                                              "broken invariant",
                                              "internal error",
                                              "crash",
                                              "hang",
                                              "not built (generator)"};

struct Generated {
  std::string family;
  TopoDS_Face face;
};

// Face i of a run is of family i mod 11 (the number of families). A face of
// the first five families keeps the number (and so the random numbers) it
// had when they were the only five: in each round of 11 faces, the 5 old
// ones number on from 5 per round; the later families' faces number 0, 1,
// 2 ... within their family and draw from a stream of their own. So a face's
// name names the same face whatever families were added after it, though a
// run of N faces holds fewer of each as families are added.
struct Numbered {
  std::size_t family;
  std::uint64_t number;
  std::uint64_t stream;
};
Numbered number_of(std::uint64_t seed, int i) {
  const std::size_t family = i % kFamilies.size();
  const std::uint64_t round = i / kFamilies.size();
  if (family < kFirstFamilies) {
    const std::uint64_t number = round * kFirstFamilies + family;
    return {family, number, seed * 1000003 + number};
  }
  return {family, round, (seed * 1000003 + round) * 31 + family};
}

Generated generate(std::uint64_t seed, int i) {
  const Numbered n = number_of(seed, i);
  Rng rng(n.stream);
  const auto& [family, make] = kFamilies[n.family];
  return {family, placed(make(rng), rng)};
}

// The child tells the parent each stage as it enters it ("@stage" lines
// before the message), so that a crash or a hang is put down to its stage.
int g_report_fd = -1;
void enter(const std::string& stage) {
  const std::string line = "@" + stage + "\n";
  if (write(g_report_fd, line.data(), line.size()) < 0) _exit(kInternal);
}

// Runs the stages on one face and checks them; the outcome and a message.
std::pair<Outcome, std::string> run_stages(const TopoDS_Face& occ, const std::string& brep, const std::string& name,
                                           double size_factor) {
  if (!BRepCheck_Analyzer(occ).IsValid()) return {kNotBuilt, "OCC finds the generated face invalid"};
  mm::FaceModel face;
  try {
    enter("boundary");
    face = mm::face_model_from_brep_string(brep, name);
  } catch (const mm::InputError& e) {
    return {kInputError, e.what()};
  }
  int wires = 0;
  for (TopExp_Explorer it(occ, TopAbs_WIRE); it.More(); it.Next()) ++wires;
  if (face.holes() != wires - 1) {
    return {kBroken, "holes " + std::to_string(face.holes()) + ", OCC's wires " + std::to_string(wires)};
  }
  GProp_GProps props;
  BRepGProp::SurfaceProperties(occ, props, 1e-10);
  if (std::abs(face.area - props.Mass()) > 1e-6 * props.Mass()) {
    std::ostringstream m;
    m << "area " << face.area << ", OCC's " << props.Mass();
    return {kBroken, m.str()};
  }
  try {
    // Axis and flow through the pipeline's entry points, with the fallbacks
    // a user's face gets (kinks as corners where the axis or flow fails,
    // finer chords where the flow still fails).
    enter("medial axis");
    mm::FaceAxis medial = mm::compute_face_medial_axis(face);
    const ::testing::AssertionResult valid = mm::test::medial_axis_is_valid(medial.face, medial.axis, 1e-6);
    if (!valid)
      return {kBroken, std::string("medial axis passed its self-check but not the tests' checks: ") + valid.message()};
    enter("mesh flow");
    const mm::FaceFlow flowed = mm::flow_of_axis(face, std::move(medial));
    const mm::FaceModel& taken = flowed.face;
    const mm::MeshFlow& flow = flowed.flow;
    if (flow.sum_k() != mm::predicted_sum_k(taken)) {
      return {kBroken,
              "sum of k " + std::to_string(flow.sum_k()) + ", predicted " + std::to_string(mm::predicted_sum_k(taken))};
    }
    enter("decomposition");
    const mm::Decomposition d = mm::decompose(taken, flowed.axis, flow, {});
    const std::vector<std::string> problems = mm::test::decomposition_problems(taken, flow, d);
    if (!problems.empty()) {
      // A fallback that says it could not give a singularity its block is loud, not wrong.
      return {d.fallback ? kSelfCheck : kBroken, "decomposition: " + problems.front()};
    }
    enter("block faces");
    std::vector<std::vector<mm::Vec2>> lines;
    for (const mm::Split& split : d.splits) lines.push_back(split.polyline);
    try {
      double area = 0.0;
      for (const TopoDS_Face& block : mm::split_face(occ, face.frame, lines)) {
        GProp_GProps block_props;
        BRepGProp::SurfaceProperties(block, block_props, 1e-10);
        area += block_props.Mass();
      }
      // Within the relative 1e-6 or OCC's own edge tolerance along the
      // face's size, whichever is larger: splitting B-spline edges moves
      // them within that tolerance, a large share of a face 0.02 across.
      const double allowed = std::max(1e-6 * props.Mass(), face.tolerance * face.size);
      if (std::abs(area - props.Mass()) > allowed) return {kBroken, "block faces' area off"};
    } catch (const mm::InputError& e) {
      return {kBroken, std::string("OCC could not cut the face into its blocks: ") + e.what()};
    }
    // The whole pipeline as a user runs it, by default at a size that keeps
    // each face to a few hundred elements; its mesh checked by the test
    // suite's checker.
    enter("mesh");
    mm::PipelineOptions options;
    options.meshing.size = size_factor * face.size;
    options.meshing.order = 1;
    const mm::MeshedFace meshed = mm::mesh_face(face, options);
    const std::vector<std::string> wrong = mm::test::mesh_validity_problems(face, meshed.blocks.mesh);
    if (!wrong.empty()) return {kBroken, "mesh passed its self-check but not the tests' checks: " + wrong.front()};
    const std::string count = mm::test::element_count_problem(face, meshed.blocks.mesh, options.meshing.size);
    if (!count.empty()) return {kCoarse, count};
  } catch (const mm::SelfCheckError& e) {
    return {kSelfCheck, e.what()};
  } catch (const mm::InputError& e) {
    return {kInputError, e.what()};
  }
  return {kOk, ""};
}

struct Options {
  std::uint64_t seed = 1;
  int count = 100;
  std::string out = "fuzz_out";
  unsigned time_limit = 60;
  std::vector<std::string> families;  // all if empty
  int from = 0;
  double size = 0.05;  // element size, a fraction of the face's diagonal
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
    const std::string v = argv[++i];
    if (a == "--seed") {
      o.seed = std::stoull(v);
    } else if (a == "--count") {
      o.count = std::stoi(v);
    } else if (a == "--out") {
      o.out = v;
    } else if (a == "--from") {
      o.from = std::stoi(v);
    } else if (a == "--size") {
      o.size = std::stod(v);
      if (!(o.size > 0.0 && o.size <= 1.0)) throw std::invalid_argument("--size must be in (0, 1]");
    } else if (a == "--time-limit") {
      o.time_limit = static_cast<unsigned>(std::stoul(v));
    } else if (a == "--families") {
      std::stringstream list(v);
      for (std::string name; std::getline(list, name, ',');) {
        if (std::none_of(kFamilies.begin(), kFamilies.end(), [&](const auto& f) { return f.first == name; }))
          throw std::invalid_argument("no family " + name);
        o.families.push_back(name);
      }
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "medialmesh_fuzz: " << e.what()
              << "\nusage: medialmesh_fuzz --seed S --count N --out DIR [--time-limit SECONDS] [--families F,G...] "
                 "[--from I] [--size F]\n";
    return 2;
  }
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  std::filesystem::create_directories(o.out);
  std::ofstream log(o.out + "/fuzz.log", std::ios::app);
  std::array<int, kOutcomes> counts{};
  std::map<std::string, std::array<int, kOutcomes>> by_family;
  std::map<std::string, int> by_stage;  // faces not ok, by the stage they stopped in
  for (int i = o.from; i < o.count; ++i) {
    const Numbered numbered = number_of(o.seed, i);
    const std::string family = kFamilies[numbered.family].first;
    if (!o.families.empty() && std::find(o.families.begin(), o.families.end(), family) == o.families.end()) continue;
    const std::string name = family + "_" + std::to_string(o.seed) + "_" + std::to_string(numbered.number);
    const std::string path = o.out + "/" + name + ".brep";
    int pipe_fds[2];
    if (pipe(pipe_fds) != 0) return 3;
    const pid_t child = fork();
    if (child == 0) {
      // The child writes the face first, so that a crash or hang leaves it behind.
      close(pipe_fds[0]);
      g_report_fd = pipe_fds[1];
      alarm(o.time_limit);
      std::pair<Outcome, std::string> result;
      Generated g;
      std::ostringstream brep;
      try {
        g = generate(o.seed, i);
        BRepTools::Write(g.face, brep);
      } catch (const Standard_Failure& e) {
        result = {kNotBuilt, std::string("OCC: ") + e.GetMessageString()};
      } catch (const std::invalid_argument& e) {  // parameters an aerofoil builder refuses
        result = {kNotBuilt, e.what()};
      }
      if (result.second.empty()) {
        std::ofstream(path) << brep.str();
        try {
          result = run_stages(g.face, brep.str(), path, o.size);
        } catch (const Standard_Failure& e) {
          result = {kInternal, std::string("OCC: ") + e.GetMessageString()};
        } catch (const std::exception& e) {
          result = {kInternal, e.what()};
        }
      }
      std::string message = result.second;
      std::replace(message.begin(), message.end(), '\n', ' ');
      if (write(pipe_fds[1], message.data(), message.size()) < 0) _exit(kInternal);
      _exit(result.first);
    }
    close(pipe_fds[1]);
    std::string report;
    char buffer[4096];
    for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) report.append(buffer, n);
    close(pipe_fds[0]);
    std::string stage = "generator", message = report;
    for (std::size_t at = 0; at < report.size() && report[at] == '@';) {
      const std::size_t end = report.find('\n', at);
      if (end == std::string::npos) break;
      stage = report.substr(at + 1, end - at - 1);
      message = report.substr(end + 1);
      at = end + 1;
    }
    int status = 0;
    waitpid(child, &status, 0);
    Outcome outcome = kCrash;
    if (WIFEXITED(status) && WEXITSTATUS(status) < kOutcomes) outcome = static_cast<Outcome>(WEXITSTATUS(status));
    if (WIFSIGNALED(status)) {
      outcome = WTERMSIG(status) == SIGALRM ? kHang : kCrash;
      message = "signal " + std::to_string(WTERMSIG(status));
    }
    ++counts[outcome];
    ++by_family[family][outcome];
    if (outcome == kOk || outcome == kNotBuilt) {
      std::filesystem::remove(path);
    } else {
      if (outcome != kCoarse) ++by_stage[stage];
      log << path << ": " << kOutcomeNames[outcome] << " in " << stage << ": " << message << "\n";
    }
  }
  int ran = 0;
  for (const int c : counts) ran += c;
  std::cout << "seed " << o.seed << ", " << ran << " faces";
  if (ran != o.count) std::cout << " of the first " << o.count;
  std::cout << ", elements " << o.size << " of the diagonal\n";
  for (int k = 0; k < kOutcomes; ++k) {
    std::cout << "  " << kOutcomeNames[k] << ": " << counts[k];
    for (const auto& [family, c] : by_family) {
      if (c[k]) std::cout << " " << family << "=" << c[k];
    }
    std::cout << "\n";
  }
  std::cout << "  not ok, by the stage they stopped in:";
  for (const char* stage :
       {"generator", "boundary", "medial axis", "mesh flow", "decomposition", "block faces", "mesh"}) {
    if (by_stage.count(stage)) std::cout << " " << stage << "=" << by_stage[stage];
  }
  std::cout << "\n";
  return counts[kCrash] + counts[kHang] + counts[kBroken] + counts[kInternal] > 0 ? 1 : 0;
}
