#pragma once
// Writes a quad mesh for solvers and viewers, placed in 3-D by the face's
// frame: Abaqus/CalculiX .inp, Gmsh 4.1 .msh (ASCII), VTK .vtu (ASCII).
#include <string>

#include "boundary/face_model.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

struct MeshFileOptions {
  bool shell_elements = false;  // .inp: S4/S8 instead of CPS4/CPS8
};

// The format comes from the extension (.inp, .msh, .vtu). Throws InputError
// naming the path for an unknown extension or a file that cannot be written.
void write_mesh_file(const QuadMesh& mesh, const Frame& frame, const std::string& path,
                     const MeshFileOptions& options = {});

}  // namespace mm
