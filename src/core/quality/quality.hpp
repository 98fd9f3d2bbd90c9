#pragma once
// The quality report of a quad mesh: what an engineer checks before solving.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "meshing/quad_mesh.hpp"
#include "quality/quad_measures.hpp"

namespace mm {

struct IrregularNode {
  int node = -1;
  Vec2 p;
  int elements = 0;  // elements at the node (its valence inside the face)
  int expected = 4;  // 4 inside, the corner's nc on the boundary
};

// One standard measure over a mesh: its least, mean and largest element
// value, and the element where it is worst (least or largest, as the
// measure runs) with that element's centroid.
struct MeasureSummary {
  double min = 0.0;
  double mean = 0.0;
  double max = 0.0;
  int worst_element = -1;
  Vec2 worst_at;
};

// The Verdict measures a report summarises, with which way is better;
// QualityReport::measures holds them in this order.
enum class Measure { ScaledJacobian, Shape, EdgeRatio, AspectRatio, Skew, Taper, Stretch, Condition };
constexpr int kMeasureCount = 8;
struct MeasureInfo {
  const char* name;  // as the JSON names it
  bool higher_is_better;
  double QuadMeasures::*value;
};
const MeasureInfo& measure_info(Measure m);

// An element a user should look at: the ones with the least shape.
struct WorstElement {
  int element = -1;
  Vec2 at;  // centroid
  QuadMeasures measures;
};

// What counts as a poor element, as FEM pre-processors colour them.
constexpr double kPoorShape = 0.3;
constexpr double kNeedleEdgeRatio = 10.0;
constexpr double kStretchedEdgeRatio = 5.0;
constexpr double kPoorScaledJacobian = 0.3;
constexpr int kWorstListed = 10;

struct QualityReport {
  int nodes = 0;
  int quads = 0;
  int triangles = 0;  // always 0: the mesh is all quads
  int inverted = 0;   // elements with a non-positive scaled Jacobian at some corner
  double min_scaled_jacobian = 0.0;
  double mean_scaled_jacobian = 0.0;  // mean over elements of their minimum corner value
  double min_angle = 0.0;             // interior, degrees; an inverted quad shows angles over 180
  double max_angle = 0.0;
  int worst_element = -1;  // the element with the least scaled Jacobian
  double area = 0.0;       // sum of element areas (signed, as meshed)
  // The Verdict measures, in Measure's order (see quad_measures.hpp).
  std::array<MeasureSummary, kMeasureCount> measures{};
  int poor_shape = 0;                        // elements with shape below kPoorShape
  int needles = 0;                           // edge ratio above kNeedleEdgeRatio
  int stretched = 0;                         // edge ratio above kStretchedEdgeRatio
  int poor_scaled_jacobian = 0;              // scaled Jacobian below kPoorScaledJacobian
  std::vector<WorstElement> worst_elements;  // the kWorstListed least shape, worst first
  // Order 2: the least over elements of min/max Jacobian determinant at the
  // 3 x 3 Gauss points with the mid-side nodes where they are (1 at order 1).
  double min_jacobian_ratio = 1.0;
  // Element sizes against the requested size H (when measure_quality was
  // given one): sqrt(area) / H over the elements, and the share of them
  // within [0.5, 1.5].
  double size = 0.0;  // H, 0 when not given
  double min_relative_size = 0.0;
  double mean_relative_size = 0.0;
  double max_relative_size = 0.0;
  double sizes_in_range = 0.0;  // fraction in [0, 1]

  const MeasureSummary& measure(Measure m) const { return measures[static_cast<int>(m)]; }
  double min_shape() const { return measure(Measure::Shape).min; }
  std::vector<IrregularNode> irregular_interior;  // valence other than 4
  std::vector<IrregularNode> irregular_boundary;  // elements other than corner_elements
  std::vector<std::pair<std::string, double>> stage_seconds;
  double seconds = 0.0;
};

// Scaled Jacobian of a quad at its worst corner, in [-1, 1].
double scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// Linear time. stage_seconds and seconds are left for the pipeline to fill.
// size > 0 is the requested element size H, for the size distribution.
// Nodes no quad uses as a corner (order-2 mid-side nodes) have no valence;
// order-2 elements are measured by their corner quads.
// Throws InputError when a quad refers to a missing node or places and nodes differ in number.
QualityReport measure_quality(const QuadMesh& mesh, double size = 0.0);

// The report of several faces meshed together and merged into `merged`
// (merge_face_meshes), from each face's own report (measured in its own
// plane: the element measures are planar). Counts and the area add up, the
// minimum and maximum are the faces' extremes, the mean scaled Jacobian is
// weighted by element count, worst_element numbers the merged elements;
// the Verdict summaries and counts combine the same way, the worst elements
// are the faces' worst (their positions each in its own face's plane).
// Irregular nodes are judged on the merged mesh: a node's elements are
// counted over all faces, and what it should have is the sum of what each
// face wants there (4 inside a face, the corner's nc on its boundary, 2 on a
// smooth boundary point), so a node inside a piece two faces share wants
// 2 + 2 whatever the angle between the faces, and where a vertex of one face
// lies inside another's edge (a T) it wants 2 + nc + nc. A node on the
// outline of the union is listed as a boundary node, any other as interior;
// IrregularNode::node is the merged node and p its position in the plane of
// the first face that has it. stage_seconds and seconds are left to the caller.
QualityReport combine_quality(const std::vector<QualityReport>& faces, const std::vector<const QuadMesh*>& meshes,
                              const MergedMesh& merged);

}  // namespace mm
