#pragma once
// OCC face -> boundary model, for code that already holds OCC shapes.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <optional>
#include <string>

#include "boundary/face_model.hpp"

namespace mm {

FaceModel face_model_from_occ(const TopoDS_Face& face, const std::string& name);

// Reads a shape from a file by its extension. Throws InputError naming the file.
TopoDS_Shape read_shape(const std::string& path);

// Face face_index (1-based, FreeCAD's FaceN) of a shape read from path; with no
// index, its only face. Throws InputError naming the file.
TopoDS_Face face_of_shape(const TopoDS_Shape& shape, std::optional<int> face_index, const std::string& path);

// The single face of BREP text (FreeCAD's Face.exportBrepToString()). Throws InputError.
TopoDS_Face face_from_brep_string(const std::string& brep, const std::string& name);

}  // namespace mm
