#pragma once
// A block's outline as one ring of pieces, each with the logical corner
// type at its start: the form the decomposition builds blocks from, and
// the orthogonal joins reshape them in.
#include <vector>

#include "decomposition/decomposition.hpp"

namespace mm {

struct BlockRing {
  std::vector<OutlinePiece> pieces;
  std::vector<int> start_type;  // per piece; 2 where no corner
};

BlockRing ring_of(const Block& b);

// Sets the block's corners, sides and outline from the ring: a side starts
// at every piece with a corner (one side holds the whole ring where there
// is none); outline points within tol of the one before are left out.
void set_outline(Block& b, const BlockRing& ring, double tol);

}  // namespace mm
