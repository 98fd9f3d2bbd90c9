#pragma once
// The boundary model: a planar face as closed loops of exact curves in the
// face's own 2-D coordinates, with its corners classified as in the paper
// (optimal corner type nc, Fig. 6 right).
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "boundary/curve.hpp"

namespace mm {

// Bad input: the message names the face and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A stage's result failed the stage's own check: a bug to report, never a
// result to pass on. The message names the face and the check.
class SelfCheckError : public std::runtime_error {
 public:
  SelfCheckError(const std::string& face, const std::string& check)
      : std::runtime_error(face + ": self-check failed: " + check), check_(check) {}
  // The check alone, without the face's name (for notes on a fallback).
  const std::string& check() const { return check_; }

 private:
  std::string check_;
};

// One edge of a loop, traversed from t_start to t_end (t_end < t_start when
// the loop runs against the curve's direction).
struct BoundaryEdge {
  Curve curve;
  double t_start = 0.0;
  double t_end = 0.0;
  int source_index = 0;  // 1-based edge index in the source face (FreeCAD's EdgeN)
  Vec2 start;            // snapped loop vertices at either end
  Vec2 end;
};

// Closed loop: edge i ends at the vertex where edge i+1 starts. The material
// is always on the left: the outer loop runs counter-clockwise, holes clockwise.
struct Loop {
  std::vector<BoundaryEdge> edges;
};

struct Corner {
  int loop = 0;
  int vertex = 0;  // vertex i is the start of edge i of the loop
  Vec2 position;
  double angle = 0.0;  // interior angle from the curve tangents, radians in [0, 2pi]
  int nc = 2;          // optimal number of elements at the corner
};

// Maps face coordinates back to 3-D: origin + x * x_dir + y * y_dir.
struct Frame {
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> x_dir{1, 0, 0};
  std::array<double, 3> y_dir{0, 1, 0};
  std::array<double, 3> normal{0, 0, 1};
};

struct FaceModel {
  std::string name;
  std::vector<Loop> loops;      // loops[0] is the outer loop
  std::vector<Corner> corners;  // the vertices that are not tangent joins
  double area = 0.0;
  double size = 0.0;       // diagonal of the bounding box
  double tolerance = 0.0;  // geometric tolerance the face was read with
  Frame frame;
  int holes() const { return static_cast<int>(loops.size()) - 1; }
  int euler() const { return 1 - holes(); }
};

// What a reader hands over: loops in any orientation and any order, edges
// chained end to start within the reader's tolerance.
struct RawFace {
  std::string name;
  std::vector<std::vector<BoundaryEdge>> loops;
  double tolerance = 1e-7;
  Frame frame;
};

// Orients and validates the loops, snaps vertices, recognises arcs and lines
// stored as B-splines, and classifies corners. Throws InputError.
FaceModel build_face_model(RawFace raw);

// The face with every join more than 1e-6 rad off tangent a corner, those
// within the 0.5 degrees build_face_model takes as smooth too: the face as
// its curves are, for when taking a kink as smooth misleads a later stage.
FaceModel with_kinks_as_corners(const FaceModel& face);
// The note a stage hands on when `what` (e.g. "the medial axis") failed its
// self-check with `failure` and passed with `kinks` such joins as corners.
std::string kinks_as_corners_note(const std::string& what, const std::string& failure, std::size_t kinks);

// Sum of singularity indices every quad mesh of the face must have
// (Poincare-Hopf): sum over corners of (2 - nc) minus 4 times the Euler characteristic.
int predicted_sum_k(const FaceModel& face);

// Optimal corner type for an interior angle: 0 below 45 degrees, 1 below 135,
// 2 below 225, 3 below 315, else 4.
int optimal_corner_type(double angle);

// Position and unit tangent in the loop's direction of travel.
CurvePoint edge_point(const BoundaryEdge& edge, double t);
Vec2 edge_tangent(const BoundaryEdge& edge, double t);
// The parameter between ta and tb (either order) of the point of the edge
// closest to p, and the distance: the nearest of 64 samples, refined by
// golden section between its neighbours.
std::pair<double, double> closest_param(const BoundaryEdge& edge, double ta, double tb, Vec2 p);
double edge_length(const BoundaryEdge& edge);
// How far the edge strays from its chord between parameters from and to:
// 0 on a line, exact on a circle, elsewhere the farthest of the 7 points
// at eighths of the range (a boundary side's sagitta).
double edge_sagitta(const BoundaryEdge& edge, double from, double to);

// Points along the edge, start and end included, with chordal deviation at
// most chord_tolerance and no more than 15 degrees of turning between points.
std::vector<Vec2> sample_edge(const BoundaryEdge& edge, double chord_tolerance);
// The points of an edge at the given parameters (t_start first, t_end last),
// its ends replaced by the snapped vertices so neighbouring edges share them.
std::vector<Vec2> edge_points(const BoundaryEdge& edge, const std::vector<double>& params);
// The curve parameters of those points, t_start first and t_end last; the
// chords turn by at most max_turn radians (15 degrees by default).
std::vector<double> sample_edge_parameters(const BoundaryEdge& edge, double chord_tolerance,
                                           double max_turn = 15.0 * kPi / 180.0);
// The loop as a closed polyline (first point not repeated at the end).
std::vector<Vec2> sample_loop(const Loop& loop, double chord_tolerance);

double signed_area(const Loop& loop);
// Integral of cross(p - ref, dp) / 2 along the edge's curve from t_from to
// t_to: the area a piece of boundary sweeps seen from ref (Green's theorem).
double edge_area_integral(const BoundaryEdge& edge, double t_from, double t_to, Vec2 ref);

struct Box {
  Vec2 min;
  Vec2 max;
};
Box bounding_box(const FaceModel& face);
// The smallest box round the points (min above max if there are none).
Box bounding_box(const std::vector<Vec2>& points);

std::array<double, 3> to_3d(const Frame& frame, Vec2 p);

}  // namespace mm
