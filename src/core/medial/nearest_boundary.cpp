#include "medial/nearest_boundary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "geometry/polygon.hpp"

namespace mm {

// Points within 1e-3 of the face size of the curves and at most 1e-2 apart
// along straight stretches, each with its boundary place, binned in a grid
// of about as many square cells as points (a plain grid: far cheaper to
// search for a few hundred points than an R-tree).
struct NearestBoundary::Samples {
  std::vector<BoundaryPlace> places;  // loop by loop, in the loop's order
  // How far the boundary may stray from the chord of places[i] and the next
  // sample along its loop: a bound from the second derivative of places[i]'s
  // curve (the chord ends on that edge's end when the next sample starts the
  // next edge), no more than the sampling's tolerance.
  std::vector<double> sag_after;
  std::vector<int> loop_first;  // per loop, the index of its first sample; one more at the end
  double max_sag = 0.0;
  Vec2 origin;
  double cell = 1.0;
  int nx = 1, ny = 1;
  std::vector<int> first;  // cell c holds places[order[first[c] .. first[c + 1])]
  std::vector<int> order;
  // Per cell, how many rings of cells round it hold no sample: the ring
  // search starts there (a medial point far from the boundary has most of
  // its disc's cells empty).
  std::vector<int> clear;

  // The samples before and after sample i along its loop (a loop is closed).
  int previous(int i) const {
    const int loop = places[i].loop;
    return i > loop_first[loop] ? i - 1 : loop_first[loop + 1] - 1;
  }
  int next(int i) const {
    const int loop = places[i].loop;
    return i + 1 < loop_first[loop + 1] ? i + 1 : loop_first[loop];
  }

  std::pair<int, int> cell_of(Vec2 p) const {
    return {std::clamp(static_cast<int>(std::floor((p.x - origin.x) / cell)), 0, nx - 1),
            std::clamp(static_cast<int>(std::floor((p.y - origin.y) / cell)), 0, ny - 1)};
  }

