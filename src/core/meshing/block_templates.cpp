#include "meshing/block_templates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "meshing/harmonic_solver.hpp"

namespace mm {
namespace {

using Chain = std::vector<int>;  // node ids along a line, ends included

[[noreturn]] void fail(int block, const std::string& what) {
  throw std::runtime_error("block " + std::to_string(block) + ": " + what);
}

// Appends nodes and quads of one block to a mesh.
struct Filler {
  QuadMesh& mesh;
  int block;

  Vec2 at(int id) const { return mesh.nodes[id]; }
  int add_node(Vec2 p) {
    mesh.nodes.push_back(p);
    mesh.places.push_back(NodePlace{});
    return static_cast<int>(mesh.nodes.size()) - 1;
  }
  void add_quad(int a, int b, int c, int d) {
    mesh.quads.push_back({a, b, c, d});
    mesh.block_of_quad.push_back(block);
  }
};

Chain reversed(Chain chain) {
  std::reverse(chain.begin(), chain.end());
  return chain;
}

// count intervals of a closed loop from index from on, wrapping around.
Chain loop_range(const Chain& loop, int from, int count) {
  const int n = static_cast<int>(loop.size());
  Chain chain(count + 1);
  for (int k = 0; k <= count; ++k) chain[k] = loop[((from + k) % n + n) % n];
  return chain;
}

// Cumulative arc-length fractions along a chain; index fractions when it has no length.
std::vector<double> arc_fractions(const Filler& f, const Chain& chain) {
  const int n = static_cast<int>(chain.size()) - 1;
  std::vector<double> fraction(n + 1, 0.0);
  for (int k = 1; k <= n; ++k) fraction[k] = fraction[k - 1] + distance(f.at(chain[k - 1]), f.at(chain[k]));
  const double total = fraction[n];
  for (int k = 0; k <= n; ++k) fraction[k] = total > 0.0 ? fraction[k] / total : double(k) / n;
  return fraction;
}

std::vector<double> averaged(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> mean(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) mean[k] = 0.5 * (a[k] + b[k]);
  return mean;
}

// A straight line of new nodes from one node to another, spaced by the given fractions.
Chain straight_line(Filler& f, int from, int to, const std::vector<double>& fractions) {
  const Vec2 a = f.at(from), b = f.at(to);
  const int n = static_cast<int>(fractions.size()) - 1;
  Chain chain(n + 1);
  chain[0] = from;
  chain[n] = to;
  for (int k = 1; k < n; ++k) chain[k] = f.add_node(a + fractions[k] * (b - a));
  return chain;
}

std::vector<double> uniform_fractions(int count) {
  std::vector<double> fraction(count + 1);
  for (int k = 0; k <= count; ++k) fraction[k] = double(k) / count;
  return fraction;
}

// A logical rectangle from its four sides, counter-clockwise: bottom (0,0) ->
// (nx,0), right (nx,0) -> (nx,ny), top (nx,ny) -> (0,ny), left (0,ny) ->
// (0,0). Interior nodes by discrete transfinite interpolation whose blending
// parameters are the sides' arc-length fractions, so graded sides grade the
// interior and every side is reproduced exactly.
void fill_patch(Filler& f, const Chain& bottom, const Chain& right, const Chain& top, const Chain& left) {
  const int nx = static_cast<int>(bottom.size()) - 1, ny = static_cast<int>(right.size()) - 1;
  if (nx < 1 || ny < 1 || static_cast<int>(top.size()) != nx + 1 || static_cast<int>(left.size()) != ny + 1 ||
      bottom.back() != right.front() || right.back() != top.front() || top.back() != left.front() ||
      left.back() != bottom.front())
    fail(f.block, "internal error: a mapped patch's sides do not match");
  std::vector<int> id((nx + 1) * (ny + 1), -1);
  auto node = [&](int i, int j) -> int& { return id[j * (nx + 1) + i]; };
  for (int i = 0; i <= nx; ++i) node(i, 0) = bottom[i], node(i, ny) = top[nx - i];
  for (int j = 0; j <= ny; ++j) node(nx, j) = right[j], node(0, j) = left[ny - j];

  const std::vector<double> sb = arc_fractions(f, bottom), tr = arc_fractions(f, right);
  const std::vector<double> st_rev = arc_fractions(f, top), tl_rev = arc_fractions(f, left);
  const Vec2 p00 = f.at(node(0, 0)), p10 = f.at(node(nx, 0)), p11 = f.at(node(nx, ny)), p01 = f.at(node(0, ny));
  for (int j = 1; j < ny; ++j) {
    const double tl = 1.0 - tl_rev[ny - j], tright = tr[j];
    for (int i = 1; i < nx; ++i) {
      const double s_bottom = sb[i], s_top = 1.0 - st_rev[nx - i];
      // Where the lines s = s_bottom..s_top and t = tl..tright cross.
      const double s = (s_bottom + (s_top - s_bottom) * tl) / (1.0 - (s_top - s_bottom) * (tright - tl));
      const double t = tl + (tright - tl) * s;
      const Vec2 p = (1 - t) * f.at(node(i, 0)) + t * f.at(node(i, ny)) + (1 - s) * f.at(node(0, j)) +
                     s * f.at(node(nx, j)) -
                     ((1 - s) * (1 - t) * p00 + s * (1 - t) * p10 + s * t * p11 + (1 - s) * t * p01);
      node(i, j) = f.add_node(p);
    }
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) f.add_quad(node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1));
}

// Midpoint subdivision of an m-sided loop: side i (corner i to corner i + 1)
// is cut c[i-1] intervals from corner i, the cut joins the centre by a
// straight line of c[i] intervals, and each corner gets a c[i] x c[i-1] patch.
void fill_midpoint(Filler& f, const Chain& loop, const std::vector<int>& corner_at, const std::vector<int>& c,
                   const std::string& what) {
  const int m = static_cast<int>(corner_at.size()), n = static_cast<int>(loop.size());
  std::vector<int> count(m);
  int total = 0;
  for (int i = 0; i < m; ++i) {
    count[i] = (i + 1 < m ? corner_at[i + 1] : n) - corner_at[i];
    total += count[i];
  }
  if (total % 2 != 0)
    fail(f.block, what + " has " + std::to_string(total) + " intervals in all; midpoint subdivision needs an even sum");
  if (static_cast<int>(c.size()) != m)
    fail(f.block, what + " needs " + std::to_string(m) + " midpoint parameters, got " + std::to_string(c.size()));
  auto c_at = [&](int i) { return c[(i % m + m) % m]; };
  for (int i = 0; i < m; ++i) {
    if (c[i] < 1) fail(f.block, what + ": midpoint parameter c_" + std::to_string(i) + " must be at least 1");
    if (count[i] != c_at(i - 1) + c_at(i + 1))
      fail(f.block, what + ": side " + std::to_string(i) + " has " + std::to_string(count[i]) + " intervals, but c_" +
                        std::to_string((i + m - 1) % m) + " + c_" + std::to_string((i + 1) % m) + " = " +
                        std::to_string(c_at(i - 1) + c_at(i + 1)));
  }
  std::vector<int> cut(m);
  Vec2 centre_at{0.0, 0.0};
  for (int i = 0; i < m; ++i) {
    cut[i] = corner_at[i] + c_at(i - 1);
    centre_at = centre_at + f.at(loop[cut[i] % n]) / m;
  }
  const int centre = f.add_node(centre_at);
  // Spoke i, cut i -> centre, spaced like the boundary pieces it faces in the
  // two patches beside it.
  std::vector<Chain> spoke(m);
  for (int i = 0; i < m; ++i) {
    const int im = (i + m - 1) % m, ip = (i + 1) % m;
    const Chain before = reversed(loop_range(loop, cut[im], c_at(i)));  // corner i -> cut i-1
    const Chain after = loop_range(loop, corner_at[ip], c_at(i));       // corner i+1 -> cut i+1
    spoke[i] = straight_line(f, loop[cut[i] % n], centre, averaged(arc_fractions(f, before), arc_fractions(f, after)));
  }
  for (int i = 0; i < m; ++i) {
    const int im = (i + m - 1) % m;
    fill_patch(f, loop_range(loop, corner_at[i], c_at(i - 1)), spoke[i], reversed(spoke[im]),
               loop_range(loop, cut[im], c_at(i)));
  }
}

bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

bool inside_loop(const Filler& f, const Chain& loop, Vec2 p) {
  bool inside = false;
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const Vec2 a = f.at(loop[k]), b = f.at(loop[(k + 1) % n]);
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) inside = !inside;
  }
  return inside;
}

