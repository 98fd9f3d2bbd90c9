#pragma once
// The quality report of a mesh as JSON, for the CLI and the Python module.
#include <nlohmann/json.hpp>

#include "quality/quality.hpp"

namespace mm {

// {"nodes", "quads", "order", "triangles", "inverted", "min_scaled_jacobian",
//  "mean_scaled_jacobian", "min_angle", "max_angle", "worst_element",
//  "irregular_interior", "irregular_boundary" (counts),
//  "irregular_interior_nodes", "irregular_boundary_nodes" ([{"x", "y",
//  "elements", "expected"}]),
//  "measures": {verdict name: {"min", "mean", "max", "worst_element" (1-based),
//  "worst_x", "worst_y"}} for scaled_jacobian, shape, edge_ratio,
//  aspect_ratio, skew, taper, stretch, condition,
//  "counts": {"shape_below_0.3", "edge_ratio_above_10", "edge_ratio_above_5",
//  "scaled_jacobian_below_0.3"}, "worst_elements": [{"element", "x", "y",
//  "shape", "edge_ratio", "scaled_jacobian"}] (least shape first),
//  "min_jacobian_ratio" (order 2 at the Gauss points; 1 at order 1),
//  "relative_sizes": {"requested", "min", "mean", "max",
//  "in_half_to_one_and_a_half"} of sqrt(area) / H (null without H),
//  "area", "seconds", "stages": {name: seconds}}
nlohmann::json mesh_report_json(const QualityReport& quality, int order);

// The same for several faces' merged mesh (combine_quality), the irregular
// nodes placed in 3-D ({"node" (1-based), "x", "y", "z", "elements",
// "expected"}), plus "shared_edges".
nlohmann::json merged_mesh_report_json(const QualityReport& quality, const MergedMesh& mesh, int shared_edges);

}  // namespace mm
