#pragma once

#include "common/strict_yaml.h"
#include "landmark/landmark_pipeline.h"
#include "sensing/landmark_estimator.h"
#include "vision/ribbon_detector.h"

namespace stickrep::landmark {

// The landmark process's settings (configs/landmark.yaml): the detector's row mode and seam
// lines, the sensing geometry and the classifier's confidence threshold, and how close in time a
// frame's sonar scan and odometry must be.
struct LandmarkConfig {
  vision::RibbonDetectorParams detector;
  sensing::LandmarkEstimatorConfig estimator;
  double max_scan_age_s = 0.3;
};

// Reads the `landmark` section; every key required, unknown keys rejected (InputError with
// file, line and key).
LandmarkConfig LoadLandmarkConfig(const StrictYaml& section);

}  // namespace stickrep::landmark
