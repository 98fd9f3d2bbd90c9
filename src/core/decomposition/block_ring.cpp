#include "decomposition/block_ring.hpp"

namespace mm {

BlockRing ring_of(const Block& b) {
  BlockRing r;
  for (std::size_t s = 0; s < b.sides.size(); ++s) {
    for (std::size_t k = 0; k < b.sides[s].pieces.size(); ++k) {
      r.pieces.push_back(b.sides[s].pieces[k]);
      r.start_type.push_back(k == 0 && s < b.corners.size() ? b.corners[s].type : 2);
    }
  }
  return r;
}

void set_outline(Block& b, const BlockRing& ring, double tol) {
  b.corners.clear();
  b.sides.clear();
  b.outline.clear();
  const std::size_t count = ring.pieces.size();
  std::size_t first = 0;
  while (first < count && ring.start_type[first] == 2) ++first;
  if (first == count) first = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = (first + k) % count;
    const OutlinePiece& piece = ring.pieces[i];
    if (ring.start_type[i] != 2) {
      b.corners.push_back({piece.points.front(), ring.start_type[i]});
      b.sides.emplace_back();
    }
    if (b.sides.empty()) b.sides.emplace_back();
    b.sides.back().pieces.push_back(piece);
    for (std::size_t j = 0; j + 1 < piece.points.size(); ++j) {
      if (b.outline.empty() || distance(b.outline.back(), piece.points[j]) > tol) b.outline.push_back(piece.points[j]);
    }
  }
}

}  // namespace mm
