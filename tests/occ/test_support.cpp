#include "test_support.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <BRepAdaptor_Curve.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <GCPnts_UniformAbscissa.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "occ/occ_reader.hpp"

namespace mm::test {

std::string shared_dir() {
  return MEDIALMESH_SHARED_DIR;
}

std::string scratch_dir() {
  const std::string dir = std::string(MEDIALMESH_BINARY_DIR) + "/test_scratch";
  std::filesystem::create_directories(dir);
  return dir;
}

std::vector<std::string> brep_files(const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".brep") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

FaceModel reference_face(const std::string& name) {
  return read_face_models(shared_dir() + "/geometry/" + name + ".brep", {}).front();
}

std::string data_brep_text(const std::string& name) {
  const std::string path = std::string(MEDIALMESH_SOURCE_DIR) + "/tests/data/" + name + ".brep";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

FaceModel data_face(const std::string& name) {
  return face_model_from_brep_string(data_brep_text(name), name.substr(name.rfind('/') + 1));
}

TopoDS_Face first_face(const TopoDS_Shape& shape) {
  TopExp_Explorer it(shape, TopAbs_FACE);
  if (!it.More()) throw std::runtime_error("shape has no face");
  return TopoDS::Face(it.Current());
}

void write_brep(const TopoDS_Shape& shape, const std::string& path) {
  if (!BRepTools::Write(shape, path.c_str())) throw std::runtime_error("cannot write " + path);
}

double discretised_area(const TopoDS_Face& face, int points_per_edge) {
  // Newell's vector area of each closed 3-D polygon; the largest is the outer
  // loop, and the holes' areas (whatever way they turn) are taken from it.
  std::vector<gp_XYZ> areas;
  for (TopExp_Explorer wires(face, TopAbs_WIRE); wires.More(); wires.Next()) {
    std::vector<gp_Pnt> pts;
    for (BRepTools_WireExplorer it(TopoDS::Wire(wires.Current()), face); it.More(); it.Next()) {
      BRepAdaptor_Curve curve(it.Current());
      GCPnts_UniformAbscissa sampler(curve, points_per_edge);
      std::vector<gp_Pnt> edge_pts;
      for (int i = 1; i <= sampler.NbPoints(); ++i) edge_pts.push_back(curve.Value(sampler.Parameter(i)));
      if (it.Orientation() == TopAbs_REVERSED) std::reverse(edge_pts.begin(), edge_pts.end());
      pts.insert(pts.end(), edge_pts.begin(), edge_pts.end() - 1);
    }
    gp_XYZ area(0, 0, 0);
    for (std::size_t i = 0; i < pts.size(); ++i) area += pts[i].XYZ().Crossed(pts[(i + 1) % pts.size()].XYZ()) * 0.5;
    areas.push_back(area);
  }
  const auto outer = std::max_element(areas.begin(), areas.end(),
                                      [](const gp_XYZ& a, const gp_XYZ& b) { return a.Modulus() < b.Modulus(); });
  double result = outer->Modulus();
  for (auto it = areas.begin(); it != areas.end(); ++it) {
    if (it != outer) result -= it->Modulus();
  }
  return result;
}

CliResult run_cli(const std::string& arguments, int time_limit) {
  // One file per process and call: CTest runs tests in parallel processes.
  static int calls = 0;
  const std::string err_path =
      scratch_dir() + "/cli_stderr_" + std::to_string(getpid()) + "_" + std::to_string(++calls) + ".txt";
  const std::string limit = time_limit > 0 ? "timeout -s KILL " + std::to_string(time_limit) + " " : "";
  const std::string command = limit + MEDIALMESH_CLI + " " + arguments + " 2>" + err_path;
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  std::stringstream text;
  text << err.rdbuf();
  result.err = text.str();
  std::remove(err_path.c_str());
  return result;
}

}  // namespace mm::test
