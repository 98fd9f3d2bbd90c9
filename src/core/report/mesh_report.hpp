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

// The same for several faces' merged mesh (combine_quality), the irregular
// nodes placed in 3-D ({"node" (1-based), "x", "y", "z", "elements",
// "expected"}), plus "shared_edges".
nlohmann::json merged_mesh_report_json(const QualityReport& quality, const MergedMesh& mesh, int shared_edges);

}  // namespace mm
