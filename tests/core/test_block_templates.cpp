// Block templates on real shapes: outlines placed by hand on squares, circles,
// polygons, lenses, teardrops and L-, U-, T-shapes; each filled block must be
// conforming, counter-clockwise, uninverted and tile the outline exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>

#include "geometry/polygon.hpp"
#include "meshing/block_templates.hpp"

namespace mm {
namespace {

struct Outlined {
  QuadMesh mesh;
  BlockOutline outline;
};

// Outline nodes from a closed polygon's corners, each side cut into counts[i]
// intervals; spacing maps [0,1] onto itself to grade a side.
Outlined polygon_outline(const std::vector<Vec2>& corners, const std::vector<int>& counts,
                         const std::function<double(int side, double)>& spacing = nullptr) {
  Outlined o;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    o.outline.corner_at.push_back(static_cast<int>(o.mesh.nodes.size()));
    const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
    for (int k = 0; k < counts[i]; ++k) {
      const double t = double(k) / counts[i];
      o.outline.nodes.push_back(static_cast<int>(o.mesh.nodes.size()));
      o.mesh.nodes.push_back(a + (spacing ? spacing(static_cast<int>(i), t) : t) * (b - a));
    }
  }
  o.mesh.places.assign(o.mesh.nodes.size(), NodePlace{0, 0, 0.0, false, 2});
  return o;
}

// Outline nodes on closed curves: pieces[i] maps [0,1] to side i, count[i] intervals each.
Outlined curve_outline(const std::vector<std::function<Vec2(double)>>& pieces, const std::vector<int>& counts,
                       bool with_corners = true) {
  Outlined o;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (with_corners) o.outline.corner_at.push_back(static_cast<int>(o.mesh.nodes.size()));
    for (int k = 0; k < counts[i]; ++k) {
      o.outline.nodes.push_back(static_cast<int>(o.mesh.nodes.size()));
      o.mesh.nodes.push_back(pieces[i](double(k) / counts[i]));
    }
  }
  o.mesh.places.assign(o.mesh.nodes.size(), NodePlace{0, 0, 0.0, false, 2});
  return o;
}

Outlined regular_polygon(int sides, const std::vector<int>& counts) {
  std::vector<Vec2> corners;
  for (int i = 0; i < sides; ++i) corners.push_back({std::cos(2 * kPi * i / sides), std::sin(2 * kPi * i / sides)});
  return polygon_outline(corners, counts);
}

Outlined ellipse(double rx, double ry, int count) {
  Outlined o = curve_outline({[&](double t) {
                               return Vec2{rx * std::cos(2 * kPi * t), ry * std::sin(2 * kPi * t)};
                             }},
                             {count}, false);
  return o;
}

double quad_area(const QuadMesh& mesh, const std::array<int, 4>& q) {
  return polygon_area({mesh.nodes[q[0]], mesh.nodes[q[1]], mesh.nodes[q[2]], mesh.nodes[q[3]]});
}

void dump_svg(const QuadMesh& mesh, const std::string& name) {
  const char* folder = std::getenv("MEDIALMESH_TEST_SVG_DIR");
  if (!folder) return;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Vec2& p : mesh.nodes)
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  const double s = 600.0 / std::max(x1 - x0, y1 - y0);
  std::ofstream out(std::string(folder) + "/" + name + ".svg");
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='640' height='640'><rect width='640' height='640' "
         "fill='white'/>";
  for (const auto& q : mesh.quads) {
    out << "<polygon fill='#cde' stroke='black' stroke-width='1' points='";
    for (int id : q) out << 20 + s * (mesh.nodes[id].x - x0) << ',' << 620 - s * (mesh.nodes[id].y - y0) << ' ';
    out << "'/>";
  }
  out << "</svg>\n";
}

struct Checked {
  std::map<int, int> interior_valences;  // valence -> interior nodes with it
  double min_scaled_jacobian = 1.0;
};

