// _medialmesh: the core and the OCC reader seen from Python (and FreeCAD).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "occ/occ_reader.hpp"
#include "pipeline/pipeline.hpp"
#include "quality/quad_measures.hpp"
#include "report/decomposition_report.hpp"
#include "report/face_report.hpp"
#include "report/medial_report.hpp"
#include "report/mesh_report.hpp"
#include "report/singularity_report.hpp"

namespace py = pybind11;

namespace {

py::object to_python(const nlohmann::json& json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

// The JSON report plus what a Python caller needs to draw or map back to 3-D.
py::object face_dict(const mm::FaceModel& face) {
  nlohmann::json report = mm::face_report_json(face);
  report["frame"] = mm::frame_json(face.frame);
  nlohmann::json loops = nlohmann::json::array();
  for (const mm::Loop& loop : face.loops) {
    nlohmann::json points = nlohmann::json::array();
    for (const mm::Vec2& p : mm::sample_loop(loop, 1e-4 * face.size)) points.push_back({p.x, p.y});
    loops.push_back(points);
  }
  report["loops"] = loops;
  return to_python(report);
}

// Elements as 0-based node indices: the 4 corners counter-clockwise, then
// for order 2 the 4 mid-side nodes (side i from corner i to i + 1).
py::array_t<int> element_array(const std::vector<std::array<int, 4>>& quads,
                               const std::vector<std::array<int, 4>>& midside) {
  const auto count = static_cast<py::ssize_t>(quads.size());
  py::array_t<int> elements({count, static_cast<py::ssize_t>(midside.empty() ? 4 : 8)});
  auto e = elements.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < count; ++i) {
    for (int c = 0; c < 4; ++c) e(i, c) = quads[i][c];
    if (!midside.empty())
      for (int c = 0; c < 4; ++c) e(i, 4 + c) = midside[i][c];
  }
  return elements;
}

// Each quad's Verdict shape (quad_measures.hpp), in the order of `meshes`'
// quads one mesh after the other: what a view colours the elements by.
py::array_t<double> element_shapes(const std::vector<const mm::QuadMesh*>& meshes) {
  py::ssize_t count = 0;
  for (const mm::QuadMesh* mesh : meshes) count += static_cast<py::ssize_t>(mesh->quads.size());
  py::array_t<double> shapes(count);
  auto s = shapes.mutable_unchecked<1>();
  py::ssize_t i = 0;
  for (const mm::QuadMesh* mesh : meshes)
    for (const auto& quad : mesh->quads)
      s(i++) =
          mm::measure_quad({mesh->nodes[quad[0]], mesh->nodes[quad[1]], mesh->nodes[quad[2]], mesh->nodes[quad[3]]})
              .shape;
  return shapes;
}

// The mesh as numpy arrays: nodes in 3-D (the face's frame) and in the face's
// plane, elements as 0-based node indices (4 corners, then 4 mid-side nodes).
py::dict mesh_dict(const mm::FaceModel& face, const mm::MeshedFace& meshed) {
  const mm::QuadMesh& mesh = meshed.blocks.mesh;
  const auto node_count = static_cast<py::ssize_t>(mesh.nodes.size());
  py::array_t<double> nodes({node_count, py::ssize_t{3}});
  py::array_t<double> plane({node_count, py::ssize_t{2}});
  auto n3 = nodes.mutable_unchecked<2>();
  auto n2 = plane.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < node_count; ++i) {
    const std::array<double, 3> p = mm::to_3d(face.frame, mesh.nodes[i]);
    for (int c = 0; c < 3; ++c) n3(i, c) = p[c];
    n2(i, 0) = mesh.nodes[i].x;
    n2(i, 1) = mesh.nodes[i].y;
  }
  const py::array_t<int> elements = element_array(mesh.quads, mesh.midside);
  const auto element_count = static_cast<py::ssize_t>(mesh.quads.size());
  py::array_t<int> blocks(element_count);
  auto b = blocks.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < element_count; ++i) b(i) = mesh.block_of_quad.empty() ? 0 : mesh.block_of_quad[i];
  py::dict result;
  result["nodes"] = nodes;
  result["nodes_2d"] = plane;
  result["elements"] = elements;
  result["element_blocks"] = blocks;
  result["element_shape"] = element_shapes({&mesh});
  nlohmann::json report = mm::mesh_report_json(meshed.quality, mesh.order());
  report["notes"] = meshed.blocks.notes;
  report["fallbacks"] = mm::fallback_list(meshed.fallbacks);
  result["report"] = to_python(report);
  nlohmann::json decomposition = mm::decomposition_report_json(face, meshed.decomposition);
  decomposition["frame"] = mm::frame_json(face.frame);
  result["decomposition"] = to_python(decomposition);
  return result;
}

