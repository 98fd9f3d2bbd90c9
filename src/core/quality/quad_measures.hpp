#pragma once
// The standard quality measures of one quad, as the Verdict library defines
// them (Stimpson, Ernst, Knupp, Pebay, Thompson: "The Verdict Geometric
// Quality Library", SAND2007-1751), the library behind VTK's vtkMeshQuality
// and most FEM pre-processors. Computed in the quad's own plane, corners
// counter-clockwise; tests check them against vtkMeshQuality itself.
#include <array>

#include "geometry/vec2.hpp"

namespace mm {

struct QuadMeasures {
  double scaled_jacobian = 0.0;  // least corner Jacobian over its two sides' lengths; [-1, 1], 1 best
  double shape = 0.0;            // 2 / condition number of the worst corner; [0, 1], 1 best; sees angle and stretch
  double edge_ratio = 0.0;       // longest side / shortest; >= 1, 1 best
  double aspect_ratio = 0.0;     // longest side x perimeter / (2 x twice the area); >= 1, 1 best
  double skew = 0.0;             // |cos| of the angle between the two principal axes; [0, 1], 0 best
  double taper = 0.0;            // how unlike a parallelogram; >= 0, 0 best
  double stretch = 0.0;          // sqrt(2) x shortest side / longest diagonal; (0, 1], 1 best
  double condition = 0.0;        // worst corner's condition number; >= 1, 1 best
  double jacobian = 0.0;         // least corner area (cross product of its sides)
  double area = 0.0;             // signed (shoelace)
};

// Verdict's conventions for degenerate quads are kept: a side of length 0
// gives scaled Jacobian and shape 0, a corner of no area a condition of
// DBL_MAX, an edge ratio with a side of 0 DBL_MAX.
QuadMeasures measure_quad(const std::array<Vec2, 4>& p);

// An 8-node quad (corners, then the mid-side node of side i, corner i to
// i + 1): the least over the largest Jacobian determinant at its 3 x 3 Gauss
// points; 1 for a parallelogram with straight sides, <= 0 when it folds.
double jacobian_ratio(const std::array<Vec2, 8>& p);

}  // namespace mm
