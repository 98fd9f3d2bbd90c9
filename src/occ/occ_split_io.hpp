#pragma once
// Block faces and split edges as BREP text or files, for the CLI and the
// Python module. No OCC types in this header.
#include <string>
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// The face given as BREP text (FreeCAD's Face.exportBrepToString()) split along
// the polylines (in the face's 2-D frame, as FaceModel::frame) into its block
// faces: BREP text of a compound of them. Throws InputError naming the face.
std::string split_face_brep(const std::string& face_brep, const std::vector<std::vector<Vec2>>& polylines,
                            const std::string& name);

// The split edges on that face in 3-D: BREP text of a compound of them.
std::string split_edges_brep(const std::string& face_brep, const std::vector<std::vector<Vec2>>& polylines,
                             const std::string& name);

// Splits face face_index (1-based, FreeCAD's FaceN; 0 takes the file's only
// face) of a BREP, STEP or IGES file and writes the block faces as a compound
// to out_path: STEP for .step/.stp, else BREP. Throws InputError.
void write_blocks_brep(const std::string& input_path, int face_index, const std::vector<std::vector<Vec2>>& polylines,
                       const std::string& out_path);

}  // namespace mm
