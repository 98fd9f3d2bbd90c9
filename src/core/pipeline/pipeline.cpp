#include "pipeline/pipeline.hpp"

#include <algorithm>
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

MeshedFaces mesh_faces(const std::vector<FaceModel>& faces, const PipelineOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  if (faces.empty()) throw InputError("no faces to mesh");
  const auto start = Clock::now();
  MeshedFaces result;
  std::vector<std::pair<std::string, double>> stages{
      {"medial_axis", 0.0}, {"singularities", 0.0}, {"decomposition", 0.0}};
  std::vector<Decomposition> decompositions;
  DecompositionOptions decomposition;
  decomposition.merge = options.merge;
  decomposition.tolerance = options.tolerance;
  for (const FaceModel& face : faces) {
    auto t = Clock::now();
    const MedialAxis axis = compute_medial_axis(face);
    stages[0].second += seconds_since(t);
    t = Clock::now();
    const MeshFlow flow = compute_mesh_flow(face, axis);
    stages[1].second += seconds_since(t);
    t = Clock::now();
    decompositions.push_back(decompose(face, axis, flow, decomposition));
    stages[2].second += seconds_since(t);
  }
  FaceSetBlockMesh blocks = mesh_blocks_together(faces, decompositions, options.meshing);
  std::vector<std::pair<std::string, double>> meshing;
  std::vector<const QuadMesh*> meshes;
  std::vector<QualityReport> reports;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    MeshedFace face;
    face.decomposition = std::move(decompositions[f]);
    face.blocks = std::move(blocks.faces[f]);
    face.quality = measure_quality(face.blocks.mesh);
    face.quality.stage_seconds = face.blocks.stage_seconds;
    for (const auto& [name, seconds] : face.blocks.stage_seconds) {
      const auto found = std::find_if(meshing.begin(), meshing.end(), [&](const auto& s) { return s.first == name; });
      if (found == meshing.end()) {
        meshing.emplace_back(name, seconds);
      } else {
        found->second += seconds;
      }
    }
    result.faces.push_back(std::move(face));
  }
  for (const MeshedFace& face : result.faces) {
    meshes.push_back(&face.blocks.mesh);
    reports.push_back(face.quality);
  }
  result.shared = std::move(blocks.shared);
  stages.insert(stages.end(), meshing.begin(), meshing.end());
  auto t = Clock::now();
  result.mesh = merge_face_meshes(faces, meshes, result.shared, blocks.tolerance);
  stages.emplace_back("merge", seconds_since(t));
  t = Clock::now();
  result.quality = combine_quality(reports, meshes, result.mesh);
  stages.emplace_back("quality", seconds_since(t));
  result.quality.stage_seconds = stages;
  result.quality.seconds = seconds_since(start);
  return result;
}

}  // namespace mm
