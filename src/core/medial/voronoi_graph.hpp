#pragma once
// The Voronoi diagram of a discretised face boundary, reduced to its part
// inside the face: the topology the exact medial axis is built from.
#include <vector>

#include "boundary/face_model.hpp"

namespace mm {

// One boundary segment of the discretisation: part of edge `edge` of loop
// `loop`, from parameter t0 (point p0) to t1 (point p1), material on its left.
struct BoundarySegment {
  int loop = 0;
  int edge = 0;
  double t0 = 0.0, t1 = 0.0;
  Vec2 p0, p1;
  int previous = 0, next = 0;  // neighbouring segments along the loop
};

// A Voronoi site: the open segment, or one of its end points.
struct Site {
  enum Part { kSegment, kStart, kEnd };
  int segment = 0;
  Part part = kSegment;
};

struct VoronoiVertex {
  Vec2 p;
  double r = 0.0;           // distance to its nearest sites
  std::vector<Site> sites;  // every site whose cell touches the vertex
};

// A straight or parabolic Voronoi edge between two sites, inside the face.
struct VoronoiEdge {
  int from = 0, to = 0;
  Site left, right;
};

struct VoronoiGraph {
  std::vector<BoundarySegment> segments;
  std::vector<VoronoiVertex> vertices;
  std::vector<VoronoiEdge> edges;
};

// Discretises the boundary (chords within chord_tolerance of the curves,
// turning by at most max_turn radians) and keeps the finite primary Voronoi
// edges that lie inside the face.
VoronoiGraph interior_voronoi_graph(const FaceModel& face, double chord_tolerance, double max_turn);

// Position of a site's point (for point sites) or nearest point (segments).
Vec2 site_point(const VoronoiGraph& graph, const Site& site, Vec2 near);

}  // namespace mm
