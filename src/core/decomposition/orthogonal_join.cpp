#include "decomposition/orthogonal_join.hpp"

#include <cmath>
#include <optional>

#include "decomposition/block_ring.hpp"
#include "decomposition/concave_arms.hpp"
#include "decomposition/facing_sides.hpp"
#include "geometry/polygon.hpp"

namespace mm {
namespace {

// Corners, sides and outline again from the ring (area and kind stay), and
// the sides a submapped block's lattice must keep apart.
void rebuild(Block& b, const BlockRing& r, double tol) {
  set_outline(b, r, tol);
  b.facing.clear();
  b.facing_outside.clear();
  if (b.kind == BlockKind::Submap && b.singularity < 0) find_facing_sides(b);
}

// The piece of split `split` running from a to b in the ring, or -1.
int piece_index(const BlockRing& r, int split, Vec2 a, Vec2 b, double tol) {
  for (std::size_t i = 0; i < r.pieces.size(); ++i) {
    const OutlinePiece& p = r.pieces[i];
    if (p.split == split && p.points.size() == 2 && distance(p.points.front(), a) <= tol &&
        distance(p.points.back(), b) <= tol)
      return static_cast<int>(i);
  }
  return -1;
}

// A piece of a split, straight from a to b; `forward` when it runs the
// split's polyline order.
OutlinePiece split_piece(int split, Vec2 a, Vec2 b, bool forward) {
  OutlinePiece p;
  p.split = split;
  p.reversed = !forward;
  p.points = {a, b};
  return p;
}

// Whether direction u leaves the concave corner along an arm of its cross
// (as the decomposition's corner splits do).
bool along_an_arm(const FaceModel& face, const Corner& c, Vec2 u) {
  for (int arm = 1; arm < c.nc; ++arm) {
    if (std::abs(signed_angle(concave_arm(face, c, arm), u)) < 1e-4) return true;
  }
  return false;
}

const Corner* concave_corner_at(const FaceModel& face, Vec2 p, double tol) {
  for (const Corner& c : face.corners) {
    if (c.nc >= 3 && distance(c.position, p) <= tol) return &c;
  }
  return nullptr;
}

// Whether the triangle b, p, q (cut off block z) holds nothing of z but
// its own two sides along the splits: no other outline point inside it or
// on pq (z would be pinched), no outline segment across pq, not z's
// singularity (the decomposer checks its members again after the joins).
bool triangle_is_clear(const Decomposition& d, const Block& z, Vec2 b, Vec2 p, Vec2 q, double tol) {
  const std::vector<Vec2> triangle{b, p, q};
  for (const Vec2 v : z.outline) {
    if (distance(v, b) <= tol || distance(v, p) <= tol) continue;
    if (distance_to_segment(v, p, q) <= tol || (distance_to_polygon(triangle, v) > tol && inside_polygon(triangle, v)))
      return false;
  }
  for (std::size_t i = 0, j = z.outline.size() - 1; i < z.outline.size(); j = i++) {
    if (segments_cross(z.outline[j], z.outline[i], p, q)) return false;
  }
  if (z.singularity >= 0) {
    const Vec2 s = d.singularities[z.singularity].p;
    if (inside_polygon(triangle, s) || distance_to_polygon(triangle, s) <= tol) return false;
  }
  return true;
}

// The interior angle of a counter-clockwise outline at `at`.
double interior_angle(Vec2 before, Vec2 at, Vec2 after) {
  return kPi - signed_angle(at - before, after - at);
}

// A corner of a ring at point v: the points before and after it and its type.
struct RingCorner {
  Vec2 before, after;
  int type = 2;
};

RingCorner ring_corner(const BlockRing& r, Vec2 v, double tol) {
  const std::size_t n = r.pieces.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (distance(r.pieces[i].points.front(), v) > tol) continue;
    const std::vector<Vec2>& previous = r.pieces[(i + n - 1) % n].points;
    return {previous[previous.size() - 2], r.pieces[i].points[1], r.start_type[i]};
  }
  return {v, v, 2};
}

// How far a corner's angle is from its logical one (type times `unit`),
// with point `from` of its neighbours moved to `to`.
double angle_error(const RingCorner& c, Vec2 at, double unit, Vec2 from, Vec2 to, double tol) {
  const Vec2 before = distance(c.before, from) <= tol ? to : c.before;
  const Vec2 after = distance(c.after, from) <= tol ? to : c.after;
  return std::abs(interior_angle(before, at, after) - c.type * unit);
}

struct Join {
  int y = -1, z = -1, w = -1;  // blocks: across the split, between the two splits, across the other split
  int other = -1;              // the split along the cross
  Vec2 b, p, q, m;             // corner, medial point, foot, the other split's next point
};

// The join for split s at its end `at_back`, if one is allowed.
std::optional<Join> find_join(const FaceModel& face, const Decomposition& d, const std::vector<BlockRing>& rings, int s,
                              bool at_back, double tol) {
  const std::vector<Vec2>& line = d.splits[s].polyline;
  if (line.size() != 3) return std::nullopt;
  Join j;
  j.b = at_back ? line[2] : line[0];
  j.p = line[1];
  const Corner* corner = concave_corner_at(face, j.b, tol);
  if (!corner) return std::nullopt;
  // Z: the block whose outline turns at B, with one element there, from
  // this split straight onto a split along the cross (either way round).
  for (std::size_t zi = 0; zi < rings.size() && j.z < 0; ++zi) {
    const BlockRing& r = rings[zi];
    const std::size_t n = r.pieces.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t next = (i + 1) % n;
      const OutlinePiece &a = r.pieces[i], &c = r.pieces[next];
      if (r.start_type[next] != 1 || a.split < 0 || c.split < 0 || a.split == c.split) continue;
      if (distance(a.points.back(), j.b) > tol || distance(c.points.front(), j.b) > tol) continue;
      const bool arrives = a.split == s && distance(a.points.front(), j.p) <= tol;
      const bool leaves = c.split == s && distance(c.points.back(), j.p) <= tol;
      if (arrives == leaves) continue;
      const OutlinePiece& along = arrives ? c : a;
      j.other = along.split;
      j.m = arrives ? along.points.back() : along.points.front();
      j.z = static_cast<int>(zi);
      break;
    }
  }
  if (j.z < 0) return std::nullopt;
  const std::vector<Vec2>& other = d.splits[j.other].polyline;
  const bool b_first = distance(other.front(), j.b) <= tol, b_last = distance(other.back(), j.b) <= tol;
  if (b_first == b_last || distance(b_first ? other[1] : other[other.size() - 2], j.m) > tol) return std::nullopt;
  const double reach = distance(j.b, j.m);
  if (!(reach > tol)) return std::nullopt;
  const Vec2 u = (j.m - j.b) / reach;
  if (!along_an_arm(face, *corner, u)) return std::nullopt;
  const double along = dot(j.p - j.b, u);
  j.q = j.b + along * u;
  // Both new pieces a fair part of the radius, the foot well inside the
  // other split's first piece: no needle of an element either side.
  const double radius = distance(j.b, j.p);
  if (along < 0.25 * radius || distance(j.p, j.q) < 0.25 * radius || along > 0.9 * reach) return std::nullopt;
  // Y across this split, W across the other, each walking the piece at B
  // the other way round; three different blocks.
  for (std::size_t k = 0; k < rings.size(); ++k) {
    if (static_cast<int>(k) == j.z) continue;
    if (piece_index(rings[k], s, j.b, j.p, tol) >= 0 || piece_index(rings[k], s, j.p, j.b, tol) >= 0)
      j.y = static_cast<int>(k);
    if (piece_index(rings[k], j.other, j.b, j.m, tol) >= 0 || piece_index(rings[k], j.other, j.m, j.b, tol) >= 0)
      j.w = static_cast<int>(k);
  }
  if (j.y < 0 || j.w < 0 || j.y == j.w) return std::nullopt;
  // Y has one element at B too: with the triangle its outline runs straight
  // through B, and its corner moves to Q.
  const BlockRing& y = rings[j.y];
  const int leaving = piece_index(y, s, j.b, j.p, tol);
  const int arriving = piece_index(y, s, j.p, j.b, tol);
  const int at_b = leaving >= 0 ? leaving : (arriving + 1) % static_cast<int>(y.pieces.size());
  if (y.start_type[at_b] != 1) return std::nullopt;
  // Made only where it brings the worst of the corners of Y and Z at B and
  // P at least 20 degrees nearer its logical angle (the new corners at Q
  // are exact; Y must run straight through B). A smaller gain is not worth
  // it: the interval counts shift across the face and the minimum quality
  // moves either way by as much.
  const double spacing = corner->angle / corner->nc, quarter = 0.5 * kPi;
  const RingCorner y_b = ring_corner(y, j.b, tol), z_b = ring_corner(rings[j.z], j.b, tol);
  const RingCorner y_p = ring_corner(y, j.p, tol), z_p = ring_corner(rings[j.z], j.p, tol);
  const double before =
      std::max({angle_error(y_b, j.b, spacing, j.b, j.b, tol), angle_error(z_b, j.b, spacing, j.b, j.b, tol),
                angle_error(y_p, j.p, quarter, j.b, j.b, tol), angle_error(z_p, j.p, quarter, j.b, j.b, tol)});
  RingCorner y_straight = y_b;
  y_straight.type = 2;
  const double after =
      std::max({angle_error(y_straight, j.b, spacing, j.p, j.q, tol), angle_error(y_p, j.p, quarter, j.b, j.q, tol),
                angle_error(z_p, j.p, quarter, j.b, j.q, tol)});
  if (!(after < before - 0.35)) return std::nullopt;
  if (!triangle_is_clear(d, d.blocks[j.z], j.b, j.p, j.q, tol)) return std::nullopt;
  return j;
}