// The invariants every filled block must have; returns the interior valences.
Checked check_block(const Outlined& o, int block, const std::string& name) {
  const QuadMesh& mesh = o.mesh;
  dump_svg(mesh, name);
  Checked c;
  const int outline_count = static_cast<int>(o.outline.nodes.size());
  EXPECT_EQ(mesh.nodes.size(), mesh.places.size()) << name;
  EXPECT_EQ(mesh.quads.size(), mesh.block_of_quad.size()) << name;
  for (std::size_t k = outline_count; k < mesh.places.size(); ++k) {
    EXPECT_EQ(mesh.places[k].loop, -1) << name;
    EXPECT_EQ(mesh.places[k].corner_elements, 0) << name;
  }
  std::map<std::pair<int, int>, int> directed;
  std::vector<int> valence(mesh.nodes.size(), 0);
  double area = 0.0;
  for (std::size_t k = 0; k < mesh.quads.size(); ++k) {
    const auto& q = mesh.quads[k];
    EXPECT_EQ(mesh.block_of_quad[k], block) << name;
    for (int i = 0; i < 4; ++i) {
      ++directed[{q[i], q[(i + 1) % 4]}];
      ++valence[q[i]];
      const Vec2 p = mesh.nodes[q[i]];
      const Vec2 e1 = mesh.nodes[q[(i + 1) % 4]] - p, e2 = mesh.nodes[q[(i + 3) % 4]] - p;
      const double sj = cross(e1, e2) / (norm(e1) * norm(e2));
      c.min_scaled_jacobian = std::min(c.min_scaled_jacobian, sj);
    }
    area += quad_area(mesh, q);
  }
  EXPECT_GT(c.min_scaled_jacobian, 0.0) << name << ": an inverted or degenerate element";
  std::vector<Vec2> outline_points;
  for (int k = 0; k < outline_count; ++k) {
    const int a = o.outline.nodes[k], b = o.outline.nodes[(k + 1) % outline_count];
    outline_points.push_back(mesh.nodes[a]);
    EXPECT_EQ(directed.count(std::make_pair(a, b)), 1u)
        << name << ": outline edge " << k << " not used once along the outline";
    EXPECT_EQ(directed.count(std::make_pair(b, a)), 0u)
        << name << ": outline edge " << k << " used against the outline";
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << name << ": edge " << edge.first << "-" << edge.second << " repeated in one direction";
    const bool on_outline =
        edge.first < outline_count && edge.second < outline_count && (edge.second == (edge.first + 1) % outline_count);
    if (!on_outline) {
      EXPECT_EQ(directed.count(std::make_pair(edge.second, edge.first)), 1u) << name << ": a boundary edge inside";
    }
  }
  EXPECT_NEAR(area, polygon_area(outline_points), 1e-9 * std::abs(polygon_area(outline_points))) << name;
  for (std::size_t k = outline_count; k < mesh.nodes.size(); ++k) ++c.interior_valences[valence[k]];
  return c;
}

int irregular(const Checked& c) {
  int count = 0;
  for (const auto& [v, n] : c.interior_valences)
    if (v != 4) count += n;
  return count;
}

BlockShape shape_of(BlockTemplate kind, std::vector<int> types = {}) {
  BlockShape shape;
  shape.kind = kind;
  shape.corner_types = std::move(types);
  return shape;
}

