// Malformed and hostile input through the command-line tool: truncated and
// corrupted BREP, STEP and IGES files, NaN in a file, faces at 1e-6 and 1e6,
// a face of thousands of edges. Never a crash or a hang: a result, or exit
// code 2 with one line (3 with one line if a stage's self-check fails).
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>

#include "occ/occ_face.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

using test::run_cli;
using test::scratch_dir;
using test::shared_dir;

// The tool reads for at most this long; a run may take at most the second.
constexpr int kReadLimit = 5;
constexpr int kRunLimit = 60;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string write_file(const std::string& name, const std::string& data) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << data;
  return path;
}

// Corrupted copies of a file: cut at several lengths, three bits flipped
// (six times), a number replaced by "nan" (four times).
std::vector<std::pair<std::string, std::string>> corrupted(const std::string& data) {
  std::vector<std::pair<std::string, std::string>> variants;
  for (const double fraction : {0.05, 0.3, 0.5, 0.8, 0.95, 0.999}) {
    variants.emplace_back("cut at " + std::to_string(fraction), data.substr(0, data.size() * fraction));
  }
  std::mt19937 rng(12);
  for (int i = 0; i < 6; ++i) {
    std::string flipped = data;
    for (int bit = 0; bit < 3; ++bit) flipped[rng() % flipped.size()] ^= static_cast<char>(1 << (rng() % 8));
    variants.emplace_back("bits flipped " + std::to_string(i), flipped);
  }
  const std::regex number("-?[0-9]+\\.[0-9]+(e[-+]?[0-9]+)?");
  std::vector<std::pair<std::size_t, std::size_t>> numbers;
  for (auto it = std::sregex_iterator(data.begin(), data.end(), number); it != std::sregex_iterator(); ++it) {
    numbers.emplace_back(it->position(), it->length());
  }
  for (int i = 0; i < 4 && !numbers.empty(); ++i) {
    const auto [at, length] = numbers[rng() % numbers.size()];
    variants.emplace_back("nan " + std::to_string(i), data.substr(0, at) + "nan" + data.substr(at + length));
  }
  return variants;
}

// A result whose singularities balance, or one line naming the file.
void expect_clean(const std::string& path, const std::string& options) {
  SCOPED_TRACE(path);
  const test::CliResult r =
      run_cli("singularities " + path + options + " --json --read-time-limit " + std::to_string(kReadLimit), kRunLimit);
  if (r.exit_code == 0) {
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["sum_k"], json["predicted_sum_k"]);
    return;
  }
  ASSERT_TRUE(r.exit_code == 2 || r.exit_code == 3) << "exit code " << r.exit_code << ": " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("medialmesh: " + path + ": ", 0), 0u) << r.err;
  if (r.exit_code == 3) EXPECT_NE(r.err.find("self-check failed"), std::string::npos) << r.err;
}

void expect_corrupted_copies_clean(const std::string& source, const std::string& extension,
                                   const std::string& options = "") {
  const std::string data = slurp(source);
  ASSERT_FALSE(data.empty()) << source;
  int i = 0;
  for (const auto& [what, bad] : corrupted(data)) {
    SCOPED_TRACE(what);
    expect_clean(write_file("hostile_" + std::to_string(getpid()) + "_" + std::to_string(i++) + extension, bad),
                 options);
  }
}

TEST(HostileInput, CorruptedBrepFiles) {
  for (const char* name :
       {"/geometry/plate_with_hole.brep", "/geometry/aerofoil3.brep", "/realcad/faces/occt_pumpcover_8.brep"}) {
    expect_corrupted_copies_clean(shared_dir() + name, ".brep");
  }
}

TEST(HostileInput, CorruptedStepFiles) {
  expect_corrupted_copies_clean(shared_dir() + "/realcad/step/trimesh_featuretype.STEP", ".step", " --face 18");
  STEPControl_Writer writer;
  writer.Transfer(test::first_face(read_shape(shared_dir() + "/geometry/bracket.brep")), STEPControl_AsIs);
  const std::string step = scratch_dir() + "/bracket_" + std::to_string(getpid()) + ".step";
  ASSERT_EQ(writer.Write(step.c_str()), IFSelect_RetDone);
  expect_corrupted_copies_clean(step, ".step");
}

