#pragma once
// What a user would check of a quad mesh, from the mesh and the face alone:
// all quads, none inverted, conforming (every inner side in exactly two
// quads, every outer side on the face's boundary), boundary nodes on the
// exact curves, the area of the face less the exact areas between the
// boundary sides and their curves, and an element count near area / H^2.
#include <string>
#include <vector>

#include "boundary/face_model.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm::test {

// The problems found, empty when the mesh is right. size is the target
// element size the mesh was made for: mesh_validity_problems and
// element_count_problem together.
std::vector<std::string> mesh_problems(const FaceModel& face, const QuadMesh& mesh, double size);

// All but the element count: what makes a mesh wrong rather than too coarse
// or too fine.
std::vector<std::string> mesh_validity_problems(const FaceModel& face, const QuadMesh& mesh);

// The element count far from area / H^2 (and from what the boundary's
// intervals need), or empty.
std::string element_count_problem(const FaceModel& face, const QuadMesh& mesh, double size);

// Sum over interior nodes of |4 - valence|: how much irregularity the mesh has.
int interior_irregularity(const QuadMesh& mesh);

}  // namespace mm::test
