// medialmesh: the batch tool. Reads CAD files and reports on or draws planar faces.
#include <sys/wait.h>
#include <unistd.h>

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "occ/occ_reader.hpp"
#include "occ/occ_split_io.hpp"
#include "pipeline/pipeline.hpp"
#include "report/decomposition_report.hpp"
#include "report/face_report.hpp"
#include "report/medial_report.hpp"
#include "report/mesh_files.hpp"
#include "report/mesh_report.hpp"
#include "report/singularity_report.hpp"
#include "svg/svg_writer.hpp"

namespace {

constexpr const char* kUsage =
    "usage: medialmesh info FILE [--face N]... [--solid S] [--json]\n"
    "       medialmesh svg FILE [--face N] -o OUT.svg\n"
    "       medialmesh medial FILE [--face N] [--json] [--svg OUT.svg]\n"
    "       medialmesh singularities FILE [--face N] [--merge F | --merge-size H] [--json] [--svg OUT.svg]\n"
    "       medialmesh decompose FILE [--face N] [--merge F | --merge-size H | --no-merge] [--json] [--svg OUT.svg]\n"
    "                            [--blocks OUT.brep|OUT.step]\n"
    "       medialmesh mesh FILE [--face N]... [--solid S] [--size H] [--order 1|2] [--merge F | --merge-size H | "
    "--no-merge]\n"
    "                       [-o OUT.inp|OUT.msh|OUT.vtu] [--shell] [--no-smooth] [--json] [--svg OUT.svg]\n"
    "FILE is a .brep, .step/.stp or .iges/.igs file; N counts faces from 1 as FreeCAD's FaceN.\n"
    "--face (or --faces) takes a number or a comma-separated list, repeatable (info and mesh only).\n"
    "mesh with several faces meshes them together: where they share a piece of edge in 3-D (in one\n"
    "plane or not) both get the same nodes, and the files hold one mesh with those nodes once.\n"
    "--solid S takes every planar face of solid S (counted from 1 as FreeCAD's Solids) at once.\n"
    "--merge [F] merges singularities closer than F times their medial radius (F in [0.25, 1],\n"
    "0.75 if left out); --merge-size H merges those closer than H (a target mesh size).\n"
    "decompose and mesh merge with F = 0.75 unless told otherwise.\n"
    "mesh: H is the target element size (a twentieth of the face's diagonal if left out); .inp files\n"
    "hold CPS4/CPS8 plane-stress elements, S4/S8 shells with --shell.\n"
    "--read-time-limit S gives up reading FILE after S seconds (60 if left out).\n";

struct Options {
  std::string command;
  std::string file;
  std::vector<int> faces;
  int solid = 0;  // 0: none given
  bool json = false;
  std::string output;
  std::string svg;
  std::string blocks;
  std::optional<double> size;
  int order = 1;
  bool shell = false;
  bool smooth = true;
  std::optional<mm::MergeTolerance> merge;
  bool no_merge = false;
  unsigned read_time_limit = 60;
};

struct UsageError {
  std::string message;
};

std::vector<int> parse_face_list(const std::string& text) {
  std::vector<int> faces;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size()) throw UsageError{"--face needs a face number, got '" + text + "'"};
    faces.push_back(value);
    begin = end + 1;
  }
  return faces;
}

