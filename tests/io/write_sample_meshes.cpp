// Writes a structured mesh of an annulus sector at order 1 and 2 in every
// mesh file format, placed by three frames (two in the global XY plane,
// facing up and down, for plane-stress elements, one tilted for shells), plus
// manifest.json with what tests/io/read_back.py must find in each file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "report/mesh_files.hpp"

namespace {

constexpr double kInner = 1.0;
constexpr double kOuter = 2.0;
constexpr double kSweep = 120.0 * mm::kPi / 180.0;
constexpr int kRadial = 3;
constexpr int kAngular = 8;

mm::Vec2 polar(double r, double angle) {
  return {r * std::cos(angle), r * std::sin(angle)};
}

// Quads run radially outwards then round the sector: counter-clockwise.
// Mid-side nodes of the arcs lie on the arcs, so order 2 is truly curved.
mm::QuadMesh annulus_sector(int order) {
  mm::QuadMesh mesh;
  const auto add_node = [&mesh](mm::Vec2 p, bool boundary) {
    mm::NodePlace place;
    if (boundary) {
      place.loop = 0;
      place.corner_elements = 2;
    }
    mesh.nodes.push_back(p);
    mesh.places.push_back(place);
    return static_cast<int>(mesh.nodes.size()) - 1;
  };
  const auto radius = [](double i) { return kInner + (kOuter - kInner) * i / kRadial; };
  const auto angle = [](double j) { return kSweep * j / kAngular; };
  std::vector<std::vector<int>> corner(kRadial + 1, std::vector<int>(kAngular + 1));
  for (int i = 0; i <= kRadial; ++i) {
    for (int j = 0; j <= kAngular; ++j) {
      corner[i][j] = add_node(polar(radius(i), angle(j)), i == 0 || i == kRadial || j == 0 || j == kAngular);
    }
  }
  for (int i = 0; i < kRadial; ++i) {
    for (int j = 0; j < kAngular; ++j) {
      mesh.quads.push_back({corner[i][j], corner[i + 1][j], corner[i + 1][j + 1], corner[i][j + 1]});
      mesh.block_of_quad.push_back(j < kAngular / 2 ? 0 : 1);
    }
  }
  if (order == 2) {
    // A side shared by two quads gets one node: radial sides keyed by (i, j), arcs likewise.
    std::vector<std::vector<int>> radial_mid(kRadial, std::vector<int>(kAngular + 1));
    std::vector<std::vector<int>> arc_mid(kRadial + 1, std::vector<int>(kAngular));
    for (int i = 0; i < kRadial; ++i) {
      for (int j = 0; j <= kAngular; ++j)
        radial_mid[i][j] = add_node(polar(radius(i + 0.5), angle(j)), j == 0 || j == kAngular);
    }
    for (int i = 0; i <= kRadial; ++i) {
      for (int j = 0; j < kAngular; ++j)
        arc_mid[i][j] = add_node(polar(radius(i), angle(j + 0.5)), i == 0 || i == kRadial);
    }
    for (int i = 0; i < kRadial; ++i) {
      for (int j = 0; j < kAngular; ++j) {
        mesh.midside.push_back({radial_mid[i][j], arc_mid[i + 1][j], radial_mid[i][j + 1], arc_mid[i][j]});
      }
    }
  }
  for (int i = 0; i <= kAngular; i += kAngular) {
    mesh.places[corner[0][i]].corner_elements = 1;
    mesh.places[corner[kRadial][i]].corner_elements = 1;
  }
  return mesh;
}

// The sum of the corner quads' areas: the annulus between two inscribed polygons.
double chord_area() {
  return 0.5 * kAngular * std::sin(kSweep / kAngular) * (kOuter * kOuter - kInner * kInner);
}

nlohmann::json frame_json(const mm::Frame& f) {
  return {{"origin", f.origin}, {"x_dir", f.x_dir}, {"y_dir", f.y_dir}, {"normal", f.normal}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: write_sample_meshes OUTPUT_FOLDER\n";
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);

  // Turned 30 degrees about z and shifted: still the global XY plane, as CPS elements need.
  const double c = std::cos(mm::kPi / 6), s = std::sin(mm::kPi / 6);
  const mm::Frame plane{{10.0, -5.0, 0.0}, {c, s, 0.0}, {-s, c, 0.0}, {0.0, 0.0, 1.0}};
  // The XY plane seen from below: CPS elements must be written reversed.
  const mm::Frame flipped{{-3.0, 4.0, 0.0}, {c, s, 0.0}, {s, -c, 0.0}, {0.0, 0.0, -1.0}};
  // A plane tilted out of every coordinate plane, for shells.
  const double a = 1.0 / std::sqrt(2.0), b = 1.0 / std::sqrt(6.0), n = 1.0 / std::sqrt(3.0);
  const mm::Frame tilted{{1.0, 2.0, 3.0}, {a, a, 0.0}, {-b, b, 2.0 * b}, {n, -n, n}};

  nlohmann::json manifest = nlohmann::json::array();
  for (int order : {1, 2}) {
    const mm::QuadMesh mesh = annulus_sector(order);
    for (const auto& [name, frame] :
         {std::pair{"plane", plane}, std::pair{"flipped", flipped}, std::pair{"tilted", tilted}}) {
      for (const char* extension : {".inp", ".msh", ".vtu"}) {
        const std::string file = "sector_o" + std::to_string(order) + "_" + name + extension;
        const std::string path = (folder / file).string();
        mm::MeshFileOptions options;
        options.shell_elements = std::string(name) == "tilted";
        mm::write_mesh_file(mesh, frame, path, options);
        manifest.push_back({{"path", path},
                            {"nodes", mesh.nodes.size()},
                            {"elements", mesh.quads.size()},
                            {"order", order},
                            {"area", chord_area()},
                            {"frame", frame_json(frame)}});
      }
    }
  }
  std::ofstream((folder / "manifest.json").string()) << manifest.dump(2) << '\n';
  std::cout << "wrote " << manifest.size() << " mesh files to " << folder << '\n';
  return 0;
}