  void build() {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const BoundaryPlace& b : places) {
      lo = {std::min(lo.x, b.point.x), std::min(lo.y, b.point.y)};
      hi = {std::max(hi.x, b.point.x), std::max(hi.y, b.point.y)};
    }
    origin = lo;
    const double w = std::max(hi.x - lo.x, 1e-300), h = std::max(hi.y - lo.y, 1e-300);
    cell = std::max(std::sqrt(w * h / static_cast<double>(std::max<std::size_t>(places.size(), 1))),
                    std::max(w, h) / 1024);
    nx = std::max(1, static_cast<int>(std::ceil(w / cell)));
    ny = std::max(1, static_cast<int>(std::ceil(h / cell)));
    first.assign(static_cast<std::size_t>(nx) * ny + 1, 0);
    std::vector<int> cell_index(places.size());
    for (std::size_t i = 0; i < places.size(); ++i) {
      const auto [cx, cy] = cell_of(places[i].point);
      cell_index[i] = cy * nx + cx;
      ++first[cell_index[i] + 1];
    }
    for (std::size_t c = 0; c + 1 < first.size(); ++c) first[c + 1] += first[c];
    order.resize(places.size());
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < places.size(); ++i) order[fill[cell_index[i]]++] = static_cast<int>(i);
    // Chessboard distance to the nearest cell holding a sample, by two passes
    // over the grid (exact for this metric).
    const int far = nx + ny;
    clear.assign(static_cast<std::size_t>(nx) * ny, far);
    for (int c = 0; c < nx * ny; ++c)
      if (first[c + 1] > first[c]) clear[c] = 0;
    const auto relax = [&](int x, int y, int dx, int dy) {
      const int ox = x + dx, oy = y + dy;
      if (ox >= 0 && ox < nx && oy >= 0 && oy < ny)
        clear[y * nx + x] = std::min(clear[y * nx + x], clear[oy * nx + ox] + 1);
    };
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) relax(x, y, -1, -1), relax(x, y, 0, -1), relax(x, y, 1, -1), relax(x, y, -1, 0);
    for (int y = ny - 1; y >= 0; --y)
      for (int x = nx - 1; x >= 0; --x) relax(x, y, 1, 1), relax(x, y, 0, 1), relax(x, y, -1, 1), relax(x, y, 1, 0);
  }

  // The k samples nearest p, nearest first (ties in no particular order):
  // rings of cells outwards until the next ring lies beyond the k-th.
  int nearest(Vec2 p, int k, std::array<std::pair<double, int>, 8>& found) const {
    int count = 0;
    const auto [cx, cy] = cell_of(p);
    const auto visit = [&](int x, int y) {
      const int c = y * nx + x;
      // Past the k-th by a margin far above rounding in the squares, a sample
      // is left out without its (dearer) distance.
      const double beyond = count == k ? found[k - 1].first * found[k - 1].first * (1 + 1e-9) : 1e300;
      for (int j = first[c]; j < first[c + 1]; ++j) {
        const Vec2 v = places[order[j]].point - p;
        if (dot(v, v) > beyond) continue;
        const double d = distance(places[order[j]].point, p);
        if (count == k && d >= found[k - 1].first) continue;
        int at = count < k ? count++ : k - 1;
        while (at > 0 && found[at - 1].first > d) found[at] = found[at - 1], --at;
        found[at] = {d, order[j]};
      }
    };
    const int rings = std::max({cx, nx - 1 - cx, cy, ny - 1 - cy});
    for (int r = clear[cy * nx + cx]; r <= rings; ++r) {
      // Every cell of ring r is at least (r - 1) cells from p, inside the grid or out.
      if (count == k && (r - 1) * cell > found[k - 1].first) break;
      for (int x = cx - r; x <= cx + r; ++x) {
        if (x < 0 || x >= nx) continue;
        if (cy - r >= 0) visit(x, cy - r);
        if (r > 0 && cy + r < ny) visit(x, cy + r);
      }
      for (int y = cy - r + 1; y <= cy + r - 1; ++y) {
        if (y < 0 || y >= ny) continue;
        if (cx - r >= 0) visit(cx - r, y);
        if (cx + r < nx) visit(cx + r, y);
      }
    }
    return count;
  }

  // Calls f(sample index, distance) for every sample at a distance from p in
  // [low, high]: per row of cells, only the columns reaching into that ring
  // (a cell to spare each way), not the whole square round the outer circle.
  template <class F>
  void within(Vec2 p, double low, double high, F f) const {
    const double low2 = low * low, high2 = high * high;
    // The cells of a row are consecutive in `order`.
    const auto visit = [&](int y, int x0, int x1) {
      x0 = std::max(x0, 0), x1 = std::min(x1, nx - 1);
      if (x0 > x1) return;
      for (int j = first[y * nx + x0]; j < first[y * nx + x1 + 1]; ++j) {
        const Vec2 v = places[order[j]].point - p;
        const double d2 = dot(v, v);
        if (d2 >= low2 && d2 <= high2) f(order[j], std::sqrt(d2));
      }
    };
    const int y0 = std::max(0, static_cast<int>(std::floor((p.y - high - origin.y) / cell)) - 1);
    const int y1 = std::min(ny - 1, static_cast<int>(std::floor((p.y + high - origin.y) / cell)) + 1);
    for (int y = y0; y <= y1; ++y) {
      const double cy0 = origin.y + y * cell, cy1 = cy0 + cell;
      const double near_y = std::max({cy0 - p.y, p.y - cy1, 0.0}), far_y = std::max(p.y - cy0, cy1 - p.y);
      if (near_y > high) continue;
      const double outer = std::sqrt(high * high - near_y * near_y);
      const int x0 = static_cast<int>(std::floor((p.x - outer - origin.x) / cell)) - 1;
      const int x1 = static_cast<int>(std::floor((p.x + outer - origin.x) / cell)) + 1;
      // Columns wholly inside the inner circle over this row hold no sample of the ring.
      const double inner = far_y < low ? std::sqrt(low * low - far_y * far_y) : -1.0;
      const int i0 = inner > 0 ? static_cast<int>(std::floor((p.x - inner - origin.x) / cell)) + 2 : x1 + 1;
      const int i1 = inner > 0 ? static_cast<int>(std::floor((p.x + inner - origin.x) / cell)) - 2 : x1;
      if (i0 > i1) {
        visit(y, x0, x1);
      } else {
        visit(y, x0, i0 - 1);
        visit(y, i1 + 1, x1);
      }
    }
  }
};

