#pragma once

#include <string>

#include "sensing/landmark_estimator.h"
#include "sensing/robot_config.h"
#include "vision/ribbon_detector.h"

namespace stickrep::landmark {

// What one frame gave.
struct FrameOutcome {
  enum class Kind {
    kObservation,  // a classified door
    kNoDoor,       // a good frame with no candidate inside a door class
    kBadFrame,     // the frame cannot be read (size, encoding): drop and count
    kNoRange,      // no usable coaxial sonar range to scale the frame: drop and count
  };
  Kind kind = Kind::kNoDoor;
  std::string reason;                    // why, for everything but kObservation
  sensing::LandmarkObservation observation;
  double center_offset_in = 0.0;         // ribbon centre along the wall from the optical axis
  int candidates = 0;                    // candidate jamb pairs the detector offered
};

// The landmark pipeline of §4.1 and Chapter 5 for one frame: the vertical edge ribbon
// detector (Figure 4.1) on rows chosen from the coaxial sonar range, then the sensing
// geometry (Short Side by default) and the Bayes door classes of Table 4.1 over the
// candidate pairs in order of confidence.
class LandmarkPipeline {
 public:
  LandmarkPipeline(const sensing::RobotConfig& robot, vision::RibbonDetectorParams detector,
                   sensing::LandmarkEstimatorConfig estimator);
  FrameOutcome Process(const vision::ImageView& frame, const sensing::SonarScan& scan) const;

 private:
  sensing::RobotConfig robot_;
  vision::RibbonDetector detector_;
  sensing::LandmarkEstimator estimator_;
};

}  // namespace stickrep::landmark
