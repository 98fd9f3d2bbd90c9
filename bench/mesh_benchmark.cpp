// The two mesh tables of the README, printed as markdown.
//
// --compare: every face of SHARED/geometry/*.brep and SHARED/realcad/faces/*.brep
// (and with --cad-faces every planar face of SHARED/realcad/step)
// meshed at H = 0.05 x the face's diagonal (--size-factor) by our pipeline (mesh_face, order 1,
// default options) and by Gmsh on the same BREP file in two quad
// configurations. Gmsh's quads are brought into the face's own coordinates and
// judged by the same measure_quality as ours.
//
// --scaling: one face meshed at sizes giving about 10^3 to 10^6 quads, with
// the seconds of every stage and the peak memory.
//
// Every run happens in a forked child: a crash (Gmsh has crashed on some faces
// in Debian's build), a hang or a thrown error becomes a table entry instead of
// the end of the benchmark, and each child's peak memory is its own.
#include <gmsh.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <BRepTools.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "occ/occ_face.hpp"
#include "occ/occ_reader.hpp"
#include "pipeline/pipeline.hpp"
#include "svg/svg_writer.hpp"

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What a child wrote when it ended normally, or why it did not.
struct ChildResult {
  std::string output;
  std::string failure;  // "crash (signal N)", "timeout" or "error: ..."; empty on success
};

// Runs work() in a forked child killed after timeout_seconds. Whatever work()
// returns comes back through a pipe; a thrown exception comes back as its message.
ChildResult run_in_child(const std::function<std::string()>& work, unsigned timeout_seconds) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("mesh_benchmark: cannot create a pipe");
  std::cout.flush();  // the child must not print the parent's buffered lines again
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("mesh_benchmark: cannot fork");
  if (pid == 0) {
    close(fds[0]);
    alarm(timeout_seconds);
    std::string out;
    int code = 0;
    try {
      out = work();
    } catch (const std::exception& e) {
      out = e.what();
      code = 2;
    } catch (...) {
      out = "unknown exception";
      code = 2;
    }
    for (std::size_t done = 0; done < out.size();) {
      const ssize_t n = write(fds[1], out.data() + done, out.size() - done);
      if (n <= 0) _exit(3);
      done += static_cast<std::size_t>(n);
    }
    close(fds[1]);
    _exit(code);  // no atexit handlers or stream flushes of the parent's state
  }
  close(fds[1]);
  std::string output;
  char buffer[65536];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) != 0;) {
    if (n > 0) output.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) {
    return {"", WTERMSIG(status) == SIGALRM ? "timeout" : "crash (signal " + std::to_string(WTERMSIG(status)) + ")"};
  }
  if (WEXITSTATUS(status) == 2) return {"", "error: " + output};
  if (WEXITSTATUS(status) != 0) return {"", "crash (exit " + std::to_string(WEXITSTATUS(status)) + ")"};
  return {output, ""};
}

double peak_rss_megabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

// One mesher's result on one face, as the comparison table shows it.
struct Measured {
  std::string failure;  // empty when meshed
  int quads = 0;
  int triangles = 0;
  int irregular_interior = 0;
  double min_sj = 0.0;
  double mean_sj = 0.0;
  double min_shape = 0.0;  // Verdict's shape: angles and stretch
  double mean_shape = 0.0;
  double max_edge_ratio = 0.0;
  int needles = 0;              // quads with edge ratio over 10
  int poor_shape = 0;           // quads with shape under 0.3
  double sizes_in_range = 0.0;  // share of quads with sqrt(area) in [H/2, 3H/2]
  double seconds = 0.0;
  double block_seconds = 0.0;  // ours only: the block meshing stages alone
};

// The quality figures of the table, as text a child hands its parent.
std::string verdict_text(const mm::QualityReport& q) {
  std::ostringstream out;
  out.precision(17);
  out << q.min_scaled_jacobian << ' ' << q.mean_scaled_jacobian << ' ' << q.min_shape() << ' '
      << q.measure(mm::Measure::Shape).mean << ' ' << q.measure(mm::Measure::EdgeRatio).max << ' ' << q.needles << ' '
      << q.poor_shape << ' ' << q.sizes_in_range;
  return out.str();
}

void read_verdict(std::istream& in, Measured& m) {
  in >> m.min_sj >> m.mean_sj >> m.min_shape >> m.mean_shape >> m.max_edge_ratio >> m.needles >> m.poor_shape >>
      m.sizes_in_range;
}

// ---------------------------------------------------------------- ours

void write_svg(const std::string& path, const mm::FaceModel& face, const mm::Decomposition& decomposition,
               const mm::QuadMesh& mesh, const mm::QualityReport& quality) {
  mm::SvgCanvas canvas(mm::bounding_box(face), 800);
  mm::draw_quad_mesh(canvas, face, decomposition, mesh, quality);
  canvas.save(path);
}