// Several faces' merged mesh as numpy arrays, its report, and each face's
// report and decomposition.
py::dict merged_mesh_dict(const std::vector<mm::FaceModel>& faces, const mm::MeshedFaces& meshed) {
  const mm::MergedMesh& mesh = meshed.mesh;
  const auto node_count = static_cast<py::ssize_t>(mesh.nodes.size());
  py::array_t<double> nodes({node_count, py::ssize_t{3}});
  auto n3 = nodes.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < node_count; ++i)
    for (int c = 0; c < 3; ++c) n3(i, c) = mesh.nodes[i][c];
  const py::array_t<int> elements = element_array(mesh.quads, mesh.midside);
  const auto element_count = static_cast<py::ssize_t>(mesh.quads.size());
  py::array_t<int> element_faces(element_count);
  py::array_t<int> blocks(element_count);
  auto f = element_faces.mutable_unchecked<1>();
  auto b = blocks.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < element_count; ++i) {
    f(i) = mesh.face_of_quad[i];
    b(i) = mesh.block_of_quad[i];
  }
  py::dict result;
  result["nodes"] = nodes;
  result["elements"] = elements;
  result["element_faces"] = element_faces;
  result["element_blocks"] = blocks;
  std::vector<const mm::QuadMesh*> face_meshes;  // merged face by face, in this order
  for (const mm::MeshedFace& face : meshed.faces) face_meshes.push_back(&face.blocks.mesh);
  result["element_shape"] = element_shapes(face_meshes);
  nlohmann::json report = mm::merged_mesh_report_json(meshed.quality, mesh, mm::shared_edge_count(meshed.shared));
  report["notes"] = meshed.faces.front().blocks.notes;
  report["fallbacks"] = mm::fallback_list(meshed.fallbacks);
  result["report"] = to_python(report);
  py::list per_face;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const mm::MeshedFace& m = meshed.faces[i];
    nlohmann::json face_report = mm::mesh_report_json(m.quality, m.blocks.mesh.order());
    face_report["face"] = faces[i].name;
    face_report["fallbacks"] = mm::fallback_list(m.fallbacks);
    nlohmann::json decomposition = mm::decomposition_report_json(faces[i], m.decomposition);
    decomposition["frame"] = mm::frame_json(faces[i].frame);
    py::dict entry;
    entry["report"] = to_python(face_report);
    entry["decomposition"] = to_python(decomposition);
    per_face.append(entry);
  }
  result["faces"] = per_face;
  return result;
}

// mesh and mesh_faces: merge factor or distance given, merging; neither, none.
mm::PipelineOptions pipeline_options(double size, int order, std::optional<double> merge,
                                     std::optional<double> merge_size, bool smooth, mm::Progress* progress) {
  mm::PipelineOptions options;
  options.meshing.progress = progress;
  options.meshing.size = size;
  options.meshing.order = order;
  options.meshing.smooth = smooth;
  options.decomposition.merge = merge.has_value() || merge_size.has_value();
  options.decomposition.tolerance = {merge.value_or(0.75), merge_size.value_or(0.0)};
  return options;
}

}  // namespace

