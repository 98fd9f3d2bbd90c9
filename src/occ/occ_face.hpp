#pragma once
// OCC face -> boundary model, for code that already holds OCC shapes.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <string>

#include "boundary/face_model.hpp"

namespace mm {

FaceModel face_model_from_occ(const TopoDS_Face& face, const std::string& name);

// Reads a shape from a file by its extension. Throws InputError naming the file.
TopoDS_Shape read_shape(const std::string& path);

}  // namespace mm
