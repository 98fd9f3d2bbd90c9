#pragma once
// The medial axis as JSON (medialmesh medial --json).
#include <nlohmann/json.hpp>

#include "medial/medial_axis.hpp"

namespace mm {

// {"vertices":[{"x","y","r","kind"}],"edges":[{"from","to","polyline":[[x,y,r],...]}]}
// A closed loop with no vertex has from = to = -1.
nlohmann::json medial_report_json(const MedialAxis& axis);

}  // namespace mm
