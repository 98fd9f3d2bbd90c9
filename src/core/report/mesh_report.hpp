#pragma once
// The quality report of a mesh as JSON, for the CLI and the Python module.
#include <nlohmann/json.hpp>

#include "quality/quality.hpp"

namespace mm {

// {"nodes", "quads", "order", "triangles", "inverted", "min_scaled_jacobian",
//  "mean_scaled_jacobian", "min_angle", "max_angle", "worst_element",
//  "irregular_interior", "irregular_boundary" (counts),
//  "irregular_interior_nodes", "irregular_boundary_nodes" ([{"x", "y",
//  "elements", "expected"}]), "area", "seconds", "stages": {name: seconds}}
nlohmann::json mesh_report_json(const QualityReport& quality, int order);

}  // namespace mm
