#pragma once
// The decomposition as JSON, for the CLI and the Python module.
#include <nlohmann/json.hpp>

#include "decomposition/decomposition.hpp"

namespace mm {

// {"blocks": [{"kind", "sides", "boundary", "area", "singularity", "corners"}],
//  "splits": [{"polyline", "reason"}], "fixed": [{"x", "y", "k"}],
//  "singularities": [...], "fallback", "notes", "face_area", "wrapped_holes"}
nlohmann::json decomposition_report_json(const FaceModel& face, const Decomposition& decomposition);

}  // namespace mm
