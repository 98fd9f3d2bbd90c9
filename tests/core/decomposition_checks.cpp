#include "decomposition_checks.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/polygon.hpp"
#include "medial/medial_axis.hpp"
#include "medial_checks.hpp"

namespace mm::test {

namespace {

double distance_to_polyline(Vec2 p, const std::vector<Vec2>& line, bool closed) {
  double best = 1e300;
  const std::size_t n = line.size();
  for (std::size_t i = 0; i + (closed ? 0 : 1) < n; ++i)
    best = std::min(best, distance_to_segment(p, line[i], line[(i + 1) % n]));
  return best;
}

// A point inside the (counter-clockwise, simple) polygon, a little to the
// left of one of its longer segments, or none if every try falls outside.
std::optional<Vec2> point_just_inside(const std::vector<Vec2>& polygon, double reach) {
  const std::size_t n = polygon.size();
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  const auto length = [&](std::size_t i) { return distance(polygon[i], polygon[(i + 1) % n]); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return length(a) > length(b); });
  for (std::size_t k = 0; k < std::min<std::size_t>(n, 8); ++k) {
    const Vec2 a = polygon[order[k]], b = polygon[(order[k] + 1) % n];
    if (!(distance(a, b) > 0)) break;
    for (double step = std::min(reach, 0.25 * distance(a, b)); step > 1e-6 * reach; step *= 0.25) {
      const Vec2 p = 0.5 * (a + b) + step * perp(normalized(b - a));
      if (inside_polygon(polygon, p) && distance_to_polyline(p, polygon, true) > 0.5 * step) return p;
    }
  }
  return std::nullopt;
}

// A point the closed outline passes twice, at least a thousandth of the
// size apart along it both ways: a disc only through that point (a block
// round a hole whose splits all end at one point), where a polygon
// template's lines from its centre would cross the hole.
std::optional<Vec2> outline_pinch(const std::vector<Vec2>& outline, double size) {
  const std::size_t n = outline.size();
  std::vector<double> along(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) along[i + 1] = along[i] + distance(outline[i], outline[(i + 1) % n]);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double between = along[j] - along[i];
      if (between > 1e-3 * size && along[n] - between > 1e-3 * size && distance(outline[i], outline[j]) <= 1e-6 * size)
        return outline[i];
    }
  }
  return std::nullopt;
}

}  // namespace

Decomposition decompose_face(const FaceModel& face, double merge_factor) {
  const MedialAxis axis = compute_medial_axis(face);
  const MeshFlow flow = compute_mesh_flow(face, axis);
  DecompositionOptions options;
  options.merge = merge_factor > 0;
  options.tolerance.radius_factor = merge_factor > 0 ? merge_factor : 0.75;
  return decompose(face, axis, flow, options);
}