TEST(BlockTemplates, MappedUnitSquare) {
  Outlined o = polygon_outline({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {5, 3, 5, 3});
  fill_block(shape_of(BlockTemplate::Submap, {1, 1, 1, 1}), {}, o.outline, 4, o.mesh);
  EXPECT_EQ(o.mesh.quads.size(), 15u);
  const Checked c = check_block(o, 4, "square");
  EXPECT_EQ(irregular(c), 0);
  EXPECT_NEAR(c.min_scaled_jacobian, 1.0, 1e-12);
}

TEST(BlockTemplates, GradedRectangleGradesTheInterior) {
  // Bottom and top graded towards x = 0, the sides towards y = 0.
  auto grade = [](int side, double t) {
    const double g = t * t;
    return side == 0 || side == 1 ? g : 1 - (1 - t) * (1 - t);
  };
  Outlined o = polygon_outline({{0, 0}, {2, 0}, {2, 1}, {0, 1}}, {6, 4, 6, 4}, grade);
  fill_block(shape_of(BlockTemplate::Submap, {1, 1, 1, 1}), {}, o.outline, 0, o.mesh);
  EXPECT_EQ(o.mesh.quads.size(), 24u);
  check_block(o, 0, "graded");
  // Every interior node lies on the column of its bottom node and the row of its right node.
  for (std::size_t k = o.outline.nodes.size(); k < o.mesh.nodes.size(); ++k) {
    const Vec2 p = o.mesh.nodes[k];
    bool on_column = false, on_row = false;
    for (int i = 1; i < 6; ++i) on_column |= std::abs(p.x - 2 * (i / 6.0) * (i / 6.0)) < 1e-12;
    for (int j = 1; j < 4; ++j) on_row |= std::abs(p.y - (j / 4.0) * (j / 4.0)) < 1e-12;
    EXPECT_TRUE(on_column && on_row) << p.x << " " << p.y;
  }
}

TEST(BlockTemplates, CircleDiscs) {
  // 600 intervals: the layout is chosen on a coarse copy of the loop.
  for (int count : {16, 24, 600}) {
    Outlined o = ellipse(1.0, 1.0, count);
    const int a = count / 4, b = count / 4;
    fill_block(shape_of(BlockTemplate::Disc), {a, b}, o.outline, 1, o.mesh);
    const int ring = static_cast<int>(o.mesh.quads.size()) - a * b;
    EXPECT_GT(ring, 0);
    EXPECT_EQ(ring % count, 0) << "the ring is whole layers";
    const Checked c = check_block(o, 1, "circle" + std::to_string(count));
    EXPECT_EQ(c.interior_valences.at(3), 4);
    EXPECT_EQ(irregular(c), 4);
    EXPECT_GT(c.min_scaled_jacobian, 0.5) << count;
  }
}

// The same ellipse at a coarse and a fine count: the fine one's layout is
// chosen on a coarse copy (of 64 nodes) and must be about as good as the
// search over every node of the coarse one.
TEST(BlockTemplates, LongDiscLoopKeepsTheCoarseLayoutQuality) {
  double worst[2];
  for (int k = 0; k < 2; ++k) {
    const int count = k == 0 ? 60 : 960;
    Outlined o = ellipse(2.0, 1.0, count);
    fill_block(shape_of(BlockTemplate::Disc), {count / 3, count / 6}, o.outline, 1, o.mesh);
    const Checked c = check_block(o, 1, "ellipse" + std::to_string(count));
    EXPECT_EQ(irregular(c), 4) << count;
    worst[k] = c.min_scaled_jacobian;
  }
  EXPECT_GT(worst[1], worst[0] - 0.1);
}

TEST(BlockTemplates, EllipseDisc) {
  Outlined o = ellipse(3.0, 1.0, 32);
  fill_block(shape_of(BlockTemplate::Disc), {11, 5}, o.outline, 2, o.mesh);
  EXPECT_EQ((o.mesh.quads.size() - 55) % 32, 0u);
  const Checked c = check_block(o, 2, "ellipse");
  EXPECT_EQ(c.interior_valences.at(3), 4);
  EXPECT_EQ(irregular(c), 4);
  EXPECT_GT(c.min_scaled_jacobian, 0.3);
}

// Midpoint subdivision: sum over corners of c_{i-1} c_i quads, a centre of valence m.
void expect_midpoint(Outlined o, const std::vector<int>& c, const std::string& name) {
  const int m = static_cast<int>(c.size());
  fill_block(shape_of(BlockTemplate::Midpoint, std::vector<int>(m, 1)), c, o.outline, 5, o.mesh);
  int quads = 0;
  for (int i = 0; i < m; ++i) quads += c[(i + m - 1) % m] * c[i];
  EXPECT_EQ(static_cast<int>(o.mesh.quads.size()), quads) << name;
  const Checked checked = check_block(o, 5, name);
  EXPECT_EQ(irregular(checked), 1) << name;
  EXPECT_EQ(checked.interior_valences.count(m), 1u) << name;
  EXPECT_GT(checked.min_scaled_jacobian, 0.2) << name;
}

TEST(BlockTemplates, MidpointTrianglesPentagonHexagon) {
  const std::vector<Vec2> triangle{{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}};
  expect_midpoint(polygon_outline(triangle, {4, 4, 4}), {2, 2, 2}, "triangle444");
  // n_i = c_{i-1} + c_{i+1}: 3 = c_2 + c_1, 5 = c_0 + c_2, 6 = c_1 + c_0.
  expect_midpoint(polygon_outline(triangle, {3, 5, 6}), {4, 2, 1}, "triangle356");
  expect_midpoint(regular_polygon(5, {4, 4, 4, 4, 4}), {2, 2, 2, 2, 2}, "pentagon");
  expect_midpoint(regular_polygon(6, {2, 2, 2, 2, 2, 2}), {1, 1, 1, 1, 1, 1}, "hexagon2");
  expect_midpoint(regular_polygon(6, {4, 6, 4, 6, 4, 6}), {3, 2, 3, 2, 3, 2}, "hexagon46");
}

// Two circular arcs meeting at (-1, 0) and (1, 0) at 90 degrees.
Outlined lens(int lower, int upper) {
  const double radius = std::sqrt(2.0);
  return curve_outline({[=](double t) {
                          const double angle = -3 * kPi / 4 + t * kPi / 2;
                          return Vec2{radius * std::cos(angle), 1 + radius * std::sin(angle)};
                        },
                        [=](double t) {
                          const double angle = kPi / 4 + t * kPi / 2;
                          return Vec2{radius * std::cos(angle), -1 + radius * std::sin(angle)};
                        }},
                       {lower, upper});
}

TEST(BlockTemplates, TwoSidedLens) {
  struct Case {
    int lower, upper;
    std::vector<int> params;
  };
  // Rest: L_0 = n_0 - u, L_1 = n_1 - v, L_2 = u + v, L_i = c_{i-1} + c_{i+1}.
  for (const Case& k : {Case{8, 8, {2, 2, 2, 2, 4}}, Case{10, 8, {3, 2, 2, 3, 4}}, Case{6, 6, {1, 1, 1, 1, 4}}}) {
    Outlined o = lens(k.lower, k.upper);
    fill_block(shape_of(BlockTemplate::TwoSided, {1, 1}), k.params, o.outline, 3, o.mesh);
    const std::vector<int>& p = k.params;
    EXPECT_EQ(static_cast<int>(o.mesh.quads.size()), p[0] * p[1] + p[2] * p[3] + p[3] * p[4] + p[4] * p[2]);
    const std::string name = "lens" + std::to_string(k.lower) + "_" + std::to_string(k.upper);
    const Checked c = check_block(o, 3, name);
    EXPECT_EQ(c.interior_valences.at(3), 2) << name;
    EXPECT_EQ(irregular(c), 2) << name;
  }
}

TEST(BlockTemplates, OneSidedTeardrop) {
  // Tip at the origin, straight flanks tangent to the unit circle about (2, 0).
  const double flank = std::sqrt(3.0);
  const Vec2 lower{flank * std::cos(-kPi / 6), flank * std::sin(-kPi / 6)};
  const Vec2 upper{lower.x, -lower.y};
  Outlined o = curve_outline({[=](double t) { return t * lower; },
                              [=](double t) {
                                const double angle = -2 * kPi / 3 + t * 4 * kPi / 3;
                                return Vec2{2 + std::cos(angle), std::sin(angle)};
                              },
                              [=](double t) { return (1 - t) * upper; }},
                             {4, 8, 4});
  o.outline.corner_at = {0};
  // u = v = 2; the rest is two-sided with sides 12 and 4: u' = 5, v' = 1, L = 7, 3, 6.
  const std::vector<int> params{2, 2, 5, 1, 1, 5, 2};
  fill_block(shape_of(BlockTemplate::OneSided, {1}), params, o.outline, 6, o.mesh);
  EXPECT_EQ(o.mesh.quads.size(), 4u + 5u + (1 * 5 + 5 * 2 + 2 * 1));
  const Checked c = check_block(o, 6, "teardrop");
  EXPECT_EQ(c.interior_valences.at(3), 3);
  EXPECT_EQ(irregular(c), 3);
}

void expect_submap(Outlined o, const std::vector<int>& types, int cells, const std::string& name) {
  fill_block(shape_of(BlockTemplate::Submap, types), {}, o.outline, 8, o.mesh);
  EXPECT_EQ(static_cast<int>(o.mesh.quads.size()), cells) << name;
  const Checked c = check_block(o, 8, name);
  EXPECT_EQ(irregular(c), 0) << name;
  EXPECT_GT(c.min_scaled_jacobian, 0.3) << name;
}

TEST(BlockTemplates, SubmappedLUT) {
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<int> l_types{1, 1, 1, 3, 1, 1};
  expect_submap(polygon_outline(l_shape, {4, 2, 2, 2, 2, 4}), l_types, 12, "L4");
  expect_submap(polygon_outline(l_shape, {5, 2, 2, 3, 3, 5}), l_types, 5 * 2 + 3 * 3, "L5");
  expect_submap(polygon_outline(l_shape, {8, 3, 5, 5, 3, 8}), l_types, 8 * 3 + 3 * 5, "L8");

  const std::vector<Vec2> u_shape{{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<int> u_types{1, 1, 1, 1, 3, 3, 1, 1};
  expect_submap(polygon_outline(u_shape, {6, 4, 2, 2, 2, 2, 2, 4}), u_types, 6 * 2 + 2 * 2 + 2 * 2, "U6");
  expect_submap(polygon_outline(u_shape, {7, 3, 2, 1, 3, 1, 2, 3}), u_types, 7 * 2 + 2 + 2, "U7");

  const std::vector<Vec2> t_shape{{0, 1}, {1, 1}, {1, 0}, {2, 0}, {2, 1}, {3, 1}, {3, 2}, {0, 2}};
  const std::vector<int> t_types{1, 3, 1, 1, 3, 1, 1, 1};
  expect_submap(polygon_outline(t_shape, {2, 2, 2, 2, 2, 2, 6, 2}), t_types, 6 * 2 + 2 * 2, "T2");
  expect_submap(polygon_outline(t_shape, {3, 4, 2, 4, 2, 2, 7, 2}), t_types, 7 * 2 + 2 * 4, "T3");
}

// The pentagon beside a plate's hole (a quarter of plate_with_hole): its
// midpoint subdivision by transfinite interpolation folds along the arc once
// the counts are fine, so the block must come out of the harmonic layout.
TEST(BlockTemplates, FoldingMidpointFillFallsBackToTheHarmonicLayout) {
  const auto line = [](Vec2 a, Vec2 b) { return [a, b](double t) { return a + t * (b - a); }; };
  const auto arc = [](double t) {
    const double angle = -0.5 * kPi - 0.5 * kPi * t;
    return Vec2{std::cos(angle), std::sin(angle)};
  };
  const std::vector<int> c{100, 57, 1, 100, 100};
  std::vector<int> counts(5);
  for (int i = 0; i < 5; ++i) counts[i] = c[(i + 4) % 5] + c[(i + 1) % 5];
  Outlined o = curve_outline(
      {line({-2, -2}, {0, -2}), line({0, -2}, {0, -1}), arc, line({-1, 0}, {-2, 0}), line({-2, 0}, {-2, -2})}, counts);
  fill_block(shape_of(BlockTemplate::Midpoint, {1, 1, 1, 1, 1}), c, o.outline, 3, o.mesh);
  const Checked checked = check_block(o, 3, "plate_pentagon");
  EXPECT_GT(checked.min_scaled_jacobian, 0.3);
  EXPECT_EQ(irregular(checked), 1);
}

void expect_error(Outlined o, const BlockShape& shape, const std::vector<int>& params, int block,
                  const std::string& wanted) {
  try {
    fill_block(shape, params, o.outline, block, o.mesh);
    ADD_FAILURE() << "no error, wanted " << wanted;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("block " + std::to_string(block) + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(wanted), std::string::npos) << what;
  }
}

TEST(BlockTemplates, BadCountsNameTheBlock) {
  const std::vector<Vec2> triangle{{0, 0}, {1, 0}, {0.5, 0.8}};
  expect_error(polygon_outline(triangle, {3, 4, 4}), shape_of(BlockTemplate::Midpoint, {1, 1, 1}), {2, 2, 1}, 7,
               "even sum");
  expect_error(polygon_outline(triangle, {4, 4, 4}), shape_of(BlockTemplate::Midpoint, {1, 1, 1}), {3, 2, 1}, 9,
               "side 0 has 4 intervals");
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  expect_error(polygon_outline(square, {5, 3, 4, 3}), shape_of(BlockTemplate::Submap, {1, 1, 1, 1}), {}, 2,
               "do not close");
  // The U's notch reaching down onto its base.
  const std::vector<Vec2> u_shape{{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  expect_error(polygon_outline(u_shape, {6, 2, 2, 2, 2, 2, 2, 2}),
               shape_of(BlockTemplate::Submap, {1, 1, 1, 1, 3, 3, 1, 1}), {}, 11, "overlaps itself");
  expect_error(polygon_outline(square, {2, 2, 2, 2}), shape_of(BlockTemplate::Submap, {1, 1, 0, 1}), {}, 12, "type 0");
  expect_error(ellipse(1, 1, 16), shape_of(BlockTemplate::Disc), {3, 4}, 13, "2a + 2b");
  expect_error(lens(8, 8), shape_of(BlockTemplate::TwoSided, {1, 1}), {8, 2, 2, 2, 4}, 14, "does not fit");
}

}  // namespace
}  // namespace mm