std::optional<double> parse_number(const std::string& text) {
  std::size_t used = 0;
  double number = 0.0;
  try {
    number = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size()) return std::nullopt;
  return number;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) throw UsageError{"no command given"};
  o.command = args[0];
  if (o.command != "info" && o.command != "svg" && o.command != "medial" && o.command != "singularities" &&
      o.command != "decompose" && o.command != "mesh")
    throw UsageError{"unknown command '" + o.command + "'"};
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError{a + " needs a value"};
      return args[++i];
    };
    if (a == "--face" || a == "--faces") {
      for (int f : parse_face_list(value())) o.faces.push_back(f);
    } else if (a == "--solid") {
      const std::string& text = value();
      const std::optional<double> number = parse_number(text);
      if (!number || *number < 1 || *number != std::floor(*number) || *number > 1e9)
        throw UsageError{"--solid needs a solid number (1, 2, ...), got '" + text + "'"};
      o.solid = static_cast<int>(*number);
    } else if (a == "--json") {
      o.json = true;
    } else if (a == "-o" || a == "--output") {
      o.output = value();
    } else if (a == "--svg") {
      o.svg = value();
    } else if (a == "--blocks") {
      o.blocks = value();
    } else if (a == "--merge" && (i + 1 >= args.size() || !parse_number(args[i + 1]))) {
      o.merge = mm::MergeTolerance{};
    } else if (a == "--merge" || a == "--merge-size") {
      const std::string& text = value();
      const std::optional<double> number = parse_number(text);
      if (!number) throw UsageError{a + " needs a number, got '" + text + "'"};
      o.merge = a == "--merge" ? mm::MergeTolerance{*number, 0.0} : mm::MergeTolerance{0.75, *number};
    } else if (a == "--size" || a == "--order") {
      const std::string& text = value();
      const std::optional<double> number = parse_number(text);
      if (!number) throw UsageError{a + " needs a number, got '" + text + "'"};
      if (a == "--size") {
        o.size = *number;
      } else {
        o.order = *number == 1.0 ? 1 : *number == 2.0 ? 2 : 0;
        if (o.order == 0) throw UsageError{"--order is 1 or 2, got '" + text + "'"};
      }
    } else if (a == "--shell") {
      o.shell = true;
    } else if (a == "--no-smooth") {
      o.smooth = false;
    } else if (a == "--no-merge") {
      o.no_merge = true;
    } else if (a == "--read-time-limit") {
      const std::string& text = value();
      const std::optional<double> seconds = parse_number(text);
      if (!seconds || *seconds < 1 || *seconds > 86400)
        throw UsageError{a + " needs seconds (1 to 86400), got '" + text + "'"};
      o.read_time_limit = static_cast<unsigned>(*seconds);
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError{"unknown option '" + a + "'"};
    } else if (o.file.empty()) {
      o.file = a;
    } else {
      throw UsageError{"more than one input file given"};
    }
  }
  if (o.file.empty()) throw UsageError{"no input file given"};
  if (o.command == "svg" && o.output.empty()) throw UsageError{"svg needs -o OUT.svg"};
  if (o.command != "info" && o.command != "mesh" && o.faces.size() > 1)
    throw UsageError{o.command + " takes a single --face"};
  if (o.solid > 0 && o.command != "info" && o.command != "mesh")
    throw UsageError{"--solid belongs to the info and mesh commands"};
  if (o.solid > 0 && !o.faces.empty()) throw UsageError{"give --face or --solid, not both"};
  // Meshing a face with itself would glue the copies along their whole outline.
  for (std::size_t i = 0; o.command == "mesh" && i < o.faces.size(); ++i) {
    if (std::count(o.faces.begin(), o.faces.begin() + i, o.faces[i]) > 0)
      throw UsageError{"face " + std::to_string(o.faces[i]) + " given twice"};
  }
  if (o.command == "medial" && !o.json && o.svg.empty()) throw UsageError{"medial needs --json or --svg OUT.svg"};
  if ((o.merge || o.no_merge) && o.command != "singularities" && o.command != "decompose" && o.command != "mesh")
    throw UsageError{"--merge belongs to the singularities, decompose and mesh commands"};
  if (o.no_merge && o.command == "singularities") throw UsageError{"--no-merge belongs to decompose and mesh"};
  if (o.command != "mesh" && (o.size || o.order != 1 || o.shell || !o.smooth))
    throw UsageError{"--size, --order, --shell and --no-smooth belong to the mesh command"};
  if (o.merge && o.no_merge) throw UsageError{"--merge and --no-merge exclude each other"};
  if (o.command == "decompose" && !o.json && o.svg.empty() && o.blocks.empty())
    throw UsageError{"decompose needs --json, --svg OUT.svg or --blocks OUT.brep"};
  if (!o.blocks.empty() && o.command != "decompose") throw UsageError{"--blocks belongs to the decompose command"};
  return o;
}

void run_singularities(const Options& o, const mm::FaceModel& given) {
  const mm::FaceFlow analysed = mm::face_flow(given);
  const mm::FaceModel& face = analysed.face;
  const mm::MeshFlow& flow = analysed.flow;
  std::vector<mm::SingularityGroup> groups;
  if (o.merge) groups = mm::merge_singularities(flow.singularities, *o.merge);
  std::vector<mm::SingularityMark> marks;
  if (o.merge) {
    for (const auto& g : groups) marks.push_back({g.p, g.k});
  } else {
    for (const auto& s : flow.singularities) marks.push_back({s.p, s.k});
  }
  nlohmann::json report = mm::singularity_report_json(face, flow, o.merge ? &groups : nullptr);
  if (!analysed.note.empty()) report["notes"] = {analysed.note};
  if (o.json) {
    std::cout << report.dump(2) << "\n";
  } else {
    std::cout << face.name << ": " << marks.size() << " singularities, sum k = " << report["sum_k"] << " (predicted "
              << report["predicted_sum_k"] << ")\n";
    for (const auto& s : report["singularities"]) {
      std::cout << "  k = " << s["k"] << " at (" << s["x"] << ", " << s["y"] << ") " << s["at"].get<std::string>()
                << "\n";
    }
  }
  if (!o.svg.empty()) {
    mm::SvgCanvas canvas(mm::bounding_box(face), 800);
    mm::draw_face(canvas, face);
    mm::draw_mesh_flow(canvas, face, flow, marks);
    canvas.save(o.svg);
  }
}

