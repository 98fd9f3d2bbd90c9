#pragma once
// Block meshing: the decomposition's blocks filled with quads that conform
// across every split. One interval assignment for the whole face, nodes on
// the exact curves, the templates, smoothing, and mid-side nodes for order 2.
#include <string>
#include <utility>
#include <vector>

#include "boundary/face_model.hpp"
#include "decomposition/decomposition.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

struct MeshingOptions {
  double size = 0.0;  // target element size, face units (> 0)
  int order = 1;      // 1: 4-node quads, 2: 8-node quads
  bool smooth = true;
};

struct BlockMesh {
  QuadMesh mesh;
  std::vector<int> segment_counts;  // intervals per segment, for the report
  std::vector<std::string> notes;
  std::vector<std::pair<std::string, double>> stage_seconds;
};

// Meshes every block of the decomposition. Throws InputError for a size that
// is not a positive number or an order other than 1 or 2, and SelfCheckError
// naming the face when the mesh fails its own checks: conformity (every inner
// edge in two quads, every outer one on the boundary), no inverted element
// (the worst one named), area equal to the face's within the chordal error.
BlockMesh mesh_blocks(const FaceModel& face, const Decomposition& decomposition, const MeshingOptions& options);

}  // namespace mm