Measured mesh_ours(const mm::FaceModel& face, double size, const std::string& svg_path, unsigned timeout) {
  const ChildResult child = run_in_child(
      [&] {
        mm::PipelineOptions options;
        options.meshing.size = size;
        const auto start = Clock::now();
        const mm::MeshedFace meshed = mm::mesh_face(face, options);
        const double seconds = seconds_since(start);
        double block_seconds = 0.0;
        for (const auto& stage : meshed.blocks.stage_seconds) block_seconds += stage.second;
        if (!svg_path.empty()) write_svg(svg_path, face, meshed.decomposition, meshed.blocks.mesh, meshed.quality);
        std::ostringstream out;
        out.precision(17);
        out << meshed.quality.quads << ' ' << meshed.quality.irregular_interior.size() << ' ' << seconds << ' '
            << block_seconds << ' ' << verdict_text(meshed.quality);
        return out.str();
      },
      timeout);
  Measured m;
  m.failure = child.failure;
  if (m.failure.empty()) {
    std::istringstream in(child.output);
    in >> m.quads >> m.irregular_interior >> m.seconds >> m.block_seconds;
    read_verdict(in, m);
  }
  return m;
}

// ---------------------------------------------------------------- Gmsh

struct GmshConfig {
  std::string label;
  int algorithm;
};

// Both configurations recombine every triangle pair into quads. Algorithm 6
// (Frontal-Delaunay) with recombination algorithm 3 (Blossom full-quad), and
// algorithm 8 (Frontal-Delaunay for quads), whose default cross-field closest
// point search crashes in Debian's 4.8 build.
const std::vector<GmshConfig> kGmshConfigs = {{"Gmsh 6+Blossom", 6}, {"Gmsh 8", 8}};

// In the child: meshes the BREP file and writes the seconds of generate(2),
// then every node (tag, dimension of the entity it is classified on, x y z),
// the quads and the triangles (node tags).
std::string gmsh_mesh_text(const std::string& path, double size, int algorithm) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(path);
  gmsh::option::setNumber("Mesh.MeshSizeMin", size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", size);
  gmsh::option::setNumber("Mesh.Algorithm", algorithm);
  gmsh::option::setNumber("Mesh.RecombineAll", 1);
  if (algorithm == 6) gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 3);
  if (algorithm == 8) gmsh::option::setNumber("Mesh.CrossFieldClosestPoint", 0);
  const auto start = Clock::now();
  gmsh::model::mesh::generate(2);
  const double seconds = seconds_since(start);

  std::ostringstream out;
  out.precision(17);
  out << seconds << '\n';
  for (int dim = 0; dim <= 2; ++dim) {
    std::vector<std::size_t> tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(tags, coords, params, dim, -1, false, false);
    out << "nodes " << tags.size() << '\n';
    for (std::size_t i = 0; i < tags.size(); ++i) {
      out << tags[i] << ' ' << dim << ' ' << coords[3 * i] << ' ' << coords[3 * i + 1] << ' ' << coords[3 * i + 2]
          << '\n';
    }
  }
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, -1);
  for (const int corners : {4, 3}) {
    const int type = corners == 4 ? 3 : 2;  // Gmsh's 4-node quadrangle and 3-node triangle
    std::vector<std::size_t> nodes;
    for (std::size_t i = 0; i < types.size(); ++i) {
      if (types[i] == type) nodes.insert(nodes.end(), node_tags[i].begin(), node_tags[i].end());
    }
    out << "elements " << nodes.size() / corners << '\n';
    for (std::size_t i = 0; i < nodes.size(); ++i) out << nodes[i] << ((i + 1) % corners == 0 ? '\n' : ' ');
  }
  gmsh::finalize();
  return out.str();
}

struct GmshNode {
  int dim = 2;
  mm::Vec2 p;
};

// A point of 3-D space in the face's own coordinates.
mm::Vec2 to_face(const mm::Frame& frame, double x, double y, double z) {
  const double d[3] = {x - frame.origin[0], y - frame.origin[1], z - frame.origin[2]};
  return {d[0] * frame.x_dir[0] + d[1] * frame.x_dir[1] + d[2] * frame.x_dir[2],
          d[0] * frame.y_dir[0] + d[1] * frame.y_dir[1] + d[2] * frame.y_dir[2]};
}

