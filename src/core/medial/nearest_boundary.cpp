#include "medial/nearest_boundary.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <iterator>
#include <utility>
#include <vector>

namespace mm {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using RPoint = bg::model::point<double, 2, bg::cs::cartesian>;

// Points within 1e-3 of the face size of the curves and at most 1e-2 apart
// along straight stretches, each with its boundary place.
struct NearestBoundary::Samples {
  bgi::rtree<std::pair<RPoint, BoundaryPlace>, bgi::quadratic<16>> tree;
};

NearestBoundary::NearestBoundary(const BoundaryIndex& index) : index_(index), samples_(new Samples) {
  const FaceModel& face = index.face();
  const double spacing = 1e-2 * face.size;
  std::vector<std::pair<RPoint, BoundaryPlace>> points;
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    for (std::size_t ei = 0; ei < face.loops[li].edges.size(); ++ei) {
      const BoundaryEdge& e = face.loops[li].edges[ei];
      const std::vector<double> params = sample_edge_parameters(e, 1e-3 * face.size);
      for (std::size_t k = 0; k + 1 < params.size(); ++k) {
        const Vec2 a = evaluate(e.curve, params[k]).p, b = evaluate(e.curve, params[k + 1]).p;
        const int steps = std::max(1, static_cast<int>(std::ceil(distance(a, b) / spacing)));
        for (int s = 0; s < steps; ++s) {
          const double t = params[k] + (params[k + 1] - params[k]) * s / steps;
          const BoundaryPlace place = index.place(static_cast<int>(li), static_cast<int>(ei), t);
          points.push_back({RPoint(place.point.x, place.point.y), place});
        }
      }
    }
  }
  samples_->tree = decltype(samples_->tree)(points.begin(), points.end());
}

NearestBoundary::~NearestBoundary() = default;

BoundaryPlace NearestBoundary::nearest(Vec2 p) const {
  std::vector<std::pair<RPoint, BoundaryPlace>> found;
  samples_->tree.query(bgi::nearest(RPoint(p.x, p.y), 6), std::back_inserter(found));
  // Nearest first (the R-tree hands them over in no order): the stretch of
  // the nearest sample is always refined from that sample itself, not from
  // a farther one of its stretch that may lie across a dip or a seam.
  std::sort(found.begin(), found.end(),
            [&](const auto& a, const auto& b) { return distance(a.second.point, p) < distance(b.second.point, p); });
  // Refine once per stretch of boundary: samples near a sample already
  // refined lead to the same place, but one edge may pass p twice (a loop
  // that is a single closed curve), each time with a nearest point of its own.
  const double same_stretch = 2e-2 * index_.face().size;
  BoundaryPlace best;
  double best_distance = 1e300;
  std::vector<BoundaryPlace> refined;
  for (const auto& [point, place] : found) {
    const double d = distance(place.point, p);
    if (d < best_distance) best = place, best_distance = d;
    const auto near = [&](const BoundaryPlace& r) {
      return r.loop == place.loop && r.edge == place.edge && distance(r.point, place.point) <= same_stretch;
    };
    if (std::any_of(refined.begin(), refined.end(), near)) continue;
    refined.push_back(place);
    const BoundaryPlace exact = nearest_on_run(index_, place, p);
    if (distance(exact.point, p) < best_distance) best = exact, best_distance = distance(exact.point, p);
  }
  return best;
}

}  // namespace mm