// Moves end B of a two-point piece to Q.
void move_end(OutlinePiece& piece, Vec2 b, Vec2 q, double tol) {
  for (Vec2& p : piece.points)
    if (distance(p, b) <= tol) p = q;
}

void apply(Decomposition& d, std::vector<BlockRing>& rings, int s, bool at_back, const Join& j, double tol) {
  std::vector<Vec2>& line = d.splits[s].polyline;
  (at_back ? line.back() : line.front()) = j.q;
  std::vector<Vec2>& other = d.splits[j.other].polyline;
  const bool b_first = distance(other.front(), j.b) <= tol;
  other.insert(b_first ? other.begin() + 1 : other.end() - 1, j.q);
  // B to Q runs the other split forwards when B is its first point.
  const auto piece_bq = [&](bool from_b) {
    return from_b ? split_piece(j.other, j.b, j.q, b_first) : split_piece(j.other, j.q, j.b, !b_first);
  };
  const auto piece_qm = [&](bool from_q) {
    return from_q ? split_piece(j.other, j.q, j.m, b_first) : split_piece(j.other, j.m, j.q, !b_first);
  };

  // Z: both pieces at B (of this split and the other) end at Q instead; the
  // corner (type 1) goes with them.
  for (OutlinePiece& piece : rings[j.z].pieces) {
    if (piece.split == s || piece.split == j.other) move_end(piece, j.b, j.q, tol);
  }

  // Y: B is straight on now (its corner type 1 + the triangle's 1 = 2), a
  // corner of type 1 at Q between the other split and this one.
  BlockRing& y = rings[j.y];
  if (const int i = piece_index(y, s, j.b, j.p, tol); i >= 0) {
    move_end(y.pieces[i], j.b, j.q, tol);  // its start, type 1, is Q now
    y.pieces.insert(y.pieces.begin() + i, piece_bq(true));
    y.start_type.insert(y.start_type.begin() + i, 2);
  } else {
    const int k = piece_index(y, s, j.p, j.b, tol);
    move_end(y.pieces[k], j.b, j.q, tol);
    const int next = (k + 1) % static_cast<int>(y.pieces.size());
    y.start_type[next] = 2;
    y.pieces.insert(y.pieces.begin() + k + 1, piece_bq(false));
    y.start_type.insert(y.start_type.begin() + k + 1, 1);
  }

  // W: the other split's piece at B in two, straight on at Q.
  BlockRing& w = rings[j.w];
  if (const int i = piece_index(w, j.other, j.b, j.m, tol); i >= 0) {
    w.pieces[i] = piece_qm(true);
    w.pieces.insert(w.pieces.begin() + i, piece_bq(true));
    w.start_type.insert(w.start_type.begin() + i + 1, 2);
  } else {
    const int k = piece_index(w, j.other, j.m, j.b, tol);
    w.pieces[k] = piece_qm(false);
    w.pieces.insert(w.pieces.begin() + k + 1, piece_bq(false));
    w.start_type.insert(w.start_type.begin() + k + 1, 2);
  }

  const double triangle = 0.5 * std::abs(cross(j.p - j.b, j.q - j.b));
  d.blocks[j.y].area += triangle;
  d.blocks[j.z].area -= triangle;
  for (const int b : {j.y, j.z, j.w}) rebuild(d.blocks[b], rings[b], tol);
}

}  // namespace

int join_splits_orthogonally(const FaceModel& face, Decomposition& d) {
  const double tol = 1e-9 * face.size;  // as the decomposer's: split ends are its boundary points exactly
  std::vector<BlockRing> rings;
  for (const Block& b : d.blocks) rings.push_back(ring_of(b));
  int joins = 0;
  for (std::size_t s = 0; s < d.splits.size(); ++s) {
    for (const bool at_back : {true, false}) {
      if (const auto join = find_join(face, d, rings, static_cast<int>(s), at_back, tol)) {
        apply(d, rings, static_cast<int>(s), at_back, *join, tol);
        ++joins;
        break;
      }
    }
  }
  return joins;
}

}  // namespace mm