NearestBoundary::NearestBoundary(const BoundaryIndex& index) : index_(index), samples_(new Samples) {
  const FaceModel& face = index.face();
  const double spacing = spacing_ = 1e-2 * face.size;
  const double tolerance = 1e-3 * face.size;
  for (std::size_t li = 0; li < face.loops.size(); ++li) {
    samples_->loop_first.push_back(static_cast<int>(samples_->places.size()));
    for (std::size_t ei = 0; ei < face.loops[li].edges.size(); ++ei) {
      const BoundaryEdge& e = face.loops[li].edges[ei];
      const std::vector<double> params = sample_edge_parameters(e, tolerance);
      for (std::size_t k = 0; k + 1 < params.size(); ++k) {
        const Vec2 a = evaluate_point(e.curve, params[k]), b = evaluate_point(e.curve, params[k + 1]);
        const int steps = std::max(1, static_cast<int>(std::ceil(distance(a, b) / spacing)));
        const double step = (params[k + 1] - params[k]) / steps;
        // Rounding of the points themselves aside (1e-12 of the face).
        const double sag = std::min(tolerance, second_derivative_bound(e.curve, std::min(params[k], params[k + 1]),
                                                                       std::max(params[k], params[k + 1])) *
                                                       step * step / 8 +
                                                   1e-12 * face.size);
        for (int s = 0; s < steps; ++s) {
          const double t = params[k] + (params[k + 1] - params[k]) * s / steps;
          samples_->places.push_back(index.place(static_cast<int>(li), static_cast<int>(ei), t));
          samples_->sag_after.push_back(sag);
          samples_->max_sag = std::max(samples_->max_sag, sag);
        }
      }
    }
  }
  samples_->loop_first.push_back(static_cast<int>(samples_->places.size()));
  samples_->build();
}

NearestBoundary::~NearestBoundary() = default;

BoundaryPlace NearestBoundary::nearest(Vec2 p) const {
  std::array<std::pair<double, int>, 8> found;
  const int count = samples_->nearest(p, 6, found);
  // Refine once per stretch of boundary, nearest sample first: the stretch
  // of the nearest sample is always refined from that sample itself, not
  // from a farther one of its stretch that may lie across a dip or a seam.
  // Samples near a sample already refined lead to the same place, but one
  // edge may pass p twice (a loop that is a single closed curve), each time
  // with a nearest point of its own.
  const double same_stretch = 2e-2 * index_.face().size;
  BoundaryPlace best;
  double best_distance = 1e300;
  std::vector<BoundaryPlace> refined;
  const auto stretch_refined = [&](const BoundaryPlace& place) {
    return std::any_of(refined.begin(), refined.end(), [&](const BoundaryPlace& r) {
      return r.loop == place.loop && r.edge == place.edge && distance(r.point, place.point) <= same_stretch;
    });
  };
  const auto refine = [&](int sample, double d) {
    const BoundaryPlace& place = samples_->places[sample];
    if (d < best_distance) best = place, best_distance = d;
    if (stretch_refined(place)) return;
    refined.push_back(place);
    const BoundaryPlace exact = nearest_on_run(index_, place, p);
    if (distance(exact.point, p) < best_distance) best = exact, best_distance = distance(exact.point, p);
  };
  // Whether the boundary on the chords either side of a sample may come
  // nearer than the best yet: it strays from a chord by at most its sag.
  // The chord from an edge's last sample to the next edge's first is the
  // last stretch of that edge (a line's foot there, beside a tangent join
  // onto an ellipse whose own local minimum the search settled on, was
  // missed by 1.1e-3: fuzz elliptic_33_274).
  const auto may_come_nearer = [&](int sample, double d) {
    double closest = d;
    for (const auto& [from, to] :
         {std::make_pair(samples_->previous(sample), sample), std::make_pair(sample, samples_->next(sample))}) {
      closest = std::min(closest, distance_to_segment(p, samples_->places[from].point, samples_->places[to].point) -
                                      samples_->sag_after[from]);
    }
    return closest < best_distance;
  };
  for (int i = 0; i < count; ++i) {
    const auto [d, sample] = found[i];
    if (i == 0 || (!stretch_refined(samples_->places[sample]) && may_come_nearer(sample, d))) refine(sample, d);
  }
  // The nearest point of a stretch lies within half a sample spacing (and
  // its chord's sag) of one of its samples, which may be farther than all of
  // the six nearest samples when another stretch is almost as near (a hole's
  // edge a hair farther than the outline): every stretch with a sample that
  // close to the best distance is refined (samples nearer than the sixth
  // nearest are among the six already) where it may come nearer.
  const double reach = best_distance + 0.5 * spacing_ + samples_->max_sag;
  if (count == 6 && found[5].first < reach) {
    samples_->within(p, found[5].first, reach, [&](int sample, double d) {
      if (!stretch_refined(samples_->places[sample]) && may_come_nearer(sample, d)) refine(sample, d);
    });
  }
  return best;
}

}  // namespace mm