// Gmsh's mesh as our QuadMesh, counter-clockwise in the face's coordinates,
// nodes on curves and points marked as boundary nodes wanting the face's
// corner type there (2 on a smooth boundary), then judged by measure_quality.
// An interior node's valence counts Gmsh's left-over triangles too.
Measured judge_gmsh(const std::string& text, const mm::FaceModel& face, double size, mm::QuadMesh& mesh) {
  std::istringstream in(text);
  Measured m;
  in >> m.seconds;
  std::map<std::size_t, GmshNode> nodes;
  std::string word;
  for (int dim = 0; dim <= 2; ++dim) {
    std::size_t count = 0;
    in >> word >> count;
    for (std::size_t i = 0; i < count; ++i) {
      std::size_t tag;
      GmshNode node;
      double x, y, z;
      in >> tag >> node.dim >> x >> y >> z;
      node.p = to_face(face.frame, x, y, z);
      nodes[tag] = node;
    }
  }
  std::vector<std::array<std::size_t, 4>> quads;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::size_t count = 0;
  in >> word >> count;
  quads.resize(count);
  for (auto& q : quads) in >> q[0] >> q[1] >> q[2] >> q[3];
  in >> word >> count;
  triangles.resize(count);
  for (auto& t : triangles) in >> t[0] >> t[1] >> t[2];
  if (!in) throw std::runtime_error("mesh_benchmark: cannot read Gmsh's mesh of " + face.name);

  std::map<std::size_t, int> index_of;  // Gmsh node tag -> our node, for nodes of quads
  for (const auto& q : quads) {
    std::array<int, 4> ours;
    for (int i = 0; i < 4; ++i) {
      const auto [it, added] = index_of.emplace(q[i], static_cast<int>(mesh.nodes.size()));
      if (added) {
        const GmshNode& node = nodes.at(q[i]);
        mm::NodePlace place;
        if (node.dim < 2) {
          place.loop = 0;
          place.corner_elements = 2;
          for (const mm::Corner& corner : face.corners) {
            if (mm::distance(corner.position, node.p) < 1e-6 * face.size) {
              place.corner_elements = corner.nc;
              place.face_corner = true;
            }
          }
        }
        mesh.nodes.push_back(node.p);
        mesh.places.push_back(place);
      }
      ours[i] = it->second;
    }
    mesh.quads.push_back(ours);
    mesh.block_of_quad.push_back(0);
  }
  // Gmsh orients elements by the surface's normal, which may be opposite to
  // the face frame's: turn the whole mesh, so inverted elements stay inverted.
  double area = 0.0;
  for (const auto& q : mesh.quads) {
    for (int i = 0; i < 4; ++i) area += 0.5 * mm::cross(mesh.nodes[q[i]], mesh.nodes[q[(i + 1) % 4]]);
  }
  if (area < 0.0) {
    for (auto& q : mesh.quads) std::swap(q[1], q[3]);
  }

  const mm::QualityReport quality = mm::measure_quality(mesh, size);
  m.quads = quality.quads;
  m.triangles = static_cast<int>(triangles.size());
  std::istringstream verdict(verdict_text(quality));
  read_verdict(verdict, m);
  m.irregular_interior = static_cast<int>(quality.irregular_interior.size());
  if (!triangles.empty()) {
    std::map<std::size_t, int> triangles_at;
    for (const auto& t : triangles) {
      for (std::size_t tag : t) ++triangles_at[tag];
    }
    std::map<int, int> quads_at_irregular;  // measure_quality's irregular interior nodes and their quads
    for (const mm::IrregularNode& n : quality.irregular_interior) quads_at_irregular[n.node] = n.elements;
    for (const auto& [tag, extra] : triangles_at) {
      if (nodes.at(tag).dim < 2) continue;
      const auto ours = index_of.find(tag);
      int quads_here = 0;
      if (ours != index_of.end()) {
        const auto irregular = quads_at_irregular.find(ours->second);
        quads_here = irregular == quads_at_irregular.end() ? 4 : irregular->second;
      }
      const bool was_irregular = ours != index_of.end() && quads_here != 4;
      const bool is_irregular = quads_here + extra != 4;
      m.irregular_interior += static_cast<int>(is_irregular) - static_cast<int>(was_irregular);
    }
  }
  return m;
}

Measured mesh_gmsh(const std::string& path, const mm::FaceModel& face, double size, int algorithm,
                   const std::string& svg_path, unsigned timeout) {
  const ChildResult child = run_in_child([&] { return gmsh_mesh_text(path, size, algorithm); }, timeout);
  if (!child.failure.empty()) {
    Measured m;
    m.failure = child.failure;
    return m;
  }
  mm::QuadMesh mesh;
  Measured m = judge_gmsh(child.output, face, size, mesh);
  if (!svg_path.empty()) write_svg(svg_path, face, mm::Decomposition{}, mesh, mm::measure_quality(mesh));
  return m;
}

