#include "landmark/landmark_config.h"

#include <string>

namespace stickrep::landmark {

LandmarkConfig LoadLandmarkConfig(const StrictYaml& c) {
  LandmarkConfig out;
  sensing::LandmarkEstimatorConfig& estimator = out.estimator;
  const std::string geometry = c.Get<std::string>("geometry");
  if (geometry == "short_side") {
    estimator.geometry = sensing::Geometry::kShortSide;
  } else if (geometry == "two_side") {
    estimator.geometry = sensing::Geometry::kTwoSide;
  } else {
    c.Fail("geometry", "'" + geometry + "' is not one of: short_side, two_side");
  }
  const std::string edges = c.Get<std::string>("short_side_edges");
  if (edges == "field_of_view") {
    estimator.short_side_edges = sensing::ShortSideEdges::kFieldOfViewEdges;
  } else if (edges == "paper_sensor_rays") {
    estimator.short_side_edges = sensing::ShortSideEdges::kPaperSensorRays;
  } else {
    c.Fail("short_side_edges", "'" + edges + "' is not one of: field_of_view, paper_sensor_rays");
  }
  estimator.min_confidence = c.Get<double>("min_confidence", 0.0, 1.0);
  const std::string rows = c.Get<std::string>("row_mode");
  if (rows == "five_rows") {
    out.detector.row_mode = vision::RowMode::kFiveRows;
  } else if (rows == "full_frame") {
    out.detector.row_mode = vision::RowMode::kFullFrame;
  } else {
    c.Fail("row_mode", "'" + rows + "' is not one of: five_rows, full_frame");
  }
  out.detector.seam_lines = c.Get<bool>("seam_lines");
  out.max_scan_age_s = c.Get<double>("max_scan_age_s", 0.01, 2.0, "s");
  c.Finish();
  return out;
}

}  // namespace stickrep::landmark
