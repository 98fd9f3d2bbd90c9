#pragma once
// Mesh flow across the medial axis and the singularities it implies (the
// paper's section 3). The flow type n says how many quarter turns a quad
// mesh's cross makes between the two touching points of a medial disc; a flux
// balance says where the mesh must have nodes of 4 + k elements.
#include <vector>

#include "boundary/face_model.hpp"
#include "medial/medial_axis.hpp"

namespace mm {

// What produced a singularity.
enum class SingularitySource {
  FlowSwitch,        // n changes along a medial edge (adjusted medial angle pi/4 or 3pi/4)
  CornerSwitch,      // the cross arm used at a concave corner changes along an edge
  Junction,          // a medial vertex touching three or more places, or (edge >= 0) a touch jump
                     // where a pruned branch left the edge (docs/flux_balance.md section 3)
  Flare,             // the end of the axis at a convex corner
  FiniteContact,     // the centre of a touched circular arc (the paper's eq. 7)
  CurvatureContact,  // an end where the disc's curvature matches the boundary's
};
const char* singularity_source_name(SingularitySource source);

struct Singularity {
  Vec2 p;
  double r = 0.0;  // medial radius there
  int k = 0;       // the mesh node there has 4 + k elements
  SingularitySource at = SingularitySource::Junction;
  int edge = -1;    // the medial edge of a switch
  int vertex = -1;  // the medial vertex
};

// A stretch of one medial edge with a single flow type.
struct FlowRun {
  int edge = 0;
  int n = 0;
  std::vector<Vec2> points;
};

// The flow at one medial point, as the flux balance used it. A concave corner
// touched is named with the arm of its cross the radius was turned onto
// (arm 0 along the corner's outgoing edge, arm nc along its incoming edge).
struct PointFlow {
  int q = 0;               // signed flow type, n = |q|; q > 0 where the disc shrinks towards the edge's end
  double deviation = 0.0;  // how far the adjusted turning is from q quarter turns (0 is ideal)
  int left_corner = -1;    // index into face.corners, or -1 for a smooth place
  int left_arm = 0;
  int right_corner = -1;
  int right_arm = 0;
};

struct MeshFlow {
  std::vector<FlowRun> runs;                   // covering every medial edge, in order
  std::vector<Singularity> singularities;      // k != 0 only
  std::vector<std::vector<PointFlow>> points;  // per medial edge, one per point of the edge
  int sum_k() const;
};

// The flow type at every medial point, with the medial angle adjusted where a
// touching point is a concave corner (the radius turned onto the nearest arm
// of the corner's cross), and the singularities from the flux balance at the
// only places it can be unbalanced: the switch points (located by bisection
// on the exact medial axis) and the medial vertices; docs/flux_balance.md
// proves each rule. Throws SelfCheckError if the sum of k is not
// predicted_sum_k(face), a flow switch has |k| > 1, or the axis folds back
// (touches running backwards or jumping on both sides of an edge).
MeshFlow compute_mesh_flow(const FaceModel& face, const MedialAxis& axis);

}  // namespace mm
