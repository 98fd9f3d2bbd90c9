#include "decomposition/decomposition.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "decomposition/block_ring.hpp"
#include "decomposition/concave_arms.hpp"
#include "decomposition/facing_sides.hpp"
#include "decomposition/orthogonal_join.hpp"
#include "geometry/polygon.hpp"
#include "medial/nearest.hpp"

// How the decomposition works.
//
// Every split is a pair of medial radii: the radii of a medial point on an
// edge (an edge cut), or all the radii of a fixed junction (a vertex cut).
// Radii of different medial points never cross, so cutting the medial axis
// at some places cuts the face into blocks: each block is one piece of the
// axis with the part of the face its discs sweep, and the outline of a block
// is found by walking round its piece of axis with the boundary on the right.
//
// Every logical corner of a block is read from the mesh flow, never from a
// measured angle: the bend of a split at its medial point has 2 - q or 2 + q
// elements (q the signed flow type there, on the side the disc shrinks to or
// the other), a split meeting a smooth edge makes two corners of one element,
// and at a concave corner each block gets the arms of the corner's cross
// between its two sides. These are the numbers the flux balance summed, so
// the corners of every block close up by the same telescoping sum that gave
// Poincare-Hopf: sum(2 - type) = 4 + (sum of k inside). decompose() checks it.
//
// The process is the paper's section 4.2: each singularity explores the axis
// until it meets a neighbouring feature; a neighbour that would leave the
// block not logically convex is resolved by the best permitted split on the
// way (n = 0 first, then a convex n = 1, medial angle nearest the ideal), or
// by a concave corner's split along its cross, or else by fixing a
// singularity (a cut through it). Blocks that still fail (more than one
// singularity, a reflex corner, a hole) get their singularity fixed, and
// multiply connected regions are cut where the flow is straightest.
namespace mm {

namespace {

// A block that fails its self-check (the message names the check): the
// process tries once more before it gives up with a SelfCheckError.
struct SelfCheckFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Cut {
  int edge = -1;  // an edge cut at position s (point index plus fraction)...
  double s = 0.0;
  int vertex = -1;      // ...or a vertex cut (a fixed junction)
  double origin = 0.0;  // s where it was placed, before refinement
  MedialPoint point;
  PointFlow behind, ahead;  // the flow just before and after s along the edge
  SplitReason reason = SplitReason::Resolve;
  std::vector<int> splits;     // indices into the output's splits
  std::vector<double> covers;  // further positions of fixed members whose split is this one
};

// Where a singularity of the mesh flow sits on the medial axis.
struct Location {
  int edge = -1;
  double s = 0.0;
  int vertex = -1;
};

// A singularity after merging, with the places of its members.
struct Unit {
  int k = 0;
  Vec2 p;
  std::vector<int> members;
  bool fixed = false;
};

// A split the concave corner's cross allows (Fig. 17): from the corner along
// arm `arm` to the medial axis, and on along the other radius there.
struct ConcavePoint {
  int corner = -1;
  int arm = 0;
  int edge = -1;
  double s = 0.0;
  MedialPoint point;
  bool corner_on_left = true;
  PointFlow flow;
};

struct End {
  int edge = 0;
  bool at_start = true;
  double angle = 0.0;
};

struct Step {
  int edge = 0;
  double from = 0.0, to = 0.0;
  bool forward() const { return to > from; }
};

enum class FeatureKind { Unit, SharpCorner, ConcaveSplit };

struct Neighbour {
  FeatureKind kind;
  int id = -1;
  std::vector<Step> path;  // from the exploring unit to the feature
};

// One item of a block outline as walked: a range of one loop or a split
// through a medial point (or a fixed vertex) between two boundary places.
struct Item {
  bool split = false;
  // range: forward along the loop from `a` to `b`, the whole loop if full
  BoundaryPlace a, b;
  bool full = false;
  // How far along the loop, in loop positions (negative where the touches
  // wobble back); none: from a and b alone.
  std::optional<double> advance;
  // split: boundary place a -> interior point -> boundary place b
  Vec2 middle;
  int bend = 2;             // elements at the interior point
  int virtual_corners = 0;  // range: convex corners of a singularity fixed onto it
  int arm_a = 1, arm_b = 1;
  int split_a = -1, split_b = -1;  // the splits the two halves lie on
  bool reversed_a = false, reversed_b = false;
};

struct Outline {
  std::vector<Item> items;
  int component = -1;
};

// Which count a piece of a block's outline carries: its own, or for a split
// piece the one of that stretch of the split, which a block lying on both of
// its sides (a split that opens a ring) walks twice, once each way.
using CountKey = std::tuple<int, double, double, double, double>;
CountKey count_key(const OutlinePiece& piece, int index) {
  if (piece.split < 0 || piece.points.empty()) return {-1 - index, 0.0, 0.0, 0.0, 0.0};
  Vec2 a = piece.points.front(), b = piece.points.back();
  if (std::tie(b.x, b.y) < std::tie(a.x, a.y)) std::swap(a, b);
  return {piece.split, a.x, a.y, b.x, b.y};
}

// Per piece: whether the block walks its count twice (see count_key). Both
// walks carry one count, so where they run opposite ways they balance each
// other and nothing else; they cannot stand in for another side's opposite.
std::vector<bool> twin_splits(const std::vector<OutlinePiece>& pieces) {
  std::map<CountKey, int> uses;
  for (std::size_t i = 0; i < pieces.size(); ++i) ++uses[count_key(pieces[i], static_cast<int>(i))];
  std::vector<bool> twin;
  for (std::size_t i = 0; i < pieces.size(); ++i) twin.push_back(uses[count_key(pieces[i], static_cast<int>(i))] > 1);
  return twin;
}

// Whether submapping can mesh a block with these types at its piece starts
// (2 where no corner): only convex, flat and reflex corners, and every
// direction its sides run in has sides running the opposite way, or their
// counts would have to be 0 (the two sides of one split left out: see
// twin_splits).
bool submappable(const std::vector<int>& types, const std::vector<bool>& twin) {
  int direction = 0;
  bool used[4] = {false, false, false, false};
  for (std::size_t i = 0; i < types.size(); ++i) {
    if (types[i] < 1 || types[i] > 3) return false;
    direction = ((direction + 2 - types[i]) % 4 + 4) % 4;
    if (!twin[i]) used[direction] = true;
  }
  return used[0] == used[2] && used[1] == used[3];
}

// Whether the sides' counts can balance for this typing with every count at
// least 1: along each axis, the net number of times each count (count_key)
// runs forward must be all zero or take both signs. Catches the two walks of
// one split that do not run opposite ways.
bool counts_can_balance(const std::vector<OutlinePiece>& pieces, const std::vector<int>& types) {
  std::map<CountKey, std::array<int, 2>> net;  // per count: net times forward along x, y
  int direction = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    direction = ((direction + 2 - types[i]) % 4 + 4) % 4;
    net[count_key(pieces[i], static_cast<int>(i))][direction % 2] += direction < 2 ? 1 : -1;
  }
  for (int axis = 0; axis < 2; ++axis) {
    bool positive = false, negative = false;
    for (const auto& [key, along] : net) positive |= along[axis] > 0, negative |= along[axis] < 0;
    if (positive != negative) return false;
  }
  return true;
}

// The interior angle of an outline at the start of piece i, in quarter turns
// (0 a cusp, 2 straight on, 4 a slit); `type` says which way a reversal goes.
double interior_quarters(const std::vector<const OutlinePiece*>& pieces, std::size_t i, int type, double tol) {
  const OutlinePiece& before = *pieces[(i + pieces.size() - 1) % pieces.size()];
  const OutlinePiece& after = *pieces[i];
  Vec2 in{0, 0}, out{0, 0};
  for (std::size_t k = before.points.size(); k-- > 1 && norm(in) <= tol;)
    in = before.points.back() - before.points[k - 1];
  for (std::size_t k = 1; k < after.points.size() && norm(out) <= tol; ++k)
    out = after.points[k] - after.points.front();
  if (norm(in) <= tol || norm(out) <= tol) return type;
  double turn = std::atan2(cross(in, out), dot(in, out));
  if (std::abs(turn) > 0.9 * M_PI) turn = type < 2 ? std::abs(turn) : -std::abs(turn);
  return 2.0 - turn / (0.5 * M_PI);
}

// How far a piece's sampled points turn along it, in quarter turns (left
// positive).
double piece_quarters(const OutlinePiece& piece, double tol) {
  double turn = 0.0;
  Vec2 last{0, 0};
  for (std::size_t k = 1; k < piece.points.size(); ++k) {
    const Vec2 d = piece.points[k] - piece.points[k - 1];
    if (norm(d) <= tol) continue;
    if (norm(last) > 0.0) turn += std::atan2(cross(last, d), dot(last, d));
    last = d;
  }
  return turn / (0.5 * M_PI);
}

// The interior angle at every piece start (interior_quarters), reversals
// turned the way `types` says.
std::vector<double> interior_angles(const std::vector<OutlinePiece>& pieces, const std::vector<int>& types,
                                    double tol) {
  std::vector<const OutlinePiece*> refs;
  for (const OutlinePiece& piece : pieces) refs.push_back(&piece);
  std::vector<double> angles;
  for (std::size_t i = 0; i < pieces.size(); ++i) angles.push_back(interior_quarters(refs, i, types[i], tol));
  return angles;
}

// The outline's direction at the middle of each piece, in quarter turns
// from the middle of the last piece (whose logical direction is 0): the
// interior angles at the piece starts and the pieces' own turning.
std::vector<double> middle_directions(const std::vector<OutlinePiece>& pieces, const std::vector<double>& angles,
                                      double tol) {
  const std::size_t n = pieces.size();
  std::vector<double> middles(n);
  double direction = 0.5 * piece_quarters(pieces[n - 1], tol);
  for (std::size_t i = 0; i < n; ++i) {
    const double along = piece_quarters(pieces[i], tol);
    direction += 2.0 - angles[i] + 0.5 * along;
    middles[i] = direction;
    direction += 0.5 * along;
  }
  return middles;
}

// The largest difference between a piece's logical direction under a typing
// and its own (middle_directions), in quarter turns.
double largest_turning_gap(const std::vector<OutlinePiece>& pieces, const std::vector<int>& typing, double tol) {
  const std::vector<double> middles = middle_directions(pieces, interior_angles(pieces, typing, tol), tol);
  double gap = 0.0;
  int turning = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    turning += 2 - typing[i];
    gap = std::max(gap, std::abs(turning - middles[i]));
  }
  return gap;
}

// Types 1..3 at the piece starts of an outline that turns 4 quarter turns
// and submaps, fewest changes from `types` first, then nearest the interior
// angles (the paper's corner rule, Fig. 6: nc by the corner's angle): a
// dynamic program over the piece starts with the turning so far and the
// directions used. Empty when no typing submaps. Following the turning, a
// piece whose logical direction is more than half a quarter turn off its
// own costs as much as a change per quarter turn.
std::vector<int> submap_typing(const std::vector<OutlinePiece>& pieces, const std::vector<int>& types, double tol,
                               bool follow_turning) {
  const int n = static_cast<int>(types.size());
  if (n < 4) return {};  // four convex corners at least
  const std::vector<bool> twin = twin_splits(pieces);
  const std::vector<double> angles = interior_angles(pieces, types, tol);
  const std::vector<double> middles = middle_directions(pieces, angles, tol);
  // State: turning so far (offset by n) and the directions used (4 bits).
  const int width = 2 * n + 1;
  const double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> cost(n + 1, std::vector<double>(width * 16, kInf));
  std::vector<std::vector<int>> from(n + 1, std::vector<int>(width * 16, -1));
  cost[0][n * 16] = 0.0;
  for (int i = 0; i < n; ++i) {
    const double angle = angles[i];
    const OutlinePiece& before = pieces[(i + n - 1) % n];
    const bool inside_edge = before.split < 0 && pieces[i].split < 0 && before.loop >= 0 &&
                             before.loop == pieces[i].loop && before.edge == pieces[i].edge;
    for (int state = 0; state < width * 16; ++state) {
      if (cost[i][state] == kInf) continue;
      const int turning = state / 16 - n, used = state % 16;
      for (int type = 1; type <= 3; ++type) {
        // A convex corner inside one boundary edge where it runs straight
        // (or turns in) gives its element an angle of 180 degrees or more:
        // its neighbours along the edge cannot leave it.
        if (type == 1 && inside_edge && angle > 2.0 - 1e-3) continue;
        const int next_turning = turning + 2 - type;
        if (next_turning < -n || next_turning > n) continue;
        const int direction = ((next_turning % 4) + 4) % 4;
        const int next = (next_turning + n) * 16 + (twin[i] ? used : used | (1 << direction));
        const double off = follow_turning ? std::max(0.0, std::abs(next_turning - middles[i]) - 0.5) : 0.0;
        const double c = cost[i][state] + (type != types[i] ? 10.0 : 0.0) + std::abs(angle - type) + 10.0 * off;
        if (c < cost[i + 1][next]) {
          cost[i + 1][next] = c;
          from[i + 1][next] = state * 4 + type;
        }
      }
    }
  }
  int best = -1;
  for (int used = 0; used < 16; ++used) {
    const bool balanced = ((used & 1) != 0) == ((used & 4) != 0) && ((used & 2) != 0) == ((used & 8) != 0);
    const int state = (4 + n) * 16 + used;
    if (balanced && cost[n][state] < kInf && (best < 0 || cost[n][state] < cost[n][best])) best = state;
  }
  if (best < 0) return {};
  std::vector<int> typing(n);
  for (int i = n, state = best; i > 0; --i) {
    typing[i - 1] = from[i][state] % 4;
    state = from[i][state] / 4;
  }
  if (!counts_can_balance(pieces, typing)) return {};
  return typing;
}

// An interior angle (in quarter turns: 157.5 degrees) over which a convex
// corner's one element is poor (scaled Jacobian under 0.38), nearer 0 as
// the elements shrink along a smooth curve: the outline runs nearly straight on.
constexpr double kFlat = 1.75;
// Fillet sectors cut off one block at most (each cut is checked again), and
// cuts across sides wrapped round a hole.
constexpr int kMaxSectorsABlock = 16;
// A side of a submapped block turning in by this many quarter turns or more
// with no corner wraps the block round a hole or bay (135 degrees); by
// kRound or more it goes all round a hole (a ring opened by one cut).
constexpr double kWrapped = 1.5;
// A split ending closer than this fraction of the face's size to a tangent
// join ends on the join (snap_to_smooth_joins).
constexpr double kSnapToJoin = 1e-5;
constexpr double kRound = 3.5;
// Samples along each part of a boundary piece that such a cut ends on.
constexpr int kCutPieceSamples = 16;

// The part of a boundary piece between parameters `from` and `to`, sampled
// at `samples` equal steps; where it starts or ends with the piece it keeps
// the piece's own end point (the outlines meet there exactly).
OutlinePiece piece_part(const FaceModel& face, const OutlinePiece& piece, double from, double to, int samples) {
  const BoundaryEdge& e = face.loops[piece.loop].edges[piece.edge];
  OutlinePiece part = piece;
  part.t_from = from;
  part.t_to = to;
  part.points = {from == piece.t_from ? piece.points.front() : edge_point(e, from).p};
  for (int k = 1; k < samples; ++k) part.points.push_back(edge_point(e, from + (to - from) * k / samples).p);
  part.points.push_back(to == piece.t_to ? piece.points.back() : edge_point(e, to).p);
  return part;
}

// An outline's centroid, if it lies inside the outline.
std::optional<Vec2> centroid_inside(const std::vector<Vec2>& outline) {
  Vec2 centroid{0, 0};
  double area = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec2 p = outline[i], q = outline[(i + 1) % outline.size()];
    const double a = cross(p, q);
    area += a;
    centroid = centroid + (p + q) * a;
  }
  if (!(std::abs(area) > 0.0)) return std::nullopt;
  centroid = centroid / (3.0 * area);
  if (!inside_polygon(outline, centroid)) return std::nullopt;
  return centroid;
}

// A boundary piece cut into `parts` equal ranges of its parameter.
std::vector<OutlinePiece> parts_of(const FaceModel& face, const OutlinePiece& piece, int parts) {
  const int samples = std::max(2, static_cast<int>(piece.points.size()) / parts);
  const double span = piece.t_to - piece.t_from;
  std::vector<OutlinePiece> result;
  for (int p = 0; p < parts; ++p) {
    const double from = piece.t_from + span * p / parts;
    const double to = p + 1 == parts ? piece.t_to : piece.t_from + span * (p + 1) / parts;
    result.push_back(piece_part(face, piece, from, to, samples));
  }
  return result;
}

// A block outline as pieces with their corner types (2 where no corner)
// and, per piece, whether it starts at a cut made in a boundary piece.
struct TypedPieces {
  std::vector<OutlinePiece> pieces;
  std::vector<int> types;
  std::vector<bool> cut;
};

// Each boundary piece cut into parts(piece) equal parameter ranges; splits
// and pieces of no length stay whole.
template <class Parts>
TypedPieces cut_pieces(const FaceModel& face, const TypedPieces& outline, Parts parts) {
  TypedPieces finer;
  for (std::size_t i = 0; i < outline.pieces.size(); ++i) {
    const OutlinePiece& piece = outline.pieces[i];
    const int n = piece.split >= 0 || piece.loop < 0 || std::abs(piece.t_to - piece.t_from) <= 0.0 ? 1 : parts(piece);
    if (n <= 1) {
      finer.pieces.push_back(piece);
      finer.types.push_back(outline.types[i]);
      finer.cut.push_back(outline.cut[i]);
      continue;
    }
    const std::vector<OutlinePiece> split = parts_of(face, piece, n);
    for (std::size_t p = 0; p < split.size(); ++p) {
      finer.pieces.push_back(split[p]);
      finer.types.push_back(p == 0 ? outline.types[i] : 2);
      finer.cut.push_back(p == 0 ? outline.cut[i] : true);
    }
  }
  return finer;
}

