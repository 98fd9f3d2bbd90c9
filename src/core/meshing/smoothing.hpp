#pragma once
// Smoothing after the templates: moves interior nodes, and boundary nodes
// along their exact curves by parameter, so that the worst element gets
// better by Verdict's shape (angles and stretch together); untangles first
// when the placement folded an element.
#include <vector>

#include "boundary/face_model.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

struct SmoothingOptions {
  int max_sweeps = 30;
  // When > 0, a boundary node slides only as far as each of its two
  // intervals turns by at most this (radians) along its curve, or by no more
  // than it did: the curves stay resolved as interval assignment resolved them.
  double max_boundary_turn = 0.0;
  // When > 0, a boundary node slides only as far as each of its two
  // intervals' chords stays within this distance of the curve, or no
  // further off than it was: the mesh keeps to the face.
  double max_boundary_sagitta = 0.0;
  std::vector<int> fixed;  // nodes that never move, besides the face corners
  // How far untangling reaches round folded elements, in rings of elements,
  // before it relaxes the region once (see untangle in smoothing.cpp).
  int untangle_rings = 8;
  // Only the joint search round the worst quads (then the node search
  // there if it moved them): for a mesh the other steps have settled, once
  // after every other smoothing run (see spread_worst in smoothing.cpp).
  bool joint_search_only = false;
};

// Smoothing raises the least Verdict shape of the quads (quad_measures.hpp),
// which sees both angle and stretch.
struct SmoothingResult {
  double min_shape_before = 0.0;
  double min_shape_after = 0.0;
  int inverted_before = 0;
  int inverted_after = 0;
  int sweeps = 0;  // smoothing sweeps, untangling passes included
};

// Never lowers the minimum shape of a mesh with no inverted
// element; face corners and options.fixed never move. Order-1 meshes only (throws
// std::invalid_argument otherwise, and on nodes or places that do not fit
// the mesh or the face). Boundary nodes keep their loop and edge, stay
// strictly between their boundary neighbours, keep places[n].t in step, and
// leave each boundary interval at least a quarter of its first length; no
// move shortens an element side below a hundredth of the side facing it,
// except in a second untangling of what the first left folded.
SmoothingResult smooth_mesh(const FaceModel& face, QuadMesh& mesh, const SmoothingOptions& options);

}  // namespace mm
