#include "singularity/merge.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>

namespace mm {

std::vector<SingularityGroup> group_singularities(const std::vector<Singularity>& singularities,
                                                  const MergeTolerance& tolerance) {
  if (tolerance.mesh_size < 0.0) throw InputError("the merge mesh size must be positive");
  if (tolerance.mesh_size == 0.0 && !(tolerance.radius_factor >= 0.25 && tolerance.radius_factor <= 1.0)) {
    std::ostringstream message;
    message << "the merge factor must lie in [0.25, 1], got " << tolerance.radius_factor;
    throw InputError(message.str());
  }
  const std::size_t count = singularities.size();
  std::vector<std::size_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  // Pairs closer than their reach, found along the singularities sorted by
  // x: no pair further apart in x than the first one's own reach can be.
  // The groups (connected sets) do not depend on the order of the unions.
  std::vector<std::size_t> by_x(count);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(),
            [&](std::size_t a, std::size_t b) { return singularities[a].p.x < singularities[b].p.x; });
  for (std::size_t ii = 0; ii < count; ++ii) {
    const Singularity& a = singularities[by_x[ii]];
    const double widest = tolerance.mesh_size > 0.0 ? tolerance.mesh_size : tolerance.radius_factor * a.r;
    for (std::size_t jj = ii + 1; jj < count && singularities[by_x[jj]].p.x - a.p.x < widest; ++jj) {
      const Singularity& b = singularities[by_x[jj]];
      const double reach =
          tolerance.mesh_size > 0.0 ? tolerance.mesh_size : tolerance.radius_factor * std::min(a.r, b.r);
      if (distance(a.p, b.p) < reach) parent[root(by_x[ii])] = root(by_x[jj]);
    }
  }
  std::map<std::size_t, SingularityGroup> groups;  // keyed by root, in order of first member
  for (std::size_t i = 0; i < count; ++i) {
    SingularityGroup& g = groups[root(i)];
    g.k += singularities[i].k;
    g.p = g.p + singularities[i].p;
    g.members.push_back(static_cast<int>(i));
  }
  std::vector<SingularityGroup> all;
  for (auto& [key, g] : groups) {
    g.p = g.p / static_cast<double>(g.members.size());
    all.push_back(std::move(g));
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.members[0] < b.members[0]; });
  return all;
}

std::vector<SingularityGroup> merge_singularities(const std::vector<Singularity>& singularities,
                                                  const MergeTolerance& tolerance) {
  std::vector<SingularityGroup> merged = group_singularities(singularities, tolerance);
  merged.erase(std::remove_if(merged.begin(), merged.end(), [](const SingularityGroup& g) { return g.k == 0; }),
               merged.end());
  return merged;
}

}  // namespace mm
