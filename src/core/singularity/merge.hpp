#pragma once
// Merging of singularities that lie close together (the paper's section 4.3):
// a coarse mesh cannot resolve them apart, so they act as one node.
#include <vector>

#include "singularity/mesh_flow.hpp"

namespace mm {

struct MergeTolerance {
  // Two singularities merge when closer than factor times the smaller of
  // their medial radii (the paper suggests a factor in [0.25, 1])...
  double radius_factor = 0.75;
  // ...or, when positive, closer than this target mesh size.
  double mesh_size = 0.0;
};

struct SingularityGroup {
  Vec2 p;  // mean of the members' positions
  int k = 0;
  std::vector<int> members;  // indices into the unmerged list
};

// Groups singularities transitively closer than the tolerance; a group's k is
// the sum of its members' and groups of net k = 0 are dropped. Throws
// InputError for a factor outside [0.25, 1] or a negative mesh size.
// The same groups, singletons and groups of net k = 0 included, in order of
// their first member.
std::vector<SingularityGroup> group_singularities(const std::vector<Singularity>& singularities,
                                                  const MergeTolerance& tolerance);

std::vector<SingularityGroup> merge_singularities(const std::vector<Singularity>& singularities,
                                                  const MergeTolerance& tolerance);

}  // namespace mm
