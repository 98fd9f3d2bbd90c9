#pragma once
// Fills one block with quads: the templates of the paper's Fig. 14
// (midpoint subdivision for 3, 5 and 6 sides, the disc, one- and two-sided
// templates) and submapping (4-sided mapping included).
#include <vector>

#include "meshing/block_shape.hpp"
#include "meshing/quad_mesh.hpp"

namespace mm {

// The block's outline as nodes already in the mesh (on the exact curves and
// splits), counter-clockwise, not closed; corner i sits at nodes[corner_at[i]]
// and corner_at[0] == 0. Side i runs from corner i to corner i + 1, so its
// interval count is the number of outline steps between them.
struct BlockOutline {
  std::vector<int> nodes;
  std::vector<int> corner_at;
};

// Appends the block's interior nodes (places with loop = -1) and its quads
// (counter-clockwise, block_of_quad = block) to the mesh. Interior nodes are
// placed by transfinite interpolation from the outline nodes. With
// regrid_wide_folds, a submapped block whose harmonic layout folds over a
// band of it is placed by Winslow's grid instead where that is better (the
// pipeline's last resort: see MeshingOptions). Throws std::runtime_error
// naming the block when the outline's counts do not satisfy the template's
// conditions.
void fill_block(const BlockShape& shape, const std::vector<int>& params, const BlockOutline& outline, int block,
                QuadMesh& mesh, bool regrid_wide_folds = false);

}  // namespace mm
