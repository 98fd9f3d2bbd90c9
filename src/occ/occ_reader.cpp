#include "occ/occ_reader.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom2dConvert.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Ellipse.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <GeomAPI.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Geom_Plane.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Precision.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gp_Trsf2d.hxx>
#include <optional>
#include <sstream>

#include "occ/occ_face.hpp"
#include "occ/silenced_stdout.hpp"

namespace mm {
namespace {

Vec2 vec(const gp_Pnt2d& p) {
  return {p.X(), p.Y()};
}
Vec2 vec(const gp_Dir2d& d) {
  return {d.X(), d.Y()};
}
std::array<double, 3> arr(const gp_XYZ& v) {
  return {v.X(), v.Y(), v.Z()};
}

const char* surface_type_name(GeomAbs_SurfaceType type) {
  switch (type) {
    case GeomAbs_Plane: return "plane";
    case GeomAbs_Cylinder: return "cylinder";
    case GeomAbs_Cone: return "cone";
    case GeomAbs_Sphere: return "sphere";
    case GeomAbs_Torus: return "torus";
    case GeomAbs_BezierSurface: return "Bezier surface";
    case GeomAbs_BSplineSurface: return "B-spline surface";
    case GeomAbs_SurfaceOfRevolution: return "surface of revolution";
    case GeomAbs_SurfaceOfExtrusion: return "surface of extrusion";
    case GeomAbs_OffsetSurface: return "offset surface";
    default: return "other surface";
  }
}

// A non-periodic spline; `shift` is added to its parameters.
BSplineCurve to_bspline(const Handle(Geom2d_BSplineCurve) & c, double shift = 0.0) {
  BSplineCurve result;
  result.degree = c->Degree();
  TColStd_Array1OfReal knots(1, c->NbPoles() + c->Degree() + 1);
  c->KnotSequence(knots);
  for (int i = knots.Lower(); i <= knots.Upper(); ++i) result.knots.push_back(knots(i) + shift);
  for (int i = 1; i <= c->NbPoles(); ++i) {
    result.poles.push_back(vec(c->Pole(i)));
    if (c->IsRational()) result.weights.push_back(c->Weight(i));
  }
  return result;
}

// A periodic spline as a non-periodic one with the same geometry whose
// parameters run over one period from `first` once `shift` is added to them.
// Not Segment(): on a whole period OCCT 7.6 returns, for some knot vectors, a
// curve that does not close (its last pole is the periodic curve's first).
// Instead a knot at `first` becomes the origin and the knots are unrolled
// from there, which moves no point of the curve.
Handle(Geom2d_BSplineCurve) opened_at(const Handle(Geom2d_BSplineCurve) & periodic, double first, double& shift) {
  Handle(Geom2d_BSplineCurve) c = Handle(Geom2d_BSplineCurve)::DownCast(periodic->Copy());
  const double period = c->LastParameter() - c->FirstParameter();
  double start = first;
  c->PeriodicNormalization(start);
  c->InsertKnot(start, 1, 1e-12 * period);  // nothing changes if a knot is there already
  int origin = c->FirstUKnotIndex();
  for (int i = origin + 1; i < c->LastUKnotIndex(); ++i) {
    if (std::abs(std::remainder(c->Knot(i) - start, period)) <
        std::abs(std::remainder(c->Knot(origin) - start, period)))
      origin = i;
  }
  c->SetOrigin(origin);
  c->SetNotPeriodic();
  shift = period * std::round((first - c->FirstParameter()) / period);
  return c;
}

// The exact 2-D curve of an edge on [first, last]; may re-parametrise, so it
// returns the parameter range to use as well.
Curve to_curve(Handle(Geom2d_Curve) c, double& first, double& last) {
  while (auto trimmed = Handle(Geom2d_TrimmedCurve)::DownCast(c)) c = trimmed->BasisCurve();
  if (auto line = Handle(Geom2d_Line)::DownCast(c)) {
    return LineCurve{vec(line->Location()), vec(line->Direction())};
  }
  if (auto circle = Handle(Geom2d_Circle)::DownCast(c)) {
    const gp_Ax22d axes = circle->Position();
    const Vec2 x = vec(axes.XDirection());
    const int sense = cross(x, vec(axes.YDirection())) > 0 ? 1 : -1;
    return CircleCurve{vec(axes.Location()), circle->Radius(), std::atan2(x.y, x.x), sense};
  }
  if (auto ellipse = Handle(Geom2d_Ellipse)::DownCast(c)) {
    const gp_Ax22d axes = ellipse->Position();
    const Vec2 x = vec(axes.XDirection());
    const int sense = cross(x, vec(axes.YDirection())) > 0 ? 1 : -1;
    return EllipseCurve{vec(axes.Location()), x, ellipse->MajorRadius(), ellipse->MinorRadius(), sense};
  }
  if (auto bezier = Handle(Geom2d_BezierCurve)::DownCast(c)) {
    return to_bspline(Geom2dConvert::CurveToBSplineCurve(bezier));
  }
  if (auto bspline = Handle(Geom2d_BSplineCurve)::DownCast(c)) {
    if (!bspline->IsPeriodic()) return to_bspline(bspline);
    double shift = 0.0;
    const Handle(Geom2d_BSplineCurve) opened = opened_at(bspline, first, shift);
    return to_bspline(opened, shift);
  }
  return OtherCurve{c->DynamicType()->Name(), [c](double t) {
                      gp_Pnt2d p;
                      gp_Vec2d d1, d2;
                      c->D2(t, p, d1, d2);
                      return CurvePoint{vec(p), {d1.X(), d1.Y()}, {d2.X(), d2.Y()}};
                    }};
}

// The plane of a planar face: its own surface if that is a plane, else the
// plane a planar B-spline (or other) surface lies in.
bool find_plane(const TopoDS_Face& face, gp_Pln& plane, bool& native, std::string& surface_name) {
  BRepAdaptor_Surface adaptor(face, /*restriction=*/false);
  surface_name = surface_type_name(adaptor.GetType());
  if (adaptor.GetType() == GeomAbs_Plane) {
    plane = adaptor.Plane();
    native = true;
    return true;
  }
  native = false;
  // OCC's test misses planes by more than 1e-7 of their size (the 2 x 2
  // poles of a converted plane of size 100, coplanar to 1e-14, fail 1e-7),
  // and by more far from the origin (a face of 200 at 1.6e4 failed 1e-6):
  // the bound is 1e-7 of the face's box, more far out, or the face's own
  // tolerance.
  Bnd_Box box;
  BRepBndLib::Add(face, box);
  double reach = 0.0, diagonal = 0.0;
  if (!box.IsVoid()) {
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    for (const double c : {x0, y0, z0, x1, y1, z1}) reach = std::max(reach, std::abs(c));
    diagonal = std::sqrt(box.SquareExtent());
  }
  const double tolerance = std::max({1e-7, BRep_Tool::Tolerance(face), 1e-7 * diagonal, 1e-10 * reach});
  GeomLib_IsPlanarSurface check(BRep_Tool::Surface(face), tolerance);
  if (!check.IsPlanar()) return false;
  plane = check.Plan();
  return true;
}

// The face's 2-D frame: seen from the face normal, origin at the world origin's
// projection on the plane, x along the world X axis projected on the plane
// (world Y if X is normal to it). A face in the XY plane facing +Z thus keeps
// its world X and Y.
Frame face_frame(const gp_Pln& plane, bool reversed) {
  gp_Dir normal = plane.Axis().Direction();
  if (plane.Position().Direct() == reversed) normal.Reverse();
  const gp_XYZ n = normal.XYZ();
  gp_XYZ x = gp_XYZ(1, 0, 0) - n * n.X();
  if (x.Modulus() < 1e-6) x = gp_XYZ(0, 1, 0) - n * n.Y();
  x.Normalize();
  const gp_XYZ origin = n * n.Dot(plane.Location().XYZ());
  return Frame{arr(origin), arr(x), arr(n.Crossed(x)), arr(n)};
}

// Plane parameters (u, v) to face-frame coordinates: a rigid motion, with a
// mirror when the plane's axes turn the other way round the face normal.
gp_Trsf2d plane_to_frame(const gp_Pln& plane, const Frame& frame) {
  const gp_Ax3 axes = plane.Position();
  const gp_XYZ fx(frame.x_dir[0], frame.x_dir[1], frame.x_dir[2]);
  const gp_XYZ fy(frame.y_dir[0], frame.y_dir[1], frame.y_dir[2]);
  const gp_XYZ offset = axes.Location().XYZ() - gp_XYZ(frame.origin[0], frame.origin[1], frame.origin[2]);
  const gp_XYZ u = axes.XDirection().XYZ(), v = axes.YDirection().XYZ();
  gp_Trsf2d t;
  t.SetValues(u.Dot(fx), v.Dot(fx), offset.Dot(fx), u.Dot(fy), v.Dot(fy), offset.Dot(fy));
  return t;
}

RawFace raw_face(const TopoDS_Face& input, const std::string& name) {
  const TopoDS_Face face = TopoDS::Face(input.Oriented(TopAbs_FORWARD));
  gp_Pln plane;
  bool native = false;
  std::string surface_name;
  if (!find_plane(face, plane, native, surface_name)) {
    throw InputError(name + ": face is not planar (surface type: " + surface_name + ")");
  }
  RawFace raw;
  raw.name = name;
  raw.frame = face_frame(plane, input.Orientation() == TopAbs_REVERSED);
  const gp_Trsf2d to_frame = plane_to_frame(plane, raw.frame);
  TopTools_IndexedMapOfShape edge_numbers;
  TopExp::MapShapes(input, TopAbs_EDGE, edge_numbers);
  // An empty parameter range breaks OCC's own wire traversal, so check first.
  for (int i = 1; i <= edge_numbers.Extent(); ++i) {
    double first = 0.0, last = 0.0;
    BRep_Tool::Range(TopoDS::Edge(edge_numbers(i)), first, last);
    if (!(last - first > Precision::PConfusion()))
      throw InputError(name + ": edge " + std::to_string(i) + " has zero length");
  }
  for (TopExp_Explorer wires(face, TopAbs_WIRE); wires.More(); wires.Next()) {
    std::vector<BoundaryEdge> loop;
    for (BRepTools_WireExplorer it(TopoDS::Wire(wires.Current()), face); it.More(); it.Next()) {
      const TopoDS_Edge& edge = it.Current();
      raw.tolerance = std::max(raw.tolerance, BRep_Tool::Tolerance(edge));
      double first = 0.0, last = 0.0;
      Handle(Geom2d_Curve) curve2d;
      if (native) {
        curve2d = BRep_Tool::CurveOnSurface(edge, face, first, last);
      } else if (Handle(Geom_Curve) curve3d = BRep_Tool::Curve(edge, first, last)) {
        curve2d = GeomAPI::To2d(curve3d, plane);
      }
      if (curve2d.IsNull()) {
        throw InputError(name + ": edge " + std::to_string(edge_numbers.FindIndex(edge)) + " has no curve");
      }
      curve2d = Handle(Geom2d_Curve)::DownCast(curve2d->Transformed(to_frame));
      BoundaryEdge boundary_edge;
      boundary_edge.curve = to_curve(curve2d, first, last);
      const bool reversed = it.Orientation() == TopAbs_REVERSED;
      boundary_edge.t_start = reversed ? last : first;
      boundary_edge.t_end = reversed ? first : last;
      boundary_edge.source_index = edge_numbers.FindIndex(edge);
      loop.push_back(std::move(boundary_edge));
    }
    raw.loops.push_back(std::move(loop));
  }
  return raw;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Face numbers (1-based) of the planar faces, for error messages.
std::string planar_face_list(const TopTools_IndexedMapOfShape& faces) {
  std::string list;
  for (int i = 1; i <= faces.Extent(); ++i) {
    BRepAdaptor_Surface adaptor(TopoDS::Face(faces(i)), false);
    if (adaptor.GetType() != GeomAbs_Plane) continue;
    list += (list.empty() ? "" : ", ") + std::to_string(i);
  }
  return list.empty() ? "none" : list;
}

}  // namespace

TopoDS_Shape read_shape(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": file not found");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not a file");
  if (!std::ifstream(path).good()) throw InputError(path + ": file cannot be opened");
  if (std::filesystem::file_size(path, ec) == 0) throw InputError(path + ": file is empty");
  const std::string ext = lower_extension(path);
  TopoDS_Shape shape;
  try {
    if (ext == ".brep" || ext == ".brp") {
      BRep_Builder builder;
      SilencedStdout silence;
      if (!BRepTools::Read(shape, path.c_str(), builder)) shape.Nullify();
    } else if (ext == ".step" || ext == ".stp") {
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) == IFSelect_RetDone && reader.TransferRoots() > 0) shape = reader.OneShape();
    } else if (ext == ".iges" || ext == ".igs") {
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) == IFSelect_RetDone && reader.TransferRoots() > 0) shape = reader.OneShape();
    } else {
      throw InputError(path + ": unknown file type '" + ext + "' (expected .brep, .step, .stp, .iges or .igs)");
    }
  } catch (const Standard_Failure& failure) {
    throw InputError(path + ": cannot be read: " + failure.GetMessageString());
  }
  if (shape.IsNull()) throw InputError(path + ": cannot be read as " + ext.substr(1) + " (no shape in the file)");
  return shape;
}

