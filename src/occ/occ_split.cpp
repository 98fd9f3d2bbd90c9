#include "occ/occ_split.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Precision.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <gp_Pnt2d.hxx>
#include <optional>
#include <sstream>

#include "occ/occ_face.hpp"
#include "occ/occ_reader.hpp"
#include "occ/occ_split_io.hpp"
#include "occ/silenced_stdout.hpp"

namespace mm {
namespace {

using Polylines = std::vector<std::vector<Vec2>>;

gp_Pnt point_3d(const Frame& frame, Vec2 p) {
  const auto q = to_3d(frame, p);
  return gp_Pnt(q[0], q[1], q[2]);
}

Vec2 point_2d(const Frame& frame, const gp_Pnt& p) {
  const gp_XYZ d = p.XYZ() - gp_XYZ(frame.origin[0], frame.origin[1], frame.origin[2]);
  return {d.Dot(gp_XYZ(frame.x_dir[0], frame.x_dir[1], frame.x_dir[2])),
          d.Dot(gp_XYZ(frame.y_dir[0], frame.y_dir[1], frame.y_dir[2]))};
}

struct Area {
  double value = 0.0;
  double error = 0.0;  // absolute error estimate of the integration
};

// BRepGProp's fixed-order integration is 7.5e-5 off on the B-spline aerofoil; the
// adaptive one matches the exact area there to 1e-15 and says how far it trusts itself.
Area area_of(const TopoDS_Shape& shape) {
  GProp_GProps props;
  const double relative_error = BRepGProp::SurfaceProperties(shape, props, 1e-12);
  return {props.Mass(), std::abs(relative_error * props.Mass())};
}

// Diagonal of the face's bounding box, the length scale for snapping.
double face_size(const TopoDS_Face& face) {
  Bnd_Box box;
  BRepBndLib::AddOptimal(face, box, /*useTriangulation=*/false);
  return std::sqrt(box.SquareExtent());
}

// The largest tolerance OCC gives an edge of the face.
double edge_tolerance(const TopoDS_Face& face) {
  double tolerance = 0.0;
  for (TopExp_Explorer it(face, TopAbs_EDGE); it.More(); it.Next()) {
    tolerance = std::max(tolerance, BRep_Tool::Tolerance(TopoDS::Edge(it.Current())));
  }
  return tolerance;
}

// The nearest point of the face's boundary to p, preferring a boundary vertex
// within snap so that a split ending at a corner ends exactly there.
bool nearest_on_boundary(const TopoDS_Face& face, const gp_Pnt& p, double snap, gp_Pnt& nearest) {
  for (TopExp_Explorer it(face, TopAbs_VERTEX); it.More(); it.Next()) {
    const gp_Pnt v = BRep_Tool::Pnt(TopoDS::Vertex(it.Current()));
    if (v.Distance(p) <= snap) {
      nearest = v;
      return true;
    }
  }
  const TopoDS_Vertex vertex = BRepBuilderAPI_MakeVertex(p);
  double best = snap;
  bool found = false;
  for (TopExp_Explorer it(face, TopAbs_EDGE); it.More(); it.Next()) {
    BRepExtrema_DistShapeShape dist(vertex, it.Current());
    if (dist.IsDone() && dist.NbSolution() > 0 && dist.Value() <= best) {
      best = dist.Value();
      nearest = dist.PointOnShape2(1);
      found = true;
    }
  }
  return found;
}

// The nearest point of another split to p, if within snap, preferring the end
// of a split so that several splits meeting at a point all end exactly there.
bool nearest_on_splits(const Polylines& splits, std::size_t own, Vec2 p, double snap, Vec2& nearest) {
  double best = snap;
  bool found = false;
  for (std::size_t s = 0; s < splits.size(); ++s) {
    if (s == own || splits[s].empty()) continue;
    for (Vec2 end : {splits[s].front(), splits[s].back()}) {
      if (distance(p, end) <= best) {
        best = distance(p, end);
        nearest = end;
        found = true;
      }
    }
  }
  if (found) return true;
  for (std::size_t s = 0; s < splits.size(); ++s) {
    if (s == own) continue;
    for (std::size_t i = 0; i + 1 < splits[s].size(); ++i) {
      const Vec2 a = splits[s][i], d = splits[s][i + 1] - a;
      const double len2 = dot(d, d);
      const double t = len2 > 0.0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
      const Vec2 q = a + t * d;
      if (distance(p, q) <= best) {
        best = distance(p, q);
        nearest = q;
        found = true;
      }
    }
  }
  return found;
}

// Split ends come from the decomposition within about 1e-9 of the face size
// of where they belong, which can exceed OCC's 1e-7 tolerance on a large
// part, and an end that stops short leaves a dangling edge instead of a cut.
// So ends near the boundary go onto it (marked in on_boundary), then the rest
// onto the split they meet.
Polylines snap_ends(const TopoDS_Face& face, const Frame& frame, Polylines splits, double snap,
                    std::vector<std::vector<bool>>& on_boundary) {
  on_boundary.assign(splits.size(), {});
  for (std::size_t s = 0; s < splits.size(); ++s) {
    on_boundary[s].assign(splits[s].size(), false);
    if (splits[s].size() < 2) continue;
    for (std::size_t end : {std::size_t{0}, splits[s].size() - 1}) {
      gp_Pnt nearest;
      if (nearest_on_boundary(face, point_3d(frame, splits[s][end]), snap, nearest)) {
        splits[s][end] = point_2d(frame, nearest);
        on_boundary[s][end] = true;
      }
    }
  }
  for (std::size_t s = 0; s < splits.size(); ++s) {
    if (splits[s].size() < 2) continue;
    for (std::size_t end : {std::size_t{0}, splits[s].size() - 1}) {
      Vec2 nearest;
      if (!on_boundary[s][end] && nearest_on_splits(splits, s, splits[s][end], snap, nearest)) {
        splits[s][end] = nearest;
      }
    }
  }
  return splits;
}

// A split point outside the face is a wrong split or a wrong frame; the
// splitter would drop that part silently. Outside only when both of OCC's
// classifiers say so: on some notched plates BRepClass_FaceClassifier calls
// points well inside outside, on others BRepTopAdaptor_FClass2d does (found
// by the fuzzer; a Boolean with a small sphere showed the points inside).
// Ends snapped onto an edge are on the boundary by construction, and both
// classifiers call some of them outside (on notched plates a thousandth of a
// unit across, the fuzzer's 14 of 2 000): they are not asked.
void check_inside(const TopoDS_Face& face, const Frame& frame, const Polylines& splits,
                  const std::vector<std::vector<bool>>& on_boundary, double tolerance) {
  BRepTopAdaptor_FClass2d classifier(face, tolerance);
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  for (std::size_t s = 0; s < splits.size(); ++s) {
    for (std::size_t i = 0; i < splits[s].size(); ++i) {
      std::vector<Vec2> points;
      if (!on_boundary[s][i]) points.push_back(splits[s][i]);
      if (i + 1 < splits[s].size()) points.push_back(0.5 * (splits[s][i] + splits[s][i + 1]));
      for (Vec2 p : points) {
        GeomAPI_ProjectPointOnSurf projection(point_3d(frame, p), surface);
        double u = 0.0, v = 0.0;
        if (projection.NbPoints() > 0) projection.LowerDistanceParameters(u, v);
        if (projection.NbPoints() > 0 && classifier.Perform(gp_Pnt2d(u, v)) != TopAbs_OUT) continue;
        if (BRepClass_FaceClassifier(face, point_3d(frame, p), tolerance).State() != TopAbs_OUT) continue;
        std::ostringstream text;
        text << "split " << s + 1 << " leaves the face at (" << p.x << ", " << p.y << ")";
        throw InputError(text.str());
      }
    }
  }
}

std::string splitter_errors(const BRepAlgoAPI_Splitter& splitter) {
  std::ostringstream text;
  splitter.DumpErrors(text);
  std::string message = text.str();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

TopoDS_Compound compound_of(const std::vector<TopoDS_Shape>& shapes) {
  TopoDS_Compound compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  for (const TopoDS_Shape& shape : shapes) builder.Add(compound, shape);
  return compound;
}

std::string brep_text(const TopoDS_Shape& shape) {
  std::ostringstream text;
  BRepTools::Write(shape, text);
  return text.str();
}

// The face without its wires shorter than `length`. Where a split ends at
// each end of a boundary edge barely longer than OCC's tolerance (the closing
// edge of an aerofoil's trailing edge, 5e-7 long, with a concave corner's
// split at both ends), the splitter merges the two ends and leaves that edge
// as a wire of its own, one degenerate edge enclosing nothing, and the block
// face is invalid (BadOrientationOfSubshape).
TopoDS_Face without_short_wires(const TopoDS_Face& face, double length) {
  TopoDS_Face result = TopoDS::Face(face.EmptyCopied());
  BRep_Builder builder;
  for (TopExp_Explorer it(face, TopAbs_WIRE); it.More(); it.Next()) {
    GProp_GProps props;
    BRepGProp::LinearProperties(it.Current(), props);
    if (props.Mass() > length) builder.Add(result, it.Current());
  }
  return result;
}

template <typename T>
std::vector<TopoDS_Shape> shapes(const std::vector<T>& items) {
  return std::vector<TopoDS_Shape>(items.begin(), items.end());
}

}  // namespace

std::vector<TopoDS_Edge> split_edges_3d(const Frame& frame, const Polylines& polylines) {
  std::vector<TopoDS_Edge> edges;
  for (const std::vector<Vec2>& polyline : polylines) {
    TopoDS_Vertex previous;
    for (std::size_t i = 0; i < polyline.size(); ++i) {
      const gp_Pnt p = point_3d(frame, polyline[i]);
      // OCC cannot make an edge shorter than its confusion tolerance.
      if (!previous.IsNull() && BRep_Tool::Pnt(previous).Distance(p) <= Precision::Confusion()) continue;
      const TopoDS_Vertex vertex = BRepBuilderAPI_MakeVertex(p);
      if (!previous.IsNull()) edges.push_back(BRepBuilderAPI_MakeEdge(previous, vertex));
      previous = vertex;
    }
  }
  return edges;
}

std::vector<TopoDS_Face> split_face(const TopoDS_Face& face, const Frame& frame, const Polylines& polylines) {
  std::vector<TopoDS_Face> blocks;
  try {
    const double size = face_size(face);
    // The boundary model keeps a B-spline it recognises as an arc as that
    // exact arc, within 1e-5 of the face size of OCC's curve: split ends on
    // it are that far from OCC's edge, or as far as OCC's own tolerance says.
    const double snap = std::max(2e-5 * size, edge_tolerance(face));
    std::vector<std::vector<bool>> on_boundary;
    const Polylines splits = snap_ends(face, frame, polylines, snap, on_boundary);
    check_inside(face, frame, splits, on_boundary, snap);
    const std::vector<TopoDS_Edge> edges = split_edges_3d(frame, splits);
    if (edges.empty()) {
      blocks.push_back(face);  // the splitter refuses to run without tools
    } else {
      // OCC's boolean operations work to an absolute precision (1e-7): a
      // face much smaller than a unit is cut at unit size and scaled back.
      const double scale = std::max(1.0, 1.0 / size);
      gp_Trsf up, down;
      up.SetScale(gp_Pnt(0, 0, 0), scale);
      down.SetScale(gp_Pnt(0, 0, 0), 1.0 / scale);
      const auto scaled = [&](const TopoDS_Shape& shape, const gp_Trsf& how) {
        return scale > 1.0 ? BRepBuilderAPI_Transform(shape, how, /*copy=*/true).Shape() : shape;
      };
      TopTools_ListOfShape arguments, tools;
      arguments.Append(scaled(face, up));
      for (const TopoDS_Edge& edge : edges) tools.Append(scaled(edge, up));
      BRepAlgoAPI_Splitter splitter;
      splitter.SetArguments(arguments);
      splitter.SetTools(tools);
      splitter.Build();
      if (splitter.HasErrors()) throw InputError("splitting into blocks failed: " + splitter_errors(splitter));
      // A split that does not separate the face (an annulus cut once) comes
      // back as an INTERNAL edge in a wire of its own inside the one face, the
      // loops it touches cut at its ends: valid, and it adds no area.
      for (TopExp_Explorer it(splitter.Shape(), TopAbs_FACE); it.More(); it.Next()) {
        blocks.push_back(TopoDS::Face(scaled(it.Current(), down)));
      }
    }
    const Area face_area = area_of(face);
    Area sum;
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      const std::string block = "block face " + std::to_string(i + 1) + " of " + std::to_string(blocks.size());
      if (!BRepCheck_Analyzer(blocks[i]).IsValid()) blocks[i] = without_short_wires(blocks[i], snap);
      if (!BRepCheck_Analyzer(blocks[i]).IsValid()) throw InputError(block + " is not valid (BRepCheck_Analyzer)");
      const Area area = area_of(blocks[i]);
      if (!(area.value > 0.0)) throw InputError(block + " has area " + std::to_string(area.value) + " (BRepGProp)");
      sum.value += area.value;
      sum.error += area.error;
    }
    // 1e-8: splitting B-spline edges moves them within OCC's own tolerance
    // (1.3e-9 of the area on the crank arm face); on faces a thousandth of a
    // unit across, that tolerance (about 1e-7 absolute) times their size
    // is the larger term.
    const double occ_tolerance = edge_tolerance(face) * face_size(face);
    if (!(std::abs(sum.value - face_area.value) <=
          1e-8 * face_area.value + face_area.error + sum.error + occ_tolerance)) {
      std::ostringstream text;
      text.precision(17);
      text << "block areas add up to " << sum.value << ", the face's area is " << face_area.value << " (BRepGProp)";
      throw InputError(text.str());
    }
  } catch (const Standard_Failure& failure) {
    throw InputError(std::string("splitting into blocks failed: ") + failure.GetMessageString());
  }
  return blocks;
}

std::string split_face_brep(const std::string& face_brep, const Polylines& polylines, const std::string& name) {
  const TopoDS_Face face = face_from_brep_string(face_brep, name);
  const Frame frame = face_model_from_occ(face, name).frame;
  try {
    return brep_text(compound_of(shapes(split_face(face, frame, polylines))));
  } catch (const InputError& error) {
    throw InputError(name + ": " + error.what());
  }
}

std::string split_edges_brep(const std::string& face_brep, const Polylines& polylines, const std::string& name) {
  const Frame frame = face_model_from_brep_string(face_brep, name).frame;
  return brep_text(compound_of(shapes(split_edges_3d(frame, polylines))));
}

void write_blocks_brep(const std::string& input_path, int face_index, const Polylines& polylines,
                       const std::string& out_path) {
  std::string ext = std::filesystem::path(out_path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool step = ext == ".step" || ext == ".stp";
  if (!step && ext != ".brep" && ext != ".brp") {
    throw InputError(out_path + ": unknown output type '" + ext + "' (expected .brep, .brp, .step or .stp)");
  }
  const TopoDS_Face face = face_of_shape(read_shape(input_path),
                                         face_index == 0 ? std::nullopt : std::optional<int>(face_index), input_path);
  const std::string name = input_path + ": face " + std::to_string(std::max(face_index, 1));
  const Frame frame = face_model_from_occ(face, name).frame;
  TopoDS_Compound blocks;
  try {
    blocks = compound_of(shapes(split_face(face, frame, polylines)));
  } catch (const InputError& error) {
    throw InputError(name + ": " + error.what());
  }
  bool written = false;
  if (step) {
    SilencedStdout silence;  // the STEP writer prints its statistics
    STEPControl_Writer writer;
    written = writer.Transfer(blocks, STEPControl_AsIs) == IFSelect_RetDone &&
              writer.Write(out_path.c_str()) == IFSelect_RetDone;
  } else {
    written = BRepTools::Write(blocks, out_path.c_str());
  }
  if (!written) throw InputError(out_path + ": cannot write");
}

}  // namespace mm
