#include "meshing/mesh_blocks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "meshing/block_templates.hpp"
#include "meshing/interval_assignment.hpp"
#include "meshing/smoothing.hpp"

namespace mm {
namespace {

// Every interval of a curved edge turns by at most this much, so that small
// holes and fillets stay resolved however large the target size is (a full
// circle gets at least 8 intervals).
constexpr double kMaxTurnPerInterval = kPi / 4.0;

// One piece of the outlines that gets one interval count: a run of a split
// between two of its polyline points (a split is cut where it crosses the
// medial axis, and blocks on either side share those runs), or a piece of a
// boundary edge used by exactly one block.
struct Segment {
  int split = -1;
  std::vector<Vec2> line;  // split runs: the polyline, in the segment's direction
  int loop = -1;
  int edge = -1;
  double t_from = 0.0;
  double t_to = 0.0;
  double length = 0.0;
  int min_count = 1;
  std::vector<int> nodes;      // along the segment's own direction, both ends included
  std::vector<double> params;  // boundary segments: curve parameter of each node
};

struct PieceUse {
  int segment = -1;
  bool reversed = false;
};

// A boundary piece sampled finely in its parameter: cumulative chord length
// and the turning of its tangent, for lengths, bounds and even spacing.
struct PieceSamples {
  std::vector<double> params;
  std::vector<Vec2> points;
  std::vector<double> arc;  // cumulative chord length
  double turning = 0.0;
};

PieceSamples sample_piece(const BoundaryEdge& edge, double t_from, double t_to, int steps) {
  PieceSamples s;
  s.params.resize(steps + 1);
  s.points.resize(steps + 1);
  s.arc.assign(steps + 1, 0.0);
  for (int i = 0; i <= steps; ++i) {
    s.params[i] = t_from + (t_to - t_from) * i / steps;
    s.points[i] = edge_point(edge, s.params[i]).p;
    if (i > 0) s.arc[i] = s.arc[i - 1] + distance(s.points[i], s.points[i - 1]);
  }
  for (int i = 1; i < steps; ++i) {
    const Vec2 a = s.points[i] - s.points[i - 1];
    const Vec2 b = s.points[i + 1] - s.points[i];
    if (norm(a) > 0.0 && norm(b) > 0.0) s.turning += std::abs(signed_angle(a, b));
  }
  return s;
}

// Parameter at a fraction of the piece's length, from the sampled table.
double param_at_length(const PieceSamples& s, double length) {
  const auto it = std::lower_bound(s.arc.begin(), s.arc.end(), length);
  if (it == s.arc.begin()) return s.params.front();
  if (it == s.arc.end()) return s.params.back();
  const std::size_t i = static_cast<std::size_t>(it - s.arc.begin());
  const double span = s.arc[i] - s.arc[i - 1];
  const double f = span > 0.0 ? (length - s.arc[i - 1]) / span : 0.0;
  return s.params[i - 1] + f * (s.params[i] - s.params[i - 1]);
}

Vec2 point_along_polyline(const std::vector<Vec2>& line, const std::vector<double>& arc, double length) {
  const auto it = std::lower_bound(arc.begin(), arc.end(), length);
  if (it == arc.begin()) return line.front();
  if (it == arc.end()) return line.back();
  const std::size_t i = static_cast<std::size_t>(it - arc.begin());
  const double span = arc[i] - arc[i - 1];
  const double f = span > 0.0 ? (length - arc[i - 1]) / span : 0.0;
  return line[i - 1] + f * (line[i] - line[i - 1]);
}

std::vector<double> cumulative_length(const std::vector<Vec2>& line) {
  std::vector<double> arc(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) arc[i] = arc[i - 1] + distance(line[i], line[i - 1]);
  return arc;
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// The parameter halfway along the curve between two parameters, by equal chords.
double middle_param(const BoundaryEdge& edge, double ta, double tb) {
  const Vec2 a = edge_point(edge, ta).p;
  const Vec2 b = edge_point(edge, tb).p;
  double lo = ta;
  double hi = tb;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const Vec2 p = edge_point(edge, mid).p;
    if (distance(a, p) < distance(p, b)) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

double quad_area(const QuadMesh& mesh, const std::array<int, 4>& q) {
  double twice = 0.0;
  for (int i = 0; i < 4; ++i) twice += cross(mesh.nodes[q[i]], mesh.nodes[q[(i + 1) % 4]]);
  return 0.5 * twice;
}

double worst_corner(const QuadMesh& mesh, const std::array<int, 4>& q) {
  double worst = 1.0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 p = mesh.nodes[q[i]];
    const Vec2 next = mesh.nodes[q[(i + 1) % 4]] - p;
    const Vec2 prev = mesh.nodes[q[(i + 3) % 4]] - p;
    const double lengths = std::sqrt(dot(next, next) * dot(prev, prev));
    worst = std::min(worst, lengths > 0.0 ? cross(next, prev) / lengths : -1.0);
  }
  return worst;
}

std::string at(Vec2 p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

class BlockMesher {
 public:
  BlockMesher(const FaceModel& face, const Decomposition& d, const MeshingOptions& options)
      // Split ends meet the boundary to the decomposition's accuracy, which
      // on faces read with loose edge tolerances is looser than ours.
      : face_(face), d_(d), options_(options), tolerance_(std::max(1e-5 * face.size, 10.0 * face.tolerance)) {}

  BlockMesh run() {
    BlockMesh result;
    collect_segments();
    join_segment_ends();
    const auto t0 = std::chrono::steady_clock::now();
    IntervalAssignment intervals;
    try {
      intervals = assign_intervals(interval_problem());
    } catch (const SelfCheckError&) {
      throw;
    } catch (const std::exception& e) {
      fail(std::string("the blocks cannot be given interval counts: ") + e.what());
    }
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<int> counts = intervals.counts;
    spread_along_boundary_runs(counts);
    place_segment_nodes(counts);
    for (std::size_t b = 0; b < d_.blocks.size(); ++b) {
      try {
        fill_block(shapes_[b], intervals.params[b], outline_of(static_cast<int>(b)), static_cast<int>(b), mesh_);
      } catch (const std::runtime_error& e) {
        fail(std::string("a block cannot be filled: ") + e.what());
      }
    }
    const auto t2 = std::chrono::steady_clock::now();
    if (options_.smooth) {
      // Boundary nodes stay where their spacing put them: sliding them for
      // the elements' sake let single intervals span too much of a small
      // hole (the chordal error grew past what interval assignment bounded).
      SmoothingOptions smoothing;
      smoothing.move_boundary = false;
      smooth_mesh(face_, mesh_, smoothing);
    }
    const auto t3 = std::chrono::steady_clock::now();
    if (options_.order == 2) add_midside_nodes();
    check_mesh();
    const auto t4 = std::chrono::steady_clock::now();
    const auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    result.stage_seconds = {{"intervals", seconds(t0, t1)},
                            {"placement", seconds(t1, t2)},
                            {"smoothing", seconds(t2, t3)},
                            {"mesh_check", seconds(t3, t4)}};
    result.segment_counts = counts;
    result.notes = intervals.notes;
    result.mesh = std::move(mesh_);
    return result;
  }

 private:
  void fail(const std::string& check) const { throw SelfCheckError(face_.name, "mesh: " + check); }

  const BoundaryEdge& edge_of(const Segment& s) const { return face_.loops[s.loop].edges[s.edge]; }

  Vec2 segment_end(const Segment& s, bool last) const {
    if (s.split >= 0) return last ? s.line.back() : s.line.front();
    return edge_point(edge_of(s), last ? s.t_to : s.t_from).p;
  }

  // Segments and, per block, the pieces of its sides as segments used
  // forwards or backwards; the block shapes for interval assignment.
  void collect_segments() {
    std::map<std::array<int, 3>, int> segment_of_run;
    for (std::size_t b = 0; b < d_.blocks.size(); ++b) {
      const Block& block = d_.blocks[b];
      BlockShape shape;
      shape.kind = template_of(block, static_cast<int>(b));
      for (const BlockCorner& c : block.corners) shape.corner_types.push_back(c.type);
      std::vector<std::vector<PieceUse>> sides;
      for (const BlockSide& side : block.sides) {
        std::vector<PieceUse> uses;
        std::vector<int> ids;
        for (const OutlinePiece& piece : side.pieces) {
          PieceUse use;
          if (piece.split >= 0) {
            const std::vector<Vec2>& polyline = d_.splits[piece.split].polyline;
            const int from = polyline_point(polyline, piece.points.front());
            const int to = polyline_point(polyline, piece.points.back());
            if (from == to) fail("a split piece of block " + std::to_string(b) + " has no length");
            const std::array<int, 3> run{piece.split, std::min(from, to), std::max(from, to)};
            auto found = segment_of_run.find(run);
            if (found == segment_of_run.end()) {
              Segment s;
              s.split = piece.split;
              s.line.assign(polyline.begin() + run[1], polyline.begin() + run[2] + 1);
              s.length = cumulative_length(s.line).back();
              found = segment_of_run.emplace(run, static_cast<int>(segments_.size())).first;
              segments_.push_back(std::move(s));
            }
            use.segment = found->second;
            use.reversed = from > to;
          } else {
            Segment s;
            s.loop = piece.loop;
            s.edge = piece.edge;
            s.t_from = piece.t_from;
            s.t_to = piece.t_to;
            const PieceSamples samples = sample_piece(edge_of(s), s.t_from, s.t_to, 64);
            s.length = samples.arc.back();
            s.min_count = std::max(1, static_cast<int>(std::ceil(samples.turning / kMaxTurnPerInterval - 1e-6)));
            use.segment = static_cast<int>(segments_.size());
            segments_.push_back(std::move(s));
          }
          uses.push_back(use);
          ids.push_back(use.segment);
        }
        sides.push_back(std::move(uses));
        shape.side_segments.push_back(std::move(ids));
      }
      uses_.push_back(std::move(sides));
      shapes_.push_back(std::move(shape));
    }
  }

  // The polyline point a split piece starts or ends at.
  int polyline_point(const std::vector<Vec2>& polyline, Vec2 p) const {
    int best = 0;
    for (std::size_t i = 1; i < polyline.size(); ++i) {
      if (distance(polyline[i], p) < distance(polyline[best], p)) best = static_cast<int>(i);
    }
    if (distance(polyline[best], p) > tolerance_) fail("a split piece ends off its split's points at " + at(p));
    return best;
  }

  BlockTemplate template_of(const Block& block, int index) const {
    if (block.kind == BlockKind::Submap) {
      if (block.singularity >= 0) {
        throw SelfCheckError(face_.name, "mesh: block " + std::to_string(index) +
                                             " holds a k = " + std::to_string(d_.singularities[block.singularity].k) +
                                             " singularity but is not a logically convex polygon");
      }
      return BlockTemplate::Submap;
    }
    switch (block.corners.size()) {
      case 0: return BlockTemplate::Disc;
      case 1: return BlockTemplate::OneSided;
      case 2: return BlockTemplate::TwoSided;
      case 4: return BlockTemplate::Submap;
      default: return BlockTemplate::Midpoint;
    }
  }

  // Consecutive pieces of an outline meet: their ends are one vertex. The
  // vertices come from the outlines' topology, and their positions are only
  // checked to agree.
  void join_segment_ends() {
    std::vector<int> parent(2 * segments_.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto start_of = [](const PieceUse& u) { return 2 * u.segment + (u.reversed ? 1 : 0); };
    const auto end_of = [](const PieceUse& u) { return 2 * u.segment + (u.reversed ? 0 : 1); };
    for (const auto& sides : uses_) {
      std::vector<PieceUse> outline;
      for (const auto& side : sides) outline.insert(outline.end(), side.begin(), side.end());
      for (std::size_t i = 0; i < outline.size(); ++i) {
        const int a = find_root(parent, end_of(outline[i]));
        const int b = find_root(parent, start_of(outline[(i + 1) % outline.size()]));
        parent[a] = b;
      }
    }
    vertex_of_end_.assign(parent.size(), -1);
    std::map<int, int> vertex_of_root;
    for (std::size_t h = 0; h < parent.size(); ++h) {
      const int root = find_root(parent, static_cast<int>(h));
      const auto found = vertex_of_root.emplace(root, static_cast<int>(vertex_of_root.size())).first;
      vertex_of_end_[h] = found->second;
    }
    const std::size_t vertices = vertex_of_root.size();
    mesh_.nodes.assign(vertices, Vec2{});
    mesh_.places.assign(vertices, NodePlace{});
    std::vector<bool> placed(vertices, false);
    // Boundary ends first: a vertex on the boundary sits on the exact curve.
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t h = 0; h < parent.size(); ++h) {
        const Segment& s = segments_[h / 2];
        if ((pass == 0) == (s.split >= 0)) continue;
        const int v = vertex_of_end_[h];
        const Vec2 p = segment_end(s, h % 2 == 1);
        if (placed[v]) {
          if (distance(mesh_.nodes[v], p) > tolerance_) {
            fail("block outlines that should meet are " + std::to_string(distance(mesh_.nodes[v], p)) + " apart at " +
                 at(p));
          }
          continue;
        }
        placed[v] = true;
        mesh_.nodes[v] = p;
        if (s.split < 0) mesh_.places[v] = boundary_place(s, h % 2 == 1 ? s.t_to : s.t_from, p);
      }
    }
  }

  NodePlace boundary_place(const Segment& s, double t, Vec2 p) const {
    NodePlace place;
    place.loop = s.loop;
    place.edge = s.edge;
    place.t = t;
    place.corner_elements = 2;
    const BoundaryEdge& edge = edge_of(s);
    const int edges = static_cast<int>(face_.loops[s.loop].edges.size());
    int vertex = -1;
    if (distance(p, edge.start) <= tolerance_) vertex = s.edge;
    if (distance(p, edge.end) <= tolerance_) vertex = (s.edge + 1) % edges;
    if (vertex >= 0) {
      place.face_corner = true;
      for (const Corner& c : face_.corners) {
        if (c.loop == s.loop && c.vertex == vertex) place.corner_elements = c.nc;
      }
    }
    return place;
  }

  IntervalProblem interval_problem() const {
    IntervalProblem problem;
    for (const Segment& s : segments_) {
      IntervalSegment is;
      is.goal = std::max(s.length / options_.size, 1e-9);
      is.min_count = s.min_count;
      problem.segments.push_back(is);
    }
    problem.blocks = shapes_;
    return problem;
  }

  // Interval assignment fixes what a side's pieces add up to; its linear
  // objective may then load a whole side's change onto one piece. Pieces of
  // boundary in a row on one side meet at no corner and no other block, so
  // their sum is spread over them by length again (largest remainders,
  // bounds kept).
  void spread_along_boundary_runs(std::vector<int>& counts) const {
    for (const auto& sides : uses_) {
      for (const auto& side : sides) {
        std::size_t begin = 0;
        while (begin < side.size()) {
          std::size_t end = begin;
          while (end < side.size() && segments_[side[end].segment].split < 0) ++end;
          if (end - begin > 1) spread(side, begin, end, counts);
          begin = end + 1;
        }
      }
    }
  }

  void spread(const std::vector<PieceUse>& side, std::size_t begin, std::size_t end, std::vector<int>& counts) const {
    int spare = 0;
    double length = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const Segment& s = segments_[side[i].segment];
      spare += counts[side[i].segment] - s.min_count;
      length += s.length;
      counts[side[i].segment] = s.min_count;
    }
    int total = spare;
    for (std::size_t i = begin; i < end; ++i) total += counts[side[i].segment];
    // One interval at a time to the piece furthest below its share by length.
    for (; spare > 0; --spare) {
      std::size_t neediest = begin;
      double most_missing = -1e300;
      for (std::size_t i = begin; i < end; ++i) {
        const double share = length > 0.0 ? total * segments_[side[i].segment].length / length : 0.0;
        const double missing = share - counts[side[i].segment];
        if (missing > most_missing) {
          most_missing = missing;
          neediest = i;
        }
      }
      ++counts[side[neediest].segment];
    }
  }

  void place_segment_nodes(const std::vector<int>& counts) {
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      Segment& s = segments_[i];
      const int n = counts[i];
      s.nodes.assign(1, vertex_of_end_[2 * i]);
      if (s.split >= 0) {
        const std::vector<Vec2>& line = s.line;
        const std::vector<double> arc = cumulative_length(line);
        for (int k = 1; k < n; ++k) add_node(s, point_along_polyline(line, arc, arc.back() * k / n), NodePlace{});
      } else {
        const PieceSamples samples = sample_piece(edge_of(s), s.t_from, s.t_to, std::max(64, 16 * n));
        s.params.assign(1, s.t_from);
        for (int k = 1; k < n; ++k) {
          const double t = param_at_length(samples, samples.arc.back() * k / n);
          NodePlace place;
          place.loop = s.loop;
          place.edge = s.edge;
          place.t = t;
          place.corner_elements = 2;
          add_node(s, edge_point(edge_of(s), t).p, place);
          s.params.push_back(t);
        }
        s.params.push_back(s.t_to);
      }
      s.nodes.push_back(vertex_of_end_[2 * i + 1]);
    }
  }

