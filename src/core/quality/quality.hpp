#pragma once
// The quality report of a quad mesh: what an engineer checks before solving.
#include <string>
#include <utility>
#include <vector>

#include "meshing/quad_mesh.hpp"

namespace mm {

struct IrregularNode {
  int node = -1;
  Vec2 p;
  int elements = 0;  // elements at the node (its valence inside the face)
  int expected = 4;  // 4 inside, the corner's nc on the boundary
};

struct QualityReport {
  int nodes = 0;
  int quads = 0;
  int triangles = 0;  // always 0: the mesh is all quads
  int inverted = 0;   // elements with a non-positive scaled Jacobian at some corner
  double min_scaled_jacobian = 0.0;
  double mean_scaled_jacobian = 0.0;  // mean over elements of their minimum corner value
  double min_angle = 0.0;             // interior, degrees; an inverted quad shows angles over 180
  double max_angle = 0.0;
  int worst_element = -1;                         // the element with the least scaled Jacobian
  double area = 0.0;                              // sum of element areas (signed, as meshed)
  std::vector<IrregularNode> irregular_interior;  // valence other than 4
  std::vector<IrregularNode> irregular_boundary;  // elements other than corner_elements
  std::vector<std::pair<std::string, double>> stage_seconds;
  double seconds = 0.0;
};

// Scaled Jacobian of a quad at its worst corner, in [-1, 1].
double scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// Linear time. stage_seconds and seconds are left for the pipeline to fill.
// Nodes no quad uses as a corner (order-2 mid-side nodes) have no valence;
// order-2 elements are measured by their corner quads.
// Throws InputError when a quad refers to a missing node or places and nodes differ in number.
QualityReport measure_quality(const QuadMesh& mesh);

// The report of several faces meshed together and merged into `merged`
// (merge_face_meshes), from each face's own report (measured in its own
// plane: the element measures are planar). Counts and the area add up, the
// minimum and maximum are the faces' extremes, the mean scaled Jacobian is
// weighted by element count, worst_element numbers the merged elements.
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
