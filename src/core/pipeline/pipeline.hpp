#pragma once
// The whole pipeline for one face, stage after stage, timed: medial axis,
// mesh flow, decomposition, block meshing and the quality report. The CLI,
// the Python module and the benchmarks all mesh through here.
#include "decomposition/decomposition.hpp"
#include "meshing/mesh_blocks.hpp"
#include "quality/quality.hpp"

namespace mm {

struct PipelineOptions {
  MeshingOptions meshing;
  bool merge = true;
  MergeTolerance tolerance;  // factor 0.75 of the medial radius unless told otherwise
};

struct MeshedFace {
  Decomposition decomposition;
  BlockMesh blocks;
  QualityReport quality;  // with the seconds of every stage
};

// Throws InputError for bad options, SelfCheckError when a stage's result
// fails its check.
MeshedFace mesh_face(const FaceModel& face, const PipelineOptions& options);

}  // namespace mm