// ---------------------------------------------------------------- tables

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<fs::path> brep_files(const fs::path& folder) {
  std::vector<fs::path> files;
  if (!fs::is_directory(folder)) throw std::runtime_error("mesh_benchmark: no folder " + folder.string());
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() == ".brep") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Every planar face of the CAD files in SHARED/realcad/step, each written
// as a BREP file of its own into `folder` (Gmsh meshes that file) and named
// after its file and face number, less those a face of `known` already is
// (the same area and diagonal: realcad/faces holds some of them).
std::vector<fs::path> cad_face_files(const fs::path& shared, const fs::path& folder,
                                     const std::vector<fs::path>& known) {
  std::vector<std::pair<double, double>> known_sizes;
  for (const fs::path& p : known) {
    const mm::FaceModel face = mm::read_face_models(p.string(), {}).front();
    known_sizes.emplace_back(face.area, face.size);
  }
  fs::create_directories(folder);
  std::vector<fs::path> files;
  std::vector<fs::path> sources;
  for (const auto& entry : fs::directory_iterator(shared / "realcad" / "step")) sources.push_back(entry.path());
  std::sort(sources.begin(), sources.end());
  for (const fs::path& source : sources) {
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(mm::read_shape(source.string()), TopAbs_FACE, faces);
    for (int i = 1; i <= faces.Extent(); ++i) {
      const TopoDS_Face face = TopoDS::Face(faces(i));
      mm::FaceModel model;
      try {
        model = mm::face_model_from_occ(face, source.stem().string());
      } catch (const mm::InputError&) {
        continue;  // not planar
      }
      const bool seen = std::any_of(known_sizes.begin(), known_sizes.end(), [&](const auto& k) {
        return std::abs(k.first - model.area) < 1e-9 * k.first && std::abs(k.second - model.size) < 1e-9 * k.second;
      });
      if (seen) continue;
      const fs::path path = folder / (source.stem().string() + "_face" + std::to_string(i) + ".brep");
      BRepTools::Write(face, path.string().c_str());
      files.push_back(path);
    }
  }
  return files;
}

// The compared faces: every reference face (true: counted in the irregular
// node total), then every real CAD face, and with cad_folder every planar
// face of realcad/step (cad_face_files).
std::vector<std::pair<fs::path, bool>> compared_faces(const fs::path& shared, const std::string& cad_folder = "") {
  std::vector<std::pair<fs::path, bool>> files;
  for (const fs::path& p : brep_files(shared / "geometry")) files.emplace_back(p, true);
  const std::vector<fs::path> real = brep_files(shared / "realcad" / "faces");
  for (const fs::path& p : real) files.emplace_back(p, false);
  if (!cad_folder.empty())
    for (const fs::path& p : cad_face_files(shared, cad_folder, real)) files.emplace_back(p, false);
  return files;
}

struct FaceRow {
  std::string name;
  bool reference = false;  // one of the 18 faces of geometry/
  Measured ours;
  std::vector<Measured> gmsh;  // one per kGmshConfigs
};

std::string cell_failure(const Measured& m, std::vector<std::string>& notes, const std::string& who) {
  notes.push_back(who + ": " + m.failure);
  const std::string word = m.failure.substr(0, m.failure.find_first_of(" :"));
  return word + " [" + std::to_string(notes.size()) + "]";
}

void print_comparison_row(const FaceRow& row, std::vector<std::string>& notes) {
  const auto quality = [](const Measured& m) {
    return fixed(m.min_shape, 3) + " | " + fixed(m.mean_shape, 3) + " | " + std::to_string(m.needles) + " | " +
           std::to_string(m.poor_shape) + " | " + fixed(m.min_sj, 3);
  };
  std::cout << "| " << row.name;
  if (row.ours.failure.empty()) {
    std::cout << " | " << row.ours.quads << " | " << row.ours.irregular_interior << " | " << quality(row.ours) << " | "
              << fixed(1e3 * row.ours.seconds, 1) << " | " << fixed(1e3 * row.ours.block_seconds, 1);
  } else {
    std::cout << " | " << cell_failure(row.ours, notes, row.name + ", ours") << " | | | | | | | | |";
  }
  for (std::size_t c = 0; c < kGmshConfigs.size(); ++c) {
    const Measured& g = row.gmsh[c];
    if (g.failure.empty()) {
      std::cout << " | " << g.quads << " | " << g.triangles << " | " << g.irregular_interior << " | " << quality(g)
                << " | " << fixed(1e3 * g.seconds, 1);
    } else {
      std::cout << " | " << cell_failure(g, notes, row.name + ", " + kGmshConfigs[c].label) << " | | | | | | | | |";
    }
  }
  std::cout << " |\n";
}