void run_decompose(const Options& o, const mm::FaceModel& given) {
  mm::DecompositionOptions options;
  options.merge = !o.no_merge;
  if (o.merge) options.tolerance = *o.merge;
  const mm::DecomposedFace decomposed = mm::decompose_face(given, options);
  const mm::FaceModel& face = decomposed.face;
  const mm::MedialAxis& axis = decomposed.axis;
  const mm::Decomposition& decomposition = decomposed.decomposition;
  if (o.json) {
    nlohmann::json report = mm::decomposition_report_json(face, decomposition);
    report["fallbacks"] = mm::fallback_list(decomposed.fallbacks);
    std::cout << report.dump(2) << "\n";
  }
  if (!o.svg.empty()) {
    mm::SvgCanvas canvas(mm::bounding_box(face), 800);
    mm::draw_decomposition(canvas, face, axis, decomposition);
    canvas.save(o.svg);
  }
  if (!o.blocks.empty()) {
    // The face split along the splits by OCC into its block faces.
    std::vector<std::vector<mm::Vec2>> lines;
    for (const mm::Split& s : decomposition.splits) lines.push_back(s.polyline);
    mm::write_blocks_brep(o.file, o.faces.empty() ? 0 : o.faces.front(), lines, o.blocks);
  }
}

// The pipeline options of the mesh command, after checking the output
// format and the size; without --size, a twentieth of `diagonal`.
mm::PipelineOptions mesh_options(const Options& o, double diagonal) {
  if (!o.output.empty()) {
    const std::string ext = o.output.size() >= 4 ? o.output.substr(o.output.size() - 4) : "";
    if (ext != ".inp" && ext != ".msh" && ext != ".vtu")
      throw mm::InputError(o.output + ": unknown mesh format (use .inp, .msh or .vtu)");
  }
  if (o.size && !(*o.size > 0.0 && std::isfinite(*o.size)))
    throw mm::InputError("--size must be a positive number, got " + std::to_string(*o.size));
  mm::PipelineOptions options;
  options.meshing.size = o.size ? *o.size : 0.05 * diagonal;
  options.meshing.order = o.order;
  options.meshing.smooth = o.smooth;
  options.decomposition.merge = !o.no_merge;
  if (o.merge) options.decomposition.tolerance = *o.merge;
  return options;
}

// The Verdict measures under the one-line summary: what a FEM engineer
// checks before solving, and where the worst element is.
void print_measures(const mm::QualityReport& q) {
  if (q.quads == 0) return;
  const auto& shape = q.measure(mm::Measure::Shape);
  const auto& edge_ratio = q.measure(mm::Measure::EdgeRatio);
  const auto& skew = q.measure(mm::Measure::Skew);
  const auto& condition = q.measure(mm::Measure::Condition);
  std::cout << "  shape min " << shape.min << ", mean " << shape.mean << " (worst at " << shape.worst_at.x << ", "
            << shape.worst_at.y << "); edge ratio max " << edge_ratio.max << ", mean " << edge_ratio.mean
            << "; skew max " << skew.max << "; condition max " << condition.max << "\n";
  std::cout << "  " << q.poor_shape << " quads with shape under " << mm::kPoorShape << ", " << q.needles
            << " with edge ratio over " << mm::kNeedleEdgeRatio << ", " << q.stretched << " over "
            << mm::kStretchedEdgeRatio;
  if (q.size > 0.0)
    std::cout << "; sizes sqrt(area)/H " << q.min_relative_size << " to " << q.max_relative_size << ", "
              << 100.0 * q.sizes_in_range << " % within 0.5 to 1.5";
  if (q.min_jacobian_ratio < 1.0) std::cout << "; least Jacobian ratio " << q.min_jacobian_ratio;
  std::cout << "\n";
}