// Whether the segment between two loop nodes' positions crosses an edge of the loop not touching them.
bool crosses_loop(const Filler& f, const Chain& loop, int from, Vec2 to) {
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const int a = loop[k], b = loop[(k + 1) % n];
    if (a == from || b == from) continue;
    if (segments_cross(f.at(from), to, f.at(a), f.at(b))) return true;
  }
  return false;
}

// The u x v quad at loop[0] (u steps forward, v steps back), its inner node at
// the parallelogram completion, pulled towards the corner until it sits
// inside the loop. Returns the rest of the loop: loop[u] .. loop[n-v], then
// back past the inner node to loop[u] (not repeated).
Chain fill_corner_quad(Filler& f, const Chain& loop, int u, int v) {
  const int n = static_cast<int>(loop.size());
  const int corner = loop[0], a = loop[u], b = loop[n - v];
  const Vec2 corner_at = f.at(corner), across = (f.at(a) - corner_at) + (f.at(b) - corner_at);
  double pull = 1.0;
  Vec2 inner = corner_at + across;
  for (int attempt = 0;; ++attempt) {
    inner = corner_at + pull * across;
    if (inside_loop(f, loop, inner) && !crosses_loop(f, loop, a, inner) && !crosses_loop(f, loop, b, inner)) break;
    if (attempt == 30) fail(f.block, "no room inside the outline for the inner node of the corner quad");
    pull *= 0.8;
  }
  const int q = f.add_node(inner);
  const Chain bottom = loop_range(loop, 0, u), left = loop_range(loop, n - v, v);
  const Chain right = straight_line(f, a, q, arc_fractions(f, reversed(left)));  // a -> q, spaced like corner -> b
  const Chain top = reversed(straight_line(f, b, q, arc_fractions(f, bottom)));  // q -> b
  fill_patch(f, bottom, right, top, left);

  Chain rest = loop_range(loop, u, n - v - u);
  rest.insert(rest.end(), top.rbegin() + 1, top.rend());          // past b, on to q
  rest.insert(rest.end(), right.rbegin() + 1, right.rend() - 1);  // past q, up to a (excluded)
  return rest;
}

