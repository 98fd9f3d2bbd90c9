#pragma once
// The arms of a concave corner's cross along which the decomposition may
// split (the paper's Fig. 17): shared by the decomposer, which splits along
// them, and the orthogonal joins, which recognise such splits.
#include <algorithm>

#include "boundary/face_model.hpp"

namespace mm {

// Arm `arm` (1 to nc - 1) of concave corner c, a unit direction into the
// face: the arm itself, or the nearest radius the corner has (perpendicular
// to one of its edges) where the arm points outside its fan of radii.
inline Vec2 concave_arm(const FaceModel& face, const Corner& c, int arm) {
  const BoundaryEdge& out = face.loops[c.loop].edges[c.vertex];
  const double spacing = c.angle / c.nc;
  const double polar = std::clamp(arm * spacing, 0.5 * kPi, c.angle - 0.5 * kPi);
  return rotated(edge_tangent(out, out.t_start), polar);
}

}  // namespace mm
