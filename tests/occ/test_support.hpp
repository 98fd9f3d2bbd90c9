#pragma once
// Shared helpers for tests that work with real OCC shapes and the CLI.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <string>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm::test {

std::string shared_dir();   // the team's reference geometry (../shared)
std::string scratch_dir();  // a folder for files the tests write

std::vector<std::string> brep_files(const std::string& folder);

// The face of ../shared/geometry/NAME.brep.
FaceModel reference_face(const std::string& name);

// The text of tests/data/NAME.brep (NAME may hold a folder: "fuzz/strip_1_2"),
// and the face it holds, named by the file's own name.
std::string data_brep_text(const std::string& name);
FaceModel data_face(const std::string& name);

TopoDS_Face first_face(const TopoDS_Shape& shape);
void write_brep(const TopoDS_Shape& shape, const std::string& path);

// Area of the face from a fine polygon through points that OCC's own
// discretiser places on its 3-D edges: an oracle independent of our curves.
double discretised_area(const TopoDS_Face& face, int points_per_edge);

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};
// Runs the command-line tool; with a time limit (seconds) it is killed after
// that long, and the exit code is then 137.
CliResult run_cli(const std::string& arguments, int time_limit = 0);

}  // namespace mm::test