// A submapped block whose corner types the mesher cannot submap (a cusp, a
// slit, or sides that leave a direction without an opposite, whose counts
// would have to be 0) is re-typed at its piece starts (submap_typing), its
// boundary pieces that turn through more than half a quarter turn first cut
// so that a corner can go where each quarter turn is made. A block with too
// few piece starts for a typing (or whose only typings put a convex corner
// where its outline runs straight) gets its boundary pieces cut into halves,
// else thirds. Cuts are kept where the typing puts a corner. Returns false
// when no typing submaps.
bool make_submappable(const FaceModel& face, Block& b, double tol, bool follow_turning) {
  BlockRing ring = ring_of(b);
  TypedPieces whole;
  whole.pieces = std::move(ring.pieces);
  whole.types = std::move(ring.start_type);
  whole.cut.assign(whole.pieces.size(), false);
  int total = 0;
  for (const int type : whole.types) total += 2 - type;
  if (total == 4 && submappable(whole.types, twin_splits(whole.pieces)) &&
      counts_can_balance(whole.pieces, whole.types))
    return true;
  TypedPieces outline = whole;
  std::vector<int> typing = submap_typing(whole.pieces, whole.types, tol, false);
  for (int parts = 2; typing.empty() && parts <= 3; ++parts) {
    TypedPieces finer = cut_pieces(face, whole, [parts](const OutlinePiece&) { return parts; });
    typing = submap_typing(finer.pieces, finer.types, tol, false);
    if (!typing.empty()) outline = std::move(finer);
  }
  // A side more than one and a half quarter turns off its logical direction
  // (one round a hole with no corner on it) folds the lattice: then, as when
  // no typing was found, the pieces that turn are cut at every half quarter
  // turn and the typing follows the turning.
  if (typing.empty() || (follow_turning && largest_turning_gap(outline.pieces, typing, tol) > 1.5)) {
    TypedPieces turned = cut_pieces(face, whole, [&](const OutlinePiece& piece) {
      return std::min(8, static_cast<int>(std::ceil(std::abs(piece_quarters(piece, tol)) / 0.5)));
    });
    std::vector<int> following = submap_typing(turned.pieces, turned.types, tol, true);
    if (!following.empty()) outline = std::move(turned), typing = std::move(following);
  }
  const std::vector<OutlinePiece>& pieces = outline.pieces;
  const std::vector<bool>& cut = outline.cut;
  if (typing.empty()) return false;
  const int n = static_cast<int>(pieces.size());
  int first = 0;
  while (typing[first] == 2) ++first;  // a turning of 4 from types 1..3 has corners
  std::vector<BlockCorner> corners;
  std::vector<BlockSide> sides;
  for (int k = 0; k < n; ++k) {
    const int i = (first + k) % n;
    if (typing[i] != 2) {
      corners.push_back({pieces[i].points.front(), typing[i]});
      sides.emplace_back();
      sides.back().pieces.push_back(pieces[i]);
    } else if (cut[i]) {  // an unused middle cut: the two halves are one piece again
      OutlinePiece& before = sides.back().pieces.back();
      before.t_to = pieces[i].t_to;
      before.points.insert(before.points.end(), pieces[i].points.begin() + 1, pieces[i].points.end());
    } else {
      sides.back().pieces.push_back(pieces[i]);
    }
  }
  b.corners = std::move(corners);
  b.sides = std::move(sides);
  return true;
}

class Decomposer {
 public:
  Decomposer(const FaceModel& face, const MedialAxis& axis, const MeshFlow& flow, const DecompositionOptions& options)
      : face_(face),
        axis_(axis),
        flow_(flow),
        points_(flow.points),
        options_(options),
        index_(face),
        tol_(1e-9 * face.size) {
    for (std::size_t i = 0; i < face.corners.size(); ++i) {
      corner_of_[{face.corners[i].loop, face.corners[i].vertex}] = static_cast<int>(i);
    }
    if (flow.points.size() != axis.edges.size()) throw std::runtime_error(face.name + ": mesh flow has no point flow");
    contract_zero_length_edges();
    locate_singularities();
    located_ = locations_;
    make_units();
    sort_ends();
    find_concave_points();
  }

  // The process's blocks, then the orthogonal joins (Fig. 18) where they
  // are made and every block passes its checks again after them.
  Decomposition run() {
    Decomposition d = run_process();
    if (!options_.orthogonal_joins) return d;
    Decomposition joined = d;
    if (join_splits_orthogonally(face_, joined) == 0 || !passes_block_checks(joined, d)) return d;
    return joined;
  }

 private:
  // The paper's process; should a block fail its self-check, the whole face
  // again with every singularity that can be fixed fixed (the paper's
  // always-possible decomposition into submappable regions).
  // Each attempt is tried with the edges' ends following the junction's
  // touches where they stay on the edge's loop, then following the edge's
  // own wherever the junction's jump (better on star-shaped faces, worse
  // where touches move fast near curved ends); every result is checked.
  Decomposition run_process() {
    std::string first;
    for (const bool fix_all : {false, true}) {
      for (const bool strict : {false, true}) {
        strict_end_touches_ = strict;
        try {
          Decomposition d = attempt(fix_all);
          if (fix_all) {
            d.fallback = true;
            d.fixed_all = true;
            d.notes.push_back(
                "every singularity that can be fixed was fixed, as a fallback: the process's own "
                "blocks did not pass their check (" +
                first + ")");
          }
          return d;
        } catch (const SelfCheckFailure& failure) {
          if (first.empty()) first = failure.what();
        }
      }
    }
    // Last: blocks whose flow numbers do not close up (the flow's local
    // bookkeeping) are typed by their angles instead, if they hold no
    // floating singularity; with every singularity that can be fixed fixed
    // if that does not do (a floating one whose block does not close up).
    lenient_ = true;
    strict_end_touches_ = false;
    for (const bool fix_all : {false, true}) {
      try {
        Decomposition d = attempt(fix_all);
        d.fallback = d.fallback || fix_all;
        d.fixed_all = fix_all;
        d.lenient_typing = true;
        d.notes.push_back(std::string("blocks whose flow does not close up typed by their angles") +
                          (fix_all ? ", with every singularity that can be fixed fixed," : "") +
                          " as a fallback: the process's own blocks did not pass their check (" + first + ")");
        return d;
      } catch (const SelfCheckFailure&) {
      }
    }
    throw SelfCheckError(face_.name, first);
  }

  Decomposition attempt(bool fix_all) {
    // A group of net k = 0 acts as a regular node only while no cut parts
    // its members; one that gets parted is taken apart and the process redone.
    for (;;) {
      if (gathered_) points_ = flow_.points, locations_ = located_, gathered_ = false;
      cuts_.clear();
      vertex_cuts_.clear();
      ++version_;
      boundary_fixed_.clear();
      notes_.clear();
      for (Unit& u : units_) u.fixed = false;
      ++version_;
      if (fix_all) {
        for (std::size_t u = 0; u < units_.size(); ++u) {
          if (floating(static_cast<int>(u)) && boundary_fixable(static_cast<int>(u))) fix(static_cast<int>(u));
        }
      }
      // Splits along every arm of every concave corner, when asked, come
      // first: the process then resolves singularities with what is left.
      for (const ConcavePoint& cp : concave_)
        if (options_.split_concave_corners || framed_.count(face_.corners[cp.corner].loop)) cut_concave(cp);
      resolve_neighbours();
      fix_unresolved();
      std::vector<Outline> outlines;
      long walked = 0;  // the version the outlines were walked at
      for (int round = 0;; ++round) {
        outlines = walk_outlines();
        walked = version_;
        if (!fix_invalid_polygons(outlines) || round > static_cast<int>(units_.size())) break;
      }
      connect_regions();
      if (take_apart_parted_groups()) continue;
      Decomposition d = finish(version_ == walked ? outlines : walk_outlines());
      d.wrapped_holes = wrapped_holes(d);
      if (!options_.frame_wrapped_holes || d.wrapped_holes.empty()) return d;
      framed_.insert(d.wrapped_holes.begin(), d.wrapped_holes.end());
    }
  }

  // Holes with a reflex corner whose every corner lies on one submapped
  // block's outline, not framed yet: the block runs round the hole, held
  // to the rest by a split or two.
  std::vector<int> wrapped_holes(const Decomposition& d) const {
    std::vector<int> wrapped;
    for (int loop = 1; loop < static_cast<int>(face_.loops.size()); ++loop) {
      if (framed_.count(loop)) continue;
      std::vector<Vec2> corners;
      bool reflex = false;
      for (const Corner& c : face_.corners) {
        if (c.loop != loop) continue;
        corners.push_back(c.position);
        reflex = reflex || c.nc >= 3;
      }
      const auto on_outline = [&](const Block& b, Vec2 p) {
        return std::any_of(b.corners.begin(), b.corners.end(),
                           [&](const BlockCorner& c) { return distance(c.p, p) <= tol_; });
      };
      if (reflex && std::any_of(d.blocks.begin(), d.blocks.end(), [&](const Block& b) {
            return b.kind == BlockKind::Submap &&
                   std::all_of(corners.begin(), corners.end(), [&](Vec2 p) { return on_outline(b, p); });
          }))
        wrapped.push_back(loop);
    }
    return wrapped;
  }

  // ---------------------------------------------------------------- set-up

  int point_count(int e) const { return static_cast<int>(axis_.edges[e].points.size()); }
  // The polyline step of edge e that holds position s (point index plus fraction).
  int step_of(int e, double s) const { return std::clamp(static_cast<int>(std::floor(s)), 0, point_count(e) - 2); }
  bool closed(int e) const { return axis_.edges[e].from < 0; }

