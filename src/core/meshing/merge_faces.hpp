#pragma once
// Several faces' meshes joined into one along the pieces of boundary they
// share (mesh_blocks_together), and the joined mesh checked as a whole.
#include <vector>

#include "boundary/face_model.hpp"
#include "meshing/mesh_blocks.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

// Nodes keep the faces' order (a single face's mesh keeps its numbering);
// a shared node takes the position of the face listed first. Throws
// SelfCheckError naming both faces and their edges when a shared node's
// partner lies further than the tolerance from it, and naming the faces when
// the whole fails a check: two nodes of no common face within the tolerance
// left apart where a piece is shared, a collapsed element side, an element side in more
// elements than faces meet there (two inside a face), or a shared piece's
// side left open.
MergedMesh merge_face_meshes(const std::vector<FaceModel>& faces, const std::vector<const QuadMesh*>& meshes,
                             const std::vector<SharedPiece>& shared, double tolerance);

}  // namespace mm