FaceModel face_model_from_occ(const TopoDS_Face& face, const std::string& name) {
  try {
    return build_face_model(raw_face(face, name));
  } catch (const Standard_Failure& failure) {
    throw InputError(name + ": geometry error: " + failure.GetMessageString());
  }
}

TopoDS_Face face_of_shape(const TopoDS_Shape& shape, std::optional<int> face_index, const std::string& path) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  if (faces.Extent() == 0) throw InputError(path + ": file holds no face");
  if (!face_index) {
    if (faces.Extent() > 1) {
      throw InputError(path + ": file holds " + std::to_string(faces.Extent()) +
                       " faces; choose one with --face N (planar faces: " + planar_face_list(faces) + ")");
    }
    face_index = 1;
  }
  if (*face_index < 1 || *face_index > faces.Extent()) {
    throw InputError(path + ": face " + std::to_string(*face_index) + " is out of range (the file holds " +
                     std::to_string(faces.Extent()) + " faces)");
  }
  return TopoDS::Face(faces(*face_index));
}

std::vector<FaceModel> read_face_models(const std::string& path, const std::vector<int>& face_indices) {
  const TopoDS_Shape shape = read_shape(path);
  if (face_indices.empty()) return {face_model_from_occ(face_of_shape(shape, std::nullopt, path), path + ": face 1")};
  std::vector<FaceModel> models;
  for (int index : face_indices) {
    const std::string name = path + ": face " + std::to_string(index);
    models.push_back(face_model_from_occ(face_of_shape(shape, index, path), name));
  }
  return models;
}

