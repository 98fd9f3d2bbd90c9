// mesh_census: the random faces of test_meshing.cpp (same generator, same
// sizes) through the whole pipeline, failures counted by their message with
// face names and numbers replaced, so the biggest causes show first.
//   mesh_census [FACES] [-v]
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <regex>

#include "face_builders.hpp"
#include "medial/medial_axis.hpp"
#include "pipeline/pipeline.hpp"
#include "quality/quality.hpp"
#include "singularity/mesh_flow.hpp"
#include "svg/svg_writer.hpp"

int main(int argc, char** argv) {
  using namespace mm;
  const int faces = argc > 1 ? std::atoi(argv[1]) : 300;
  const bool verbose = argc > 2 && std::strcmp(argv[2], "-v") == 0;
  const int picture = argc > 3 ? std::atoi(argv[3]) : -1;  // with -v: draws this face to census_N.svg
  std::mt19937 rng(test::kCensusSeed);
  int meshed = 0, errors = 0;
  std::map<std::string, int> causes;
  std::multimap<double, int> worst;        // min scaled Jacobian at order 1 -> face number
  std::multimap<double, int> worst_shape;  // min Verdict shape at order 1 -> face number
  long quads = 0, needles = 0, poor = 0;   // order 1: all quads, edge ratio over 10, shape under 0.3
  const std::regex numbers("-?[0-9]+(\\.[0-9]+)?(e-?[0-9]+)?");
  for (int number = 0; meshed + errors < faces; ++number) {
    FaceModel face;
    try {
      face = test::random_meshing_face(rng, number);
    } catch (const InputError&) {
      continue;
    }
    for (const int order : {1, 2}) {
      PipelineOptions options;
      options.meshing.size = test::random_meshing_size(face, number);
      options.meshing.order = order;
      try {
        if (number == picture && order == 1) {
          const FaceAxis medial = compute_face_medial_axis(face);
          const MeshFlow flow = compute_mesh_flow(medial.face, medial.axis);
          const Decomposition decomposition = decompose(medial.face, medial.axis, flow, DecompositionOptions{});
          SvgCanvas canvas(bounding_box(face), 900);
          draw_decomposition(canvas, medial.face, medial.axis, decomposition);
          for (const Block& block : decomposition.blocks) {
            Vec2 c{0, 0};
            for (const Vec2& q : block.outline) c = c + q * (1.0 / block.outline.size());
            for (const auto& corner : block.corners)
              canvas.text(corner.p + (c - corner.p) * 0.15, std::to_string(corner.type), 11, "fill:#000");
          }
          canvas.save("census_" + std::to_string(number) + ".svg");
        }
        // The pipeline's own entry point, with its fallbacks (less merging).
        const MeshedFace m = mesh_face(face, options);
        if (number == picture && order == 1) {
          SvgCanvas mesh_canvas(bounding_box(face), 900);
          draw_quad_mesh(mesh_canvas, face, m.decomposition, m.blocks.mesh, m.quality);
          mesh_canvas.save("census_" + std::to_string(number) + "_mesh.svg");
          std::cout << "min scaled Jacobian " << m.quality.min_scaled_jacobian << "\n";
        }
        if (order == 1) {
          worst.emplace(m.quality.min_scaled_jacobian, number);
          worst_shape.emplace(m.quality.min_shape(), number);
          quads += m.quality.quads, needles += m.quality.needles, poor += m.quality.poor_shape;
        }
      } catch (const std::exception& e) {
        std::string what = e.what();
        if (verbose) {
          std::cout << number << " order " << order << ": " << what << "\n";
          try {
            const FaceAxis medial = compute_face_medial_axis(face);
            const Decomposition decomposition =
                decompose(medial.face, medial.axis, compute_mesh_flow(medial.face, medial.axis), {});
            for (std::size_t b = 0; b < decomposition.blocks.size(); ++b) {
              const Block& block = decomposition.blocks[b];
              std::cout << "  block " << b << (block.kind == BlockKind::Polygon ? " polygon" : " submap") << " k "
                        << (block.singularity >= 0 ? decomposition.singularities[block.singularity].k : 0)
                        << " corners";
              for (const auto& c : block.corners) std::cout << " " << c.type;
              std::cout << "\n";
            }
          } catch (const std::exception&) {
          }
        }
        const auto colon = what.find(face.name);
        if (colon != std::string::npos) what.erase(colon, face.name.size());
        ++causes[std::regex_replace(what, numbers, "#")];
        ++errors;
        break;
      }
      if (order == 2) ++meshed;
    }
  }
  std::cout << "meshed " << meshed << " errors " << errors << "\n";
  const auto report = [](const char* what, const std::multimap<double, int>& by) {
    int below[3] = {0, 0, 0};
    for (const auto& [value, number] : by)
      for (int k = 0; k < 3; ++k) below[k] += value < 0.1 * (k + 1) ? 1 : 0;
    std::cout << what << " below 0.1 / 0.2 / 0.3: " << below[0] << " / " << below[1] << " / " << below[2]
              << "; worst faces:";
    for (auto it = by.begin(); it != by.end() && std::distance(by.begin(), it) < 8; ++it)
      std::cout << " " << it->second << " (" << it->first << ")";
    std::cout << "\n";
  };
  report("min scaled Jacobian", worst);
  report("min shape", worst_shape);
  std::cout << "quads " << quads << ", with edge ratio over 10 " << needles << ", with shape under 0.3 " << poor
            << "\n";
  std::multimap<int, std::string, std::greater<int>> sorted;
  for (const auto& [what, count] : causes) sorted.emplace(count, what);
  for (const auto& [count, what] : sorted) std::cout << count << "\t" << what << "\n";
}