void fill_two_sided(Filler& f, const Chain& loop, int corner1_at, const std::vector<int>& p, const std::string& what) {
  const int n = static_cast<int>(loop.size());
  if (p.size() != 5) fail(f.block, what + " needs 5 parameters (u, v, c_0, c_1, c_2), got " + std::to_string(p.size()));
  const int u = p[0], v = p[1], n0 = corner1_at, n1 = n - corner1_at;
  if (u < 1 || v < 1 || u >= n0 || v >= n1)
    fail(f.block, what + ": the corner quad " + std::to_string(u) + " x " + std::to_string(v) +
                      " does not fit sides of " + std::to_string(n0) + " and " + std::to_string(n1) + " intervals");
  const Chain rest = fill_corner_quad(f, loop, u, v);
  fill_midpoint(f, rest, {0, n0 - u, n - v - u}, {p[2], p[3], p[4]}, "the 3-sided rest of " + what);
}

void fill_one_sided(Filler& f, const Chain& loop, const std::vector<int>& p, const std::string& what) {
  const int n = static_cast<int>(loop.size());
  if (p.size() != 7)
    fail(f.block, what + " needs 7 parameters (u, v, then five two-sided), got " + std::to_string(p.size()));
  const int u = p[0], v = p[1];
  if (u < 1 || v < 1 || u + v >= n)
    fail(f.block, what + ": the corner quad " + std::to_string(u) + " x " + std::to_string(v) +
                      " does not fit a side of " + std::to_string(n) + " intervals");
  const Chain rest = fill_corner_quad(f, loop, u, v);
  fill_two_sided(f, rest, n - u - v, std::vector<int>(p.begin() + 2, p.end()), "the two-sided rest of " + what);
}

// The template's placement stands when its worst element is at least this
// good: the bar smoothing works up to (smoothing.cpp kGoodEnough). Below it
// the harmonic layout is tried as well and the better one kept.
constexpr double kPlacementGoodEnough = 0.9;
// The harmonic solve stops once no node is further than this fraction of
// the block's mean side from the mean of its neighbours: far below what
// changes an element's quality.
constexpr double kHarmonicTolerance = 1e-5;

double worst_scaled_jacobian(const QuadMesh& mesh, std::size_t first_quad) {
  double worst = 1.0;
  for (std::size_t k = first_quad; k < mesh.quads.size(); ++k)
    worst = std::min(worst, worst_corner_jacobian(mesh, mesh.quads[k]));
  return worst;
}