void print_comparison_summary(const std::vector<FaceRow>& rows) {
  int reference_faces = 0;
  for (const FaceRow& row : rows) reference_faces += row.reference;
  for (std::size_t c = 0; c < kGmshConfigs.size(); ++c) {
    const std::string& label = kGmshConfigs[c].label;
    int ours_irregular = 0, gmsh_irregular = 0, both_reference = 0;
    int both = 0, worst_at_least = 0, mean_at_least = 0, sj_better = 0;
    int ours_needles = 0, gmsh_needles = 0, ours_poor = 0, gmsh_poor = 0, ours_quads = 0, gmsh_quads = 0;
    int reference_under = 0;
    double ours_seconds = 0.0, gmsh_seconds = 0.0, ours_sizes = 0.0, gmsh_sizes = 0.0;
    std::vector<double> ratios;
    for (const FaceRow& row : rows) {
      const Measured& g = row.gmsh[c];
      if (!row.ours.failure.empty() || !g.failure.empty()) continue;
      ++both;
      if (row.reference) {
        ++both_reference;
        ours_irregular += row.ours.irregular_interior;
        gmsh_irregular += g.irregular_interior;
        reference_under += row.ours.min_shape < 0.3;
      }
      worst_at_least += row.ours.min_shape >= g.min_shape;
      mean_at_least += row.ours.mean_shape >= g.mean_shape;
      sj_better += row.ours.min_sj > g.min_sj;
      ours_needles += row.ours.needles, gmsh_needles += g.needles;
      ours_poor += row.ours.poor_shape, gmsh_poor += g.poor_shape;
      ours_quads += row.ours.quads, gmsh_quads += g.quads;
      ours_sizes += row.ours.sizes_in_range * row.ours.quads, gmsh_sizes += g.sizes_in_range * g.quads;
      ours_seconds += row.ours.seconds;
      gmsh_seconds += g.seconds;
      ratios.push_back(g.seconds / row.ours.seconds);
    }
    const double per_element = ours_seconds > 0 && gmsh_quads > 0
                                   ? (gmsh_seconds / gmsh_quads) / (ours_seconds / std::max(1, ours_quads))
                                   : 0.0;
    std::cout << "\n**Ours against " << label << "** (faces both meshed: " << both << " of " << rows.size() << ")\n"
              << "- worst Verdict shape at least " << label << "'s on " << worst_at_least << " of " << both
              << " faces, mean shape on " << mean_at_least
              << "; reference faces with a worst shape under 0.3: " << reference_under << " of " << both_reference
              << "\n"
              << "- quads with edge ratio over 10: ours " << ours_needles << " of " << ours_quads << ", " << label
              << " " << gmsh_needles << " of " << gmsh_quads << "; with shape under 0.3: ours " << ours_poor << ", "
              << label << " " << gmsh_poor << "\n"
              << "- quads with sqrt(area) within [H/2, 3H/2]: ours "
              << fixed(100.0 * ours_sizes / std::max(1, ours_quads), 1) << " %, " << label << " "
              << fixed(100.0 * gmsh_sizes / std::max(1, gmsh_quads), 1) << " %\n"
              << "- irregular interior nodes over the reference faces (" << both_reference << " of " << reference_faces
              << "): ours " << ours_irregular << ", " << label << " " << gmsh_irregular << "\n"
              << "- min scaled Jacobian better: ours on " << sj_better << " faces\n"
              << "- time ratio " << label << " / ours: total "
              << fixed(ours_seconds > 0 ? gmsh_seconds / ours_seconds : 0, 2) << " (" << fixed(1e3 * gmsh_seconds, 0)
              << " ms / " << fixed(1e3 * ours_seconds, 0) << " ms), per-face median " << fixed(median(ratios), 2)
              << ", per element " << fixed(per_element, 2) << "\n";
  }
}

std::string gmsh_version(unsigned timeout) {
  const ChildResult child = run_in_child(
      [] {
        gmsh::initialize(0, nullptr, false);
        std::string version;
        gmsh::option::getString("General.Version", version);
        gmsh::finalize();
        return version;
      },
      timeout);
  return child.failure.empty() ? child.output : child.failure;
}

// A repeated run's time, where it is the least so far: one mesher's time
// moves by up to a fifth from run to run on this kind of machine, so each
// face's time is the least of the repeats (its mesh is the same each time).
void keep_faster(Measured& best, const Measured& again) {
  if (!best.failure.empty() || !again.failure.empty() || again.seconds >= best.seconds) return;
  best.seconds = again.seconds;
  best.block_seconds = again.block_seconds;
}