  // Junctions the medial stage left at one point, joined by an edge of no
  // length (under 1e-6 of the face size), act as one vertex: the walk round the axis needs one order of
  // the edges round a point.
  void contract_zero_length_edges() {
    rep_.resize(axis_.vertices.size());
    std::iota(rep_.begin(), rep_.end(), 0);
    contracted_.assign(axis_.edges.size(), false);
    const auto root = [&](int v) {
      while (rep_[v] != v) v = rep_[v] = rep_[rep_[v]];
      return v;
    };
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const MedialEdge& edge = axis_.edges[e];
      if (edge.from < 0 || edge.from == edge.to) continue;
      double length = 0.0;
      for (std::size_t i = 1; i < edge.points.size(); ++i) length += distance(edge.points[i - 1].p, edge.points[i].p);
      if (length > 1e-6 * face_.size) continue;  // the medial axis's own accuracy
      contracted_[e] = true;
      rep_[root(edge.from)] = root(edge.to);
    }
    for (std::size_t v = 0; v < rep_.size(); ++v) rep_[v] = root(static_cast<int>(v));
  }

  // The vertex an edge starts (at_start) or ends at, coincident junctions as one.
  int end_vertex(int e, bool at_start) const { return rep_[at_start ? axis_.edges[e].from : axis_.edges[e].to]; }

  static constexpr double kAtEnd = 1e-2;  // of the last polyline step
  void locate_singularities() {
    for (const Singularity& s : flow_.singularities) {
      Location loc;
      if (s.vertex >= 0) {
        loc.vertex = rep_[s.vertex];
      } else if (contracted_[s.edge]) {
        loc.vertex = end_vertex(s.edge, true);
      } else {
        loc.edge = s.edge;
        loc.s = project(s.edge, s.p);
        // A switch at the very end of an edge that ends at a junction is at
        // the junction: cut there, not a hair's breadth away.
        const double last = point_count(s.edge) - 1.0;
        for (const bool at_start : {true, false}) {
          const int v = at_start ? axis_.edges[s.edge].from : axis_.edges[s.edge].to;
          const double gap = at_start ? loc.s : last - loc.s;
          if (v >= 0 && gap < kAtEnd && axis_.vertices[v].kind == MedialVertexKind::Junction) {
            loc = Location{};
            loc.vertex = rep_[v];
            break;
          }
        }
        // A switch so near the end of a branch into a contact that its two
        // touches are one place: its split, the two radii, would enclose a
        // block of no area. It is the contact's own.
        const int v = loc.s < 0.5 * last ? axis_.edges[s.edge].from : axis_.edges[s.edge].to;
        if (loc.edge >= 0 && v >= 0 && contact_vertex(axis_.vertices[v])) {
          const int i = step_of(s.edge, loc.s);
          const MedialPoint& near = axis_.edges[s.edge].points[loc.s - i < 0.5 ? i : i + 1];
          if (distance(nearest_on_run(index_, near.left, s.p).point, nearest_on_run(index_, near.right, s.p).point) <=
              sliver_length()) {
            loc = Location{};
            loc.vertex = rep_[v];
          }
        }
      }
      locations_.push_back(loc);
    }
  }

  // Position of p along edge e's polyline (point index plus fraction).
  double project(int e, Vec2 p) const {
    const auto& pts = axis_.edges[e].points;
    double best = 1e300, s = 0.0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const Vec2 a = pts[i].p, d = pts[i + 1].p - a;
      const double len2 = dot(d, d);
      const double f = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
      const double dist = distance(a + f * d, p);
      if (dist < best) best = dist, s = static_cast<double>(i) + f;
    }
    return s;
  }

  // One unit per group of merged singularities, net k = 0 groups included:
  // those need no block of their own, but no cut may part them.
  void make_units() {
    std::vector<SingularityGroup> groups;
    if (options_.merge) groups = group_singularities(flow_.singularities, options_.tolerance);
    units_.clear();
    ++version_;
    for (SingularityGroup& g : groups) {
      if (g.members.size() > 1 && !taken_apart_.count(g.members.front())) units_.push_back({g.k, g.p, g.members});
    }
    unit_of_.assign(flow_.singularities.size(), -1);
    for (const Unit& u : units_) {
      for (int m : u.members) unit_of_[m] = 0;
    }
    for (std::size_t i = 0; i < flow_.singularities.size(); ++i) {
      if (unit_of_[i] < 0 && flow_.singularities[i].k != 0)
        units_.push_back({flow_.singularities[i].k, flow_.singularities[i].p, {static_cast<int>(i)}});
    }
    std::sort(units_.begin(), units_.end(), [](const Unit& a, const Unit& b) { return a.members[0] < b.members[0]; });
    unit_of_.assign(flow_.singularities.size(), -1);
    member_pairs_.clear();
    for (std::size_t u = 0; u < units_.size(); ++u) {
      const auto& members = units_[u].members;
      for (std::size_t i = 0; i < members.size(); ++i) {
        unit_of_[members[i]] = static_cast<int>(u);
        for (std::size_t j = i + 1; j < members.size(); ++j) {
          const Vec2 a = flow_.singularities[members[i]].p, b = flow_.singularities[members[j]].p;
          member_pairs_.push_back({a, b, distance(a, b) + tol_});
        }
      }
    }
    std::sort(member_pairs_.begin(), member_pairs_.end(),
              [](const MemberPair& x, const MemberPair& y) { return x.a.x < y.a.x; });
    widest_pair_ = 0.0;
    for (const MemberPair& pair : member_pairs_) widest_pair_ = std::max(widest_pair_, pair.reach);
    vertex_member_.assign(axis_.vertices.size(), -1);
    for (std::size_t m = 0; m < locations_.size(); ++m) {
      if (locations_[m].vertex >= 0) vertex_member_[locations_[m].vertex] = static_cast<int>(m);
    }
  }

  // Whether a cut at p could part the members of a group: p lies between two of them.
  // Only pairs whose first member lies within the widest reach of p in x
  // can hold it (the pairs sorted by that x; the window a hair wider so
  // that rounding never drops one).
  bool inside_a_group(Vec2 p) const {
    const double window = widest_pair_ * (1.0 + 1e-9) + tol_;
    auto it = std::lower_bound(member_pairs_.begin(), member_pairs_.end(), p.x - window,
                               [](const MemberPair& pair, double x) { return pair.a.x < x; });
    for (; it != member_pairs_.end() && it->a.x <= p.x + window; ++it) {
      if (distance(p, it->a) <= it->reach && distance(p, it->b) <= it->reach) return true;
    }
    return false;
  }

  // Groups of net k = 0 whose members ended up in different pieces: taken
  // apart for the next attempt. Returns whether there were any.
  bool take_apart_parted_groups() {
    Pieces p = pieces();
    bool any = false;
    for (const Unit& u : units_) {
      if (u.k != 0) continue;
      std::set<int> comps;
      for (int m : u.members) comps.insert(component_of(p, m));
      if (comps.size() > 1) taken_apart_.insert(u.members.front()), any = true;
    }
    if (any) make_units();
    return any;
  }

  // The direction an edge leaves its end vertex in, taken a tenth of the
  // vertex's radius out (or at the edge's farthest point if it is shorter):
  // near a junction the medial points can wobble back past the vertex, and
  // the first step would then point the wrong way and misorder the ends.
  Vec2 end_direction(int e, bool at_start) const {
    const auto& pts = axis_.edges[e].points;
    const int n = point_count(e);
    const auto at = [&](int k) { return pts[at_start ? k : n - 1 - k].p; };
    const int vertex = at_start ? axis_.edges[e].from : axis_.edges[e].to;
    const double reach = std::max(tol_, 0.1 * axis_.vertices[vertex].r);
    Vec2 farthest{1, 0};
    double far = tol_;
    for (int k = leaving_point(e, at_start); k < n; ++k) {
      const double d = distance(at(k), at(0));
      if (d > reach) return at(k) - at(0);
      if (d > far) far = d, farthest = at(k) - at(0);
    }
    return farthest;
  }

  // The point (counted from the end at_start) an edge leaves its end vertex
  // from: the first, unless the edge overshoots its vertex along a
  // neighbouring edge, turns right back and passes the vertex again (a
  // medial defect), when it is the nearest point to the vertex after the
  // turn. Only the edge's first half is searched for such a turn.
  int leaving_point(int e, bool at_start) const {
    const auto& pts = axis_.edges[e].points;
    const int n = point_count(e);
    const auto at = [&](int k) { return pts[at_start ? k : n - 1 - k].p; };
    for (int k = 1; k + 1 < n / 2; ++k) {
      const Vec2 in = at(k) - at(k - 1), out = at(k + 1) - at(k);
      if (!(dot(in, out) < -0.9 * norm(in) * norm(out))) continue;
      int nearest = k + 1;
      for (int j = k + 2; j <= n / 2; ++j) {
        if (distance(at(j), at(0)) < distance(at(nearest), at(0))) nearest = j;
      }
      return std::min(nearest + 1, n - 1);
    }
    return std::min(1, n - 1);
  }

  // That point itself.
  const MedialPoint& leaving_neighbour(int e, bool at_start) const {
    const int k = leaving_point(e, at_start);
    return axis_.edges[e].points[at_start ? k : point_count(e) - 1 - k];
  }

  void sort_ends() {
    ends_.resize(axis_.vertices.size());
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const MedialEdge& edge = axis_.edges[e];
      if (edge.from < 0 || contracted_[e]) continue;
      for (const bool at_start : {true, false}) {
        const Vec2 d = end_direction(static_cast<int>(e), at_start);
        ends_[end_vertex(static_cast<int>(e), at_start)].push_back(
            {static_cast<int>(e), at_start, std::atan2(d.y, d.x)});
      }
    }
    for (auto& list : ends_) {
      std::sort(list.begin(), list.end(), [](const End& a, const End& b) { return a.angle < b.angle; });
    }
  }

  // ------------------------------------------------- concave corner splits

  BoundaryPlace corner_place(const Corner& c) const {
    BoundaryPlace place = index_.place(c.loop, c.vertex, face_.loops[c.loop].edges[c.vertex].t_start);
    place.corner = c.vertex;
    place.corner_itself = true;
    place.point = c.position;
    return place;
  }

  void find_concave_points() {
    for (std::size_t ci = 0; ci < face_.corners.size(); ++ci) {
      const Corner& c = face_.corners[ci];
      if (!index_.is_reflex(c.loop, c.vertex) || c.nc < 3) continue;
      for (int arm = 1; arm < c.nc; ++arm) {
        if (auto point = concave_point(static_cast<int>(ci), arm, concave_arm(face_, c, arm))) {
          concave_.push_back(*point);
        }
      }
    }
  }

  std::optional<ConcavePoint> concave_point(int ci, int arm, Vec2 d) const {
    const Corner& c = face_.corners[ci];
    // The first crossing of the ray with the axis is the medial point whose
    // radius it is: up to there the corner is the nearest boundary point.
    double best = 1e300;
    int best_edge = -1, best_i = 0;
    double best_f = 0.0;
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const auto& pts = axis_.edges[e].points;
      for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const Vec2 a = pts[i].p, b = pts[i + 1].p;
        const Vec2 ab = b - a;
        const double den = cross(d, ab);
        if (std::abs(den) < 1e-300) continue;
        const double t = cross(a - c.position, ab) / den;
        const double f = cross(a - c.position, d) / den;
        if (t > tol_ && f >= 0.0 && f <= 1.0 && t < best) {
          best = t;
          best_edge = static_cast<int>(e);
          best_i = static_cast<int>(i);
          best_f = f;
        }
      }
    }
    if (best_edge < 0) return std::nullopt;
    const auto& pts = axis_.edges[best_edge].points;
    const MedialPoint& near = best_f < 0.5 ? pts[best_i] : pts[best_i + 1];
    const bool on_left = distance(near.left.point, c.position) <= distance(near.right.point, c.position);
    BoundaryPlace other = on_left ? near.right : near.left;
    // Exact point on the ray as far from the other side as from the corner.
    double t = best;
    for (int it = 0; it < 30; ++it) {
      const Vec2 m = c.position + t * d;
      other = nearest_on_run(index_, other, m);
      const Vec2 away = m - other.point;
      const double dist = norm(away);
      if (dist <= 0) break;
      const double slope = 1.0 - dot(d, away) / dist;
      if (std::abs(slope) < 1e-6) break;
      const double step = (t - dist) / slope;
      t -= step;
      if (std::abs(step) < 1e-13 * face_.size) break;
    }
    if (!(t > tol_) || std::abs(t - best) > 0.25 * best + 1e-6 * face_.size) t = best;
    ConcavePoint cp;
    cp.corner = ci;
    cp.arm = arm;
    cp.edge = best_edge;
    cp.point.p = c.position + t * d;
    cp.point.r = t;
    other = nearest_on_run(index_, other, cp.point.p);
    (on_left ? cp.point.left : cp.point.right) = corner_place(c);
    (on_left ? cp.point.right : cp.point.left) = other;
    cp.s = project(best_edge, cp.point.p);
    cp.corner_on_left = on_left;
    cp.flow = points_[best_edge][best_f < 0.5 ? best_i : best_i + 1];
    (on_left ? cp.flow.left_corner : cp.flow.right_corner) = ci;
    (on_left ? cp.flow.left_arm : cp.flow.right_arm) = arm;
    const double n = point_count(best_edge) - 1;
    if (cp.s <= 1e-9 || cp.s >= n - 1e-9) return std::nullopt;  // at a vertex: that vertex decides
    return cp;
  }

  // ------------------------------------------------------------- the cuts

  bool cut_at(int e, double s) const {
    for (const Cut& c : cuts_) {
      if (c.edge != e) continue;
      if (std::abs(c.s - s) < 1e-9) return true;
      for (const double covered : c.covers)
        if (std::abs(covered - s) < 1e-9) return true;
    }
    return false;
  }

  bool vertex_cut(int v) const { return vertex_cuts_.count(v) > 0; }

  bool withdrawn(int e, double s) const { return withdrawn_.count({e, std::lround(s * 1e6)}) > 0; }

  void cut_edge_at_point(int e, int i, SplitReason reason) {
    if (cut_at(e, i) || (reason != SplitReason::Connect && withdrawn(e, i))) return;
    Cut c;
    c.edge = e;
    c.s = c.origin = i;
    c.point = axis_.edges[e].points[i];
    c.behind = c.ahead = points_[e][i];
    c.reason = reason;
    refine(c);
    add_edge_cut(c);
  }

  // Adds a cut on an axis edge. The edge marks, if they were up to date,
  // are brought up to date as edge_marks() would rebuild them: the cut's
  // mark after those at its position, and no mark for a concave corner's
  // split that the cut now makes. (Rebuilt after every cut, they were a
  // tenth of a plate with 100 holes' decomposition.)
  void add_edge_cut(const Cut& c) {
    const bool marks_current = marks_version_ == version_;
    cuts_.push_back(c);
    snap_to_smooth_joins(cuts_.back().point);
    ++version_;
    if (!marks_current) return;
    mark_edge_cut(c);
    marks_version_ = version_;
  }

  // Edge marks kept up to date: the concave corners' splits that cuts on
  // edge e now make are no feature; a new cut's mark goes after those at its
  // place (the order of edge_marks()'s stable sort), and the splits it makes go.
  void drop_cut_concave_marks(int e) {
    std::vector<Mark>& list = marks_[e];
    list.erase(
        std::remove_if(list.begin(), list.end(),
                       [&](const Mark& m) { return m.concave >= 0 && cut_at(e, cut_position(concave_[m.concave])); }),
        list.end());
  }
  void mark_edge_cut(const Cut& c) {
    drop_cut_concave_marks(c.edge);
    std::vector<Mark>& list = marks_[c.edge];
    const auto after = std::upper_bound(list.begin(), list.end(), c.s, [](double s, const Mark& m) { return s < m.s; });
    list.insert(after, {c.s, -1, -1, true});
  }

  // The exact medial point near a cut's polyline point where the medial
  // angle is nearest the ideal of its flow type (pi for n = 0, pi / 2 for
  // n = 1), found by golden-section search on the exact axis.
  void refine(Cut& c) const {
    const int n = std::abs(c.behind.q);
    if (n > 1) return;
    const double ideal = n == 0 ? kPi : 0.5 * kPi;
    const auto& pts = axis_.edges[c.edge].points;
    const int i = static_cast<int>(c.s);
    const auto exact = [&](double s) -> std::optional<MedialPoint> {
      const int j = step_of(c.edge, s);
      const Vec2 guess = pts[j].p + (s - j) * (pts[j + 1].p - pts[j].p);
      const Bisected b = bisect(index_, guess, pts[i].left, pts[i].right);
      if (!b.converged || b.a.corner >= 0 || b.b.corner >= 0) return std::nullopt;
      if (distance(b.p, guess) > distance(pts[j].p, pts[j + 1].p)) return std::nullopt;
      return MedialPoint{b.p, b.r, b.a, b.b};
    };
    const auto error = [&](double s) {
      const auto m = exact(s);
      return m ? std::abs(medial_angle(*m) - ideal) : 1e300;
    };
    if (std::abs(medial_angle(c.point) - ideal) < 1e-9) return;
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = std::max(0.0, c.s - 0.5), hi = std::min(point_count(c.edge) - 1.0, c.s + 0.5);
    // Never across another feature of the edge.
    const auto keep_apart = [&](double mark) {
      if (mark > c.s) hi = std::min(hi, mark - 1e-3);
      if (mark < c.s) lo = std::max(lo, mark + 1e-3);
    };
    for (const Location& loc : locations_) {
      if (loc.edge == c.edge) keep_apart(loc.s);
    }
    for (const ConcavePoint& cp : concave_) {
      if (cp.edge == c.edge) keep_apart(cp.s);
    }
    for (const Cut& other : cuts_) {
      if (other.edge == c.edge) keep_apart(other.s);
    }
    if (!(hi > lo)) return;
    double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
    double f1 = error(x1), f2 = error(x2);
    for (int it = 0; it < 40; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1, x1 = hi - golden * (hi - lo), f1 = error(x1);
      } else {
        lo = x1, x1 = x2, f1 = f2, x2 = lo + golden * (hi - lo), f2 = error(x2);
      }
    }
    const double best = 0.5 * (lo + hi);
    if (error(best) >= std::abs(medial_angle(c.point) - ideal)) return;
    if (const auto m = exact(best)) c.point = *m, c.s = best;
  }

  // Where a concave corner's split cuts its edge: at the point itself, or
  // on a switch between the polyline points either side of it (the switch
  // is then taken to be on the split).
  double cut_position(const ConcavePoint& cp) const {
    const int i = step_of(cp.edge, cp.s);
    for (const Location& loc : locations_) {
      if (loc.edge == cp.edge && loc.s > i && loc.s < i + 1) return loc.s;
    }
    return cp.s;
  }

  // A split's end a hair from a tangent join is put on the join. Where a
  // line runs on into an arc the arc's centre touches the whole arc, and the
  // end found on it stopped 4.6e-6 short of the join on a face of 3.6
  // (MODERN_Chair_1.brep face 50): the piece of arc between became a
  // segment of its own, with an element of edge ratio 44 694 along it.
  void snap_to_smooth_joins(MedialPoint& m) const {
    for (BoundaryPlace* place : {&m.left, &m.right}) {
      if (place->corner >= 0) continue;
      const Loop& loop = face_.loops[place->loop];
      const BoundaryEdge& e = loop.edges[place->edge];
      // The end nearer in parameter: a closed curve's two ends are one point
      // (a circle's seam), and the place must stay on its own side of it.
      const bool at_end = std::abs(place->t - e.t_end) < std::abs(place->t - e.t_start);
      const int vertex = at_end ? (place->edge + 1) % static_cast<int>(loop.edges.size()) : place->edge;
      const Vec2 join = at_end ? e.end : e.start;
      if (index_.is_corner(place->loop, vertex) || distance(place->point, join) > kSnapToJoin * face_.size) continue;
      *place = index_.place(place->loop, place->edge, at_end ? e.t_end : e.t_start);
      place->point = join;
    }
  }

  // Returns whether the cut is new.
  bool cut_concave(const ConcavePoint& cp) {
    if (cut_at(cp.edge, cut_position(cp)) || withdrawn(cp.edge, cp.s)) return false;
    Cut c;
    c.edge = cp.edge;
    c.s = c.origin = cp.s;
    c.point = cp.point;
    // The flow on either side, both turned onto the arm: where the arm is
    // the corner's radius perpendicular to an edge the adjusted direction
    // jumps there, and the flow may switch right at the split.
    const int i = step_of(cp.edge, cp.s);
    c.behind = points_[cp.edge][i];
    c.ahead = points_[cp.edge][i + 1];
    for (PointFlow* f : {&c.behind, &c.ahead}) {
      (cp.corner_on_left ? f->left_corner : f->right_corner) = cp.corner;
      (cp.corner_on_left ? f->left_arm : f->right_arm) = cp.arm;
    }
    c.s = cut_position(cp);
    c.reason = SplitReason::ConcaveCorner;
    add_edge_cut(c);
    return true;
  }

  // Cuts through a unit's members: they become corners of blocks. Only
  // switches on edges and junctions can be fixed (a finite contact's k
  // belongs to the disc sector round it, which no cut can take from it).
  // Whether fixing the unit may move a contact's singularity onto the
  // boundary it touches: -k convex corners on a finite contact's arc, or at
  // a curvature contact's touching point, instead of a node inside (what
  // mapped meshing does with a fillet, a round end or a bump: a k = -1 at
  // the end of a branch into a bump otherwise sits beside the reflex corner
  // of the cut through the branch's k = +1 and has no convex block); and a
  // flare's k onto its corner, which gets nc + k elements (a slot's corner
  // in a thin strip, whose k = +1 no merge joins to the k = -1 beside it, a
  // flare's radius being 0; an obtuse corner's k = -1, one element then).
  static bool contact_vertex(const MedialVertex& v) {
    return v.kind == MedialVertexKind::FiniteContact || v.kind == MedialVertexKind::CurvatureContact;
  }
  bool flare_fixable(const MedialVertex& v, int k) const {
    if (k > 0) return true;
    const int ci = v.touches.empty() ? -1 : corner_index(v.touches.front());
    return k < 0 && ci >= 0 && face_.corners[ci].nc + k >= 1;
  }
  bool boundary_fixable(int u) const {
    for (int m : units_[u].members) {
      const Location& loc = locations_[m];
      if (loc.vertex < 0) continue;
      const MedialVertex& v = axis_.vertices[loc.vertex];
      const bool junction = v.kind == MedialVertexKind::Junction && v.edges.size() >= 2;
      const bool contact = (contact_vertex(v) && flow_.singularities[m].k < 0) ||
                           (v.kind == MedialVertexKind::Flare && flare_fixable(v, flow_.singularities[m].k));
      if (!junction && !contact) return false;
    }
    return true;
  }

  // At a vertex fixed onto the boundary, the index (into ends_[v]) of the end
  // after which the widest touched arc lies.
  int widest_gap(int v) const {
    const auto& list = ends_[v];
    int best = 0;
    double widest = -1.0;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const End& x = list[k];
      const End& y = list[(k + 1) % list.size()];
      const auto& xp = axis_.edges[x.edge].points;
      const auto& yp = axis_.edges[y.edge].points;
      const BoundaryPlace& a = x.at_start ? xp.front().left : xp.back().right;
      const BoundaryPlace& b = y.at_start ? yp.front().right : yp.back().left;
      double span = loop_position(b) - loop_position(a);
      if (span <= 0) span += static_cast<double>(face_.loops[a.loop].edges.size());
      if (span > widest) widest = span, best = static_cast<int>(k);
    }
    return best;
  }

  bool fixable(int u) const {
    for (int m : units_[u].members) {
      const Location& loc = locations_[m];
      if (loc.vertex >= 0 && (axis_.vertices[loc.vertex].kind != MedialVertexKind::Junction ||
                              axis_.vertices[loc.vertex].edges.size() < 2))
        return false;
    }
    return true;
  }

  void fix(int u) {
    const bool marks_current = marks_version_ == version_;
    std::vector<int> marked_edges;  // where the members' marks are, before any gathering moves them
    for (const int m : units_[u].members) marked_edges.push_back(locations_[m].edge);
    units_[u].fixed = true;
    ++version_;
    gather_at_junction(u);
    for (int m : units_[u].members) {
      const Location& loc = locations_[m];
      if (loc.vertex >= 0 &&
          (contact_vertex(axis_.vertices[loc.vertex]) || axis_.vertices[loc.vertex].kind == MedialVertexKind::Flare)) {
        boundary_fixed_[loc.vertex] -= flow_.singularities[m].k;
        continue;
      }
      if (loc.vertex >= 0) {
        if (vertex_cut(loc.vertex)) continue;
        Cut c;
        c.vertex = loc.vertex;
        c.reason = SplitReason::Fix;
        cuts_.push_back(c);
        ++version_;
        vertex_cuts_.insert(loc.vertex);
        continue;
      }
      if (cut_at(loc.edge, loc.s)) continue;
      const int i = step_of(loc.edge, loc.s);
      Cut c;
      c.edge = loc.edge;
      c.s = loc.s;
      c.point = fix_point(loc.edge, i, flow_.singularities[m].p, flow_.singularities[m].r);
      c.behind = points_[loc.edge][i];
      c.ahead = points_[loc.edge][i + 1];
      c.reason = SplitReason::Fix;
      ++version_;
      // Members a hair's breadth apart (a switch beside the junction-like
      // point where a pruned branch left the edge) would get one split
      // twice, with a block of no area between: one split takes both, with
      // the flow from before the first to after the last.
      if (Cut* same = coinciding_fix(c)) {
        same->covers.push_back(c.s);
        if (c.s < same->s) same->behind = c.behind;
        if (c.s > same->s) same->ahead = c.ahead;
        if (marks_current) drop_cut_concave_marks(same->edge);
        continue;
      }
      snap_to_smooth_joins(c.point);
      cuts_.push_back(c);
      if (marks_current) mark_edge_cut(c);
    }
    if (marks_current) {  // the unit no longer floats: its members are no feature
      for (const int e : marked_edges) {
        if (e < 0) continue;
        marks_[e].erase(
            std::remove_if(marks_[e].begin(), marks_[e].end(), [&](const Mark& mark) { return mark.unit == u; }),
            marks_[e].end());
      }
      marks_version_ = version_;
    }
  }

  // A merged unit whose members sit on the edges round one junction, with
  // nothing between them and it, is fixed at the junction: one node of
  // valence 4 + k, as the merge meant, rather than its members' nodes apart
  // with a thin block wedged between their cuts (four holes in a rectangle:
  // two k = +1 switches either side of the junction become one k = +2
  // node whose six elements meet at about 60 degrees). Between each member
  // and the junction the flow becomes the member's far side's, as though
  // the switch were at the junction; only where the junction's sectors
  // then get 4 + k elements between them, at least one each.
  struct Gathering {
    struct Stretch {
      int from = 0, to = 0;  // the edge's points [from, to) between its member and the junction
      int q = 0;             // the member's far side's flow, which they take
    };
    int vertex = -1;
    std::map<int, Stretch> stretches;  // per edge whose member moves
  };

  std::optional<Gathering> junction_gathering(int u) const {
    const std::vector<int>& members = units_[u].members;
    // A k = +2 only: its six elements can meet at 60 degrees; seven and more
    // meet at under 52 (MODERN_Table_1.brep face 14's k = +3: 0.866 -> 0.782),
    // and a k = +1 group (two +1 and a -1) gathered meshed worse as often as
    // better (trimesh_baseiface_10 at 0.01 of the diagonal 0.605 -> 0.386).
    if (members.size() < 2 || units_[u].k != 2) return std::nullopt;
    std::vector<int> candidates;
    for (const int m : members) {
      const Location& loc = locations_[m];
      std::vector<int> here;
      if (loc.vertex >= 0) {
        here = {loc.vertex};
      } else if (!closed(loc.edge)) {
        here = {end_vertex(loc.edge, true), end_vertex(loc.edge, false)};
      }
      if (m == members.front()) candidates = here;
      candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                      [&](int v) { return std::find(here.begin(), here.end(), v) == here.end(); }),
                       candidates.end());
    }
    if (candidates.size() != 1) return std::nullopt;
    Gathering g;
    g.vertex = candidates.front();
    const int v = g.vertex;
    if (axis_.vertices[v].kind != MedialVertexKind::Junction || ends_[v].size() < 3 || vertex_cut(v))
      return std::nullopt;
    if (vertex_member_[v] >= 0 && unit_of_[vertex_member_[v]] != u) return std::nullopt;
    for (const int m : members) {
      const Location& loc = locations_[m];
      if (loc.vertex >= 0) continue;
      const int e = loc.edge;
      const bool at_start = end_vertex(e, true) == v;
      if (at_start == (end_vertex(e, false) == v) || g.stretches.count(e)) return std::nullopt;
      const auto between = [&](double s) { return at_start ? s < loc.s + 1e-12 : s > loc.s - 1e-12; };
      for (std::size_t other = 0; other < locations_.size(); ++other) {
        if (static_cast<int>(other) != m && locations_[other].edge == e && between(locations_[other].s))
          return std::nullopt;
      }
      for (const ConcavePoint& cp : concave_) {
        if (cp.edge == e && between(cp.s)) return std::nullopt;
      }
      for (const Cut& c : cuts_) {
        if (c.edge == e && between(c.s)) return std::nullopt;
      }
      const int i = step_of(e, loc.s);
      g.stretches[e] = at_start ? Gathering::Stretch{0, i + 1, points_[e][i + 1].q}
                                : Gathering::Stretch{i + 1, point_count(e), points_[e][i].q};
    }
    int elements = 0;
    for (const End& end : ends_[v]) {
      const int bend = 2 - gathered_away_q(g, end.edge, end.at_start);
      if (bend < 1 || bend > 3) return std::nullopt;  // every sector a corner it can mesh
      elements += bend;
    }
    if (elements != 4 + units_[u].k) return std::nullopt;
    return g;
  }

  // away_q at the junction once the gathering's members are there.
  int gathered_away_q(const Gathering& g, int e, bool at_start) const {
    const auto it = g.stretches.find(e);
    if (it == g.stretches.end()) return away_q(e, at_start);
    return at_start ? it->second.q : -it->second.q;
  }

  void gather_at_junction(int u) {
    const std::optional<Gathering> g = junction_gathering(u);
    if (!g) return;
    for (const auto& [e, stretch] : g->stretches)
      for (int j = stretch.from; j < stretch.to; ++j) points_[e][j].q = stretch.q;
    for (const int m : units_[u].members) locations_[m] = Location{-1, 0.0, g->vertex};
    gathered_ = true;
    notes_.push_back("fixed a k = " + std::to_string(units_[u].k) +
                     " singularity at the junction its members surround");
  }

  // A fix cut on the same edge whose split is the new one's to the sliver
  // length, with no feature of the edge between the two.
  Cut* coinciding_fix(const Cut& c) {
    const double sliver = sliver_length();
    for (Cut& other : cuts_) {
      if (other.edge != c.edge || other.reason != SplitReason::Fix) continue;
      if (distance(other.point.p, c.point.p) > sliver ||
          distance(other.point.left.point, c.point.left.point) > sliver ||
          distance(other.point.right.point, c.point.right.point) > sliver)
        continue;
      const double lo = std::min(other.s, c.s), hi = std::max(other.s, c.s);
      const auto between = [&](double s) { return s > lo + 1e-9 && s < hi - 1e-9; };
      const bool apart =
          std::any_of(locations_.begin(), locations_.end(),
                      [&](const Location& l) { return l.edge == c.edge && between(l.s); }) ||
          std::any_of(cuts_.begin(), cuts_.end(), [&](const Cut& x) { return x.edge == c.edge && between(x.s); });
      if (!apart) return &other;
    }
    return nullptr;
  }

  // The split through a singularity at p between points i and i + 1 of
  // edge e: its radii go to the two places nearest p on the runs the nearer
  // point touches. Where the touches move fast along the segment (the
  // boundary curving towards the axis) both searches can end at one place
  // (p lies a little off the exact axis) and the split would be no cut at
  // all; a point can also carry one place as both its touches (a medial
  // defect), or the two can pass each other (see in_order). Then the other
  // point's runs are tried, and last the nearer medial point whose two
  // touches differ is taken, with its touches.
  MedialPoint fix_point(int e, int i, Vec2 p, double r) const {
    const auto& pts = axis_.edges[e].points;
    const bool first_nearer = distance(pts[i].p, p) <= distance(pts[i + 1].p, p);
    const int order[2] = {first_nearer ? i : i + 1, first_nearer ? i + 1 : i};
    const auto apart = [&](const MedialPoint& m) { return distance(m.left.point, m.right.point) > tol_; };
    // Near the end of a branch into a curvature contact the two searches can
    // also pass each other: the radii then cross, and the block beyond the
    // split is turned inside out. Where the touches lie close along one loop
    // their order must stay the medial point's own.
    const auto in_order = [&](const MedialPoint& m, const MedialPoint& own) {
      if (m.left.loop != m.right.loop || own.left.loop != own.right.loop || m.left.loop != own.left.loop) return true;
      const double step = signed_step(own.right, own.left);
      if (std::abs(step) > 0.25 * static_cast<double>(face_.loops[own.left.loop].edges.size())) return true;
      return (signed_step(m.right, m.left) > 0) == (step > 0);
    };
    // An end point carries its vertex's touches, which at a junction need not
    // continue the edge's own (plate_5_1451: a junction touching two slots
    // and the outline, where a singularity fixed beside it got a radius to
    // the slot across): the runs there are those the edge leaves along.
    const int n = point_count(e);
    const auto runs_at = [&](int j) -> const MedialPoint& {
      return n < 3 || (j != 0 && j != n - 1) ? pts[j] : leaving_neighbour(e, j == 0);
    };
    for (const int j : order) {
      const MedialPoint& own = runs_at(j);
      const MedialPoint point{p, r, nearest_on_run(index_, own.left, p), nearest_on_run(index_, own.right, p)};
      if (apart(point) && in_order(point, own)) return point;
    }
    for (const int j : order) {
      if (apart(pts[j])) return pts[j];
    }
    return pts[order[0]];
  }

  // ------------------------------------------------------------ exploring

  struct Mark {
    double s;
    int unit = -1;     // a member of this unit
    int concave = -1;  // a concave corner's split
    bool cut = false;
  };

  // Per edge, its features sorted by position; rebuilt after every change
  // of the cuts or of which units float.
  const std::vector<std::vector<Mark>>& edge_marks() const {
    if (marks_version_ == version_) return marks_;
    marks_version_ = version_;
    std::vector<std::vector<Mark>>& marks = marks_;
    marks.resize(axis_.edges.size());
    for (auto& list : marks) list.clear();  // keeping their memory
    for (std::size_t m = 0; m < locations_.size(); ++m) {
      if (locations_[m].edge >= 0 && unit_of_[m] >= 0 && floating(unit_of_[m]))
        marks[locations_[m].edge].push_back({locations_[m].s, unit_of_[m]});
    }
    for (std::size_t i = 0; i < concave_.size(); ++i) {
      if (!cut_at(concave_[i].edge, cut_position(concave_[i])))
        marks[concave_[i].edge].push_back({concave_[i].s, -1, static_cast<int>(i)});
    }
    for (const Cut& c : cuts_) {
      if (c.edge >= 0) marks[c.edge].push_back({c.s, -1, -1, true});
    }
    for (auto& list : marks) {  // stable: add_edge_cut puts a new cut after the marks at its place
      std::stable_sort(list.begin(), list.end(), [](const Mark& a, const Mark& b) { return a.s < b.s; });
    }
    return marks;
  }

  // A unit that needs a block of its own and has not been fixed.
  bool floating(int u) const { return units_[u].k != 0 && !units_[u].fixed; }

  int vertex_unit(int v) const {
    const int m = vertex_member_[v];
    return m >= 0 && unit_of_[m] >= 0 && floating(unit_of_[m]) ? unit_of_[m] : -1;
  }

  int corner_index(const BoundaryPlace& place) const {
    if (place.corner < 0) return -1;
    const auto it = corner_of_.find({place.loop, place.corner});
    return it == corner_of_.end() ? -1 : it->second;
  }

  // The features the medial axis leads to from unit u, each with its path.
  std::vector<Neighbour> explore(int u) const {
    const auto& marks = edge_marks();
    std::vector<Neighbour> found;
    std::vector<std::tuple<int, int, double>> visited;  // a few: searched, not a set
    std::vector<Step> path;
    // Walk along edge e from s0 in direction dir until a feature or a vertex.
    std::function<void(int, double, int)> walk = [&](int e, double s0, int dir) {
      const std::tuple<int, int, double> here{e, dir, s0};
      if (std::find(visited.begin(), visited.end(), here) != visited.end()) return;
      visited.push_back(here);
      const int last = point_count(e) - 1;
      const Mark* next = nullptr;
      for (const Mark& m : marks[e]) {
        if (dir > 0 && m.s > s0 + 1e-12 && (!next || m.s < next->s)) next = &m;
        if (dir < 0 && m.s < s0 - 1e-12 && (!next || m.s > next->s)) next = &m;
      }
      if (next) {
        path.push_back({e, s0, next->s});
        if (next->unit >= 0 && next->unit != u) found.push_back({FeatureKind::Unit, next->unit, path});
        if (next->concave >= 0) found.push_back({FeatureKind::ConcaveSplit, next->concave, path});
        path.pop_back();
        return;
      }
      const double end = dir > 0 ? last : 0;
      path.push_back({e, s0, end});
      if (closed(e)) {
        walk(e, dir > 0 ? 0.0 : static_cast<double>(last), dir);
      } else {
        arrive(e, end_vertex(e, dir < 0), dir < 0, walk, found, u, path);
      }
      path.pop_back();
    };
    for (int m : units_[u].members) {
      const Location& loc = locations_[m];
      if (loc.vertex >= 0) {
        for (const End& end : ends_[loc.vertex]) {
          walk(end.edge, end.at_start ? 0.0 : point_count(end.edge) - 1.0, end.at_start ? 1 : -1);
        }
      } else {
        walk(loc.edge, loc.s, 1);
        walk(loc.edge, loc.s, -1);
      }
    }
    return found;
  }

  template <class Walk>
  void arrive(int e, int v, bool at_start, Walk& walk, std::vector<Neighbour>& found, int u,
              std::vector<Step>& path) const {
    const MedialVertex& vertex = axis_.vertices[v];
    const int w = vertex_unit(v);
    if (w >= 0) {
      if (w != u) found.push_back({FeatureKind::Unit, w, path});
      return;
    }
    if (vertex_cut(v)) return;
    if (vertex.kind == MedialVertexKind::Flare) {
      const int ci = vertex.touches.empty() ? -1 : corner_index(vertex.touches.front());
      if (ci >= 0 && face_.corners[ci].nc == 0) found.push_back({FeatureKind::SharpCorner, ci, path});
      return;
    }
    if (vertex.kind != MedialVertexKind::Junction) return;  // finite and curvature contacts: resolved
    for (const End& end : ends_[v]) {
      if (end.edge == e && end.at_start == at_start) continue;
      walk(end.edge, end.at_start ? 0.0 : point_count(end.edge) - 1.0, end.at_start ? 1 : -1);
    }
  }

  // Elements the unit's block gets at the bend of a cut with flow q, the unit
  // lying behind the cut (it was reached walking forwards) or ahead of it.
  static int bend_for(bool unit_behind, int q) { return unit_behind ? 2 + q : 2 - q; }

  // The best permitted split on the path, and its flow type: n = 0 anywhere;
  // n = 1 only where its bend is convex for the unit. An n = 1
  // split leaves a reflex corner beyond it, so it needs no singularity there
  // that must float (none at all, or, for_anchor, none that cannot be fixed).
  struct Chosen {
    int edge, point, n;
  };
  // Among equals, a point on the way to more of the unit's other unresolved
  // neighbours is better: one split there resolves them all. Then medial
  // angles nearer their ideal, in steps of 20 degrees: finer steps let a few
  // degrees outrank the position, and round a hole both splits of a ring
  // then crowded one singularity, leaving the other block wrapped most of the
  // way round the hole (1 500 random faces: 13 meshes failed that way or
  // otherwise, 9 with these steps). Then points away from the path's ends,
  // and last the point nearest the path's middle. On the way to a sharp
  // corner (a cusp) every medial angle tends to pi at the tip, so the angle
  // would drag the split into the tip and leave a sliver block there: the
  // angle is not asked, and the point nearest the unit leaves the tip most
  // room.
  static constexpr double kDeviationStep = 0.35;  // radians, 20 degrees
  std::optional<Chosen> best_cut(const std::vector<Step>& path, bool convex_n1_allowed, bool for_anchor = false,
                                 const std::vector<const Neighbour*>& others = {}, bool to_sharp_corner = false) const {
    double length = 0.0;
    for (const Step& st : path) length += arc(st.edge, st.from, st.to);
    using Score = std::tuple<int, int, int, int, double>;
    struct Candidate {
      Score score;
      int edge, point, dir;
    };
    std::vector<Candidate> candidates;
    double walked = 0.0;
    for (const Step& st : path) {
      const auto& pts = axis_.edges[st.edge].points;
      const int lo = static_cast<int>(std::floor(std::min(st.from, st.to))) + 1;
      const int hi = static_cast<int>(std::ceil(std::max(st.from, st.to))) - 1;
      // Arc length walked up to point i, carried along in the step's direction.
      double at = walked;
      double at_s = st.from;
      const int step = st.forward() ? 1 : -1;
      for (int i = st.forward() ? lo : hi; i >= lo && i <= hi; i += step) {
        at += arc(st.edge, at_s, i);
        at_s = i;
        const PointFlow& pf = points_[st.edge][i];
        if (pf.left_corner >= 0 || pf.right_corner >= 0) continue;
        if (distance(pts[i].left.point, pts[i].right.point) < 1e-6 * face_.size) continue;
        if (inside_a_group(pts[i].p)) continue;
        const int n = std::abs(pf.q);
        if (n > 1) continue;
        if (n == 1 && (!convex_n1_allowed || bend_for(st.forward(), pf.q) != 1)) continue;
        const bool outer = at < 0.1 * length || at > 0.9 * length;
        int shared = 0;
        for (const Neighbour* other : others) shared += on_path(other->path, st.edge, i) ? 1 : 0;
        candidates.push_back({{n, -shared, to_sharp_corner ? 0 : static_cast<int>(pf.deviation / kDeviationStep),
                               outer ? 1 : 0, to_sharp_corner ? at : std::abs(at - 0.5 * length)},
                              st.edge,
                              i,
                              st.forward() ? 1 : -1});
      }
      walked += arc(st.edge, st.from, st.to);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
    for (const Candidate& c : candidates) {
      const int n = std::get<0>(c.score);
      if (n == 1 && reaches_floating_unit(c.edge, c.point, c.dir, for_anchor)) continue;
      return Chosen{c.edge, c.point, n};
    }
    return std::nullopt;
  }

  static bool on_path(const std::vector<Step>& path, int e, double s) {
    return std::any_of(path.begin(), path.end(), [&](const Step& st) {
      return st.edge == e && s > std::min(st.from, st.to) && s < std::max(st.from, st.to);
    });
  }

  bool path_has_cut(const std::vector<Step>& path) const {
    return std::any_of(cuts_.begin(), cuts_.end(),
                       [&](const Cut& c) { return c.edge >= 0 && on_path(path, c.edge, c.s); });
  }

  // Whether the axis beyond position s of edge e, walking in direction dir
  // up to the cuts, holds a floating unit.
  bool reaches_floating_unit(int e0, double s0, int dir0, bool only_unfixable) const {
    const auto counts = [&](int unit) { return unit >= 0 && (!only_unfixable || !fixable(unit)); };
    const auto& marks = edge_marks();
    std::vector<std::tuple<int, int, double>> visited;  // a few: searched, not a set
    std::vector<std::tuple<int, double, int>> todo{{e0, s0, dir0}};
    while (!todo.empty()) {
      const auto [e, s, dir] = todo.back();
      todo.pop_back();
      const std::tuple<int, int, double> here{e, dir, s};
      if (std::find(visited.begin(), visited.end(), here) != visited.end()) continue;
      visited.push_back(here);
      bool stopped = false;
      for (const Mark& m : marks[e]) {
        const bool beyond = dir > 0 ? m.s > s + 1e-12 : m.s < s - 1e-12;
        if (!beyond) continue;
        if (counts(m.unit)) return true;
        if (m.cut) {
          // A unit between s and the cut still counts: keep looking at nearer marks.
          const double cut_s = m.s;
          for (const Mark& other : marks[e]) {
            const bool between = dir > 0 ? other.s > s && other.s < cut_s : other.s < s && other.s > cut_s;
            if (between && counts(other.unit)) return true;
          }
          stopped = true;
          break;
        }
      }
      if (stopped) continue;
      const int last = point_count(e) - 1;
      if (closed(e)) {
        todo.push_back({e, dir > 0 ? 0.0 : static_cast<double>(last), dir});
        continue;
      }
      const int v = end_vertex(e, dir < 0);
      if (counts(vertex_unit(v))) return true;
      if (vertex_cut(v)) continue;
      for (const End& end : ends_[v]) {
        if (end.edge == e && end.at_start == (dir < 0)) continue;
        todo.push_back(
            {end.edge, end.at_start ? 0.0 : static_cast<double>(point_count(end.edge) - 1), end.at_start ? 1 : -1});
      }
    }
    return false;
  }

  // Length of the edge's polyline between two positions.
  double arc(int e, double a, double b) const {
    const auto& pts = axis_.edges[e].points;
    const double lo = std::min(a, b), hi = std::max(a, b);
    const auto at = [&](double s) {
      const int i = step_of(e, s);
      return pts[i].p + (s - i) * (pts[i + 1].p - pts[i].p);
    };
    double total = 0.0;
    Vec2 prev = at(lo);
    for (int i = static_cast<int>(std::floor(lo)) + 1; i < hi; ++i) {
      total += distance(prev, pts[i].p);
      prev = pts[i].p;
    }
    return total + distance(prev, at(hi));
  }

  // Whether a concave corner's split makes a straight or convex side for the unit.
  bool concave_resolves(const ConcavePoint& cp, bool unit_behind) const {
    const int nc = face_.corners[cp.corner].nc;
    const int bend = bend_for(unit_behind, cp.flow.q);
    const int at_corner = (cp.corner_on_left == unit_behind) ? cp.arm : nc - cp.arm;
    return bend >= 1 && bend <= 2 && at_corner >= 1 && at_corner <= 2;
  }

  // Step 3 of section 4.2, first half: splits where a permitted one exists.
  // Units in the order they are dealt with: first those that cannot be
  // fixed (finite contacts: their k belongs to the disc round them), which
  // then have their way with their neighbours.
  std::vector<int> processing_order() const {
    std::vector<int> order(units_.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_partition(order.begin(), order.end(), [&](int u) { return !fixable(u); });
    return order;
  }

  void resolve_neighbours() {
    for (const int u : processing_order()) {
      if (!floating(u)) continue;
      const bool anchor = !fixable(u);
      const std::vector<Neighbour> neighbours = explore(u);
      std::vector<const Neighbour*> unresolved;
      for (const Neighbour& nb : neighbours) {
        if (nb.kind == FeatureKind::ConcaveSplit && concave_resolves(concave_[nb.id], nb.path.back().forward())) {
          cut_concave(concave_[nb.id]);
        } else if (nb.kind != FeatureKind::Unit || floating(nb.id)) {
          unresolved.push_back(&nb);
        }
      }
      for (const Neighbour* nbp : unresolved) {
        const Neighbour& nb = *nbp;
        if (!floating(u)) break;
        if (path_has_cut(nb.path)) continue;  // an earlier split resolved it too
        const bool to_unit = nb.kind == FeatureKind::Unit;
        if (to_unit && !floating(nb.id)) continue;
        const bool n1_allowed = !to_unit || (anchor && fixable(nb.id));
        if (const auto where = best_cut(nb.path, n1_allowed, anchor, unresolved, nb.kind == FeatureKind::SharpCorner)) {
          cut_edge_at_point(where->edge, where->point, SplitReason::Resolve);
          if (to_unit && where->n == 1) {
            fix(nb.id);  // its side of the split has the reflex corner
            notes_.push_back("fixed a k = " + std::to_string(units_[nb.id].k) +
                             " singularity next to one that cannot be fixed");
          }
        }
      }
    }
  }

  // Second half: where no permitted split exists, fix a singularity: the
  // neighbour if that leaves this unit a convex corner, else this one.
  void fix_unresolved() {
    for (bool changed = true; changed;) {
      changed = false;
      for (const int u : processing_order()) {
        if (!floating(u)) continue;
        for (const Neighbour& nb : explore(u)) {
          const bool behind = nb.path.back().forward();
          if (nb.kind == FeatureKind::ConcaveSplit && concave_resolves(concave_[nb.id], behind)) {
            changed = cut_concave(concave_[nb.id]) || changed;
            continue;
          }
          if (nb.kind == FeatureKind::Unit && fixable(nb.id) && neighbour_fix_convex(nb)) {
            fix(nb.id);
            notes_.push_back("fixed a k = " + std::to_string(units_[nb.id].k) + " singularity next to another");
          } else if (nb.kind == FeatureKind::Unit && !fixable(u)) {
            continue;  // inseparable from a singularity that cannot be fixed: they may share a block
          } else if (fixable(u)) {
            fix(u);
            notes_.push_back("fixed a k = " + std::to_string(units_[u].k) + " singularity: no permitted split");
          } else {
            continue;
          }
          changed = true;
          break;
        }
      }
    }
  }

  // Whether fixing the neighbouring unit at the end of the path leaves the
  // exploring unit a straight or convex corner there.
  bool neighbour_fix_convex(const Neighbour& nb) const {
    const Unit& v = units_[nb.id];
    if (v.members.size() != 1) {
      const std::optional<Gathering> g = junction_gathering(nb.id);
      if (!g) return false;
      // The exploring unit's block takes the sector of the edge its path reaches the junction by.
      int sector = nb.path.back().edge;
      bool at_start = !nb.path.back().forward();
      for (const Step& st : nb.path) {
        const bool toward_start = !st.forward();
        if (st.to == (toward_start ? 0.0 : point_count(st.edge) - 1.0) &&
            end_vertex(st.edge, toward_start) == g->vertex)
          sector = st.edge, at_start = toward_start;
      }
      const int type = 2 - gathered_away_q(*g, sector, at_start);
      return type >= 1 && type <= 2;
    }
    const Location& loc = locations_[v.members.front()];
    const Step& last = nb.path.back();
    int type = 0;
    if (loc.vertex >= 0) {
      const bool at_start = last.to == 0.0;
      type = 2 - away_q(last.edge, at_start);
    } else {
      const int i = step_of(loc.edge, loc.s);
      type = last.forward() ? 2 + points_[loc.edge][i].q : 2 - points_[loc.edge][i + 1].q;
    }
    return type >= 1 && type <= 2;
  }

  // q of an edge at one of its ends, pointing away from that end's vertex.
  int away_q(int e, bool at_start) const { return at_start ? points_[e].front().q : -points_[e].back().q; }

  // ------------------------------------------------------- regions and walks

  // Components of the axis between the cuts: node ids for vertices and for
  // the intervals of every edge between its cuts.
  struct Pieces {
    std::vector<std::vector<int>> cuts;  // per edge, cut indices sorted by s
    std::vector<int> base;               // first interval id of each edge
    std::vector<int> parent;
    int find(int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    }
    void join(int a, int b) { parent[find(a)] = find(b); }
  };

  Pieces pieces() const {
    Pieces p;
    p.cuts.resize(axis_.edges.size());
    for (std::size_t c = 0; c < cuts_.size(); ++c) {
      if (cuts_[c].edge >= 0) p.cuts[cuts_[c].edge].push_back(static_cast<int>(c));
    }
    int next = static_cast<int>(axis_.vertices.size());
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      auto& list = p.cuts[e];
      std::sort(list.begin(), list.end(), [&](int a, int b) { return cuts_[a].s < cuts_[b].s; });
      p.base.push_back(next);
      next += static_cast<int>(list.size()) + 1;
    }
    p.parent.resize(next);
    std::iota(p.parent.begin(), p.parent.end(), 0);
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      const MedialEdge& edge = axis_.edges[e];
      const int count = static_cast<int>(p.cuts[e].size());
      if (edge.from < 0) {
        p.join(p.base[e], p.base[e] + count);  // a closed loop: its first and last intervals meet
        continue;
      }
      const int from = end_vertex(static_cast<int>(e), true), to = end_vertex(static_cast<int>(e), false);
      if (contracted_[e]) {
        for (int i = 0; i <= count; ++i) p.join(from, p.base[e] + i);
        continue;
      }
      if (!vertex_cut(from)) p.join(from, p.base[e]);
      if (!vertex_cut(to)) p.join(to, p.base[e] + count);
    }
    return p;
  }

  int interval_of(const Pieces& p, int e, double s) const {
    int i = 0;
    for (int c : p.cuts[e]) {
      if (cuts_[c].s < s) ++i;
    }
    return p.base[e] + i;
  }

  // The component a flow singularity lies in, or -1 when it is on a cut.
  int component_of(Pieces& p, int m) const {
    const Location& loc = locations_[m];
    if (loc.vertex >= 0) return vertex_cut(loc.vertex) || boundary_fixed_.count(loc.vertex) ? -1 : p.find(loc.vertex);
    if (cut_at(loc.edge, loc.s)) return -1;
    return p.find(interval_of(p, loc.edge, loc.s));
  }

  const BoundaryPlace& side_place(const MedialPoint& m, bool forward) const { return forward ? m.right : m.left; }

  // Walks round every piece of the axis: one closed outline per boundary of a region.
  std::vector<Outline> walk_outlines() {
    make_splits();
    Pieces p = pieces();
    std::vector<Outline> outlines;
    if (axis_.edges.empty()) {
      // A disc: one finite contact, the whole outer loop round it.
      Outline o;
      Item all;
      all.a = all.b = index_.place(0, 0, face_.loops[0].edges[0].t_start);
      all.full = true;
      o.items.push_back(all);
      o.component = axis_.vertices.empty() ? 0 : p.find(0);
      outlines.push_back(o);
      return outlines;
    }
    std::set<std::tuple<int, bool, int>> visited;  // (edge, forward, interval)
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      if (contracted_[e]) continue;
      const int intervals = static_cast<int>(p.cuts[e].size()) + 1;
      for (int i = 0; i < intervals; ++i) {
        for (const bool forward : {true, false}) {
          if (visited.count({static_cast<int>(e), forward, i})) continue;
          Outline o = walk(p, static_cast<int>(e), forward, i, visited);
          o.component = p.find(p.base[e] + i);
          outlines.push_back(std::move(o));
        }
      }
    }
    return outlines;
  }

  // Position where interval i of edge e starts or ends, and the medial point there.
  double interval_start(const Pieces& p, int e, int i) const { return i == 0 ? 0.0 : cuts_[p.cuts[e][i - 1]].s; }
  double interval_end(const Pieces& p, int e, int i) const {
    const int count = static_cast<int>(p.cuts[e].size());
    return i == count ? point_count(e) - 1.0 : cuts_[p.cuts[e][i]].s;
  }

  Outline walk(const Pieces& p, int e0, bool fwd0, int i0, std::set<std::tuple<int, bool, int>>& visited) {
    Outline o;
    int e = e0, i = i0;
    bool fwd = fwd0;
    // The walk enters each interval at one end and leaves at the other.
    std::set<std::tuple<int, bool, int>> seen;
    for (int guard = 0; guard < 4 * static_cast<int>(cuts_.size() + axis_.edges.size()) + 8; ++guard) {
      // Every state has one successor and one predecessor, so a walk returns
      // to its start; a state met twice otherwise means an inconsistent axis.
      if (!seen.insert({e, fwd, i}).second) break;
      visited.insert({e, fwd, i});
      const int count = static_cast<int>(p.cuts[e].size());
      Item range;
      range.a = place_at(p, e, fwd, i, true);
      range.b = place_at(p, e, fwd, i, false);
      range.full = closed(e) && count == 0;
      range.advance = advance(p, e, fwd, i, range);
      o.items.push_back(range);
      const bool at_cut = fwd ? i < count : i > 0;
      if (at_cut) {
        const Cut& c = cuts_[p.cuts[e][fwd ? i : i - 1]];
        o.items.push_back(cut_item(c, fwd));
        fwd = !fwd;
      } else if (closed(e)) {
        i = fwd ? 0 : count;  // round the loop into its first (last) interval
      } else {
        const int v = end_vertex(e, !fwd);
        const bool at_start = !fwd;
        if (vertex_cut(v)) {
          o.items.push_back(vertex_item(v, e, at_start));
          fwd = !fwd;
        } else {
          const auto& list = ends_[v];
          std::size_t k = 0;
          while (k < list.size() && !(list[k].edge == e && list[k].at_start == at_start)) ++k;
          const End& next = list[(k + 1) % list.size()];
          e = next.edge;
          fwd = next.at_start;
          i = fwd ? 0 : static_cast<int>(p.cuts[e].size());
          // The boundary between the two edges' touches: empty at a junction,
          // the touched arc at a finite contact.
          Item gap;
          gap.a = range.b;
          gap.b = place_at(p, e, fwd, i, true);
          // Only a finite contact's disc touches an arc between two edges;
          // elsewhere the two touches are one point, at most a step apart
          // (which must never be read as the rest of the loop).
          if (axis_.vertices[v].kind != MedialVertexKind::FiniteContact)
            gap.advance = gap.a.loop == gap.b.loop ? signed_step(gap.a, gap.b) : 0.0;
          const auto fixed_here = boundary_fixed_.find(v);
          if (fixed_here != boundary_fixed_.end() && widest_gap(v) == static_cast<int>(k))
            gap.virtual_corners = fixed_here->second;
          o.items.push_back(gap);
        }
      }
      if (e == e0 && fwd == fwd0 && i == i0) {
        chain_ranges(o);
        return o;
      }
    }
    throw SelfCheckFailure("decomposition: a block outline does not close");
  }

  // How far the walking side's touching point moves along its loop over an
  // interval: the sum of the small steps between consecutive medial points,
  // so that touches that wobble back a little on a curved boundary never
  // turn a short range into the whole loop the other way round.
  std::optional<double> advance(const Pieces& p, int e, bool fwd, int i, const Item& range) const {
    if (range.full) return std::nullopt;
    const auto& pts = axis_.edges[e].points;
    const double lo = interval_start(p, e, i), hi = interval_end(p, e, i);
    std::vector<const BoundaryPlace*> places{&range.a};
    const int first = static_cast<int>(std::floor(lo)) + 1, last = static_cast<int>(std::ceil(hi)) - 1;
    if (fwd) {
      for (int k = first; k <= last; ++k) places.push_back(&pts[k].right);
    } else {
      for (int k = last; k >= first; --k) places.push_back(&pts[k].left);
    }
    places.push_back(&range.b);
    double total = 0.0;
    for (std::size_t k = 0; k + 1 < places.size(); ++k) {
      if (places[k]->loop != range.a.loop || places[k + 1]->loop != range.a.loop) return std::nullopt;
      total += signed_step(*places[k], *places[k + 1]);
    }
    return total;
  }

  // How far a range runs along its loop as walked, negative where it runs
  // back a little.
  double item_advance(const Item& it) const {
    if (it.full) return static_cast<double>(face_.loops[it.a.loop].edges.size());
    if (it.advance) return *it.advance;
    // Ends a sliver apart are one place, or two across an edge shorter than
    // a sliver (a fillet 7.6e-7 long between two lines on fuzz
    // filleted_33_390, where the touches before it had stepped back over it
    // and the run came out a whole edge short): the short way round, never
    // the rest of the loop.
    if (distance(it.a.point, it.b.point) <= sliver_length()) return signed_step(it.a, it.b);
    const double step = loop_position(it.b) - loop_position(it.a);
    return step > 0.0 ? step : step + static_cast<double>(face_.loops[it.a.loop].edges.size());
  }

  // The ranges between two splits of an outline (or all of a split-less
  // outline) run forwards along one loop from the first split's end to the
  // second's, their advances adding up to the run's. Where the touches of
  // the axis wobble back (near a curved end of the axis the touches of its
  // last points can lie beyond the end's own), a range's end lies behind its
  // start and would cover boundary its neighbour covers too, so a block
  // would overlap the next: each range is clamped to the run instead, never
  // behind the range before it, never past the run's end.
  void chain_ranges(Outline& o) const {
    const std::size_t count = o.items.size();
    std::size_t first = 0;
    while (first < count && !o.items[first].split) ++first;
    first = first == count ? 0 : (first + 1) % count;  // the start of a run
    for (std::size_t done = 0; done < count;) {
      std::vector<std::size_t> run;
      while (done < count && !o.items[(first + run.size()) % count].split) {
        run.push_back((first + run.size()) % count);
        ++done;
      }
      if (!run.empty()) chain_run(o, run);
      first = (first + run.size() + 1) % count;
      if (done < count) ++done;  // the split that ends the run
    }
  }

  // A range that does not start where the one before it ended (round a
  // closed axis edge, whose first and last points touch a hair apart) steps
  // there as a junction's gap would: the step counts in the run, and the
  // range starts at the end before it, or the two would overlap or part.
  void chain_run(Outline& o, const std::vector<std::size_t>& run) const {
    const int loop = o.items[run.front()].a.loop;
    // Each item's advance and the step to its start from the end before it,
    // as walked (before any end is moved below).
    std::vector<double> steps(run.size(), 0.0), advances(run.size(), 0.0);
    double total = 0.0;
    for (std::size_t k = 0; k < run.size(); ++k) {
      const Item& it = o.items[run[k]];
      if (it.full || it.a.loop != loop || it.b.loop != loop) return;
      if (k > 0) steps[k] = signed_step(o.items[run[k - 1]].b, it.a);
      advances[k] = item_advance(it);
      total += steps[k] + advances[k];
    }
    const double start = loop_position(o.items[run.front()].a), end = start + std::max(total, 0.0);
    double raw = start, at = start;  // the run so far as walked, and as clamped
    bool moved = false;              // whether `at` has left the walked position
    for (std::size_t k = 0; k < run.size(); ++k) {
      Item& it = o.items[run[k]];
      raw += steps[k] + advances[k];
      const double next = std::clamp(raw, at, end);
      if (moved || steps[k] != 0.0) it.a = place_at_position(loop, at);
      it.advance = next - at;
      at = next;
      moved = next != raw;
      if (moved && k + 1 < run.size()) it.b = place_at_position(loop, at);
    }
  }

  // The boundary place at an unwrapped loop position.
  BoundaryPlace place_at_position(int loop, double position) const {
    const int n = static_cast<int>(face_.loops[loop].edges.size());
    const double wrapped = position - n * std::floor(position / n);
    const int edge = std::min(static_cast<int>(wrapped), n - 1);
    const BoundaryEdge& e = face_.loops[loop].edges[edge];
    return index_.place(loop, edge, e.t_start + (wrapped - edge) * (e.t_end - e.t_start));
  }

  // The step from a to b along their loop, the short way round (negative
  // when b lies just behind a).
  double signed_step(const BoundaryPlace& a, const BoundaryPlace& b) const {
    const double n = static_cast<double>(face_.loops[a.loop].edges.size());
    const double step = loop_position(b) - loop_position(a);
    return step - n * std::round(step / n);
  }

  // The boundary place on the walking side at position s of interval i.
  BoundaryPlace place_at(const Pieces& p, int e, bool fwd, int i, bool entering) const {
    const int count = static_cast<int>(p.cuts[e].size());
    // Interval i is bounded by cut i - 1 below and cut i above.
    const bool low_end = fwd == entering;
    const int cut = low_end ? (i > 0 ? p.cuts[e][i - 1] : -1) : (i < count ? p.cuts[e][i] : -1);
    if (cut >= 0) return side_place(cuts_[cut].point, fwd);
    if (!closed(e) && vertex_cut(end_vertex(e, low_end)))
      return junction_place(end_vertex(e, low_end), e, low_end, fwd);
    return end_place(e, low_end, fwd);
  }

  // The touching place on one side (right: forwards) at an end of edge e,
  // continuing the edge's own touches: the end point carries its vertex's,
  // which at a junction touching several loops need not continue them (the
  // mesh flow follows the neighbour's touches there too). The neighbour is
  // the point the edge leaves from (leaving_point): an overshoot's points
  // have their sides swapped.
  BoundaryPlace end_place(int e, bool at_start, bool right) const {
    const auto& pts = axis_.edges[e].points;
    const MedialPoint& end = at_start ? pts.front() : pts.back();
    const BoundaryPlace& own = right ? end.right : end.left;
    if (pts.size() < 3) return own;
    const MedialPoint& next = leaving_neighbour(e, at_start);
    const BoundaryPlace& neighbour = right ? next.right : next.left;
    // A touch on another loop is surely the junction's, not the edge's; on
    // the same loop, a jump of more than twice the medial step is taken as
    // the junction's only in the strict attempt (near a curved end the
    // edge's own touch may move that fast and still continue).
    const bool jumps = neighbour.loop != own.loop || (strict_end_touches_ && distance(neighbour.point, own.point) >
                                                                                 2.0 * distance(next.p, end.p) + tol_);
    return jumps ? nearest_on_run(index_, neighbour, end.p) : own;
  }

  // The arm of a concave corner's cross a split meets the boundary along;
  // on a smooth edge it is arm 1 of the edge's own straight cross.
  int split_arm(const BoundaryPlace& place, int corner, int arm) const {
    if (corner >= 0) return arm;
    const int ci = place_corner(place);
    if (ci < 0) return 1;
    const Corner& c = face_.corners[ci];
    return place.edge == c.vertex ? 1 : c.nc - 1;
  }

  // The face corner a boundary place stands on, or -1.
  int place_corner(const BoundaryPlace& place) const {
    const Loop& loop = face_.loops[place.loop];
    const int n = static_cast<int>(loop.edges.size());
    for (const int v : {place.edge, (place.edge + 1) % n}) {
      const auto it = corner_of_.find({place.loop, v});
      if (it != corner_of_.end() && distance(face_.corners[it->second].position, place.point) <= tol_)
        return it->second;
    }
    return -1;
  }

  Item cut_item(const Cut& c, bool fwd) const {
    // Walking forwards the block is behind the cut: right side, bend, left side.
    const PointFlow& f = fwd ? c.behind : c.ahead;
    Item it;
    it.split = true;
    it.a = fwd ? c.point.right : c.point.left;
    it.b = fwd ? c.point.left : c.point.right;
    it.middle = c.point.p;
    it.bend = fwd ? 2 + f.q : 2 - f.q;
    it.arm_a = fwd ? split_arm(it.a, f.right_corner, f.right_arm) : split_arm(it.a, f.left_corner, f.left_arm);
    it.arm_b = fwd ? split_arm(it.b, f.left_corner, f.left_arm) : split_arm(it.b, f.right_corner, f.right_arm);
    it.split_a = it.split_b = c.splits.empty() ? -1 : c.splits.front();
    it.reversed_a = it.reversed_b = !fwd;
    return it;
  }

  // A fixed junction, entered along one of its edges: round that edge's sector.
  Item vertex_item(int v, int e, bool at_start) const {
    const PointFlow& f = at_start ? points_[e].front() : points_[e].back();
    // Arriving at the start walks backwards (left side first), at the end forwards.
    const bool fwd = !at_start;
    Item it;
    it.split = true;
    it.a = junction_place(v, e, at_start, fwd);
    it.b = junction_place(v, e, at_start, !fwd);
    it.middle = axis_.vertices[v].p;
    it.bend = 2 - away_q(e, at_start);
    it.arm_a = fwd ? split_arm(it.a, f.right_corner, f.right_arm) : split_arm(it.a, f.left_corner, f.left_arm);
    it.arm_b = fwd ? split_arm(it.b, f.left_corner, f.left_arm) : split_arm(it.b, f.right_corner, f.right_arm);
    it.split_a = radius_split(v, it.a.point);
    it.split_b = radius_split(v, it.b.point);
    it.reversed_a = false;  // radii run from the boundary to the vertex
    it.reversed_b = true;
    return it;
  }

  // An end's touch at a fixed junction, where its radius goes. Round the
  // junction each end's left touch is the next end's right one, unless the
  // medial axis pruned a branch between them (the boundary there an arc at
  // the junction's radius, its centre the junction): the sector between
  // the two touches then holds no edge, and no block would walk it. The
  // later end's right touch takes the earlier one's left, so that its block
  // runs along that arc.
  BoundaryPlace junction_place(int v, int e, bool at_start, bool right) const {
    const BoundaryPlace own = end_place(e, at_start, right);
    const auto& list = ends_[v];
    if (right != at_start || list.size() < 2) return own;  // not the side turned away from the earlier end
    std::size_t k = 0;
    while (k < list.size() && !(list[k].edge == e && list[k].at_start == at_start)) ++k;
    if (k == list.size()) return own;
    const End& before = list[(k + list.size() - 1) % list.size()];
    const BoundaryPlace left_of_before = end_place(before.edge, before.at_start, !before.at_start);
    return distance(left_of_before.point, own.point) > tol_ ? left_of_before : own;
  }

  int radius_split(int v, Vec2 touch) const {
    for (const Cut& c : cuts_) {
      if (c.vertex != v) continue;
      for (int s : c.splits) {
        if (distance(splits_[s].polyline.front(), touch) <= 1e3 * tol_) return s;
      }
    }
    return -1;
  }

  // ------------------------------------------------- checking the polygons

  // A polygon block must hold one unit, whole, and have only convex corners,
  // a single simple outline, and at most six sides. Fixes the units of blocks
  // that fail; returns whether anything changed.
  bool fix_invalid_polygons(const std::vector<Outline>& outlines) {
    Pieces p = pieces();
    std::map<int, std::vector<int>> units_in, outlines_of;
    std::set<int> broken_units;
    for (std::size_t u = 0; u < units_.size(); ++u) {
      if (!floating(static_cast<int>(u))) continue;
      std::set<int> comps;
      for (int m : units_[u].members) comps.insert(component_of(p, m));
      if (comps.size() != 1 || comps.count(-1)) {
        broken_units.insert(static_cast<int>(u));
        continue;
      }
      units_in[*comps.begin()].push_back(static_cast<int>(u));
    }
    for (std::size_t i = 0; i < outlines.size(); ++i) outlines_of[outlines[i].component].push_back(static_cast<int>(i));
    bool withdrew = false;
    for (const auto& [comp, list] : units_in) {
      bool ok = outlines_of[comp].size() == 1;
      if (ok) {
        // Several singularities in one convex block act as one merged node
        // (section 4.3): accepted when nothing could split them apart.
        int k = 0;
        for (int u : list) k += units_[u].k;
        ok = polygon_block(outlines[outlines_of[comp].front()], k) &&
             (list.size() == 1 || std::any_of(list.begin(), list.end(), [&](int u) { return !fixable(u); }));
      }
      if (ok && list.size() > 1 && std::none_of(list.begin(), list.end(), [&](int u) { return fixable(u); }) &&
          part_at_junction(comp, list))
        return true;
      if (!ok) broken_units.insert(list.begin(), list.end());
      // A singularity that cannot be fixed keeps its block: withdraw the
      // splits that make its reflex corners, so their own singularities get
      // fixed instead.
      if (!ok && list.size() == 1 && !fixable(list.front()) && outlines_of[comp].size() == 1) {
        withdrew = withdraw_reflex_splits(outlines[outlines_of[comp].front()]) || withdrew;
      }
    }
    bool changed = withdrew;
    for (int u : broken_units) {
      // A finite contact is moved onto its arc only once withdrawing splits has not helped.
      if (!fixable(u) && (changed || !boundary_fixable(u))) continue;
      fix(u);
      notes_.push_back("fixed a k = " + std::to_string(units_[u].k) +
                       " singularity: its block was not a convex polygon");
      changed = true;
    }
    return changed;
  }

  // Singularities that cannot be fixed (fillets' finite contacts) sharing
  // one convex block are one merged node; where a junction of the block's
  // axis lies between them, its radii part them instead, each into a convex
  // polygon of its own. A rounded rectangle's short side: its two fillets'
  // k = -1 merged into a k = -2 whose 2-sided block grows lopsided as the
  // elements shrink (0.40 at a hundredth of the diagonal); parted, a 3-sided
  // block round each fillet and a mapped middle. Kept only if so.
  bool part_at_junction(int comp, const std::vector<int>& list) {
    Pieces p = pieces();  // the same for every try: a failed one is taken back
    for (std::size_t v = 0; v < axis_.vertices.size(); ++v) {
      if (rep_[v] != static_cast<int>(v) || vertex_cut(static_cast<int>(v)) ||
          axis_.vertices[v].kind != MedialVertexKind::Junction || ends_[v].size() < 3 ||
          p.find(static_cast<int>(v)) != comp)
        continue;
      Cut c;
      c.vertex = static_cast<int>(v);
      c.reason = SplitReason::Resolve;
      cuts_.push_back(c);
      vertex_cuts_.insert(c.vertex);
      ++version_;
      if (parted_into_polygons(list)) {
        notes_.push_back("parted " + std::to_string(list.size()) +
                         " singularities that cannot be fixed at a junction between them");
        return true;
      }
      cuts_.pop_back();
      vertex_cuts_.erase(c.vertex);
      ++version_;
      make_splits();  // the splits of the outlines being checked, again
    }
    return false;
  }

  // Whether each unit now lies alone in a convex polygon block.
  bool parted_into_polygons(const std::vector<int>& list) {
    std::vector<Outline> outlines;
    try {
      outlines = walk_outlines();
    } catch (const SelfCheckFailure&) {
      return false;
    }
    Pieces p = pieces();
    std::map<int, int> unit_of;  // component -> the one unit in it
    for (int u : list) {
      std::set<int> comps;
      for (int m : units_[u].members) comps.insert(component_of(p, m));
      if (comps.size() != 1 || comps.count(-1) || !unit_of.emplace(*comps.begin(), u).second) return false;
    }
    for (const auto& [comp, u] : unit_of) {
      const Outline* only = nullptr;
      for (const Outline& o : outlines) {
        if (o.component != comp) continue;
        if (only) return false;
        only = &o;
      }
      if (!only || !polygon_block(*only, units_[u].k)) return false;
    }
    return true;
  }

  // Whether an outline can be a polygon block round singularities of net k:
  // convex or flat corners only, a single simple outline that never comes
  // back to a point, and at most six sides (k from -4 to +2).
  bool polygon_block(const Outline& o, int k) const {
    const std::vector<int> types = corner_types(o);
    return std::all_of(types.begin(), types.end(), [](int t) { return t == 1 || t == 2; }) && simple(o) &&
           !pinched(o) && k <= 2 && k >= -4;
  }

  bool withdraw_reflex_splits(const Outline& o) {
    const BlockRing flat = flatten(o);
    std::set<int> bad;
    const std::size_t count = flat.pieces.size();
    for (std::size_t i = 0; i < count; ++i) {
      if (flat.start_type[i] == 1 || flat.start_type[i] == 2) continue;
      for (const OutlinePiece* piece : {&flat.pieces[i], &flat.pieces[(i + count - 1) % count]}) {
        if (piece->split < 0) continue;
        const int c = split_owner_[piece->split];
        if (cuts_[c].reason == SplitReason::Resolve || cuts_[c].reason == SplitReason::ConcaveCorner) bad.insert(c);
      }
    }
    for (auto it = bad.rbegin(); it != bad.rend(); ++it) {
      withdrawn_.insert({cuts_[*it].edge, std::lround(cuts_[*it].origin * 1e6)});
      cuts_.erase(cuts_.begin() + *it);
      ++version_;
    }
    if (!bad.empty()) notes_.push_back("withdrew splits that left a singularity that cannot be fixed a reflex corner");
    return !bad.empty();
  }

  // A block outline that uses no split twice.
  static bool simple(const Outline& o) {
    std::set<int> seen;
    for (const Item& it : o.items) {
      if (!it.split) continue;
      if (!seen.insert(it.split_a).second) return false;
      if (it.split_b != it.split_a && !seen.insert(it.split_b).second) return false;
    }
    return true;
  }

  // A block outline that comes back to a point it left: round a hole whose
  // splits all end at one point (a blade's trailing edge, say). The block is
  // a disc only through that point, and a template's lines from its centre
  // to its sides' midpoints would cross the hole.
  bool pinched(const Outline& o) const {
    const BlockRing flat = flatten(o);
    std::vector<double> along;  // outline length to each piece's start
    double length = 0.0;
    for (const OutlinePiece& piece : flat.pieces) {
      along.push_back(length);
      for (std::size_t k = 1; k < piece.points.size(); ++k) length += distance(piece.points[k - 1], piece.points[k]);
    }
    const double apart = 1e-3 * face_.size;  // along the outline both ways, so no mere zero-length piece
    for (std::size_t i = 0; i < flat.pieces.size(); ++i) {
      for (std::size_t j = i + 1; j < flat.pieces.size(); ++j) {
        const double between = along[j] - along[i];
        if (between > apart && length - between > apart &&
            distance(flat.pieces[i].points.front(), flat.pieces[j].points.front()) <= sliver_length())
          return true;
      }
    }
    return false;
  }

  // Section 4.6: cut the cycles of the axis where the flow is straightest,
  // keeping the worst places to cut for the spanning forest (Kruskal).
  void connect_regions() {
    Pieces p = pieces();
    struct Candidate {
      std::tuple<int, int, double> cost;
      int edge, interval, point;
    };
    std::vector<Candidate> intervals;
    for (std::size_t e = 0; e < axis_.edges.size(); ++e) {
      if (contracted_[e]) continue;
      const int count = static_cast<int>(p.cuts[e].size());
      for (int i = 0; i <= count; ++i) {
        const double lo = interval_start(p, static_cast<int>(e), i), hi = interval_end(p, static_cast<int>(e), i);
        Candidate c{{1 << 20, 0, 0.0}, static_cast<int>(e), i, -1};
        for (int k = static_cast<int>(std::floor(lo)) + 1; k <= static_cast<int>(std::ceil(hi)) - 1; ++k) {
          const PointFlow& pf = points_[e][k];
          const MedialPoint& mp = axis_.edges[e].points[k];
          if (inside_a_group(mp.p) || distance(mp.left.point, mp.right.point) < 1e-6 * face_.size) continue;
          const bool smooth = pf.left_corner < 0 && pf.right_corner < 0;
          const double mid = std::abs(k - 0.5 * (lo + hi)) / std::max(hi - lo, 1.0);
          const std::tuple<int, int, double> cost{std::abs(pf.q) + (smooth ? 0 : 8),
                                                  static_cast<int>(pf.deviation / 0.035), mid};
          if (cost < c.cost) c.cost = cost, c.point = k;
        }
        intervals.push_back(c);
      }
    }
    // Worst first: they join the forest; a cheap interval closing a cycle is cut.
    std::sort(intervals.begin(), intervals.end(),
              [](const Candidate& a, const Candidate& b) { return a.cost > b.cost; });
    std::vector<int> parent(p.parent.size() + 2 * intervals.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    int fresh = static_cast<int>(p.parent.size());
    for (const Candidate& c : intervals) {
      const MedialEdge& edge = axis_.edges[c.edge];
      const int count = static_cast<int>(p.cuts[c.edge].size());
      // The interval's two end nodes: a vertex not cut, or a dead end at a cut.
      const auto node = [&](bool low) {
        const bool at_cut = low ? c.interval > 0 : c.interval < count;
        if (!at_cut && edge.from < 0) return p.base[c.edge];  // round a closed loop
        if (at_cut) return fresh++;
        const int v = end_vertex(c.edge, low);
        return vertex_cut(v) ? fresh++ : v;
      };
      const int a = find(node(true)), b = find(node(false));
      if (a != b) {
        parent[a] = b;
        continue;
      }
      if (c.point >= 0) {
        cut_edge_at_point(c.edge, c.point, SplitReason::Connect);
      } else {
        throw std::runtime_error(face_.name + ": decomposition: a loop of the medial axis has no point to split at");
      }
    }
  }

  // ------------------------------------------------------------ the result

  void make_splits() {
    splits_.clear();
    split_owner_.clear();
    for (std::size_t ci = 0; ci < cuts_.size(); ++ci) {
      Cut& c = cuts_[ci];
      c.splits.clear();
      if (c.edge >= 0) {
        c.splits.push_back(static_cast<int>(splits_.size()));
        split_owner_.push_back(static_cast<int>(ci));
        splits_.push_back({{c.point.right.point, c.point.p, c.point.left.point}, c.reason});
        continue;
      }
      // A fixed junction (with any junction at the same point): one radius
      // to every place its edges' ends touch.
      std::vector<Vec2> touched;
      for (const End& end : ends_[c.vertex]) {
        for (const bool right : {true, false}) {
          const Vec2 t = junction_place(c.vertex, end.edge, end.at_start, right).point;
          if (std::none_of(touched.begin(), touched.end(), [&](Vec2 q) { return distance(q, t) <= tol_; }))
            touched.push_back(t);
        }
      }
      for (const Vec2 t : touched) {
        c.splits.push_back(static_cast<int>(splits_.size()));
        split_owner_.push_back(static_cast<int>(ci));
        splits_.push_back({{t, axis_.vertices[c.vertex].p}, c.reason});
      }
    }
  }

  // The corner type at the start of every piece of the outline (2: none).
  std::vector<int> corner_types(const Outline& o) const { return flatten(o).start_type; }

  // Position along a loop: edge index plus the fraction of its parameter range.
  double loop_position(const BoundaryPlace& place) const {
    const Loop& loop = face_.loops[place.loop];
    const int n = static_cast<int>(loop.edges.size());
    if (place.corner >= 0 && place.corner_itself) return place.corner;
    const BoundaryEdge& e = loop.edges[place.edge];
    const double span = e.t_end - e.t_start;
    const double f = span != 0 ? std::clamp((place.t - e.t_start) / span, 0.0, 1.0) : 0.0;
    const double pos = place.edge + f;
    return pos >= n ? pos - n : pos;
  }

  // The pieces of boundary edges forward along a loop from a to b; a range
  // with virtual corners is also cut where they are (evenly along it), and
  // those pieces are marked as starting at one.
  std::vector<OutlinePiece> range_pieces(const Item& it, std::vector<bool>& starts_at_virtual, bool sampled) const {
    std::vector<OutlinePiece> result;
    const Loop& loop = face_.loops[it.a.loop];
    const int n = static_cast<int>(loop.edges.size());
    // Ends at one point are no range, unless the walk went round the loop
    // between them (a hole touched only by an axis edge from a fixed
    // junction back to itself).
    const double advance = item_advance(it);
    if (!(advance >= 1e-12)) return result;
    if (advance <= 0.5 * n && distance(it.a.point, it.b.point) <= sliver_length()) return result;
    const double pa = loop_position(it.a);
    const double pb = pa + advance;
    std::vector<std::pair<double, bool>> breaks;  // loop position, virtual corner there
    for (int k = static_cast<int>(std::floor(pa)) + 1; k < pb; ++k) breaks.emplace_back(k, false);
    for (int v = 0; v < it.virtual_corners; ++v)
      breaks.emplace_back(pa + (v + 0.5) / it.virtual_corners * (pb - pa), true);
    std::sort(breaks.begin(), breaks.end());
    breaks.emplace_back(pb, false);
    double lo = pa;
    bool virtual_start = false;
    for (const auto& [hi, is_virtual] : breaks) {
      if (hi - lo > 1e-15) {
        const int k = static_cast<int>(std::floor(lo + 1e-12));
        const BoundaryEdge& e = loop.edges[k % n];
        OutlinePiece piece;
        piece.loop = it.a.loop;
        piece.edge = k % n;
        piece.t_from = e.t_start + (lo - k) * (e.t_end - e.t_start);
        piece.t_to = e.t_start + (hi - k) * (e.t_end - e.t_start);
        piece.points.push_back(lo == pa ? it.a.point : lo == k ? e.start : edge_point(e, piece.t_from).p);
        const bool up = e.t_end >= e.t_start;
        for (double t : sampled ? edge_samples(it.a.loop, k % n) : std::vector<double>{}) {
          const bool inside = up ? (t > piece.t_from && t < piece.t_to) : (t < piece.t_from && t > piece.t_to);
          if (inside) piece.points.push_back(edge_point(e, t).p);
        }
        piece.points.push_back(hi == pb ? it.b.point : hi == k + 1.0 ? e.end : edge_point(e, piece.t_to).p);
        result.push_back(std::move(piece));
        starts_at_virtual.push_back(virtual_start);
      }
      lo = std::max(lo, hi);
      virtual_start = is_virtual;
    }
    drop_slivers_at_ends(result, starts_at_virtual, it);
    return result;
  }

  // Boundary between two split ends, or between a split end and a loop
  // vertex, shorter than this is no piece: one interval there would put two
  // nodes on one point.
  double sliver_length() const { return 1e-6 * face_.size; }

  // A split that ends a hair's breadth before a loop vertex (on a circle's
  // seam, say) leaves a piece of next to no length between them: one
  // interval there would put two nodes on one point. Such a piece goes, and
  // its neighbour reaches the split's end instead.
  void drop_slivers_at_ends(std::vector<OutlinePiece>& pieces, std::vector<bool>& starts_at_virtual,
                            const Item& it) const {
    const double sliver = sliver_length();
    const auto length = [](const OutlinePiece& p) { return distance(p.points.front(), p.points.back()); };
    const std::size_t first = starts_at_virtual.size() - pieces.size();
    if (pieces.size() > 1 && length(pieces.front()) <= sliver && !starts_at_virtual[first + 1]) {
      pieces.erase(pieces.begin());
      starts_at_virtual.erase(starts_at_virtual.begin() + static_cast<std::ptrdiff_t>(first + 1));
      pieces.front().points.front() = it.a.point;
    }
    if (pieces.size() > 1 && length(pieces.back()) <= sliver && !starts_at_virtual.back()) {
      pieces.pop_back();
      starts_at_virtual.pop_back();
      pieces.back().points.back() = it.b.point;
    }
  }

  // The corner type where a boundary edge ends (and the next starts) inside a range.
  int joint_type(int loop, int edge_index) const {
    const int n = static_cast<int>(face_.loops[loop].edges.size());
    const auto it = corner_of_.find({loop, (edge_index + 1) % n});
    return it == corner_of_.end() ? 2 : face_.corners[it->second].nc;
  }

  // How far the sampled outlines handed out may stray from the curved sides.
  double chord_tolerance() const { return 1e-4 * face_.size; }

  // Parameters of the points drawn along a boundary edge, computed once.
  const std::vector<double>& edge_samples(int loop, int edge) const {
    auto& cached = samples_[{loop, edge}];
    if (cached.empty()) cached = sample_edge_parameters(face_.loops[loop].edges[edge], chord_tolerance());
    return cached;
  }

  // The outline as pieces with the corner type at each piece's start;
  // sampled: with points along the curved pieces (for the blocks handed
  // out), else only their ends.
  BlockRing flatten(const Outline& o, bool sampled = false) const {
    BlockRing flat;
    // Per piece: the arm of the cross it leaves its start along and arrives
    // at its end along, where that end is a split's end on the boundary; a
    // boundary piece leaves along arm 0 and arrives along arm nc (2 if smooth).
    std::vector<int> arm_out, arm_in;
    std::vector<int> bend;  // per piece: elements at its start when it starts at a split's bend, else -1
    // A singularity fixed onto a point of the boundary (a curvature
    // contact's touch or a flare's corner: a range of no length) moves its
    // corners to the start of the next boundary piece: its elements there
    // less the corners (2 - 1 at a curvature contact with k = -1; a corner
    // of nc elements with a flare's k = +1 gets nc + 1).
    int at_point = 0;
    std::vector<int> moved;  // per piece: corners of a singularity fixed at its start, taken from its type
    for (const Item& it : o.items) {
      if (!it.split) {
        std::vector<bool> virtual_start;
        std::vector<OutlinePiece> pieces = range_pieces(it, virtual_start, sampled);
        if (pieces.empty()) at_point += it.virtual_corners;
        for (std::size_t k = 0; k < pieces.size(); ++k) {
          flat.pieces.push_back(std::move(pieces[k]));
          arm_out.push_back(0);
          arm_in.push_back(-1);
          bend.push_back(virtual_start[k] ? 1 : -1);  // a singularity fixed onto the boundary
          moved.push_back(at_point);
          at_point = 0;
        }
        continue;
      }
      // A fixed junction's radius whose touch the walk placed elsewhere than
      // the cut did has no split: a failed block, not a piece of nothing.
      if (it.split_a < 0 || it.split_b < 0)
        throw SelfCheckFailure("decomposition: a split on a block's outline through (" + std::to_string(it.middle.x) +
                               ", " + std::to_string(it.middle.y) + ") was never made");
      OutlinePiece first, second;
      first.split = it.split_a;
      first.reversed = it.reversed_a;
      first.points = {it.a.point, it.middle};
      second.split = it.split_b;
      second.reversed = it.reversed_b;
      second.points = {it.middle, it.b.point};
      flat.pieces.push_back(first);
      arm_out.push_back(it.arm_a);
      arm_in.push_back(-1);
      bend.push_back(-1);
      moved.push_back(0);
      flat.pieces.push_back(second);
      arm_out.push_back(-1);
      arm_in.push_back(it.arm_b);
      bend.push_back(it.bend);
      moved.push_back(0);
    }
    // The point was the outline's last item: its corners go to the first boundary piece.
    for (std::size_t i = 0; at_point != 0 && i < flat.pieces.size(); ++i) {
      if (flat.pieces[i].split < 0) moved[i] += at_point, at_point = 0;
    }
    const std::size_t count = flat.pieces.size();
    flat.start_type.assign(count, 2);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t prev = (i + count - 1) % count;
      const OutlinePiece& a = flat.pieces[prev];
      const OutlinePiece& b = flat.pieces[i];
      if (bend[i] >= 0) {
        flat.start_type[i] = bend[i];
      } else if (a.split < 0 && b.split < 0) {
        flat.start_type[i] = a.edge != b.edge || count == 1 ? joint_type(a.loop, a.edge) : 2;
      } else {
        // A split's end on the boundary: the arms between the two sides.
        int nc = 2;
        if (a.split < 0) {
          BoundaryPlace place;
          place.loop = a.loop;
          place.edge = a.edge;
          place.point = b.points.front();
          const int ci = place_corner(place);
          if (ci >= 0) nc = face_.corners[ci].nc;
        }
        flat.start_type[i] = (a.split < 0 ? nc : arm_in[prev]) - (b.split < 0 ? 0 : arm_out[i]);
      }
      flat.start_type[i] -= moved[i];
    }
    return flat;
  }

  double piece_area(const OutlinePiece& piece, Vec2 ref) const {
    if (piece.split >= 0 || piece.loop < 0) {
      double a = 0.0;
      for (std::size_t i = 0; i + 1 < piece.points.size(); ++i)
        a += 0.5 * cross(piece.points[i] - ref, piece.points[i + 1] - piece.points[i]);
      return a;
    }
    const BoundaryEdge& e = face_.loops[piece.loop].edges[piece.edge];
    const Vec2 start = edge_point(e, piece.t_from).p, end = edge_point(e, piece.t_to).p;
    return 0.5 * cross(piece.points.front() - ref, start - piece.points.front()) +
           edge_area_integral(e, piece.t_from, piece.t_to, ref) + 0.5 * cross(end - ref, piece.points.back() - end);
  }

  Decomposition finish(const std::vector<Outline>& outlines) {
    Decomposition d;
    d.splits = splits_;
    d.notes = notes_;
    Pieces p = pieces();
    std::map<int, int> unit_in;   // component -> its floating singularity in the output
    std::map<int, int> k_inside;  // component -> sum of the flow's k strictly inside
    for (std::size_t m = 0; m < locations_.size(); ++m) {
      const int comp = component_of(p, static_cast<int>(m));
      if (comp >= 0) k_inside[comp] += flow_.singularities[m].k;
    }
    std::map<int, std::vector<int>> floating_in;  // component -> its floating units
    for (std::size_t u = 0; u < units_.size(); ++u) {
      if (units_[u].k == 0) continue;  // a regular node for the mesh
      if (units_[u].fixed) {
        // Members gathered at a junction are its node.
        const Location& first = locations_[units_[u].members.front()];
        const bool gathered = units_[u].members.size() > 1 && first.vertex >= 0 &&
                              std::all_of(units_[u].members.begin(), units_[u].members.end(),
                                          [&](int m) { return locations_[m].vertex == first.vertex; });
        const Vec2 p = gathered ? axis_.vertices[first.vertex].p : units_[u].p;
        d.singularities.push_back({p, units_[u].k, true, units_[u].members});
      } else {
        floating_in[component_of(p, units_[u].members.front())].push_back(static_cast<int>(u));
      }
    }
    for (const auto& [comp, list] : floating_in) {
      // Singularities sharing a block are one merged node of the mesh.
      DecomposedSingularity merged{{0, 0}, 0, false, {}};
      for (int u : list) {
        merged.p = merged.p + units_[u].p / static_cast<double>(list.size());
        merged.k += units_[u].k;
        merged.members.insert(merged.members.end(), units_[u].members.begin(), units_[u].members.end());
      }
      if (list.size() > 1)
        d.notes.push_back("merged " + std::to_string(list.size()) + " singularities that share a block");
      unit_in[comp] = static_cast<int>(d.singularities.size());
      d.singularities.push_back(merged);
    }
    std::map<int, int> outline_count;
    for (const Outline& o : outlines) ++outline_count[o.component];
    for (const Outline& o : outlines) {
      if (outline_count[o.component] != 1) throw SelfCheckFailure("decomposition: a block is not simply connected");
      Block b = make_block(o);
      if (const std::string problem = outline_problem(b); !problem.empty()) throw SelfCheckFailure(problem);
      const int sum = quarter_turns(b);
      if (sum != 4 + k_inside[o.component] && lenient_ && unit_in.count(o.component) == 0 &&
          make_submappable(face_, b, tol_, options_.submap_corners_follow_turning)) {
        d.notes.push_back("a block's corner types from the mesh flow did not close up; it was re-typed by its angles");
      } else if (sum != 4 + k_inside[o.component]) {
        throw SelfCheckFailure("decomposition: the corners of a block sum to " + std::to_string(sum) +
                               " quarter turns, its singularities need " + std::to_string(4 + k_inside[o.component]));
      }
      const auto it = unit_in.find(o.component);
      const bool convex =
          std::all_of(b.corners.begin(), b.corners.end(), [](const BlockCorner& c) { return c.type == 1; });
      if (it != unit_in.end()) {
        b.singularity = it->second;
        if (!holds_its_singularity(b, d))
          throw SelfCheckFailure("decomposition: a block's singularity lies outside its outline");
        b.kind = convex && simple(o) && b.corners.size() <= 6 ? BlockKind::Polygon : BlockKind::Submap;
        if (b.kind == BlockKind::Submap) {
          d.fallback = true;
          d.notes.push_back("a k = " + std::to_string(d.singularities[it->second].k) +
                            " singularity could be neither given a convex block nor fixed");
        }
      } else {
        b.kind = convex && b.corners.size() == 4 && simple(o) ? BlockKind::Polygon : BlockKind::Submap;
        Block typed = b;
        const bool typeable = typed.kind == BlockKind::Polygon ||
                              make_submappable(face_, typed, tol_, options_.submap_corners_follow_turning);
        if ((!typeable || has_flat_convex_corner(typed)) && simple(o) && flat_cornered_to_polygon(b, d)) {
          d.notes.push_back(
              "a block of " + std::to_string(b.corners.size()) +
              " corners became a polygon round a k = " + std::to_string(static_cast<int>(b.corners.size()) - 4) +
              " of its own, not a quadrilateral with a corner where its outline runs straight");
        } else if (typeable) {
          b = std::move(typed);
        } else if (!cusp_to_polygon(o, b, d)) {
          throw SelfCheckFailure("decomposition: a block's corners cannot be typed for submapping");
        }
      }
      if (b.kind == BlockKind::Submap && b.singularity < 0) find_facing_sides(b);
      d.blocks.push_back(std::move(b));
    }
    for (std::size_t b = 0; b < d.blocks.size(); ++b) {
      int carved = 0;
      while (carved < kMaxSectorsABlock && carve_fillet_sector(d, b)) ++carved;
    }
    for (std::size_t b = 0; b < d.blocks.size(); ++b) {
      int cut = 0;
      while (cut < kMaxSectorsABlock && cut_across_wrapped_side(d, b)) ++cut;
    }
    double total = 0.0;  // of the blocks as delivered, fillet sectors cut off
    for (const Block& b : d.blocks) total += b.area;
    if (!adds_up_to_the_face(total)) {
      std::ostringstream text;
      text << std::setprecision(10) << "decomposition: the blocks' areas add up to " << total << ", the face's is "
           << face_.area << " (off by " << std::setprecision(3) << (total - face_.area) / face_.area << " of it)";
      throw SelfCheckFailure(text.str());
    }
    return d;
  }

  // A fixed k = -1 finite contact is a convex corner on its arc where the
  // outline runs straight on (a fillet's middle): the one element there has
  // an angle near 180 degrees, nearer as the elements shrink. Where that arc
  // is one whole boundary edge in a submapped block, turns by 45 to 135
  // degrees, and the normals at its ends meet near the contact (its centre),
  // the two radii from there to the arc's ends (a split) cut the arc's sector
  // off the block as a triangle round the singularity, floating again; the
  // rest keeps the arc's turning as two convex corners and a reflex one.
  // Returns whether block b was cut.
  bool carve_fillet_sector(Decomposition& d, std::size_t b) const {
    if (d.blocks[b].kind != BlockKind::Submap) return false;
    const BlockRing ring = ring_of(d.blocks[b]);
    const std::vector<OutlinePiece>& pieces = ring.pieces;
    const std::size_t n = pieces.size();
    const std::vector<double> angles = interior_angles(pieces, ring.start_type, tol_);
    for (std::size_t i = 0; i < n; ++i) {
      const auto on_edge = [&](std::size_t k) {
        return pieces[k].split < 0 && pieces[k].loop >= 0 && pieces[k].loop == pieces[i].loop &&
               pieces[k].edge == pieces[i].edge;
      };
      if (ring.start_type[i] != 1 || angles[i] <= kFlat || !on_edge((i + n - 1) % n)) continue;
      std::size_t first = i, last = i;  // the pieces along the edge, first to last
      while (on_edge((first + n - 1) % n) && (first + n - 1) % n != i) first = (first + n - 1) % n;
      while (on_edge((last + 1) % n) && (last + 1) % n != first) last = (last + 1) % n;
      if ((last + 1) % n == first) continue;  // the whole outline: no rest
      bool one_corner = ring.start_type[first] == 2 && ring.start_type[(last + 1) % n] == 2;
      for (std::size_t k = (first + 1) % n; k != (last + 1) % n; k = (k + 1) % n)
        one_corner = one_corner && (k == i || ring.start_type[k] == 2);
      const BoundaryEdge& edge = face_.loops[pieces[i].loop].edges[pieces[i].edge];
      const double t_a = pieces[first].t_from, t_b = pieces[last].t_to;
      const double span = std::abs(edge.t_end - edge.t_start);
      const bool whole = std::min(std::abs(t_a - edge.t_start), std::abs(t_a - edge.t_end)) <= 1e-9 * span &&
                         std::min(std::abs(t_b - edge.t_start), std::abs(t_b - edge.t_end)) <= 1e-9 * span;
      if (!one_corner || !whole) continue;
      const double along = t_b > t_a ? 1.0 : -1.0;
      const Vec2 a = pieces[first].points.front(), c = pieces[last].points.back();
      const Vec2 ta = normalized(along * edge_point(edge, t_a).d1), tc = normalized(along * edge_point(edge, t_b).d1);
      const double turn = signed_angle(ta, tc);
      if (turn < 0.25 * kPi || turn > 0.75 * kPi) continue;
      // The inward normals' meeting point: a + ra perp(ta) = c + rc perp(tc).
      const Vec2 na = perp(ta), nc = perp(tc);
      const double det = cross(nc, na);
      const double ra = cross(nc, c - a) / det, rc = cross(na, c - a) / det;
      if (!(ra > 0.0 && rc > 0.0) || std::abs(ra - rc) > 0.25 * std::max(ra, rc)) continue;
      const Vec2 centre = a + ra * na;
      int contact = -1;
      for (std::size_t j = 0; j < d.singularities.size(); ++j) {
        const DecomposedSingularity& sing = d.singularities[j];
        if (sing.fixed && sing.k == -1 && distance(sing.p, centre) <= 0.25 * std::min(ra, rc))
          contact = static_cast<int>(j);
      }
      if (contact < 0 || !inside_polygon(d.blocks[b].outline, centre)) continue;
      const std::vector<Vec2>& outline = d.blocks[b].outline;
      bool crosses = false;
      for (std::size_t k = 0; k < outline.size() && !crosses; ++k) {
        const Vec2 p = outline[k], q = outline[(k + 1) % outline.size()];
        crosses = segments_cross(a, centre, p, q, 1e-9) || segments_cross(centre, c, p, q, 1e-9);
      }
      if (crosses) continue;

      const int split = static_cast<int>(d.splits.size());
      const auto radius = [&](Vec2 from, Vec2 to, bool reversed) { return split_piece(split, from, to, reversed); };
      BlockRing sector, rest;
      for (std::size_t k = first;; k = (k + 1) % n) {
        sector.pieces.push_back(pieces[k]);
        sector.start_type.push_back(k == first ? 1 : 2);
        if (k == last) break;
      }
      sector.pieces.push_back(radius(c, centre, true));
      sector.start_type.push_back(1);
      sector.pieces.push_back(radius(centre, a, true));
      sector.start_type.push_back(1);
      for (std::size_t k = (last + 1) % n; k != first; k = (k + 1) % n) {
        rest.pieces.push_back(pieces[k]);
        rest.start_type.push_back(k == (last + 1) % n ? 1 : ring.start_type[k]);
      }
      rest.pieces.push_back(radius(a, centre, false));
      rest.start_type.push_back(1);
      rest.pieces.push_back(radius(centre, c, false));
      rest.start_type.push_back(3);

      Block triangle;
      set_outline(triangle, sector, tol_);
      triangle.kind = BlockKind::Polygon;
      triangle.area = ring_area(sector);
      const std::optional<Vec2> middle = centroid_inside(triangle.outline);
      Block cut = d.blocks[b];
      set_outline(cut, rest, tol_);
      cut.area = ring_area(rest);  // its own outline's, so that the areas' sum checks the cut
      cut.facing.clear();
      cut.facing_outside.clear();
      if (!middle || !(triangle.area > 0.0) || !(cut.area > 0.0) ||
          !make_submappable(face_, cut, tol_, options_.submap_corners_follow_turning))
        continue;
      find_facing_sides(cut);
      triangle.singularity = contact;
      d.singularities[contact].p = *middle;
      d.singularities[contact].fixed = false;
      d.splits.push_back({{a, centre, c}, SplitReason::Resolve});
      d.blocks[b] = std::move(cut);
      d.blocks.push_back(std::move(triangle));
      d.notes.push_back("a k = -1 fixed on its arc got the arc's sector as its own triangle");
      return true;
    }
    return false;
  }

  // A submapped block with a side that runs round a hole (or a deep smooth
  // bay) turning in by kWrapped or more with no corner on it wraps its
  // lattice round that side: the elements along it fan, and the harmonic
  // layout folds beside it as they shrink (fuzz seed 45's blobs at 0.01 of
  // the diagonal). A cut along the side's normal from its middle to the
  // boundary across the block parts it into two, each with a right-angled
  // corner at either end of the cut and a side turning half as far, kept if
  // both are submappable with no convex corner where the outline runs on.
  // Returns whether block b was cut.
  bool cut_across_wrapped_side(Decomposition& d, std::size_t b) const {
    if (d.blocks[b].kind != BlockKind::Submap || d.blocks[b].singularity >= 0) return false;
    const BlockRing ring = ring_of(d.blocks[b]);
    const std::vector<OutlinePiece>& pieces = ring.pieces;
    const std::size_t n = pieces.size();
    const std::vector<double> angles = interior_angles(pieces, ring.start_type, tol_);
    std::vector<double> lengths;
    for (const OutlinePiece& piece : pieces) lengths.push_back(polyline_length(piece.points));
    for (std::size_t first = 0; first < n; ++first) {
      if (ring.start_type[first] == 2) continue;
      std::size_t last = first;  // the side: first up to the piece before the next corner
      while (ring.start_type[(last + 1) % n] == 2 && (last + 1) % n != first) last = (last + 1) % n;
      double turning = 0.0, length = 0.0;
      bool boundary = true;
      for (std::size_t k = first;; k = (k + 1) % n) {
        boundary = boundary && pieces[k].split < 0 && pieces[k].loop >= 0;
        turning += piece_quarters(pieces[k], tol_) + (k == first ? 0.0 : 2.0 - angles[k]);
        length += lengths[k];
        if (k == last) break;
      }
      // A side all round a hole (a ring opened by one cut) is the ring's
      // lattice, not a wrap.
      if (!boundary || turning > -kWrapped || turning < -kRound) continue;
      // The side's middle, by length, on its piece's curve.
      std::size_t at = first;
      double before = 0.0;
      while (at != last && before + lengths[at] < 0.5 * length) {
        before += lengths[at];
        at = (at + 1) % n;
      }
      const OutlinePiece& side_piece = pieces[at];
      const double fraction = (0.5 * length - before) / lengths[at];
      const double t_h = side_piece.t_from + fraction * (side_piece.t_to - side_piece.t_from);
      const BoundaryEdge& side_edge = face_.loops[side_piece.loop].edges[side_piece.edge];
      const CurvePoint on_side = edge_point(side_edge, t_h);
      const Vec2 h = on_side.p;
      const Vec2 inward = perp(normalized((side_piece.t_to > side_piece.t_from ? 1.0 : -1.0) * on_side.d1));
      // The first piece of the outline the normal from h meets.
      std::size_t hit = n;
      double reach = std::numeric_limits<double>::infinity();
      Vec2 o{0, 0};
      for (std::size_t k = 0; k < n; ++k) {
        if (k == at) continue;
        const std::vector<Vec2>& pts = pieces[k].points;
        for (std::size_t j = 1; j < pts.size(); ++j) {
          const Vec2 e = pts[j] - pts[j - 1];
          const double det = cross(inward, e);
          if (std::abs(det) <= 1e-12 * norm(e)) continue;
          const double along = cross(pts[j - 1] - h, e) / det, within = cross(pts[j - 1] - h, inward) / det;
          if (along > tol_ && along < reach && within >= 0.0 && within <= 1.0) {
            reach = along, hit = k;
            o = h + along * inward;
          }
        }
      }
      if (hit == n || pieces[hit].split >= 0 || pieces[hit].loop < 0) continue;
      const OutlinePiece& far_piece = pieces[hit];
      const BoundaryEdge& far_edge = face_.loops[far_piece.loop].edges[far_piece.edge];
      const double t_o = closest_param(far_edge, far_piece.t_from, far_piece.t_to, o).first;
      o = edge_point(far_edge, t_o).p;
      if (distance(o, far_piece.points.front()) <= 1e3 * tol_ || distance(o, far_piece.points.back()) <= 1e3 * tol_)
        continue;
      // Right-angled enough at the far end too, on both sides of the cut.
      const Vec2 far_tangent =
          normalized((far_piece.t_to > far_piece.t_from ? 1.0 : -1.0) * edge_point(far_edge, t_o).d1);
      const double meets = std::abs(signed_angle(far_tangent, normalized(h - o)));
      if (meets < 0.25 * kPi || meets > 0.75 * kPi) continue;

      const int split = static_cast<int>(d.splits.size());
      // The cut's ends on their pieces' curves, the pieces sampled as a split's run is.
      const auto part = [&](const OutlinePiece& piece, double from, double to) {
        return piece_part(face_, piece, from, to, kCutPieceSamples);
      };
      // A half: its first piece (from a new corner at one end of the cut),
      // the ring's pieces after `after` up to `end`, the piece of `end` up to
      // the cut, and back across the cut. Block one runs from h round to o,
      // block two from o round to h.
      const auto half_ring = [&](OutlinePiece start, std::size_t after, std::size_t end, OutlinePiece last, Vec2 from,
                                 Vec2 to, bool reversed) {
        BlockRing r;
        r.pieces.push_back(std::move(start));
        r.start_type.push_back(1);
        for (std::size_t k = (after + 1) % n; k != end; k = (k + 1) % n) {
          r.pieces.push_back(pieces[k]);
          r.start_type.push_back(ring.start_type[k]);
        }
        r.pieces.push_back(std::move(last));
        r.start_type.push_back(ring.start_type[end]);
        r.pieces.push_back(split_piece(split, from, to, reversed));
        r.start_type.push_back(1);
        return r;
      };
      const BlockRing one = half_ring(part(side_piece, t_h, side_piece.t_to), at, hit,
                                      part(far_piece, far_piece.t_from, t_o), o, h, true);
      const BlockRing two = half_ring(part(far_piece, t_o, far_piece.t_to), hit, at,
                                      part(side_piece, side_piece.t_from, t_h), h, o, false);

      std::array<Block, 2> halves{d.blocks[b], d.blocks[b]};
      bool fine = true;
      for (int k = 0; k < 2 && fine; ++k) {
        Block& half = halves[k];
        const BlockRing& r = k == 0 ? one : two;
        set_outline(half, r, tol_);
        half.area = ring_area(r);
        half.facing.clear();
        half.facing_outside.clear();
        fine = half.area > 0.0 && make_submappable(face_, half, tol_, options_.submap_corners_follow_turning) &&
               !has_flat_convex_corner(half);
      }
      if (!fine) continue;
      for (Block& half : halves) find_facing_sides(half);
      d.splits.push_back({{h, o}, SplitReason::Resolve});
      d.blocks[b] = std::move(halves[0]);
      d.blocks.push_back(std::move(halves[1]));
      d.notes.push_back("a block whose side ran round a hole or bay was cut across from that side's middle");
      return true;
    }
    return false;
  }

  static double polyline_length(const std::vector<Vec2>& points) {
    double length = 0.0;
    for (std::size_t k = 1; k < points.size(); ++k) length += distance(points[k - 1], points[k]);
    return length;
  }

  // A straight piece of a new split, run forwards or backwards.
  static OutlinePiece split_piece(int split, Vec2 from, Vec2 to, bool reversed) {
    OutlinePiece piece;
    piece.split = split;
    piece.reversed = reversed;
    piece.points = {from, to};
    return piece;
  }

  // Whether a block has a convex corner where its outline runs nearly
  // straight on (interior angle over kFlat).
  bool has_flat_convex_corner(const Block& b) const {
    const BlockRing ring = ring_of(b);
    const std::vector<double> angles = interior_angles(ring.pieces, ring.start_type, tol_);
    for (std::size_t i = 0; i < ring.pieces.size(); ++i)
      if (ring.start_type[i] == 1 && angles[i] > kFlat) return true;
    return false;
  }

  // A block with no singularity whose outline has two or three sharp convex
  // corners and otherwise runs on, straight or gently curving, cannot be
  // submapped without more convex corners where it runs nearly straight:
  // the one element there gets an angle near 180 degrees, ever nearer as
  // the elements shrink (a smooth blob's wedges between two cuts: 0.32 at
  // the default size, 0.06 at a tenth of it). Such a block becomes the
  // logically convex polygon of its m sharp corners round a singularity of
  // k = m - 4 of its own at its centroid (a triangle round a k = -1, a D
  // round a k = -2): valence-3 nodes that smoothing floats to where their
  // elements are best. Returns false when the block is not such a block.
  bool flat_cornered_to_polygon(Block& b, Decomposition& d) const {
    // The corners are the piece starts sharper than kSharp (135 degrees); no
    // other may turn in by more than kReflex (198 degrees), nor a side turn
    // along it by more than 135 degrees (a triangle's; a quarter turn kept
    // a census face's with a 100-degree arc a submap) or a half turn (a D's).
    constexpr double kSharp = 1.5, kReflex = 2.2;
    const BlockRing ring = ring_of(b);
    const std::vector<OutlinePiece>& pieces = ring.pieces;
    const std::vector<double> angles = interior_angles(pieces, ring.start_type, tol_);
    std::vector<std::size_t> sharp;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (angles[i] <= kSharp) sharp.push_back(i);
      if (angles[i] > kReflex || angles[i] <= 0.0) return false;
    }
    const int m = static_cast<int>(sharp.size());
    if (m != 2 && m != 3) return false;
    const double side_turning = m == 3 ? 1.5 : 2.0;
    const std::optional<Vec2> centroid = centroid_inside(b.outline);
    if (!centroid) return false;
    std::vector<BlockCorner> corners;
    std::vector<BlockSide> sides;
    double turning = 0.0;  // along the side so far, in quarter turns
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const std::size_t i = (sharp.front() + k) % pieces.size();
      if (std::find(sharp.begin(), sharp.end(), i) != sharp.end()) {
        corners.push_back({pieces[i].points.front(), 1});
        sides.emplace_back();
        turning = 0.0;
      } else {
        turning += 2.0 - angles[i];
      }
      sides.back().pieces.push_back(pieces[i]);
      turning += piece_quarters(pieces[i], tol_);
      if (std::abs(turning) > side_turning) return false;
    }
    b.corners = std::move(corners);
    b.sides = std::move(sides);
    b.kind = BlockKind::Polygon;
    b.singularity = static_cast<int>(d.singularities.size());
    d.singularities.push_back({*centroid, m - 4, false, {}});
    return true;
  }

  // A block of convex corners and cusps (corners of no element: a sharp
  // corner the flow gives 0, or the bend of a split near the end of a
  // branch) with no singularity, which no typing submaps without a convex
  // corner where its outline runs straight (a sharp triangle): each cusp
  // gets one element, and the block becomes the logically convex polygon of
  // its m corners round a singularity of k = m - 4 of its own (a triangle's
  // three quads round a k = -1), at its centroid. Returns false when the
  // block is not such a block.
  bool cusp_to_polygon(const Outline& o, Block& b, Decomposition& d) const {
    const int m = static_cast<int>(b.corners.size());
    const auto cusp = [](const BlockCorner& c) { return c.type == 0; };
    if (m < 3 || m > 6 || !simple(o) || std::none_of(b.corners.begin(), b.corners.end(), cusp) ||
        std::any_of(b.corners.begin(), b.corners.end(), [](const BlockCorner& c) { return c.type > 1; }))
      return false;
    const std::optional<Vec2> centroid = centroid_inside(b.outline);
    if (!centroid) return false;
    for (BlockCorner& c : b.corners) c.type = 1;
    b.kind = BlockKind::Polygon;
    if (m != 4) {
      b.singularity = static_cast<int>(d.singularities.size());
      d.singularities.push_back({*centroid, m - 4, false, {}});
    }
    d.notes.push_back("a block with a cusp that no typing submaps became a " + std::to_string(m) +
                      "-sided polygon (its cusp one element)");
    return true;
  }

  // The checks finish() makes of every block, made again after the
  // orthogonal joins reshaped some: pieces meeting, no split pieces
  // crossing, counter-clockwise, corners closing up as before (`unjoined`,
  // block for block), each singularity's members inside its block, and the
  // areas adding up to the face's.
  bool passes_block_checks(const Decomposition& d, const Decomposition& unjoined) const {
    if (d.blocks.size() != unjoined.blocks.size()) return false;
    double total = 0.0;
    for (std::size_t i = 0; i < d.blocks.size(); ++i) {
      const Block& b = d.blocks[i];
      if (!outline_problem(b).empty() || quarter_turns(b) != quarter_turns(unjoined.blocks[i]) ||
          (b.singularity >= 0 && !holds_its_singularity(b, d)))
        return false;
      total += b.area;
    }
    return adds_up_to_the_face(total);
  }

  // What is wrong with a block's outline, or empty: pieces that miss each
  // other or their edges, split pieces that cross, or an outline that runs
  // clockwise (a block turned inside out: the areas may still add up, the
  // others' covering it twice).
  std::string outline_problem(const Block& b) const {
    if (const double gap = widest_joint(b); gap > 1e-5 * face_.size + 10 * face_.tolerance)
      return "decomposition: pieces of a block's outline miss each other or their edges by " + std::to_string(gap);
    if (splits_cross(b)) return "decomposition: a block's outline crosses itself";
    if (!(b.area > 0.0)) return "decomposition: a block's outline runs clockwise (no area)";
    return {};
  }

  // sum(2 - type) over the block's corners: 4 + the k it holds when it closes up.
  static int quarter_turns(const Block& b) {
    int sum = 0;
    for (const BlockCorner& c : b.corners) sum += 2 - c.type;
    return sum;
  }

  // Whether every member of the block's singularity lies in its outline.
  bool holds_its_singularity(const Block& b, const Decomposition& d) const {
    for (int m : d.singularities[b.singularity].members)
      if (!holds(b.outline, flow_.singularities[m].p)) return false;
    return true;
  }

  bool adds_up_to_the_face(double total_area) const {
    return std::abs(total_area - face_.area) <= 1e-9 * face_.area + 1e-6 * face_.tolerance * face_.size;
  }

  // Whether p lies inside a closed outline or on it. Where the medial axis
  // misses a branch, a piece of axis can sweep a region apart from the one
  // its outline walks round: the areas still add up, but a singularity on
  // that piece would be put in the wrong block.
  bool holds(const std::vector<Vec2>& outline, Vec2 p) const {
    return inside_polygon(outline, p) || distance_to_polygon(outline, p) <= chord_tolerance();
  }

  // Whether two split pieces of a block's outline cross (two splits ending
  // at nearly one boundary point in the wrong order make a bow-tie whose
  // area still adds up). A block has few split pieces, so all pairs.
  static bool splits_cross(const Block& b) {
    std::vector<std::pair<Vec2, Vec2>> segments;
    for (const BlockSide& side : b.sides) {
      for (const OutlinePiece& piece : side.pieces) {
        if (piece.split < 0) continue;
        for (std::size_t i = 0; i + 1 < piece.points.size(); ++i)
          segments.emplace_back(piece.points[i], piece.points[i + 1]);
      }
    }
    const auto side_of = [](Vec2 a, Vec2 b, Vec2 p) { return cross(b - a, p - a); };
    for (std::size_t i = 0; i < segments.size(); ++i) {
      for (std::size_t j = i + 1; j < segments.size(); ++j) {
        const auto [a, b2] = segments[i];
        const auto [c, d] = segments[j];
        const double scale = 1e-12 * (norm(b2 - a) + norm(d - c)) * (norm(b2 - a) + norm(d - c));
        const double d1 = side_of(a, b2, c), d2 = side_of(a, b2, d), d3 = side_of(c, d, a), d4 = side_of(c, d, b2);
        if (((d1 > scale && d2 < -scale) || (d1 < -scale && d2 > scale)) &&
            ((d3 > scale && d4 < -scale) || (d3 < -scale && d4 > scale)))
          return true;
      }
    }
    return false;
  }

  // The widest gap round a block's outline between a piece's end and the
  // next one's start, or between a boundary piece's ends and its edge at its
  // parameters (the mesh puts the nodes there and joins the ends into one: a
  // boundary walk that mixed up the edges by a shorter one shows here).
  double widest_joint(const Block& b) const {
    std::vector<const OutlinePiece*> pieces;
    for (const BlockSide& side : b.sides)
      for (const OutlinePiece& piece : side.pieces) pieces.push_back(&piece);
    double widest = 0.0;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const OutlinePiece& piece = *pieces[i];
      const OutlinePiece& next = *pieces[(i + 1) % pieces.size()];
      if (piece.points.empty() || next.points.empty()) continue;
      widest = std::max(widest, distance(piece.points.back(), next.points.front()));
      if (piece.split >= 0) continue;
      const BoundaryEdge& edge = face_.loops[piece.loop].edges[piece.edge];
      widest = std::max({widest, distance(piece.points.front(), edge_point(edge, piece.t_from).p),
                         distance(piece.points.back(), edge_point(edge, piece.t_to).p)});
    }
    return widest;
  }

  Block make_block(const Outline& o) const {
    const BlockRing flat = flatten(o, true);
    Block b;
    set_outline(b, flat, tol_);
    b.area = ring_area(flat);
    return b;
  }

  // The area a ring of pieces encloses (exact along boundary edges).
  double ring_area(const BlockRing& ring) const {
    const std::size_t count = ring.pieces.size();
    const Vec2 ref = ring.pieces.empty() ? Vec2{} : ring.pieces.front().points.front();
    double area = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      // Consecutive pieces meet to the sliver length, not exactly: the gap's chord counts too.
      const OutlinePiece& piece = ring.pieces[i];
      const Vec2 previous_end = ring.pieces[(i + count - 1) % count].points.back();
      area += 0.5 * cross(previous_end - ref, piece.points.front() - previous_end) + piece_area(piece, ref);
    }
    return area;
  }

  const FaceModel& face_;
  const MedialAxis& axis_;
  const MeshFlow& flow_;
  // The flow's point flows and the singularities' places, as this attempt
  // has them: fixing a merged unit at a junction moves its members there.
  std::vector<std::vector<PointFlow>> points_;
  DecompositionOptions options_;
  BoundaryIndex index_;
  double tol_;
  std::map<std::pair<int, int>, int> corner_of_;
  bool strict_end_touches_ = false;  // see end_place
  bool lenient_ = false;             // see run
  std::vector<int> rep_;             // per medial vertex, the one it stands with (coincident junctions)
  std::vector<bool> contracted_;     // per medial edge: of no length, its ends one vertex
  std::vector<Location> locations_;
  std::vector<Location> located_;  // as found, before any attempt moved them
  bool gathered_ = false;          // whether points_ and locations_ differ from the flow's
  std::vector<Unit> units_;
  std::vector<int> unit_of_;
  std::vector<std::vector<End>> ends_;
  std::vector<ConcavePoint> concave_;
  mutable std::map<std::pair<int, int>, std::vector<double>> samples_;  // see edge_samples
  std::vector<Cut> cuts_;
  long version_ = 0;  // bumped by every change of cuts_ or of units_' fixed flags
  mutable long marks_version_ = -1;
  mutable std::vector<std::vector<Mark>> marks_;  // see edge_marks
  std::set<int> vertex_cuts_;                     // vertices with a vertex cut
  struct MemberPair {  // positions of two members of one group, and how far a point between them may be
    Vec2 a, b;
    double reach;
  };
  std::vector<MemberPair> member_pairs_;      // sorted by a.x
  double widest_pair_ = 0.0;                  // the largest reach
  std::vector<int> vertex_member_;            // per medial vertex, the flow singularity there or -1
  std::set<int> taken_apart_;                 // first members of groups taken apart
  std::set<int> framed_;                      // holes split along their corners' arms (frame_wrapped_holes)
  std::map<int, int> boundary_fixed_;         // finite-contact vertex -> convex corners put on its arc
  std::vector<int> split_owner_;              // the cut each split belongs to
  std::set<std::pair<int, long>> withdrawn_;  // (edge, position x 1e6) of withdrawn cuts, never placed again
  std::vector<Split> splits_;
  std::vector<std::string> notes_;
};

}  // namespace