TEST(HostileInput, CorruptedIgesFiles) {
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 1);
  writer.AddShape(test::first_face(read_shape(shared_dir() + "/geometry/bracket.brep")));
  writer.ComputeModel();
  const std::string iges = scratch_dir() + "/bracket_" + std::to_string(getpid()) + ".iges";
  ASSERT_TRUE(writer.Write(iges.c_str()));
  expect_corrupted_copies_clean(iges, ".iges");
}

// Reference faces scaled by 1e-6 and 1e6 about the origin, and the plate also
// about a point 0.36 away (a tiny face far from the origin, where doubles
// hold fewer digits of it), give the same singularities: no tolerance is
// absolute.
TEST(HostileInput, TinyAndHugeFaces) {
  for (const char* name : {"plate_with_hole", "aerofoil3", "bracket", "ellipse"}) {
    const std::string source = shared_dir() + "/geometry/" + name + ".brep";
    const test::CliResult reference = run_cli("singularities " + source + " --json", kRunLimit);
    ASSERT_EQ(reference.exit_code, 0) << reference.err;
    const auto expected = nlohmann::json::parse(reference.out);
    std::vector<gp_Pnt> centres{gp_Pnt(0, 0, 0)};
    if (std::string(name) == "plate_with_hole") centres.emplace_back(0.3, -0.2, 0);
    for (const gp_Pnt& centre : centres) {
      for (const double scale : {1e-6, 1e6}) {
        SCOPED_TRACE(std::string(name) + " at " + std::to_string(scale) + " about x = " + std::to_string(centre.X()));
        gp_Trsf t;
        t.SetScale(centre, scale);
        const std::string path = scratch_dir() + "/" + name + "_scaled_" + std::to_string(getpid()) + ".brep";
        test::write_brep(BRepBuilderAPI_Transform(read_shape(source), t, true).Shape(), path);
        const test::CliResult r = run_cli("singularities " + path + " --json", kRunLimit);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto json = nlohmann::json::parse(r.out);
        EXPECT_EQ(json["sum_k"], expected["sum_k"]);
        ASSERT_EQ(json["singularities"].size(), expected["singularities"].size());
        for (std::size_t i = 0; i < json["singularities"].size(); ++i) {
          EXPECT_EQ(json["singularities"][i]["k"], expected["singularities"][i]["k"]);
        }
      }
    }
  }
}

// A wavy outline of 2 000 straight edges: read and analysed within the run limit.
TEST(HostileInput, ThousandsOfEdges) {
  BRepBuilderAPI_MakePolygon polygon;
  const int edges = 2000;
  for (int i = 0; i < edges; ++i) {
    const double a = 2 * kPi * i / edges, r = 1 + 0.05 * std::sin(40 * a);
    polygon.Add(gp_Pnt(r * std::cos(a), r * std::sin(a), 0));
  }
  polygon.Close();
  const std::string path = scratch_dir() + "/edges_2000_" + std::to_string(getpid()) + ".brep";
  test::write_brep(BRepBuilderAPI_MakeFace(polygon.Wire()).Face(), path);
  const test::CliResult r = run_cli("singularities " + path + " --json", kRunLimit);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["sum_k"], json["predicted_sum_k"]);
}

TEST(HostileInput, BadReadTimeLimit) {
  const std::string square = shared_dir() + "/geometry/square.brep";
  EXPECT_EQ(run_cli("info " + square + " --read-time-limit 0").exit_code, 2);
  EXPECT_EQ(run_cli("info " + square + " --read-time-limit x").exit_code, 2);
  EXPECT_EQ(run_cli("info " + square + " --read-time-limit 5").exit_code, 0);
}

}  // namespace
}  // namespace mm