void run_comparison(const fs::path& shared, double size_factor, const std::string& svg_dir, int repeats,
                    unsigned timeout, const std::string& cad_folder) {
  const std::vector<std::pair<fs::path, bool>> files = compared_faces(shared, cad_folder);
  std::cout << "## Ours against Gmsh " << gmsh_version(timeout) << " at H = " << size_factor
            << " x the face's diagonal\n\n"
            << "Ours: mesh_face, order 1, default options; time = the whole call (medial axis to quality), the "
               "least of "
            << repeats
            << " runs (each in a fresh child process, as Gmsh's), "
               "\"blocks ms\" = the block meshing stages alone. Gmsh: generate(2) alone, the least of as many runs. "
               "All meshes judged by "
               "measure_quality in the face's own coordinates (Verdict's measures, checked against VTK's "
               "vtkMeshQuality): shape = Verdict shape, ER>10 = quads with edge ratio over 10, <0.3 = quads of shape "
               "under 0.3, SJ = scaled Jacobian (element minimum), irr = irregular interior nodes.\n\n"
            << "| face | ours quads | irr | min shape | mean shape | ER>10 | <0.3 | min SJ | ms | blocks ms";
  for (const GmshConfig& c : kGmshConfigs) {
    std::cout << " | " << c.label << " quads | tris | irr | min shape | mean shape | ER>10 | <0.3 | min SJ | ms";
  }
  std::cout << " |\n|---|";
  for (int i = 0; i < 9 + 9 * static_cast<int>(kGmshConfigs.size()); ++i) std::cout << "---:|";
  std::cout << "\n";

  std::vector<FaceRow> rows;
  std::vector<std::string> notes;
  for (const auto& [path, reference] : files) {
    FaceRow row;
    row.name = path.stem().string();
    row.reference = reference;
    const std::string svg_base = svg_dir.empty() ? "" : (fs::path(svg_dir) / row.name).string();
    try {
      const mm::FaceModel face = mm::read_face_models(path.string(), {}).front();
      const double size = size_factor * face.size;
      row.ours = mesh_ours(face, size, svg_base.empty() ? "" : svg_base + "_ours.svg", timeout);
      for (int r = 1; r < repeats; ++r) keep_faster(row.ours, mesh_ours(face, size, "", timeout));
      for (const GmshConfig& c : kGmshConfigs) {
        const std::string svg = svg_base.empty() ? "" : svg_base + "_gmsh" + std::to_string(c.algorithm) + ".svg";
        row.gmsh.push_back(mesh_gmsh(path.string(), face, size, c.algorithm, svg, timeout));
        for (int r = 1; r < repeats; ++r)
          keep_faster(row.gmsh.back(), mesh_gmsh(path.string(), face, size, c.algorithm, "", timeout));
      }
    } catch (const std::exception& e) {
      row.ours.failure = std::string("error: ") + e.what();
      row.gmsh.assign(kGmshConfigs.size(), row.ours);
    }
    print_comparison_row(row, notes);
    rows.push_back(row);
  }
  if (!notes.empty()) std::cout << "\n";
  for (std::size_t i = 0; i < notes.size(); ++i) std::cout << "[" << i + 1 << "] " << notes[i] << "\n";
  print_comparison_summary(rows);
}

// One size of the scaling table, measured in a child of its own.
struct ScalingRun {
  std::string failure;
  int quads = 0;
  int nodes = 0;
  double seconds = 0.0;
  double peak_megabytes = 0.0;
  double start_megabytes = 0.0;  // the child's peak before meshing (the parent's share)
  std::vector<std::pair<std::string, double>> stages;
};

ScalingRun mesh_for_scaling(const mm::FaceModel& face, double size, unsigned timeout) {
  const ChildResult child = run_in_child(
      [&] {
        const double start_megabytes = peak_rss_megabytes();
        mm::PipelineOptions options;
        options.meshing.size = size;
        const mm::MeshedFace meshed = mm::mesh_face(face, options);
        std::ostringstream out;
        out.precision(17);
        out << meshed.quality.quads << ' ' << meshed.quality.nodes << ' ' << meshed.quality.seconds << ' '
            << peak_rss_megabytes() << ' ' << start_megabytes << ' ' << meshed.quality.stage_seconds.size() << '\n';
        for (const auto& [name, seconds] : meshed.quality.stage_seconds) out << name << ' ' << seconds << '\n';
        return out.str();
      },
      timeout);
  ScalingRun run;
  run.failure = child.failure;
  if (!run.failure.empty()) return run;
  std::istringstream in(child.output);
  std::size_t stages = 0;
  in >> run.quads >> run.nodes >> run.seconds >> run.peak_megabytes >> run.start_megabytes >> stages;
  run.stages.resize(stages);
  for (auto& stage : run.stages) in >> stage.first >> stage.second;
  return run;
}

