#include "pipeline/pipeline.hpp"

#include <chrono>

#include "medial/medial_axis.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

MeshedFace mesh_face(const FaceModel& face, const PipelineOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const auto start = Clock::now();
  MeshedFace result;
  std::vector<std::pair<std::string, double>> stages;
  auto t = Clock::now();
  const MedialAxis axis = compute_medial_axis(face);
  stages.emplace_back("medial_axis", seconds_since(t));
  t = Clock::now();
  const MeshFlow flow = compute_mesh_flow(face, axis);
  stages.emplace_back("singularities", seconds_since(t));
  t = Clock::now();
  DecompositionOptions decomposition;
  decomposition.merge = options.merge;
  decomposition.tolerance = options.tolerance;
  result.decomposition = decompose(face, axis, flow, decomposition);
  stages.emplace_back("decomposition", seconds_since(t));
  result.blocks = mesh_blocks(face, result.decomposition, options.meshing);
  stages.insert(stages.end(), result.blocks.stage_seconds.begin(), result.blocks.stage_seconds.end());
  t = Clock::now();
  result.quality = measure_quality(result.blocks.mesh);
  stages.emplace_back("quality", seconds_since(t));
  result.quality.stage_seconds = stages;
  result.quality.seconds = seconds_since(start);
  return result;
}

}  // namespace mm
