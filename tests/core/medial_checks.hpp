#pragma once
// Checks every medial axis must pass, whatever the face.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "boundary/face_model.hpp"
#include "medial/medial_axis.hpp"

namespace mm::test {

// Exact distances to a face's boundary and inside tests, from a fine
// polyline whose nearest points are refined on the true curves.
class BoundaryProbe {
 public:
  explicit BoundaryProbe(const FaceModel& face);
  double distance_to_boundary(Vec2 p) const { return distance(nearest(p).point, p); }
  BoundaryPlace nearest(Vec2 p) const;
  // Exact within the polylines' chord tolerance of an edge's interior,
  // where their chords could put p on the wrong side.
  bool inside(Vec2 p) const;

 private:
  BoundaryIndex index_;
  double chord_tolerance_;
  std::vector<std::vector<std::pair<BoundaryPlace, Vec2>>> loops_;  // sample places and points
};

// The medial vertices of one kind.
std::vector<const MedialVertex*> of_kind(const MedialAxis& axis, MedialVertexKind kind);

// Every medial point (vertices and edge points) lies inside the face at
// distance r from the boundary, its touching points are at distance r, no
// boundary point is closer; flares sit on convex corners; the axis is one
// connected graph with as many independent cycles as the face has holes.
// Distances are checked to `tolerance` times the face's diagonal, plus the
// geometric tolerance the face was read with.
::testing::AssertionResult medial_axis_is_valid(const FaceModel& face, const MedialAxis& axis, double tolerance);

}  // namespace mm::test
