#pragma once
// Reading CAD files into boundary models. No OCC types in this header, so the
// CLI and the Python module compile without OCC's headers.
#include <string>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm {

// Reads a BREP, STEP or IGES file (chosen by extension) and builds the models
// of the faces with the given 1-based indices (FreeCAD's FaceN numbering).
// With no indices, a file holding one face gives that face; a file holding
// several is an InputError listing its planar faces. Throws InputError.
std::vector<FaceModel> read_face_models(const std::string& path, const std::vector<int>& face_indices);

// The planar faces of solid `solid` of a file (1-based, FreeCAD's Solids
// order), by their face numbers in the file: every planar face of a part,
// to mesh together. Throws InputError when the file holds fewer solids or
// the solid no planar face.
std::vector<int> planar_faces_of_solid(const std::string& path, int solid);

// A single face given as BREP text (FreeCAD's Face.exportBrepToString()).
FaceModel face_model_from_brep_string(const std::string& brep, const std::string& name);

}  // namespace mm