  void add_node(Segment& s, Vec2 p, const NodePlace& place) {
    s.nodes.push_back(static_cast<int>(mesh_.nodes.size()));
    mesh_.nodes.push_back(p);
    mesh_.places.push_back(place);
  }

  BlockOutline outline_of(int block) const {
    BlockOutline outline;
    const Block& b = d_.blocks[block];
    for (std::size_t side = 0; side < uses_[block].size(); ++side) {
      if (!b.corners.empty()) outline.corner_at.push_back(static_cast<int>(outline.nodes.size()));
      for (const PieceUse& use : uses_[block][side]) {
        std::vector<int> nodes = segments_[use.segment].nodes;
        if (use.reversed) std::reverse(nodes.begin(), nodes.end());
        outline.nodes.insert(outline.nodes.end(), nodes.begin(), nodes.end() - 1);
      }
    }
    return outline;
  }

  // The parameter of a boundary segment's node k now (smoothing slides nodes
  // along their edges; the segment's ends are vertices that stay put).
  double current_param(const Segment& s, int k) const {
    const NodePlace& place = mesh_.places[s.nodes[k]];
    if (k > 0 && k + 1 < static_cast<int>(s.nodes.size()) && place.loop == s.loop && place.edge == s.edge)
      return place.t;
    return s.params[k];
  }

