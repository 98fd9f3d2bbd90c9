#pragma once
// Writes a quad mesh for solvers and viewers, placed in 3-D by the face's
// frame (or several faces' merged mesh): Abaqus/CalculiX .inp, Gmsh 4.1 .msh (ASCII), VTK .vtu (ASCII).
#include <string>

#include "boundary/face_model.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

struct MeshFileOptions {
  bool shell_elements = false;  // .inp: S4/S8 instead of CPS4/CPS8
};

// The format comes from the extension (.inp, .msh, .vtu). Throws InputError
// naming the path for an unknown extension or a file that cannot be written.
// Nodes and elements keep the mesh's order (1-based in .inp and .msh); an
// 8-node quad lists its corners, then the mid-side node of each side i
// (corner i to i + 1), as all three formats do. .inp: node set NALL, element
// set EALL, boundary node set NBOUNDARY; plane-stress elements are written
// reversed when the frame looks down the z axis, since CalculiX wants them
// counter-clockwise seen from +z (and in the plane z = 0, which is the
// caller's choice of frame). .msh: one surface entity in physical group 1
// "face". .vtu: the decomposition block of each element as cell data.
void write_mesh_file(const QuadMesh& mesh, const Frame& frame, const std::string& path,
                     const MeshFileOptions& options = {});

// The same for a mesh already in 3-D, several faces merged (mesh_faces):
// .inp plane-stress elements are reversed face by face (those whose face
// looks down the z axis), NBOUNDARY is the outline of the union, and .vtu
// also gets the face of each element.
void write_mesh_file(const MergedMesh& mesh, const std::string& path, const MeshFileOptions& options = {});

}  // namespace mm