// The discrete harmonic map of the block's new nodes (every one the mean of
// its neighbours, the outline fixed), started from the nodes' current
// places. On a convex outline it never folds (Tutte), whatever the
// template's shape.
void place_harmonically(Filler& f, int first_new, std::size_t first_quad) {
  const int m = static_cast<int>(f.mesh.nodes.size()) - first_new;
  if (m <= 0) return;
  // Each new node's neighbours along the block's sides, an inner side seen
  // from both its quads; lists gathered by counting, then made unique.
  const std::size_t quads = f.mesh.quads.size() - first_quad;
  std::vector<int> start(m + 1, 0);
  double side_sum = 0.0;
  for (std::size_t k = first_quad; k < f.mesh.quads.size(); ++k) {
    const auto& q = f.mesh.quads[k];
    for (int i = 0; i < 4; ++i) {
      const Vec2 side = f.at(q[(i + 1) % 4]) - f.at(q[i]);
      side_sum += std::sqrt(dot(side, side));
      if (q[i] >= first_new) start[q[i] - first_new + 1] += 2;
    }
  }
  for (int k = 0; k < m; ++k) start[k + 1] += start[k];
  std::vector<int> seen(start[m]), fill(start.begin(), start.end() - 1);
  for (std::size_t k = first_quad; k < f.mesh.quads.size(); ++k) {
    const auto& q = f.mesh.quads[k];
    for (int i = 0; i < 4; ++i)
      if (q[i] >= first_new) {
        seen[fill[q[i] - first_new]++] = q[(i + 1) % 4];
        seen[fill[q[i] - first_new]++] = q[(i + 3) % 4];
      }
  }
  const double mean_side = side_sum / (4.0 * double(quads));
  // (D - A_free) x = sum of fixed neighbours, D the degrees.
  HarmonicSystem system;
  system.offset.assign(1, 0);
  system.degree.assign(m, 0.0);
  system.neighbour.reserve(start[m] / 2 + m);
  std::vector<Vec2> rhs(m, Vec2{0.0, 0.0}), x(f.mesh.nodes.begin() + first_new, f.mesh.nodes.end());
  for (int k = 0; k < m; ++k) {
    std::sort(seen.begin() + start[k], seen.begin() + start[k + 1]);
    const auto end = std::unique(seen.begin() + start[k], seen.begin() + start[k + 1]);
    for (auto it = seen.begin() + start[k]; it != end; ++it) {
      system.degree[k] += 1.0;
      if (*it >= first_new)
        system.neighbour.push_back(*it - first_new);
      else
        rhs[k] = rhs[k] + f.at(*it);
    }
    system.offset.push_back(static_cast<int>(system.neighbour.size()));
  }
  // The cap only guards against a stall: the result is judged anyway.
  try {
    solve_harmonic(system, rhs, x, kHarmonicTolerance * mean_side, 200);
  } catch (const std::invalid_argument& e) {
    fail(f.block, std::string("the harmonic layout cannot be solved: ") + e.what());
  }
  std::copy(x.begin(), x.end(), f.mesh.nodes.begin() + first_new);
}

// Winslow's sweeps stop once no node moves by more than this fraction of
// the block's mean side, or after this many. Each move is over-relaxed by
// kOverRelaxation: on the fuzz blobs this grid is for, 239 sweeps instead
// of 1 759 (3 180 quads), 1 361 instead of over 8 000 (18 088 quads).
constexpr double kWinslowTolerance = 1e-4;
constexpr int kWinslowSweeps = 4000;
constexpr double kOverRelaxation = 1.8;
// A harmonic map folded over at least this many of a submapped block's
// quads, and this share of them, is a band across the block, not a few
// elements at a corner: 65 to 1 544 quads (5 to 8 %) on blobs whose
// lattice wraps half round a hole (fuzz seed 45), 1 to 3 on the test faces
// at the default size.
constexpr std::size_t kWideFold = 10;
constexpr double kWideFoldShare = 0.02;

// Winslow's elliptic grid generation on a submapped block's lattice: every
// interior node solves the inverted Laplace equations (the logical
// coordinates harmonic over the block, not the places harmonic over the
// lattice), by over-relaxed Gauss-Seidel sweeps from the nodes' current
// places. Where the outline bends far inwards (a side wrapped half round a
// hole) the harmonic map pulls rows of nodes across it and folds;
// Winslow's grid follows the bend. `at(i, j)` is the node at a lattice
// point; an interior point has all eight lattice neighbours (its four cells
// are inside).
template <class At>
void place_by_winslow(Filler& f, const At& at, const std::vector<std::array<int, 2>>& interior,
                      std::size_t first_quad) {
  double side_sum = 0.0;
  for (std::size_t k = first_quad; k < f.mesh.quads.size(); ++k) {
    const auto& q = f.mesh.quads[k];
    for (int i = 0; i < 4; ++i) side_sum += norm(f.at(q[(i + 1) % 4]) - f.at(q[i]));
  }
  const double still = kWinslowTolerance * side_sum / (4.0 * double(f.mesh.quads.size() - first_quad));
  for (int sweep = 0; sweep < kWinslowSweeps; ++sweep) {
    double moved = 0.0;
    for (const auto& [i, j] : interior) {
      const auto p = [&](int di, int dj) { return f.at(at(i + di, j + dj)); };
      const Vec2 along_x = 0.5 * (p(1, 0) - p(-1, 0)), along_y = 0.5 * (p(0, 1) - p(0, -1));
      const double a = dot(along_y, along_y), g = dot(along_x, along_x), b = dot(along_x, along_y);
      if (!(a + g > 0.0)) continue;
      const Vec2 cross_term = p(1, 1) - p(1, -1) - p(-1, 1) + p(-1, -1);
      const Vec2 next =
          (a * (p(1, 0) + p(-1, 0)) + g * (p(0, 1) + p(0, -1)) - (0.5 * b) * cross_term) / (2.0 * (a + g));
      Vec2& node = f.mesh.nodes[at(i, j)];
      moved = std::max(moved, distance(next, node));
      node = node + kOverRelaxation * (next - node);
    }
    if (moved < still) break;
  }
}

