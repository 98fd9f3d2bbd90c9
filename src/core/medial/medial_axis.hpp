#pragma once
// The medial axis of a face: the centres of the maximal discs inside it, as a
// graph of vertices and edges, every point with its radius and the boundary
// places its disc touches (the paper's section 1.1).
#include <string>
#include <vector>

#include "boundary/face_model.hpp"
#include "medial/nearest.hpp"

namespace mm {

struct MedialPoint {
  Vec2 p;
  double r = 0.0;
  BoundaryPlace left;   // touching point on the left going from `from` to `to`
  BoundaryPlace right;  // and on the right
};

// Angle between the radii to the two touching points, in [0, pi].
double medial_angle(const MedialPoint& point);

enum class MedialVertexKind {
  Junction,          // the disc touches 3 or more places
  Flare,             // a convex corner: r = 0
  FiniteContact,     // the centre of a circular arc the disc touches along a range
  CurvatureContact,  // the disc's curvature equals the boundary's at one touching point
};
const char* medial_vertex_kind_name(MedialVertexKind kind);

struct MedialVertex {
  Vec2 p;
  double r = 0.0;
  MedialVertexKind kind = MedialVertexKind::Junction;
  std::vector<BoundaryPlace> touches;
  // Finite contact: the angle the touched arc range subtends at the centre
  // (pi for the round end of a slot, 2 pi for a full circle).
  double contact_angle = 0.0;
  std::vector<int> edges;  // incident medial edges
};

// A medial edge from vertex `from` to vertex `to` (both -1 for a closed loop
// with no vertex, such as the axis of an annulus), as points in order.
struct MedialEdge {
  int from = -1;
  int to = -1;
  std::vector<MedialPoint> points;
};

struct MedialAxis {
  std::vector<MedialVertex> vertices;
  std::vector<MedialEdge> edges;
};

// How many times finer the chords of each rebuild of the axis are.
inline constexpr double kChordRefinement = 4.0;

// Builds the axis from a Voronoi diagram of chords of the boundary; if a
// medial disc of the result holds boundary (by more than 1e-7 of the face
// size plus its tolerance: the chords misled the topology near a nearly
// degenerate spot), misses a place it touches by more than 1e-6 of the face
// size plus its tolerance, or the axis is not one connected graph with a
// cycle round each hole, builds it again from chords kChordRefinement times
// finer, at most twice, and keeps the best. Throws SelfCheckError if the
// best still holds boundary or misses a touching place by more than 1e-6 of
// the face size plus its tolerance, or is not one connected graph with a
// cycle round each hole. `fineness` > 1 starts from chords that many times
// finer (turning that many times less): for a later stage that finds the
// axis incomplete (a branch lost where the chords misled the diagram yet
// every point left passes the checks).
MedialAxis compute_medial_axis(const FaceModel& face, double fineness = 1.0);

// The stage's entry point: compute_medial_axis, and where its self-check
// fails on a face with joins taken as smooth that are not tangent, the axis
// of the face with those joins as corners (with_kinks_as_corners). The later
// stages must take `face` from here: its corners are the axis's. Throws the
// first SelfCheckError if both fail.
struct FaceAxis {
  FaceModel face;
  MedialAxis axis;
  std::string note;               // empty, or what was done and why
  bool kinks_as_corners = false;  // built with the face's kinks as corners (a fallback)
};
FaceAxis compute_face_medial_axis(const FaceModel& face);

// How far the boundary reaches into the worst medial disc (vertex or edge
// point): 0 or less for an exact axis.
double medial_axis_violation(const FaceModel& face, const MedialAxis& axis);

}  // namespace mm