// A result a fallback made says so: which, and the notes that say why.
void print_fallbacks(const std::vector<mm::Fallback>& fallbacks, const std::vector<std::string>& notes) {
  if (fallbacks.empty()) return;
  std::cout << "  fallback: " << mm::fallback_names(fallbacks) << "\n";
  for (const std::string& note : notes)
    if (note.find("fallback") != std::string::npos) std::cout << "    " << note << "\n";
}

// Meshes the face; writes the mesh file, the report and the picture asked for.
void run_mesh(const Options& o, const mm::FaceModel& face) {
  const mm::PipelineOptions options = mesh_options(o, face.size);
  const mm::MeshedFace meshed = mm::mesh_face(face, options);
  const mm::QuadMesh& mesh = meshed.blocks.mesh;
  if (!o.output.empty()) {
    mm::MeshFileOptions file;
    file.shell_elements = o.shell;
    mm::write_mesh_file(mesh, face.frame, o.output, file);
  }
  if (o.json) {
    nlohmann::json report = mm::mesh_report_json(meshed.quality, mesh.order());
    report["face"] = face.name;
    report["frame"] = mm::frame_json(face.frame);
    report["size"] = options.meshing.size;
    report["blocks"] = meshed.decomposition.blocks.size();
    report["singularities"] = meshed.decomposition.singularities.size();
    report["notes"] = meshed.blocks.notes;
    report["fallbacks"] = mm::fallback_list(meshed.fallbacks);
    std::cout << report.dump(2) << "\n";
  } else {
    const mm::QualityReport& q = meshed.quality;
    std::cout << face.name << ": " << q.quads << " quads (order " << mesh.order() << "), " << q.nodes
              << " nodes, min scaled Jacobian " << q.min_scaled_jacobian << ", mean " << q.mean_scaled_jacobian
              << ", angles " << q.min_angle << " to " << q.max_angle << " degrees, " << q.irregular_interior.size()
              << " irregular interior nodes, " << q.seconds << " s\n";
    print_measures(q);
    print_fallbacks(meshed.fallbacks, meshed.blocks.notes);
  }
  if (!o.svg.empty()) {
    mm::SvgCanvas canvas(mm::bounding_box(face), 800);
    mm::draw_quad_mesh(canvas, face, meshed.decomposition, mesh, meshed.quality);
    canvas.save(o.svg);
  }
}

// Meshes several faces together; writes the merged mesh, the report (the
// merged mesh's, each face's under "faces") and a picture of the merged mesh.
void run_mesh_faces(const Options& o, const std::vector<mm::FaceModel>& faces) {
  double largest = 0.0;
  for (const mm::FaceModel& face : faces) largest = std::max(largest, face.size);
  const mm::PipelineOptions options = mesh_options(o, largest);
  const mm::MeshedFaces meshed = mm::mesh_faces(faces, options);
  const int shared_edges = mm::shared_edge_count(meshed.shared);
  if (!o.output.empty()) {
    mm::MeshFileOptions file;
    file.shell_elements = o.shell;
    mm::write_mesh_file(meshed.mesh, o.output, file);
  }
  if (o.json) {
    nlohmann::json report = mm::merged_mesh_report_json(meshed.quality, meshed.mesh, shared_edges);
    report["size"] = options.meshing.size;
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const mm::MeshedFace& m = meshed.faces[f];
      nlohmann::json face = mm::mesh_report_json(m.quality, m.blocks.mesh.order());
      face["face"] = faces[f].name;
      face["frame"] = mm::frame_json(faces[f].frame);
      face["blocks"] = m.decomposition.blocks.size();
      face["singularities"] = m.decomposition.singularities.size();
      face["notes"] = m.blocks.notes;
      face["fallbacks"] = mm::fallback_list(m.fallbacks);
      list.push_back(face);
    }
    report["faces"] = list;
    report["fallbacks"] = mm::fallback_list(meshed.fallbacks);
    std::cout << report.dump(2) << "\n";
  } else {
    const mm::QualityReport& q = meshed.quality;
    std::cout << faces.size() << " faces meshed together, " << shared_edges << " shared edges: " << q.quads
              << " quads (order " << meshed.mesh.order() << "), " << q.nodes << " nodes, min scaled Jacobian "
              << q.min_scaled_jacobian << ", mean " << q.mean_scaled_jacobian << ", angles " << q.min_angle << " to "
              << q.max_angle << " degrees, " << q.irregular_interior.size() << " irregular interior nodes, "
              << q.seconds << " s\n";
    print_measures(q);
    if (!meshed.fallbacks.empty()) std::cout << "  fallback: " << mm::fallback_names(meshed.fallbacks) << "\n";
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const mm::MeshedFace& m = meshed.faces[f];
      std::cout << "  " << faces[f].name << ": " << m.quality.quads << " quads, min scaled Jacobian "
                << m.quality.min_scaled_jacobian;
      if (!m.fallbacks.empty()) std::cout << " (fallback: " << mm::fallback_names(m.fallbacks) << ")";
      std::cout << "\n";
    }
  }
  if (!o.svg.empty()) {
    std::vector<std::vector<int>> chains;
    for (const mm::SharedPiece& p : meshed.shared) {
      chains.emplace_back();
      for (int n : p.nodes_a) chains.back().push_back(meshed.mesh.node_of[p.face_a][n]);
    }
    mm::draw_merged_mesh(meshed.mesh, chains, meshed.quality, 800).save(o.svg);
  }
}