// Keeps the template's placement when it is good enough; otherwise also
// tries the harmonic one (it rescues templates whose straight inner lines
// fold on curved or sharp outlines; it loses the sides' grading, so it must
// earn its place) and keeps the better worst element.
void keep_better_of_harmonic(Filler& f, int first_new, std::size_t first_quad) {
  const double placed = worst_scaled_jacobian(f.mesh, first_quad);
  if (placed >= kPlacementGoodEnough) return;
  const std::vector<Vec2> kept(f.mesh.nodes.begin() + first_new, f.mesh.nodes.end());
  place_harmonically(f, first_new, first_quad);
  if (worst_scaled_jacobian(f.mesh, first_quad) <= placed)
    std::copy(kept.begin(), kept.end(), f.mesh.nodes.begin() + first_new);
}

Vec2 area_centroid(const Filler& f, const Chain& loop) {
  double area = 0.0;
  Vec2 sum{0.0, 0.0};
  const int n = static_cast<int>(loop.size());
  for (int k = 0; k < n; ++k) {
    const Vec2 a = f.at(loop[k]), b = f.at(loop[(k + 1) % n]);
    const double w = cross(a, b);
    area += w;
    sum = sum + w * (a + b);
  }
  return sum / (3.0 * area);
}

double loop_length(const Filler& f, const Chain& loop) {
  double length = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k) length += distance(f.at(loop[k]), f.at(loop[(k + 1) % loop.size()]));
  return length;
}

// The O-grid: ring corners at loop[start], +a, +a+b, +2a+b; an inner a x b
// quadrilateral whose corners are the ring corners moved in by `depth` along
// the loop's principal axes (so an elongated loop keeps an even ring), its
// sides spaced like the loop's; straight radial lines between, with as many
// layers as make ring elements near square. Returns how uniform the element
// sizes are (smallest over largest of ring depth, inner and outer spacing).
double fill_disc_layout(Filler& f, const Chain& loop, int start, double depth_fraction, int a, int b) {
  const int n = static_cast<int>(loop.size());
  const Chain outer = loop_range(loop, start, n);  // closed: outer[n] == outer[0]
  const std::array<int, 4> offset{0, a, a + b, 2 * a + b}, count{a, b, a, b};
  const Vec2 centre = area_centroid(f, loop);
  // Principal axes of the loop's nodes about the centroid, and its half extents along them.
  double xx = 0.0, xy = 0.0, yy = 0.0;
  for (int id : loop) {
    const Vec2 d = f.at(id) - centre;
    xx += d.x * d.x, xy += d.x * d.y, yy += d.y * d.y;
  }
  const double angle = 0.5 * std::atan2(2.0 * xy, xx - yy);
  const Vec2 axis[2] = {{std::cos(angle), std::sin(angle)}, {-std::sin(angle), std::cos(angle)}};
  double half[2] = {0.0, 0.0};
  for (int id : loop)
    for (int k = 0; k < 2; ++k) half[k] = std::max(half[k], std::abs(dot(f.at(id) - centre, axis[k])));
  const double inset = depth_fraction * std::min(half[0], half[1]);
  std::array<int, 4> inner_corner;
  for (int k = 0; k < 4; ++k) {
    const Vec2 d = f.at(outer[offset[k]]) - centre;
    Vec2 moved = centre;
    for (int j = 0; j < 2; ++j) moved = moved + (1.0 - inset / half[j]) * dot(d, axis[j]) * axis[j];
    inner_corner[k] = f.add_node(moved);
  }
  Chain inner;  // the inner loop, aligned with outer
  std::array<Chain, 4> inner_side;
  for (int k = 0; k < 4; ++k) {
    const Chain outer_side(outer.begin() + offset[k], outer.begin() + offset[k] + count[k] + 1);
    inner_side[k] = straight_line(f, inner_corner[k], inner_corner[(k + 1) % 4], arc_fractions(f, outer_side));
    inner.insert(inner.end(), inner_side[k].begin(), inner_side[k].end() - 1);
  }
  double depth = 0.0;
  for (int k = 0; k < n; ++k) depth += distance(f.at(outer[k]), f.at(inner[k])) / n;
  const double outer_spacing = loop_length(f, loop) / n, inner_spacing = loop_length(f, inner) / n;
  const int layers = std::max(1, static_cast<int>(std::lround(2.0 * depth / (outer_spacing + inner_spacing))));

  fill_patch(f, inner_side[0], inner_side[1], inner_side[2], inner_side[3]);
  std::vector<Chain> radial(n + 1);
  for (int k = 0; k < n; ++k) radial[k] = straight_line(f, outer[k], inner[k], uniform_fractions(layers));
  radial[n] = radial[0];
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < layers; ++l) f.add_quad(radial[k][l], radial[k + 1][l], radial[k + 1][l + 1], radial[k][l + 1]);
  const double sizes[3] = {depth / layers, outer_spacing, inner_spacing};
  return *std::min_element(sizes, sizes + 3) / *std::max_element(sizes, sizes + 3);
}

