#pragma once
// Exact distances to the boundary: nearest points on the true curves, medial
// points placed on exact bisectors, junctions on exact equidistant points.
#include <array>
#include <vector>

#include "boundary/face_model.hpp"

namespace mm {

// A place on the boundary: edge `edge` of loop `loop` at parameter t. When the
// place is a corner (t at an end of the edge where the boundary is not smooth)
// `corner` holds that loop vertex's index, else -1.
struct BoundaryPlace {
  int loop = 0;
  int edge = 0;
  double t = 0.0;
  int corner = -1;
  Vec2 point;
  // The place stands for the corner vertex itself (not for an edge whose
  // nearest point happens to be its end), so a search from it may go on
  // along either edge meeting there.
  bool corner_itself = false;
};

// The face with, per loop vertex, whether it is a corner (not a tangent join).
class BoundaryIndex {
 public:
  explicit BoundaryIndex(const FaceModel& face);
  const FaceModel& face() const { return face_; }
  bool is_corner(int loop, int vertex) const { return corner_[loop][vertex]; }
  bool is_reflex(int loop, int vertex) const { return reflex_[loop][vertex]; }
  const BoundaryEdge& edge(int loop, int e) const { return face_.loops[loop].edges[e]; }
  int edge_count(int loop) const { return static_cast<int>(face_.loops[loop].edges.size()); }
  BoundaryPlace place(int loop, int edge, double t) const;  // fills corner and point

 private:
  const FaceModel& face_;
  std::vector<std::vector<bool>> corner_;
  std::vector<std::vector<bool>> reflex_;  // corners whose interior angle exceeds pi
};

// Nearest point to m on the smooth run of boundary through `start`, found by
// Newton's method from start.t and carried across tangent joins. It goes on
// past a reflex corner, where the nearest point moves on without a jump, but
// stops at a convex one, where it jumps (that jump is the corner's flare);
// from a place that is a corner itself it may leave along either edge.
BoundaryPlace nearest_on_run(const BoundaryIndex& index, const BoundaryPlace& start, Vec2 m);

// True if a and b are the same point of the boundary: within tolerance of
// each other and within a few times that along their loop, so that the two
// sides of a neck narrower than the tolerance stay two places.
bool same_place(const BoundaryIndex& index, const BoundaryPlace& a, const BoundaryPlace& b, double tolerance);

struct Bisected {
  Vec2 p;
  double r = 0.0;
  BoundaryPlace a, b;
  bool converged = false;
};

// The point of the exact bisector of the runs through a and b nearest to m.
Bisected bisect(const BoundaryIndex& index, Vec2 m, BoundaryPlace a, BoundaryPlace b);

struct Equidistant {
  Vec2 p;
  double r = 0.0;
  std::vector<BoundaryPlace> places;
  bool converged = false;
};

// The point near m equally far from the runs through three places.
Equidistant equidistant(const BoundaryIndex& index, Vec2 m, const std::vector<BoundaryPlace>& places);

// The same with each place's foot kept on its own edge within the parameter
// window windows[k] (lower, upper): from a point a little off the answer the
// nearest place on a run that curves nearly round it may lie far away (the
// distance has no local minimum near the answer's foot there), and the
// plain search slides to it. Converged only where every foot settles inside
// its window, a true local nearest point.
Equidistant equidistant_within(const BoundaryIndex& index, Vec2 m, const std::vector<BoundaryPlace>& places,
                               const std::vector<std::array<double, 2>>& windows);

// Curvature at parameter t of an edge, positive where the boundary bends
// round the material (its centre of curvature is inside).
double curvature(const BoundaryEdge& edge, double t);

}  // namespace mm
