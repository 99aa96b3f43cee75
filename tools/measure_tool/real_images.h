#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "landmark/landmark_pipeline.h"
#include "sensing/robot_config.h"
#include "vision/ribbon_detector.h"

namespace stickrep::measure {

// The detector on image files a user brings: real hallway frames of any size, turned into
// the 512 x 480 mono8 frames the robot's camera gives (resized, not cropped), with a
// coaxial range given or the default six feet of §4.1.1.
struct ImageRunConfig {
  std::vector<std::string> files;
  double range_in = 72.0;
  // Without a sonar the stare and the range are unknown: the width gate admits every stare
  // within this of square-on and ranges within range_tolerance of range_in.
  double max_stare_deg = 45.0;
  double range_tolerance = 0.5;
  std::string annotations;  // optional: true jamb columns per image
  std::string draw_dir;     // optional: write each frame with its detections drawn
  int top = 5;              // pairs printed per image
  double hit_tolerance_px = 5.0;  // a pair hits a door when both jambs are this close
};

// True doors of one image, as jamb column pairs in the 512-column frame.
struct ImageTruth {
  std::vector<std::pair<double, double>> doors;
};

// Reads an annotation file: one line per image, `NAME: LJ RJ [LJ RJ ...]` with columns in
// the image's own pixels, or `NAME: -` for a frame with no door; `#` starts a comment.
// NAME is the image file's name without its folder. Columns are scaled to 512 with each
// image's width when the image is read. Throws InputError (file, line, reason).
std::map<std::string, std::vector<std::pair<double, double>>> LoadAnnotations(
    const std::string& path);

// An image file as the camera's frame: grey, 512 x 480. Throws InputError when the file
// cannot be read as an image. `source_width` receives the file's width in pixels.
cv::Mat LoadFrame(const std::string& path, int* source_width = nullptr);

// Runs the detector and the casing rule on every file; prints the ranked pairs and, with
// annotations, precision and recall; draws when asked. Returns the report.
std::string RunOnImages(const ImageRunConfig& config, const sensing::RobotConfig& robot);

// `image` (mono8) with the processed rows, the footprints, the first three candidates
// (green, orange, red) and true jambs (magenta ticks at the bottom) drawn in colour.
cv::Mat DrawDetections(const cv::Mat& image, const vision::RibbonDetection& detection,
                       const std::vector<sensing::JambCandidate>& ranked,
                       const std::vector<std::pair<double, double>>& truth,
                       const std::string& caption);

}  // namespace stickrep::measure