// Loops longer than this choose their disc layout on a coarse copy. On the
// circle and three B-spline blobs from 0.03 to 0.005 of the diagonal, 64
// chose layouts as good as 192 did (the same minimum, means within 5e-4)
// in a fifth of the time: every trial fills the whole coarse disc.
constexpr int kDiscTrialNodes = 64;

void fill_disc(Filler& f, const Chain& loop, const std::vector<int>& p) {
  const int n = static_cast<int>(loop.size());
  if (p.size() != 2) fail(f.block, "a disc needs 2 parameters (a, b), got " + std::to_string(p.size()));
  const int a = p[0], b = p[1];
  if (a < 1 || b < 1 || 2 * a + 2 * b != n)
    fail(f.block, "a disc of " + std::to_string(n) + " intervals cannot hold an inner " + std::to_string(a) + " x " +
                      std::to_string(b) + " rectangle (needs 2a + 2b = " + std::to_string(n) + ")");
  // Try ring corner positions and inner sizes on a scratch copy of the loop;
  // keep the best worst element, then the most uniform sizes. A long loop is
  // copied coarsely (every trial fills the whole disc, and the best layout
  // hardly depends on the resolution), the chosen start mapped back.
  const double stride = n > kDiscTrialNodes ? double(n) / kDiscTrialNodes : 1.0;
  const int trial_a = stride > 1.0 ? std::max(1, static_cast<int>(std::lround(a / stride))) : a;
  const int trial_b = stride > 1.0 ? std::max(1, static_cast<int>(std::lround(b / stride))) : b;
  const int trial_n = 2 * trial_a + 2 * trial_b;
  const auto fine_index = [&](int k) { return static_cast<int>(std::lround(double(k) * n / trial_n)) % n; };
  QuadMesh scratch;
  Chain scratch_loop(trial_n);
  for (int k = 0; k < trial_n; ++k) scratch.nodes.push_back(f.at(loop[fine_index(k)])), scratch_loop[k] = k;
  scratch.places.resize(trial_n);
  const int step = std::max(1, trial_n / 96);
  double best_score = -std::numeric_limits<double>::infinity(), best_depth = 0.5;
  int best_start = 0;
  for (int start = 0; start < trial_n; start += step) {
    for (double depth = 0.25; depth < 0.7; depth += 0.1) {
      scratch.nodes.resize(trial_n);
      scratch.places.resize(trial_n);
      scratch.quads.clear();
      scratch.block_of_quad.clear();
      Filler trial{scratch, f.block};
      const double uniformity = fill_disc_layout(trial, scratch_loop, start, depth, trial_a, trial_b);
      // The worst corner only falls: once this layout cannot beat the best
      // (rounding keeps the order of the sums), the rest need not be valued.
      double worst = 1.0;
      for (const auto& q : scratch.quads) {
        worst = std::min(worst, worst_corner_jacobian(scratch, q));
        if (worst + 0.5 * uniformity <= best_score) break;
      }
      const double score = worst + 0.5 * uniformity;
      if (score > best_score) best_score = score, best_start = start, best_depth = depth;
    }
  }
  best_start = fine_index(best_start);
  fill_disc_layout(f, loop, best_start, best_depth, a, b);
}

