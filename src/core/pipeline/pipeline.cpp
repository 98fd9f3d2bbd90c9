#include "pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>

#include "medial/medial_axis.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

namespace {

using Clock = std::chrono::steady_clock;
using StageSeconds = std::vector<std::pair<std::string, double>>;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Adds to the stage of that name, appended when new: several faces' stages sum.
void add_stage(StageSeconds& stages, const std::string& name, double seconds) {
  const auto found = std::find_if(stages.begin(), stages.end(), [&](const auto& s) { return s.first == name; });
  if (found == stages.end()) {
    stages.emplace_back(name, seconds);
  } else {
    found->second += seconds;
  }
}

// Medial axis, mesh flow and decomposition of one face, each timed into stages.
Decomposition decompose_face(const FaceModel& face, const PipelineOptions& options, StageSeconds& stages) {
  auto t = Clock::now();
  const MedialAxis axis = compute_medial_axis(face);
  add_stage(stages, "medial_axis", seconds_since(t));
  t = Clock::now();
  const MeshFlow flow = compute_mesh_flow(face, axis);
  add_stage(stages, "singularities", seconds_since(t));
  t = Clock::now();
  DecompositionOptions decomposition;
  decomposition.merge = options.merge;
  decomposition.tolerance = options.tolerance;
  Decomposition result = decompose(face, axis, flow, decomposition);
  add_stage(stages, "decomposition", seconds_since(t));
  return result;
}

}  // namespace

MeshedFace mesh_face(const FaceModel& face, const PipelineOptions& options) {
  const auto start = Clock::now();
  MeshedFace result;
  StageSeconds stages;
  result.decomposition = decompose_face(face, options, stages);
  result.blocks = mesh_blocks(face, result.decomposition, options.meshing);
  stages.insert(stages.end(), result.blocks.stage_seconds.begin(), result.blocks.stage_seconds.end());
  const auto t = Clock::now();
  result.quality = measure_quality(result.blocks.mesh);
  stages.emplace_back("quality", seconds_since(t));
  result.quality.stage_seconds = stages;
  result.quality.seconds = seconds_since(start);
  return result;
}

MeshedFaces mesh_faces(const std::vector<FaceModel>& faces, const PipelineOptions& options) {
  if (faces.empty()) throw InputError("no faces to mesh");
  const auto start = Clock::now();
  MeshedFaces result;
  StageSeconds stages;
  std::vector<Decomposition> decompositions;
  for (const FaceModel& face : faces) decompositions.push_back(decompose_face(face, options, stages));
  FaceSetBlockMesh blocks = mesh_blocks_together(faces, decompositions, options.meshing);
  std::vector<const QuadMesh*> meshes;
  std::vector<QualityReport> reports;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    MeshedFace face;
    face.decomposition = std::move(decompositions[f]);
    face.blocks = std::move(blocks.faces[f]);
    face.quality = measure_quality(face.blocks.mesh);
    face.quality.stage_seconds = face.blocks.stage_seconds;
    for (const auto& [name, seconds] : face.blocks.stage_seconds) add_stage(stages, name, seconds);
    result.faces.push_back(std::move(face));
  }
  for (const MeshedFace& face : result.faces) {
    meshes.push_back(&face.blocks.mesh);
    reports.push_back(face.quality);
  }
  result.shared = std::move(blocks.shared);
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