const char* split_reason_name(SplitReason reason) {
  switch (reason) {
    case SplitReason::Resolve: return "resolve";
    case SplitReason::ConcaveCorner: return "concave_corner";
    case SplitReason::Fix: return "fix";
    case SplitReason::Connect: return "connect";
  }
  return "unknown";
}

namespace {

// Samples of each boundary edge in the whole-face block's outline.
constexpr int kWholeFaceEdgeSamples = 64;

// The whole face as one polygon block (DecompositionOptions::whole_face).
Decomposition whole_face_block(const FaceModel& face) {
  const auto refuse = [&](const std::string& why) {
    return SelfCheckError(face.name, "decomposition: the whole face cannot be one block: " + why);
  };
  if (face.holes() > 0) throw refuse("it has holes");
  const std::vector<BoundaryEdge>& edges = face.loops[0].edges;
  std::vector<int> type(edges.size(), 2);  // at each edge's start: 2 where the loop runs on smoothly
  for (const Corner& c : face.corners) {
    if (c.loop != 0 || c.nc == 2) continue;
    if (c.nc > 2) throw refuse("it has a reflex corner");
    type[c.vertex] = 1;  // a cusp (nc 0) too: its one element
  }
  const long corners = std::count(type.begin(), type.end(), 1);
  if (corners > 6) throw refuse("it has " + std::to_string(corners) + " corners (a polygon block takes 6 at most)");
  BlockRing ring;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    OutlinePiece edge;  // the whole edge, its ends the loop's vertices
    edge.loop = 0;
    edge.edge = static_cast<int>(e);
    edge.t_from = edges[e].t_start;
    edge.t_to = edges[e].t_end;
    edge.points = {edges[e].start, edges[e].end};
    ring.pieces.push_back(piece_part(face, edge, edge.t_from, edge.t_to, kWholeFaceEdgeSamples));
    ring.start_type.push_back(type[e]);
  }
  Decomposition d;
  Block b;
  set_outline(b, ring, face.tolerance);
  b.kind = BlockKind::Polygon;
  b.area = face.area;
  if (corners != 4) {
    const std::optional<Vec2> centroid = centroid_inside(b.outline);
    if (!centroid) throw refuse("its centroid lies outside it");
    b.singularity = 0;
    d.singularities.push_back({*centroid, static_cast<int>(corners) - 4, false, {}});
  }
  d.blocks.push_back(std::move(b));
  d.notes.push_back("the whole face became one block of its " + std::to_string(corners) +
                    " corners (a last resort: the medial decomposition failed its self-check)");
  return d;
}

}  // namespace

Decomposition decompose(const FaceModel& face, const MedialAxis& axis, const MeshFlow& flow,
                        const DecompositionOptions& options) {
  if (options.whole_face) return whole_face_block(face);
  return Decomposer(face, axis, flow, options).run();
}

}  // namespace mm