// Submapping: integer logical coordinates from the turning at the corners; the
// lattice cells inside the logical outline are the quads. A plain 4-sided
// outline is filled by transfinite interpolation, anything with a reflex
// corner by the discrete harmonic map with the outline fixed.
void fill_submap(Filler& f, const BlockShape& shape, const Chain& loop, const std::vector<int>& corner_at,
                 bool regrid_wide_folds) {
  const int n = static_cast<int>(loop.size()), corners = static_cast<int>(corner_at.size());
  if (static_cast<int>(shape.corner_types.size()) != corners)
    fail(f.block, "the shape has " + std::to_string(shape.corner_types.size()) + " corner types for " +
                      std::to_string(corners) + " corners");
  int turning = 0;
  for (int i = 0; i < corners; ++i) {
    const int type = shape.corner_types[i];
    if (type < 1 || type > 3)
      fail(f.block, "corner " + std::to_string(i) + " of type " + std::to_string(type) +
                        " cannot be submapped (only convex, flat and reflex corners, types 1 to 3)");
    turning += 2 - type;
  }
  if (turning != 4)
    fail(f.block, "the corner types turn by " + std::to_string(turning) + " quarter turns, a submapped block needs 4");

  const int step_x[4] = {1, 0, -1, 0}, step_y[4] = {0, 1, 0, -1};
  std::vector<std::array<int, 2>> logical(n);
  int sums[4] = {0, 0, 0, 0};
  int x = 0, y = 0, direction = 0;
  for (int i = 0; i < corners; ++i) {
    if (i > 0) direction = (direction + 2 - shape.corner_types[i] + 4) % 4;
    const int end = i + 1 < corners ? corner_at[i + 1] : n;
    sums[direction] += end - corner_at[i];
    for (int k = corner_at[i]; k < end; ++k) {
      logical[k] = {x, y};
      x += step_x[direction], y += step_y[direction];
    }
  }
  if (sums[0] != sums[2] || sums[1] != sums[3])
    fail(f.block, "the submapped sides do not close: " + std::to_string(sums[0]) + " intervals east against " +
                      std::to_string(sums[2]) + " west, " + std::to_string(sums[1]) + " north against " +
                      std::to_string(sums[3]) + " south");

  int x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  for (const auto& p : logical) {
    x_min = std::min(x_min, p[0]), x_max = std::max(x_max, p[0]);
    y_min = std::min(y_min, p[1]), y_max = std::max(y_max, p[1]);
  }
  const int width = x_max - x_min, height = y_max - y_min;
  std::vector<int> id((width + 1) * (height + 1), -1);
  auto node = [&](int i, int j) -> int& { return id[(j - y_min) * (width + 1) + (i - x_min)]; };
  for (int k = 0; k < n; ++k) {
    int& slot = node(logical[k][0], logical[k][1]);
    // A block that runs along a split both ways (one cut to a hole) meets
    // the split's nodes twice, at the same logical places: a slit.
    if (slot >= 0 && loop[slot] != loop[k])
      fail(f.block, "the submapped logical outline overlaps itself (outline nodes " + std::to_string(slot) + " and " +
                        std::to_string(k) + " meet)");
    slot = k;
  }
  // Cells inside: parity of the vertical outline edges left of each cell.
  std::vector<char> crossing(width * height, 0);
  for (int k = 0; k < n; ++k) {
    const auto p = logical[k], q = logical[(k + 1) % n];
    if (p[0] == q[0] && p[0] < x_max) crossing[(std::min(p[1], q[1]) - y_min) * width + (p[0] - x_min)] ^= 1;
  }
  std::vector<char> cell_inside(width * height, 0);
  for (int j = 0; j < height; ++j) {
    char parity = 0;
    for (int i = 0; i < width; ++i) {
      parity ^= crossing[j * width + i];
      cell_inside[j * width + i] = parity;
    }
  }
  for (int& slot : id)
    if (slot >= 0) slot = loop[slot];

  const bool plain_rectangle = std::count(shape.corner_types.begin(), shape.corner_types.end(), 3) == 0;
  if (plain_rectangle) {
    std::array<int, 4> turn_at{};  // outline indices of the four convex corners
    int found = 0;
    for (int i = 0; i < corners; ++i)
      if (shape.corner_types[i] == 1) turn_at[found++] = corner_at[i];
    std::array<Chain, 4> side;
    for (int s = 0; s < 4; ++s) {
      const int from = turn_at[s], to = s + 1 < 4 ? turn_at[s + 1] : turn_at[0] + n;
      side[s] = loop_range(loop, from, to - from);
    }
    fill_patch(f, side[0], side[1], side[2], side[3]);
    return;
  }

  // Interior lattice points: not on the outline, next to an inside cell.
  std::vector<std::array<int, 2>> interior;
  for (int j = y_min + 1; j < y_max; ++j)
    for (int i = x_min + 1; i < x_max; ++i)
      if (node(i, j) < 0 && cell_inside[(j - y_min) * width + (i - x_min)]) {
        node(i, j) = -2;
        interior.push_back({i, j});
      }
  const int first_new = static_cast<int>(f.mesh.nodes.size());
  const std::size_t first_quad = f.mesh.quads.size();
  for (const auto& p : interior) node(p[0], p[1]) = f.add_node(Vec2{0.0, 0.0});
  // Start from the mean of linear interpolations between the outline nodes
  // met along each interior node's lattice row and column (the outline is a
  // lattice polygon, so going straight from an interior node meets it before
  // leaving): near the harmonic map, so conjugate gradients finish early.
  const auto from_outline = [&](int i, int j) { return node(i, j) >= 0 && node(i, j) < first_new; };
  const auto blend = [&](int a, int b, int k, int from, int to) {
    const double s = double(k - from) / double(to - from);
    return (1.0 - s) * f.at(a) + s * f.at(b);
  };
  for (int j = y_min + 1; j < y_max; ++j)
    for (int i = x_min, last = x_min; i < x_max; ++i) {
      if (from_outline(i, j)) last = i;
      if (node(i, j) < first_new) continue;
      int next = i + 1;
      while (!from_outline(next, j)) ++next;
      for (int k = i; k < next; ++k)
        f.mesh.nodes[node(k, j)] = 0.5 * blend(node(last, j), node(next, j), k, last, next);
      i = next;
      last = next;
    }
  for (int i = x_min + 1; i < x_max; ++i)
    for (int j = y_min, last = y_min; j < y_max; ++j) {
      if (from_outline(i, j)) last = j;
      if (node(i, j) < first_new) continue;
      int next = j + 1;
      while (!from_outline(i, next)) ++next;
      for (int k = j; k < next; ++k)
        f.mesh.nodes[node(i, k)] = f.mesh.nodes[node(i, k)] + 0.5 * blend(node(i, last), node(i, next), k, last, next);
      j = next;
      last = next;
    }
  for (int j = y_min; j < y_max; ++j)
    for (int i = x_min; i < x_max; ++i)
      if (cell_inside[(j - y_min) * width + (i - x_min)])
        f.add_quad(node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1));
  place_harmonically(f, first_new, first_quad);
  // A harmonic map folded over a band of the block (an outline bent far
  // inwards), when asked: Winslow's grid from there, kept if its worst
  // element is better. Only as a last resort: where smoothing untangles
  // the harmonic map, its mesh came out better (on the test faces at a
  // fifth of the default size, 0.87 against 0.42 on bspline_29_1052).
  if (!regrid_wide_folds) return;
  double harmonic = 1.0;
  std::size_t folded = 0;
  for (std::size_t k = first_quad; k < f.mesh.quads.size(); ++k) {
    const double value = worst_corner_jacobian(f.mesh, f.mesh.quads[k]);
    harmonic = std::min(harmonic, value);
    folded += value <= 0.0 ? 1 : 0;
  }
  const std::size_t quads = f.mesh.quads.size() - first_quad;
  if (folded < kWideFold || double(folded) < kWideFoldShare * double(quads)) return;
  const std::vector<Vec2> kept(f.mesh.nodes.begin() + first_new, f.mesh.nodes.end());
  place_by_winslow(f, node, interior, first_quad);
  if (worst_scaled_jacobian(f.mesh, first_quad) <= harmonic)
    std::copy(kept.begin(), kept.end(), f.mesh.nodes.begin() + first_new);
}

}  // namespace