std::vector<std::string> decomposition_problems(const FaceModel& face, const MeshFlow& flow, const Decomposition& d) {
  std::vector<std::string> problems;
  const auto problem = [&](const std::string& what) { problems.push_back(face.name + ": " + what); };
  const double tol = 1e-7 * face.size + face.tolerance;
  const BoundaryProbe probe(face);  // exact distances to the boundary

  double total = 0.0;
  for (std::size_t b = 0; b < d.blocks.size(); ++b) {
    const Block& block = d.blocks[b];
    const std::string name = "block " + std::to_string(b);
    total += block.area;
    if (!(block.area > 0)) problem(name + " has area " + std::to_string(block.area));
    // Simple: no two outline segments cross (a submap block may run along one split twice).
    const auto& o = block.outline;
    for (std::size_t i = 0; i < o.size(); ++i) {
      for (std::size_t j = i + 2; j < o.size(); ++j) {
        if (i == 0 && j + 1 == o.size()) continue;
        if (segments_cross(o[i], o[(i + 1) % o.size()], o[j], o[(j + 1) % o.size()], 1e-9)) {
          problem(name + " outline crosses itself");
          i = o.size();
          break;
        }
      }
    }
    // Each boundary piece lies on its edge between its parameters, and each
    // piece ends where the next begins: the mesh builds its nodes from them.
    std::vector<const OutlinePiece*> pieces;
    for (const BlockSide& side : block.sides)
      for (const OutlinePiece& piece : side.pieces) pieces.push_back(&piece);
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const OutlinePiece& piece = *pieces[i];
      const Vec2 from = piece.split >= 0 ? piece.points.front()
                                         : edge_point(face.loops[piece.loop].edges[piece.edge], piece.t_from).p;
      const Vec2 to =
          piece.split >= 0 ? piece.points.back() : edge_point(face.loops[piece.loop].edges[piece.edge], piece.t_to).p;
      const OutlinePiece& next = *pieces[(i + 1) % pieces.size()];
      const Vec2 next_from =
          next.split >= 0 ? next.points.front() : edge_point(face.loops[next.loop].edges[next.edge], next.t_from).p;
      if (distance(from, piece.points.front()) > 1e-5 * face.size || distance(to, next_from) > 1e-5 * face.size) {
        problem(name + " has an outline piece off its edge or apart from the next at (" + std::to_string(to.x) + ", " +
                std::to_string(to.y) + ")");
        break;
      }
    }
    int turning = 0;
    for (const BlockCorner& c : block.corners) turning += 2 - c.type;
    int inside_k = 0;
    if (block.singularity >= 0) inside_k = d.singularities[block.singularity].k;
    if (turning != 4 + inside_k) {
      problem(name + " corners turn by " + std::to_string(turning) + " quarter turns, not " +
              std::to_string(4 + inside_k));
    }
    if (block.kind == BlockKind::Polygon) {
      if (block.corners.size() > 6)
        problem(name + " is a polygon of " + std::to_string(block.corners.size()) + " sides");
      for (const BlockCorner& c : block.corners) {
        if (c.type != 1) problem(name + " is a polygon with a corner of type " + std::to_string(c.type));
      }
      if (block.singularity < 0 && block.corners.size() != 4) problem(name + " is a polygon with no singularity");
      if (const std::optional<Vec2> pinch = outline_pinch(block.outline, face.size))
        problem(name + " is a polygon whose outline comes back to (" + std::to_string(pinch->x) + ", " +
                std::to_string(pinch->y) + ")");
    } else if (block.singularity >= 0) {
      problem(name + " is a submap block holding a singularity");
    } else {
      // What submapping can mesh: convex, flat or reflex corners only, and
      // sides running each way that sides run the opposite way (else the
      // counts there would have to be 0).
      int direction = 0;
      bool runs[4] = {false, false, false, false};
      for (const BlockCorner& c : block.corners) {
        if (c.type < 1 || c.type > 3)
          problem(name + " is a submap block with a corner of type " + std::to_string(c.type));
        direction = ((direction + 2 - c.type) % 4 + 4) % 4;
        runs[direction] = true;
      }
      if (runs[0] != runs[2] || runs[1] != runs[3])
        problem(name + " is a submap block with sides one way and none the opposite way");
    }
  }
  if (std::abs(total - face.area) > 1e-9 * face.area) {
    problem("blocks add up to " + std::to_string(total) + ", the face is " + std::to_string(face.area));
  }
  // No two blocks overlap: their outlines never cross by more than the
  // tolerance (two splits may end on one boundary point a few 1e-8 of the
  // size apart), and a point just inside each block lies in no other (one
  // simple polygon inside another crosses nothing). With the areas adding
  // up, the blocks tile the face.
  std::vector<Box> boxes;
  for (const Block& block : d.blocks) boxes.push_back(bounding_box(block.outline));
  const auto boxes_meet = [&](std::size_t a, std::size_t b) {
    return boxes[a].min.x <= boxes[b].max.x + tol && boxes[b].min.x <= boxes[a].max.x + tol &&
           boxes[a].min.y <= boxes[b].max.y + tol && boxes[b].min.y <= boxes[a].max.y + tol;
  };
  for (std::size_t a = 0; a < d.blocks.size(); ++a) {
    const auto& oa = d.blocks[a].outline;
    const std::optional<Vec2> inner = point_just_inside(oa, 1e-4 * face.size);
    if (!inner) problem("block " + std::to_string(a) + " has no point inside it near its outline");
    for (std::size_t b = 0; b < d.blocks.size(); ++b) {
      if (b == a || !boxes_meet(a, b)) continue;
      const auto& ob = d.blocks[b].outline;
      if (inner && inside_polygon(ob, *inner) && distance_to_polyline(*inner, ob, true) > tol)
        problem("block " + std::to_string(a) + " lies in block " + std::to_string(b));
      if (b < a) continue;
      bool crossing = false;
      for (std::size_t i = 0; i < oa.size() && !crossing; ++i)
        for (std::size_t j = 0; j < ob.size() && !crossing; ++j)
          crossing = segments_cross(oa[i], oa[(i + 1) % oa.size()], ob[j], ob[(j + 1) % ob.size()], tol);
      if (crossing) problem("blocks " + std::to_string(a) + " and " + std::to_string(b) + " cross");
    }
  }
  // Every floating singularity in exactly one block, inside its outline.
  for (std::size_t s = 0; s < d.singularities.size(); ++s) {
    const DecomposedSingularity& sing = d.singularities[s];
    int holders = 0;
    for (const Block& block : d.blocks) {
      if (block.singularity != static_cast<int>(s)) continue;
      ++holders;
      for (int m : sing.members) {
        const Vec2 p = flow.singularities[m].p;
        if (!inside_polygon(block.outline, p) && distance_to_polyline(p, block.outline, true) > tol)
          problem("a k = " + std::to_string(sing.k) + " singularity lies outside its block");
      }
    }
    if (!sing.fixed && holders != 1) problem("a floating singularity is in " + std::to_string(holders) + " blocks");
    if (sing.fixed && holders != 0) problem("a fixed singularity is inside a block");
  }
  // Splits: inside the face, ends on the boundary or on another split, no crossings.
  for (std::size_t i = 0; i < d.splits.size(); ++i) {
    const auto& line = d.splits[i].polyline;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Vec2 mid = 0.5 * (line[k] + line[k + 1]);
      if (!probe.inside(mid) && probe.distance_to_boundary(mid) > tol)
        problem("split " + std::to_string(i) + " leaves the face");
    }
    for (const Vec2 end : {line.front(), line.back()}) {
      double nearest = probe.distance_to_boundary(end);
      for (std::size_t j = 0; j < d.splits.size(); ++j) {
        if (j != i) nearest = std::min(nearest, distance_to_polyline(end, d.splits[j].polyline, false));
      }
      if (nearest > 1e-5 * face.size)
        problem("split " + std::to_string(i) + " ends in the open, " + std::to_string(nearest / face.size) +
                " of the size away");
    }
    for (std::size_t j = i + 1; j < d.splits.size(); ++j) {
      const auto& other = d.splits[j].polyline;
      for (std::size_t a = 0; a + 1 < line.size(); ++a) {
        for (std::size_t b = 0; b + 1 < other.size(); ++b) {
          if (segments_cross(line[a], line[a + 1], other[b], other[b + 1], 1e-9))
            problem("splits " + std::to_string(i) + " and " + std::to_string(j) + " cross");
        }
      }
    }
  }
  return problems;
}

}  // namespace mm::test