PYBIND11_MODULE(_medialmesh, m) {
  m.doc() = "MedialMesh core: boundary model, medial axis and singularities of planar faces";
  py::register_exception<mm::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<mm::SelfCheckError>(m, "SelfCheckError", PyExc_RuntimeError);
  static py::exception<mm::Cancelled> cancelled(m, "Cancelled", PyExc_Exception);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const mm::Cancelled&) {
      cancelled("meshing cancelled");
    }
  });

  py::class_<mm::Progress>(m, "Progress",
                           "How far a mesh() or mesh_faces() call has got, read from another thread while it "
                           "runs, and cancel() to stop it: the call then raises Cancelled.")
      .def(py::init<>())
      .def_property_readonly(
          "stage", [](const mm::Progress& p) { return p.state().stage; },
          "The stage running: 'medial axis', 'decomposition', 'interval counts', 'blocks', 'smoothing', "
          "'checks', 'joining faces', 'quality'; '' before the first")
      .def_property_readonly(
          "done", [](const mm::Progress& p) { return p.state().done; }, "Steps of the stage done (faces, blocks)")
      .def_property_readonly(
          "total", [](const mm::Progress& p) { return p.state().total; }, "Steps the stage has; 0: not counted")
      .def("cancel", &mm::Progress::cancel, "Ask the running call to stop at its next step")
      .def_property_readonly("cancelled", &mm::Progress::cancelled);

  m.def(
      "face_model",
      [](const std::string& brep, const std::string& name) {
        return face_dict(mm::face_model_from_brep_string(brep, name));
      },
      py::arg("brep"), py::arg("name") = "face",
      "Boundary model of one planar face given as BREP text (Face.exportBrepToString()).");

  m.def(
      "medial_axis",
      [](const std::string& brep, const std::string& name) {
        const mm::FaceAxis medial = mm::compute_face_medial_axis(mm::face_model_from_brep_string(brep, name));
        nlohmann::json report = mm::medial_report_json(medial.axis);
        if (!medial.note.empty()) report["notes"] = {medial.note};
        report["frame"] = mm::frame_json(medial.face.frame);
        return to_python(report);
      },
      py::arg("brep"), py::arg("name") = "face",
      "Medial axis of one planar face given as BREP text: {'vertices': [{'x','y','r','kind'}], "
      "'edges': [{'from','to','polyline': [[x, y, r], ...]}], 'frame': {...}} in the face's 2-D frame.");

  m.def(
      "analyse",
      [](const std::string& brep, const std::string& name, std::optional<double> merge_factor,
         std::optional<double> mesh_size) {
        const mm::FaceFlow analysed = mm::face_flow(mm::face_model_from_brep_string(brep, name));
        const mm::FaceModel& face = analysed.face;
        const mm::MedialAxis& axis = analysed.axis;
        const mm::MeshFlow& flow = analysed.flow;
        std::vector<mm::SingularityGroup> groups;
        const bool merge = merge_factor || mesh_size;
        if (merge)
          groups = mm::merge_singularities(flow.singularities, {merge_factor.value_or(0.75), mesh_size.value_or(0.0)});
        nlohmann::json report = mm::singularity_report_json(face, flow, merge ? &groups : nullptr);
        report["medial_axis"] = mm::medial_report_json(axis);
        if (!analysed.note.empty()) report["notes"] = {analysed.note};
        report["frame"] = mm::frame_json(face.frame);
        return to_python(report);
      },
      py::arg("brep"), py::arg("name") = "face", py::arg("merge_factor") = py::none(),
      py::arg("mesh_size") = py::none(),
      "Medial axis, flow types and singularities of one planar face given as BREP text: "
      "{'medial_axis': {...}, 'flow': [{'edge','n','polyline'}], 'singularities': [{'x','y','k','at',...}], "
      "'sum_k', 'predicted_sum_k', 'frame'}; with merge_factor (0.25 to 1) or mesh_size the singularities "
      "are merged groups with 'members' into 'unmerged'.");

  m.def(
      "decompose",
      [](const std::string& brep, const std::string& name, std::optional<double> merge,
         std::optional<double> mesh_size) {
        mm::DecompositionOptions options;
        options.merge = merge.has_value() || mesh_size.has_value();
        options.tolerance = {merge.value_or(0.75), mesh_size.value_or(0.0)};
        const mm::DecomposedFace decomposed = mm::decompose_face(mm::face_model_from_brep_string(brep, name), options);
        nlohmann::json report = mm::decomposition_report_json(decomposed.face, decomposed.decomposition);
        report["frame"] = mm::frame_json(decomposed.face.frame);
        report["fallbacks"] = mm::fallback_list(decomposed.fallbacks);
        return to_python(report);
      },
      py::arg("brep"), py::arg("name") = "face", py::arg("merge") = py::none(), py::arg("mesh_size") = py::none(),
      "Block decomposition of one planar face given as BREP text: {'blocks': [{'kind', 'sides', 'boundary', "
      "'area', 'singularity', 'corners', 'side_pieces'}], 'splits': [{'polyline', 'reason'}], 'fixed', "
      "'singularities', 'fallback', 'fallbacks', 'notes', 'face_area', 'frame'} in the face's 2-D frame; merge (a "
      "factor "
      "in 0.25 to 1) or mesh_size merge close singularities first, neither: no merging. Raises InputError "
      "for a face that cannot be read, SelfCheckError when the decomposition fails its own checks.");

  m.def(
      "mesh",
      [](const std::string& brep, double size, int order, std::optional<double> merge, std::optional<double> merge_size,
         bool smooth, const std::string& name, mm::Progress* progress) {
        const mm::FaceModel face = mm::face_model_from_brep_string(brep, name);
        const mm::PipelineOptions options = pipeline_options(size, order, merge, merge_size, smooth, progress);
        mm::MeshedFace meshed;
        {
          py::gil_scoped_release release;  // the FreeCAD GUI keeps drawing while we mesh
          meshed = mm::mesh_face(face, options);
        }
        return mesh_dict(face, meshed);
      },
      py::arg("brep"), py::arg("size"), py::arg("order") = 1, py::arg("merge") = 0.75,
      py::arg("merge_size") = py::none(), py::arg("smooth") = true, py::arg("name") = "face",
      py::arg("progress") = py::none(),
      "All-quad mesh of one planar face given as BREP text, with target element size `size` and element "
      "order 1 (4-node) or 2 (8-node): {'nodes': (N, 3) array in 3-D, 'nodes_2d': (N, 2) in the face's "
      "frame, 'elements': (M, 4 or 8) 0-based node indices (corners counter-clockwise, then mid-side "
      "nodes), 'element_blocks': (M,), 'element_shape': (M,) Verdict shape, 'report': quality report, 'decomposition': "
      "the blocks}. merge is "
      "the merge factor (None: no merging), merge_size a merge distance. progress: a Progress told the stages "
      "as they run (the GIL is let go meanwhile). Raises InputError for bad input, SelfCheckError when a stage "
      "fails its own checks, Cancelled when progress.cancel() was called.");

  m.def(
      "mesh_faces",
      [](const std::vector<std::string>& breps, double size, int order, std::optional<double> merge,
         std::optional<double> merge_size, bool smooth, std::optional<std::vector<std::string>> names,
         mm::Progress* progress) {
        if (names && names->size() != breps.size())
          throw mm::InputError("mesh_faces: " + std::to_string(breps.size()) + " faces but " +
                               std::to_string(names->size()) + " names");
        std::vector<mm::FaceModel> faces;
        for (std::size_t i = 0; i < breps.size(); ++i)
          faces.push_back(
              mm::face_model_from_brep_string(breps[i], names ? (*names)[i] : "face " + std::to_string(i + 1)));
        const mm::PipelineOptions options = pipeline_options(size, order, merge, merge_size, smooth, progress);
        mm::MeshedFaces meshed;
        {
          py::gil_scoped_release release;
          meshed = mm::mesh_faces(faces, options);
        }
        return merged_mesh_dict(faces, meshed);
      },
      py::arg("breps"), py::arg("size"), py::arg("order") = 1, py::arg("merge") = 0.75,
      py::arg("merge_size") = py::none(), py::arg("smooth") = true, py::arg("names") = py::none(),
      py::arg("progress") = py::none(),
      "All-quad mesh of several planar faces meshed together, each given as BREP text: where faces share a "
      "piece of edge in 3-D (coplanar or not, T-junctions included) they get the same nodes, and the result "
      "is one mesh: {'nodes': (N, 3) array, 'elements': (M, 4 or 8) 0-based node indices (corners "
      "counter-clockwise seen from each face's normal, then mid-side nodes), 'element_faces': (M,) index "
      "into breps, 'element_blocks': (M,) block within its face, 'element_shape': (M,) Verdict shape, 'report': "
      "quality report of the merged mesh "
      "(the keys of mesh()'s report, irregular nodes in 3-D, plus 'shared_edges'), 'faces': [{'report', "
      "'decomposition'}] per face}. names name the faces in messages ('face 1', ... if left out); progress "
      "as for mesh(). Raises InputError for bad input, SelfCheckError when a stage or the merged mesh fails "
      "its own checks, Cancelled when progress.cancel() was called.");

  m.def(
      "read_faces",
      [](const std::string& path, const std::vector<int>& faces) {
        py::list result;
        for (const auto& face : mm::read_face_models(path, faces)) result.append(face_dict(face));
        return result;
      },
      py::arg("path"), py::arg("faces") = std::vector<int>{},
      "Boundary models of faces (1-based numbers) read from a BREP, STEP or IGES file.");
}
