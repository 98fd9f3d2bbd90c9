#pragma once
// Block decomposition around the mesh singularities (the paper's section 4).
// Every split is a pair of medial radii (or the radii of a medial vertex), so
// the blocks are the pieces of the medial axis left between the splits, each
// with the part of the face its discs sweep: logically convex polygons that
// hold one floating singularity, and submappable regions everywhere else.
#include <string>
#include <utility>
#include <vector>

#include "boundary/face_model.hpp"
#include "medial/medial_axis.hpp"
#include "singularity/merge.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

struct DecompositionOptions {
  bool merge = true;         // merge close singularities first (sections 4.3 and 4.4)
  MergeTolerance tolerance;  // how close is close
  // Split along every arm of every concave corner's cross, not only where a
  // singularity needs it: smaller blocks, fewer reflex corners in any one
  // (for regions whose submapped placement folds).
  bool split_concave_corners = false;
  // Split along the arms of the corners of every hole that one submapped
  // block runs round (Decomposition::wrapped_holes): the splits frame the
  // hole as a grid frames a rectangular hole (the pipeline's retry of a poor mesh).
  bool frame_wrapped_holes = false;
  // Where the corner rule leaves a side of a submapped block more than 135
  // degrees off its logical direction, type the corners again following the
  // outline's turning (else the lattice folds; off: a fallback).
  bool submap_corners_follow_turning = true;
  // Where a split ends at a concave corner off its cross, beside a split
  // along the cross, end it on that split at a right angle (Fig. 18).
  bool orthogonal_joins = true;
  // The whole face as one polygon block of its corners, with no medial
  // axis: for a face of one loop with no reflex corner and at most 6
  // corners (else a SelfCheckError saying why not), a last resort where
  // the medial decomposition fails its self-check.
  bool whole_face = false;
};

enum class SplitReason {
  Resolve,        // between a singularity and a neighbouring feature (n = 0 or a convex n = 1)
  ConcaveCorner,  // along an arm of a concave corner's cross
  Fix,            // through a singularity that could not float
  Connect,        // makes a multiply connected region simply connected (section 4.6)
};
const char* split_reason_name(SplitReason reason);

// A split: boundary point, medial point, boundary point (or, for a fixed
// medial vertex, one radius from the boundary to the vertex).
struct Split {
  std::vector<Vec2> polyline;
  SplitReason reason = SplitReason::Resolve;
};

// A piece of a block's outline: part of one boundary edge (t_from to t_to,
// in the outline's direction) or a split run forwards or backwards.
struct OutlinePiece {
  int split = -1;  // >= 0: index into Decomposition::splits
  bool reversed = false;
  int loop = -1;  // else this boundary edge
  int edge = -1;
  double t_from = 0.0;
  double t_to = 0.0;
  std::vector<Vec2> points;  // sampled, in the outline's direction
};

// A logical corner: where the outline turns by a multiple of a quarter turn.
// type is the number of elements the block has there: 1 convex, 0 a cusp,
// 3 or 4 reflex (2, straight on, is no corner).
struct BlockCorner {
  Vec2 p;
  int type = 1;
};

struct BlockSide {
  std::vector<OutlinePiece> pieces;
};

enum class BlockKind { Polygon, Submap };

struct Block {
  BlockKind kind = BlockKind::Submap;
  std::vector<BlockCorner> corners;  // counter-clockwise; side i runs from corner i to corner i + 1
  std::vector<BlockSide> sides;      // one side with the whole outline when there is no corner
  std::vector<Vec2> outline;         // closed, counter-clockwise, first point not repeated
  double area = 0.0;
  int singularity = -1;  // index into Decomposition::singularities: the one floating inside
  // Submap: pairs (s, t) of sides running opposite ways where t lies across
  // the block from s (the first side straight into the block from a point of
  // s), and where t lies across something outside the block from s (the
  // first side of the block straight out of it: another block, a hole),
  // which the submap's lattice must keep at least one interval apart.
  std::vector<std::pair<int, int>> facing, facing_outside;
};

// A singularity after merging; fixed ones are corners of blocks, not inside one.
struct DecomposedSingularity {
  Vec2 p;
  int k = 0;
  bool fixed = false;
  std::vector<int> members;  // indices into MeshFlow::singularities
};

struct Decomposition {
  std::vector<Split> splits;
  std::vector<Block> blocks;
  std::vector<DecomposedSingularity> singularities;
  bool fallback = false;  // some singularity could not be given its polygon
  // The process's own blocks did not pass their checks, and these are:
  bool fixed_all = false;       // with every singularity that can be fixed fixed
  bool lenient_typing = false;  // with blocks that do not close up typed by their angles
  // Holes with reflex corners that one submapped block runs round, every
  // corner of the hole on its outline (loop indices): the block's lattice
  // wraps the hole and converges on its corners.
  std::vector<int> wrapped_holes;
  std::vector<std::string> notes;  // what the process had to do, for the user
};

// Decomposes the face. Returns only a decomposition that tiles the face
// (checked: block areas add up to the face's, every block's corner types
// close up with the singularities it holds) and whose submap blocks can be
// submapped (corner types 1 to 3, sides each way balanced by sides the
// opposite way; blocks the mesh flow types otherwise are re-typed by their
// angles); throws SelfCheckError naming the face and the check when neither
// the process nor its fall-backs pass.
Decomposition decompose(const FaceModel& face, const MedialAxis& axis, const MeshFlow& flow,
                        const DecompositionOptions& options);

}  // namespace mm