std::vector<int> planar_faces_of_solid(const std::string& path, int solid) {
  const TopoDS_Shape shape = read_shape(path);
  TopTools_IndexedMapOfShape faces, solids;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  if (solid < 1 || solid > solids.Extent()) {
    throw InputError(path + ": solid " + std::to_string(solid) + " is out of range (the file holds " +
                     std::to_string(solids.Extent()) + " solids)");
  }
  std::vector<int> planar;
  TopTools_IndexedMapOfShape own;
  TopExp::MapShapes(solids(solid), TopAbs_FACE, own);
  for (int i = 1; i <= own.Extent(); ++i) {
    const TopoDS_Face& face = TopoDS::Face(own(i));
    gp_Pln plane;
    bool native = false;
    std::string surface_name;
    if (find_plane(face, plane, native, surface_name)) planar.push_back(faces.FindIndex(face));
  }
  if (planar.empty()) throw InputError(path + ": solid " + std::to_string(solid) + " has no planar face");
  std::sort(planar.begin(), planar.end());
  return planar;
}

TopoDS_Face face_from_brep_string(const std::string& brep, const std::string& name) {
  TopoDS_Shape shape;
  try {
    std::istringstream stream(brep);
    BRep_Builder builder;
    SilencedStdout silence;
    BRepTools::Read(shape, stream, builder);
  } catch (const Standard_Failure& failure) {
    throw InputError(name + ": cannot read BREP text: " + failure.GetMessageString());
  }
  if (shape.IsNull()) throw InputError(name + ": BREP text holds no shape");
  TopExp_Explorer it(shape, TopAbs_FACE);
  if (!it.More()) throw InputError(name + ": BREP text holds no face");
  const TopoDS_Face face = TopoDS::Face(it.Current());
  it.Next();
  if (it.More()) throw InputError(name + ": BREP text holds more than one face");
  return face;
}

FaceModel face_model_from_brep_string(const std::string& brep, const std::string& name) {
  return face_model_from_occ(face_from_brep_string(brep, name), name);
}

}  // namespace mm
