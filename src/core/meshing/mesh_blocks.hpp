#pragma once
// Block meshing: the decomposition's blocks filled with quads that conform
// across every split. One interval assignment for the whole face, nodes on
// the exact curves, the templates, smoothing, and mid-side nodes for order 2.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "boundary/face_model.hpp"
#include "decomposition/decomposition.hpp"
#include "meshing/quad_mesh.hpp"
#include "support/progress.hpp"

namespace mm {

struct MeshingOptions {
  double size = 0.0;  // target element size, face units (> 0)
  int order = 1;      // 1: 4-node quads, 2: 8-node quads
  bool smooth = true;
  // Untangling reaches 24 rings of elements round a fold, not 8: the
  // pipeline's last resort (a fold in a fine mesh spans more elements).
  bool wide_untangling = false;
  // A submapped block whose harmonic layout folds over a band of it (a
  // lattice wrapped half round a hole, the fold widening as the elements
  // shrink) is placed by Winslow's elliptic grid where that is better: the
  // pipeline's very last resort, as smoothing untangles most such folds
  // into better meshes.
  bool regrid_wide_folds = false;
  // How far a boundary side's chord may lie off its curve, as a fraction of
  // the size: the mesh check fails a mesh whose sides stray further (it
  // would leave the face or miss part of it there), and every boundary
  // piece gets the intervals that keep its sides within half of this
  // (smoothing then slides boundary nodes along their curves, unevenly).
  double max_sagitta = 0.2;
  // Told each stage and block as meshing goes, and asked whether to stop
  // (support/progress.hpp); nullptr: nobody is watching.
  Progress* progress = nullptr;
};

struct BlockMesh {
  QuadMesh mesh;
  std::vector<int> segment_counts;  // intervals per segment, for the report
  std::vector<std::string> notes;
  bool coarser_than_asked = false;  // under 0.4 of area / H^2 elements (a note says so)
  std::vector<std::pair<std::string, double>> stage_seconds;
};

// Meshes every block of the decomposition. When no interval counts satisfy the
// blocks' templates, polygon blocks' corners that are valence-3 points on a
// neighbour's side are taken as flat and the assignment retried (a note says
// so); smoothing slides boundary nodes along their curves within the
// turning interval assignment allowed, and when that leaves a folded or poor
// element (scaled Jacobian under 0.3), runs again up to 4 times without the
// turning bound, keeping the best mesh; an interior node in only
// two elements (blocks' corners at a split's bend adding up to two) has the
// two joined into one, with a note. Throws InputError for a
// size that is not a positive number or an order other than 1 or 2, and
// SelfCheckError naming the face when the mesh fails its own checks: conformity
// (every inner edge in two quads, every outer one on the boundary), no inverted
// element (the worst one named), area equal to that of the polygon of the
// boundary nodes (the face's less the exact areas between the boundary
// intervals' chords and curves).
BlockMesh mesh_blocks(const FaceModel& face, const Decomposition& decomposition, const MeshingOptions& options);

// A piece of boundary two faces meshed together share: the same 3-D curve
// between the same two points, with the same nodes (one stretch, see below).
struct SharedPiece {
  int face_a = -1;  // the face that placed the nodes
  int face_b = -1;
  int edge_a = 0;  // the piece's edge in each face, 1-based source numbers (FreeCAD's EdgeN)
  int edge_b = 0;
  std::array<int, 2> loop_edge_a{};  // the same edges as (loop, edge) of each face's model
  std::array<int, 2> loop_edge_b{};
  std::vector<int> nodes_a;  // the piece's nodes in face_a's mesh, ends included
  std::vector<int> nodes_b;  // their partners in face_b's mesh, in the same order
};

// The edges shared: distinct pairs of a face's edge and another face's edge
// that have a piece in common (an edge cut by splits or T-junctions into
// several pieces counts once per partner edge).
int shared_edge_count(const std::vector<SharedPiece>& shared);

struct FaceSetBlockMesh {
  std::vector<BlockMesh> faces;
  std::vector<SharedPiece> shared;
  // How far apart points may be and still be one: ten times the largest
  // tolerance the faces were read with, at least 1e-5 of a face's diagonal,
  // at most a twentieth of the element size.
  double tolerance = 0.0;
};

// Meshes several faces so that the pieces of boundary they share in 3-D get
// the same nodes. Every edge is first cut where another face's loop vertex
// lies on it (a T-junction); the parts of edges between such points
// ("stretches") of two faces that coincide in 3-D (ends and middles within
// the tolerance, through the faces' frames) are shared. Each face keeps its
// own segments (its splits' ends), so other faces' splits do not cut it into
// more pieces that each need an interval; one interval assignment for all
// faces makes a shared stretch's segments sum alike in every face. The
// face whose stretch holds the most segments (split ends) places its nodes
// by arc length segment by segment; every other face moves its own split
// ends on the stretch along the edge to the nodes its counts reach, and
// puts its other nodes on its own curve nearest to the placing face's.
// Each face's mesh is then finished and checked as mesh_blocks'.
// Throws as mesh_blocks; when the faces' blocks cannot be given counts
// together, the SelfCheckError names all the faces.
FaceSetBlockMesh mesh_blocks_together(const std::vector<FaceModel>& faces,
                                      const std::vector<Decomposition>& decompositions, const MeshingOptions& options);

}  // namespace mm
