#pragma once
// The orthogonal join of the paper's Fig. 18: a split that ends at a
// concave corner off the corner's cross is cut short where it meets, at a
// right angle, the split that leaves that corner along its cross.
#include "boundary/face_model.hpp"
#include "decomposition/decomposition.hpp"

namespace mm {

// A split (boundary, medial point P, concave corner B) and a split leaving B
// along an arm of B's cross, the block between them with one element at B:
// the split is ended instead at Q, the foot of P on the other split, and the
// triangle B, P, Q goes to the block across the first split, whose outline
// now runs straight through B along the cross. Every block keeps its corner
// types, only the corner at B moves to Q (a T-junction, one element on
// either side, straight through for the third block), so the blocks still
// tile the face and close up. Joins only where that brings the worst corner
// angle at B and P at least 20 degrees nearer its logical size, both new
// pieces are at least a quarter of the old radius and the triangle holds
// nothing else of the block. A split is joined at one end at most. Returns
// the number of joins made; decompose() keeps them only if every block
// passes its checks again.
int join_splits_orthogonally(const FaceModel& face, Decomposition& d);

}  // namespace mm