std::vector<mm::FaceModel> read_faces(const Options& o) {
  return mm::read_face_models(o.file, o.solid > 0 ? mm::planar_faces_of_solid(o.file, o.solid) : o.faces);
}

// OCC's readers crash (null handles in a truncated BREP, a corrupted STEP)
// or loop for ever on some malformed files, and a NaN in a file can crash its
// projections. So a child process reads the file first, under a time limit;
// only if it gets through (with faces or with an error) does this process
// read it, to the same end.
std::vector<mm::FaceModel> read_faces_guarded(const Options& o) {
  std::cout.flush();
  const pid_t child = fork();
  if (child == 0) {
    alarm(o.read_time_limit);  // SIGALRM ends the child
    try {
      read_faces(o);
    } catch (...) {
    }
    _exit(0);
  }
  int status = 0;
  if (child < 0 || waitpid(child, &status, 0) != child) throw std::runtime_error("cannot start a reading process");
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM) {
    throw mm::InputError(o.file + ": cannot be read within " + std::to_string(o.read_time_limit) +
                         " s (a malformed file?)");
  }
  if (WIFSIGNALED(status)) {
    throw mm::InputError(o.file + ": cannot be read: the reader crashed on malformed data (signal " +
                         std::to_string(WTERMSIG(status)) + ")");
  }
  return read_faces(o);
}

int run(const Options& o) {
  const std::vector<mm::FaceModel> faces = read_faces_guarded(o);
  if (o.command == "info") {
    if (o.json) {
      nlohmann::json all = nlohmann::json::array();
      for (const auto& face : faces) all.push_back(mm::face_report_json(face));
      std::cout << nlohmann::json{{"faces", all}}.dump(2) << "\n";
    } else {
      for (const auto& face : faces) std::cout << mm::face_report_table(face);
    }
  } else if (o.command == "svg") {
    mm::SvgCanvas canvas(mm::bounding_box(faces.front()), 800);
    mm::draw_face(canvas, faces.front());
    mm::draw_corners(canvas, faces.front());
    canvas.save(o.output);
  } else if (o.command == "singularities") {
    run_singularities(o, faces.front());
  } else if (o.command == "decompose") {
    run_decompose(o, faces.front());
  } else if (o.command == "mesh" && faces.size() > 1) {
    run_mesh_faces(o, faces);
  } else if (o.command == "mesh") {
    run_mesh(o, faces.front());
  } else {
    const mm::FaceAxis medial = mm::compute_face_medial_axis(faces.front());
    nlohmann::json report = mm::medial_report_json(medial.axis);
    if (!medial.note.empty()) report["notes"] = {medial.note};
    if (o.json) std::cout << report.dump(2) << "\n";
    if (!o.svg.empty()) {
      mm::SvgCanvas canvas(mm::bounding_box(medial.face), 800);
      mm::draw_face(canvas, medial.face);
      mm::draw_medial_axis(canvas, medial.face, medial.axis);
      canvas.save(o.svg);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // OCC's readers print progress to stdout; JSON output must stay clean.
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  try {
    const Options options = parse(argc, argv);
    return run(options);
  } catch (const UsageError& e) {
    std::cerr << "medialmesh: " << e.message << "\n" << kUsage;
    return 2;
  } catch (const mm::InputError& e) {
    std::cerr << "medialmesh: " << e.what() << "\n";
    return 2;
  } catch (const mm::SelfCheckError& e) {
    std::cerr << "medialmesh: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "medialmesh: internal error: " << e.what() << "\n";
    return 3;
  }
}
