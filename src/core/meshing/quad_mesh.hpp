#pragma once
// The quad mesh every meshing stage hands on: plain arrays of nodes and
// elements in the face's own 2-D coordinates, with what each boundary node
// knows about the exact curve it lies on.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "geometry/vec2.hpp"

namespace mm {

// Where a node lies: on a boundary edge (loop >= 0) at curve parameter t, or
// inside the face (loop < 0). corner_elements is the number of elements the
// theory wants at the node (the corner's nc, 2 on a smooth boundary point),
// 0 for interior nodes.
struct NodePlace {
  int loop = -1;
  int edge = -1;
  double t = 0.0;
  bool face_corner = false;  // a vertex of the face: never moves
  int corner_elements = 0;
};

struct QuadMesh {
  std::vector<Vec2> nodes;
  std::vector<NodePlace> places;            // one per node
  std::vector<std::array<int, 4>> quads;    // corner nodes, counter-clockwise
  std::vector<std::array<int, 4>> midside;  // order 2 only: node on side i (corner i to i + 1)
  std::vector<int> block_of_quad;           // the decomposition block each quad came from
  int order() const { return midside.empty() ? 1 : 2; }
};

// Scaled Jacobian of quad q at its worst corner, in [-1, 1]; a collapsed side
// counts as -1. The meshing stages judge their own placements by it.
inline double worst_corner_jacobian(const QuadMesh& mesh, const std::array<int, 4>& q) {
  double worst = 1.0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 p = mesh.nodes[q[i]];
    const Vec2 next = mesh.nodes[q[(i + 1) % 4]] - p;
    const Vec2 prev = mesh.nodes[q[(i + 3) % 4]] - p;
    const double lengths = std::sqrt(dot(next, next) * dot(prev, prev));
    worst = std::min(worst, lengths > 0.0 ? cross(next, prev) / lengths : -1.0);
  }
  return worst;
}

// Several faces' meshes as one mesh in 3-D (a single face's too): each
// node once, the nodes along the pieces of boundary the faces share merged.
struct MergedMesh {
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<int, 4>> quads;       // counter-clockwise seen from their face's normal
  std::vector<std::array<int, 4>> midside;     // order 2 only, as in QuadMesh
  std::vector<int> face_of_quad;               // index into the faces meshed
  std::vector<int> block_of_quad;              // the block within its face
  std::vector<bool> on_boundary;               // on an element side no other element has: the union's outline
  std::vector<std::vector<int>> node_of;       // per face: its own mesh's node -> merged node
  std::vector<std::array<double, 3>> normals;  // per face: x_dir x y_dir of its frame
  int order() const { return midside.empty() ? 1 : 2; }
};

}  // namespace mm
