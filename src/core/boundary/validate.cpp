#include "boundary/validate.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

namespace mm {
namespace bg = boost::geometry;
namespace {

using Point = bg::model::d2::point_xy<double>;
using Polygon = bg::model::polygon<Point, /*clockwise=*/false, /*closed=*/true>;

std::string describe(bg::validity_failure_type failure) {
  switch (failure) {
    case bg::failure_few_points:
    case bg::failure_wrong_topological_dimension: return "face has no area";
    case bg::failure_spikes:
    case bg::failure_self_intersections: return "self-intersecting wire";
    case bg::failure_wrong_orientation: return "wire orientation is inconsistent";
    case bg::failure_interior_rings_outside: return "a hole lies outside the outer wire";
    case bg::failure_nested_interior_rings: return "a hole lies inside another hole";
    case bg::failure_disconnected_interior: return "holes cut the face into separate pieces";
    case bg::failure_intersecting_interiors: return "holes overlap";
    case bg::failure_invalid_coordinate: return "a vertex has an invalid coordinate";
    default: return "invalid face boundary";
  }
}

}  // namespace

std::string find_region_problem(const std::vector<std::vector<Vec2>>& loops) {
  Polygon polygon;
  auto fill = [](const std::vector<Vec2>& loop, auto& ring) {
    for (const Vec2& p : loop) ring.push_back(Point(p.x, p.y));
    if (!loop.empty()) ring.push_back(Point(loop.front().x, loop.front().y));
  };
  fill(loops.front(), polygon.outer());
  for (std::size_t i = 1; i < loops.size(); ++i) {
    polygon.inners().emplace_back();
    fill(loops[i], polygon.inners().back());
  }
  // Each wire on its own first: a crossing wire can look merely mis-oriented to is_valid.
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (bg::intersects(i == 0 ? polygon.outer() : polygon.inners()[i - 1])) {
      return "self-intersecting wire (loop " + std::to_string(i + 1) + ")";
    }
  }
  bg::validity_failure_type failure = bg::no_failure;
  if (bg::is_valid(polygon, failure) || failure == bg::failure_duplicate_points) return "";
  return describe(failure);
}

}  // namespace mm