void run_scaling(const fs::path& shared, const std::string& face_name, unsigned timeout) {
  const fs::path path = shared / "geometry" / (face_name + ".brep");
  const mm::FaceModel face = mm::read_face_models(path.string(), {}).front();
  const std::vector<double> targets = {1e3, 1e4, 1e5, 1e6};
  std::vector<std::tuple<double, double, ScalingRun>> runs;  // target quads, H, result
  // Quads grow as area / H^2; the first run calibrates the constant.
  double quads_per_area_over_h2 = 1.0;
  for (const double target : targets) {
    const double size = std::sqrt(quads_per_area_over_h2 * face.area / target);
    ScalingRun run = mesh_for_scaling(face, size, timeout);
    if (runs.empty() && run.failure.empty()) quads_per_area_over_h2 = run.quads * size * size / face.area;
    runs.emplace_back(target, size, run);
  }

  std::vector<std::string> stage_names;
  for (const auto& entry : runs) {
    for (const auto& stage : std::get<2>(entry).stages) {
      if (std::find(stage_names.begin(), stage_names.end(), stage.first) == stage_names.end())
        stage_names.push_back(stage.first);
    }
  }
  std::cout << "\n## Scaling: " << face_name << " (diagonal " << fixed(face.size, 3) << ")\n\n"
            << "Seconds per stage of mesh_face (order 1, default options); peak RSS of the child process that "
               "meshed (getrusage); \"before MB\" is that child's peak before meshing, inherited from the "
               "benchmark itself.\n\n"
            << "| target quads | H | quads | nodes";
  for (const std::string& name : stage_names) std::cout << " | " << name << " s";
  std::cout << " | total s | peak MB | before MB |\n|";
  for (std::size_t i = 0; i < stage_names.size() + 7; ++i) std::cout << "---:|";
  std::cout << "\n";
  for (const auto& [target, size, run] : runs) {
    std::cout << "| " << fixed(target, 0) << " | " << fixed(size, 5);
    if (!run.failure.empty()) {
      std::cout << " | " << run.failure << " |\n";
      continue;
    }
    std::cout << " | " << run.quads << " | " << run.nodes;
    for (const std::string& name : stage_names) {
      double seconds = 0.0;
      for (const auto& stage : run.stages) seconds += stage.first == name ? stage.second : 0.0;
      std::cout << " | " << fixed(seconds, 3);
    }
    std::cout << " | " << fixed(run.seconds, 3) << " | " << fixed(run.peak_megabytes, 1) << " | "
              << fixed(run.start_megabytes, 1) << " |\n";
  }
}

// --stages: where our time goes. Each repeat is a child of its own that
// meshes the face twice: the first call cold (as --compare times it: a fresh
// process, libraries not yet touched), the second warm (as in a FreeCAD
// session after its first mesh). Per stage the least over the repeats.
struct StageTimes {
  std::string failure;
  int quads = 0;
  std::map<std::string, double> cold, warm;  // stage -> seconds; "total" the whole call
};

StageTimes stage_times(const mm::FaceModel& face, double size, int repeats, unsigned timeout) {
  StageTimes times;
  for (int r = 0; r < repeats; ++r) {
    const ChildResult child = run_in_child(
        [&] {
          mm::PipelineOptions options;
          options.meshing.size = size;
          std::ostringstream out;
          out.precision(17);
          for (int call = 0; call < 2; ++call) {
            const mm::MeshedFace meshed = mm::mesh_face(face, options);
            out << meshed.quality.quads << ' ' << meshed.quality.stage_seconds.size() + 1 << " total "
                << meshed.quality.seconds << '\n';
            for (const auto& [name, seconds] : meshed.quality.stage_seconds) out << name << ' ' << seconds << '\n';
          }
          return out.str();
        },
        timeout);
    if (!child.failure.empty()) {
      times.failure = child.failure;
      return times;
    }
    std::istringstream in(child.output);
    for (auto* into : {&times.cold, &times.warm}) {
      std::size_t stages = 0;
      in >> times.quads >> stages;
      for (std::size_t i = 0; i < stages; ++i) {
        std::string name;
        double seconds = 0.0;
        in >> name >> seconds;
        const auto found = into->find(name);
        if (found == into->end() || seconds < found->second) (*into)[name] = seconds;
      }
    }
  }
  return times;
}

