#pragma once
// Decomposition splits back onto the OCC face: split edges in 3-D and the
// block faces they cut the face into. Includes OCC headers; code without OCC
// uses occ/occ_split_io.hpp.
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm {

// Each split, a polyline in the face's 2-D frame, as straight edges on the
// face's plane in 3-D; consecutive pieces of a polyline share their vertex and
// zero-length pieces are dropped.
std::vector<TopoDS_Edge> split_edges_3d(const Frame& frame, const std::vector<std::vector<Vec2>>& polylines);

// The block faces the splits cut the face into. frame is the face's own
// (FaceModel::frame). Split ends within 1e-6 of the face size of the boundary
// or of another split are moved onto it first. Every block is checked valid
// (BRepCheck_Analyzer; an invalid one first loses any wire shorter than that
// snap distance, a degenerate edge the splitter leaves where two splits end
// at both ends of a tiny boundary edge) and the block areas must add up to
// the face's area; a failed check throws InputError naming it.
std::vector<TopoDS_Face> split_face(const TopoDS_Face& face, const Frame& frame,
                                    const std::vector<std::vector<Vec2>>& polylines);

}  // namespace mm
