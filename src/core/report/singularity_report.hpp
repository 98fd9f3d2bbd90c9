#pragma once
// Mesh flow and singularities as JSON (medialmesh singularities --json).
#include <nlohmann/json.hpp>

#include "singularity/merge.hpp"

namespace mm {

// {"singularities":[{"x","y","k","at","r"}],"sum_k","predicted_sum_k",
//  "flow":[{"edge","n","polyline":[[x,y],...]}]}
// With merged groups, "singularities" lists the groups (with "members",
// indices into "unmerged") and "unmerged" the singularities before merging.
nlohmann::json singularity_report_json(const FaceModel& face, const MeshFlow& flow,
                                       const std::vector<SingularityGroup>* merged);

}  // namespace mm