  // Each node's quads in compressed lists, so that the quads on a side are
  // found next to one of its nodes (linear in the mesh: no map of all sides).
  struct QuadsAtNodes {
    std::vector<int> first;  // node n's quads: quads[first[n] .. first[n + 1])
    std::vector<int> quads;
  };

  QuadsAtNodes quads_at_nodes() const {
    const std::size_t nodes = mesh_.nodes.size();
    QuadsAtNodes at;
    at.first.assign(nodes + 1, 0);
    for (const auto& q : mesh_.quads)
      for (int n : q) ++at.first[n + 1];
    for (std::size_t n = 0; n < nodes; ++n) at.first[n + 1] += at.first[n];
    at.quads.resize(at.first[nodes]);
    std::vector<int> fill(at.first.begin(), at.first.end() - 1);
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e)
      for (int n : mesh_.quads[e]) at.quads[fill[n]++] = static_cast<int>(e);
    return at;
  }

  // Order 2: a node in the middle of every element side, on the exact curve
  // for sides along the boundary.
  void add_midside_nodes() {
    const QuadsAtNodes at = quads_at_nodes();
    std::map<std::pair<int, int>, int> on_boundary;  // only the boundary's intervals: few
    std::vector<char> boundary_node(mesh_.nodes.size(), 0);
    const auto add = [&](Vec2 p, const NodePlace& place) {
      mesh_.nodes.push_back(p);
      mesh_.places.push_back(place);
      return static_cast<int>(mesh_.nodes.size()) - 1;
    };
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k) {
        const double t =
            middle_param(edge_of(s), current_param(s, static_cast<int>(k)), current_param(s, static_cast<int>(k + 1)));
        NodePlace place;
        place.loop = s.loop;
        place.edge = s.edge;
        place.t = t;
        const int a = s.nodes[k], b = s.nodes[k + 1];
        on_boundary[{std::min(a, b), std::max(a, b)}] = add(edge_point(edge_of(s), t).p, place);
        boundary_node[a] = boundary_node[b] = 1;
      }
    }
    mesh_.midside.resize(mesh_.quads.size());
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
      for (int i = 0; i < 4; ++i) {
        const int a = mesh_.quads[e][i];
        const int b = mesh_.quads[e][(i + 1) % 4];
        int middle = -1;
        if (boundary_node[a] && boundary_node[b]) {
          const auto found = on_boundary.find({std::min(a, b), std::max(a, b)});
          if (found != on_boundary.end()) middle = found->second;
        }
        // An inner side's node comes from the first quad along it.
        for (int k = at.first[a]; k < at.first[a + 1] && middle < 0; ++k) {
          const int other = at.quads[k];
          if (other >= static_cast<int>(e)) continue;
          for (int j = 0; j < 4; ++j) {
            const int c = mesh_.quads[other][j], d = mesh_.quads[other][(j + 1) % 4];
            if ((c == a && d == b) || (c == b && d == a)) middle = mesh_.midside[other][j];
          }
        }
        if (middle < 0) middle = add(0.5 * (mesh_.nodes[a] + mesh_.nodes[b]), NodePlace{});
        mesh_.midside[e][i] = middle;
      }
    }
  }

  // The mesh's own checks: conformity, orientation, area.
  void check_mesh() const {
    const std::size_t nodes = mesh_.nodes.size();
    const QuadsAtNodes quads_at = quads_at_nodes();
    const auto quads_on_side = [&](int a, int b) {
      int count = 0;
      for (int k = quads_at.first[a]; k < quads_at.first[a + 1]; ++k) {
        const auto& q = mesh_.quads[quads_at.quads[k]];
        for (int i = 0; i < 4; ++i)
          if (q[i] == a && (q[(i + 1) % 4] == b || q[(i + 3) % 4] == b)) ++count;
      }
      return count;
    };
    // The outer sides are exactly the boundary's intervals, each once: with
    // every element turning counter-clockwise, the elements then cover the
    // face once (the mapping's degree is the boundary's winding number).
    std::vector<std::pair<int, int>> boundary_intervals;
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k)
        boundary_intervals.emplace_back(std::min(s.nodes[k], s.nodes[k + 1]), std::max(s.nodes[k], s.nodes[k + 1]));
    }
    std::sort(boundary_intervals.begin(), boundary_intervals.end());
    std::vector<char> interval_used(boundary_intervals.size(), 0), on_boundary_interval(nodes, 0);
    for (const auto& [a, b] : boundary_intervals) on_boundary_interval[a] = on_boundary_interval[b] = 1;
    for (const auto& q : mesh_.quads) {
      for (int i = 0; i < 4; ++i) {
        const int a = q[i];
        const int b = q[(i + 1) % 4];
        if (a == b) fail("an element has a collapsed side at " + at(mesh_.nodes[a]));
        const int count = quads_on_side(a, b);
        const Vec2 p = 0.5 * (mesh_.nodes[a] + mesh_.nodes[b]);
        if (count > 2) fail("an element side at " + at(p) + " is shared by " + std::to_string(count) + " elements");
        const std::pair<int, int> side{std::min(a, b), std::max(a, b)};
        const auto interval = on_boundary_interval[a] && on_boundary_interval[b]
                                  ? std::lower_bound(boundary_intervals.begin(), boundary_intervals.end(), side)
                                  : boundary_intervals.end();
        const bool on_boundary = interval != boundary_intervals.end() && *interval == side;
        if ((count == 1) != on_boundary)
          fail("an element side at " + at(p) +
               (count == 1 ? " is open but not on the boundary" : " is on the boundary but closed"));
        if (on_boundary) interval_used[interval - boundary_intervals.begin()] = 1;
      }
    }
    for (std::size_t k = 0; k < boundary_intervals.size(); ++k) {
      if (!interval_used[k])
        fail("no element lies along the boundary at " + at(mesh_.nodes[boundary_intervals[k].first]));
    }
    double outer_chord_error = 0.0;
    for (const Segment& s : segments_) {
      if (s.split >= 0) continue;
      for (std::size_t k = 0; k + 1 < s.nodes.size(); ++k) {
        const Vec2 a = mesh_.nodes[s.nodes[k]];
        const Vec2 b = mesh_.nodes[s.nodes[k + 1]];
        const double t =
            middle_param(edge_of(s), current_param(s, static_cast<int>(k)), current_param(s, static_cast<int>(k + 1)));
        const Vec2 m = edge_point(edge_of(s), t).p;
        // The area between a chord and its arc is at most chord x sagitta.
        outer_chord_error += distance(a, b) * std::abs(cross(normalized(b - a), m - a));
      }
    }
    double area = 0.0;
    int worst = -1;
    double worst_value = 2.0;
    for (std::size_t e = 0; e < mesh_.quads.size(); ++e) {
      area += quad_area(mesh_, mesh_.quads[e]);
      const double value = worst_corner(mesh_, mesh_.quads[e]);
      if (value < worst_value) {
        worst_value = value;
        worst = static_cast<int>(e);
      }
    }
    if (worst >= 0 && worst_value <= 0.0) {
      Vec2 centre;
      for (int n : mesh_.quads[worst]) centre = centre + 0.25 * mesh_.nodes[n];
      std::ostringstream s;
      s << "element " << worst + 1 << " at " << at(centre) << " is inverted (scaled Jacobian " << worst_value << ")";
      fail(s.str());
    }
    if (std::abs(area - face_.area) > outer_chord_error + 1e-9 * face_.area) {
      fail("the elements cover " + std::to_string(area) + ", the face is " + std::to_string(face_.area));
    }
  }

  const FaceModel& face_;
  const Decomposition& d_;
  const MeshingOptions& options_;
  double tolerance_;
  std::vector<Segment> segments_;
  std::vector<std::vector<std::vector<PieceUse>>> uses_;  // per block, per side
  std::vector<BlockShape> shapes_;
  std::vector<int> vertex_of_end_;  // per segment end (2 s + 0 start, 2 s + 1 end)
  QuadMesh mesh_;
};

}  // namespace

BlockMesh mesh_blocks(const FaceModel& face, const Decomposition& decomposition, const MeshingOptions& options) {
  if (!(options.size > 0.0) || !std::isfinite(options.size))
    throw InputError("mesh size must be a positive number, got " + std::to_string(options.size));
  if (options.order != 1 && options.order != 2)
    throw InputError("element order must be 1 or 2, got " + std::to_string(options.order));
  return BlockMesher(face, decomposition, options).run();
}

}  // namespace mm