void fill_block(const BlockShape& shape, const std::vector<int>& params, const BlockOutline& outline, int block,
                QuadMesh& mesh, bool regrid_wide_folds) {
  Filler f{mesh, block};
  const int first_new = static_cast<int>(mesh.nodes.size());
  const std::size_t first_quad = mesh.quads.size();
  const Chain& loop = outline.nodes;
  const int n = static_cast<int>(loop.size());
  if (n < 2) fail(block, "an outline needs at least 2 nodes, got " + std::to_string(n));
  for (int id : loop)
    if (id < 0 || id >= static_cast<int>(mesh.nodes.size()))
      fail(block, "outline node " + std::to_string(id) + " is not in the mesh");
  const std::vector<int>& corner_at = outline.corner_at;
  for (std::size_t i = 0; i < corner_at.size(); ++i)
    if ((i == 0 && corner_at[0] != 0) || (i > 0 && corner_at[i] <= corner_at[i - 1]) || corner_at[i] >= n)
      fail(block, "corner positions on the outline must start at 0 and increase within the outline");
  const int corners = static_cast<int>(corner_at.size());
  auto need_corners = [&](int wanted, const char* kind) {
    if (corners != wanted)
      fail(block, std::string(kind) + " needs " + std::to_string(wanted) + " corners, the outline has " +
                      std::to_string(corners));
  };
  switch (shape.kind) {
    case BlockTemplate::Midpoint:
      if (corners < 3)
        fail(block, "midpoint subdivision needs at least 3 corners, the outline has " + std::to_string(corners));
      fill_midpoint(f, loop, corner_at, params, "the " + std::to_string(corners) + "-sided block");
      break;
    case BlockTemplate::TwoSided:
      need_corners(2, "the two-sided template");
      fill_two_sided(f, loop, corner_at[1], params, "the two-sided block");
      break;
    case BlockTemplate::OneSided:
      need_corners(1, "the one-sided template");
      fill_one_sided(f, loop, params, "the one-sided block");
      break;
    case BlockTemplate::Disc:
      if (corners > 1) fail(block, "a disc has no corners, the outline has " + std::to_string(corners));
      fill_disc(f, loop, params);
      break;
    case BlockTemplate::Submap:
      if (!params.empty()) fail(block, "submapping takes no parameters, got " + std::to_string(params.size()));
      fill_submap(f, shape, loop, corner_at, regrid_wide_folds);
      break;
  }
  keep_better_of_harmonic(f, first_new, first_quad);
}

}  // namespace mm
