#pragma once
// The face report as JSON and as a readable table (medialmesh info).
#include <nlohmann/json.hpp>
#include <string>

#include "boundary/face_model.hpp"

namespace mm {

// {"face","area","holes","euler","edges":[{"type","length"}],
//  "corners":[{"x","y","angle_deg","nc"}],"predicted_sum_k"}
nlohmann::json face_report_json(const FaceModel& face);

// {"origin", "x_dir", "y_dir", "normal"}: how the face's 2-D coordinates map to 3-D.
nlohmann::json frame_json(const Frame& frame);

std::string face_report_table(const FaceModel& face);

}  // namespace mm
