#pragma once
// Which sides of a submapped block face each other (Block::facing and
// facing_outside), for the submap's lattice to keep apart.
#include "decomposition/decomposition.hpp"

namespace mm {

// Fills b.facing and b.facing_outside from its sides and corner types.
void find_facing_sides(Block& b);

}  // namespace mm