void run_stages(const fs::path& shared, double size_factor, int repeats, unsigned timeout) {
  std::vector<std::pair<std::string, StageTimes>> rows;
  std::vector<std::string> names{"total"};
  for (const auto& [path, reference] : compared_faces(shared)) {
    StageTimes t;
    try {
      const mm::FaceModel face = mm::read_face_models(path.string(), {}).front();
      t = stage_times(face, size_factor * face.size, repeats, timeout);
    } catch (const std::exception& e) {
      t.failure = std::string("error: ") + e.what();
    }
    for (const auto& [name, seconds] : t.cold)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    rows.emplace_back(path.stem().string(), t);
  }
  std::cout << "## Stage times at H = " << size_factor << " x the face's diagonal (ms, least of " << repeats
            << " runs; cold = first call in a fresh process, warm = the second)\n\n| face | quads";
  for (const std::string& n : names) std::cout << " | " << n;
  std::cout << " | warm total";
  for (const std::string& n : names)
    if (n != "total") std::cout << " | warm " << n;
  std::cout << " |\n|---|";
  for (std::size_t i = 0; i < 2 * names.size() + 1; ++i) std::cout << "---:|";
  std::cout << "\n";
  std::map<std::string, double> cold_sum, warm_sum;
  const auto get = [](const std::map<std::string, double>& m, const std::string& n) {
    const auto found = m.find(n);
    return found == m.end() ? 0.0 : found->second;
  };
  for (const auto& [name, t] : rows) {
    std::cout << "| " << name;
    if (!t.failure.empty()) {
      std::cout << " | " << t.failure << " |\n";
      continue;
    }
    std::cout << " | " << t.quads;
    for (const std::string& n : names) {
      std::cout << " | " << fixed(1e3 * get(t.cold, n), 2);
      cold_sum[n] += get(t.cold, n);
    }
    for (const std::string& n : names) {
      std::cout << " | " << fixed(1e3 * get(t.warm, n), 2);
      warm_sum[n] += get(t.warm, n);
    }
    std::cout << " |\n";
  }
  std::cout << "| all | ";
  for (const std::string& n : names) std::cout << " | " << fixed(1e3 * cold_sum[n], 1);
  for (const std::string& n : names) std::cout << " | " << fixed(1e3 * warm_sum[n], 1);
  std::cout << " |\n";
}

const char* const kUsage =
    "usage: mesh_benchmark [--compare] [--scaling] [--stages] [--shared DIR] [--scaling-face NAME] [--svg-dir DIR]\n"
    "                      [--repeat N] [--timeout S] [--size-factor F]\n"
    "Prints the comparison with Gmsh and the scaling table as markdown (both unless one is named).\n"
    "--compare: each face's time, ours and Gmsh's, the least of N runs (--repeat, 3).\n"
    "--stages: our time per stage on every compared face, cold and warm, the least of N runs (--repeat, 3).\n"
    "--shared: the folder holding geometry/ and realcad/faces/ (default " MM_SHARED_DIR
    ").\n"
    "--scaling-face: a face of geometry/ (default plate_with_hole). --svg-dir: draw every compared mesh there.\n"
    "--timeout: seconds a single meshing may take before it counts as a timeout (default 600).\n"
    "--size-factor: H for --compare and --stages as a fraction of each face's diagonal (default 0.05).\n"
    "--cad-faces DIR: --compare also every planar face of SHARED/realcad/step, each written to DIR as a BREP\n"
    "  file (those realcad/faces already holds left out).\n";

}  // namespace

int main(int argc, char** argv) {
  bool compare = false, scaling = false, stages = false;
  int repeats = 3;
  fs::path shared = MM_SHARED_DIR;
  std::string scaling_face = "plate_with_hole", svg_dir, cad_folder;
  unsigned timeout = 600;
  double size_factor = 0.05;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--compare") {
      compare = true;
    } else if (a == "--scaling") {
      scaling = true;
    } else if (a == "--stages") {
      stages = true;
    } else if (a == "--repeat" && has_value) {
      repeats = std::max(1, std::stoi(argv[++i]));
    } else if (a == "--shared" && has_value) {
      shared = argv[++i];
    } else if (a == "--scaling-face" && has_value) {
      scaling_face = argv[++i];
    } else if (a == "--svg-dir" && has_value) {
      svg_dir = argv[++i];
    } else if (a == "--cad-faces" && has_value) {
      cad_folder = argv[++i];
    } else if (a == "--size-factor" && has_value) {
      char* end = nullptr;
      size_factor = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(size_factor > 0.0)) {
        std::cerr << "mesh_benchmark: --size-factor must be a positive number\n";
        return 2;
      }
    } else if (a == "--timeout" && has_value) {
      timeout = static_cast<unsigned>(std::stoul(argv[++i]));
    } else {
      std::cerr << kUsage;
      return 2;
    }
  }
  if (!compare && !scaling && !stages) compare = scaling = true;
  try {
    if (!svg_dir.empty()) fs::create_directories(svg_dir);
    if (compare) run_comparison(shared, size_factor, svg_dir, repeats, timeout, cad_folder);
    if (scaling) run_scaling(shared, scaling_face, timeout);
    if (stages) run_stages(shared, size_factor, repeats, timeout);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
