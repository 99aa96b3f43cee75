#pragma once

#include <string>
#include <vector>

#include "sensing/landmark_estimator.h"
#include "sensing/robot_config.h"
#include "vision/door_mark_reader.h"
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
  std::string reason;  // why, for everything but kObservation
  sensing::LandmarkObservation observation;
  double center_offset_in = 0.0;  // ribbon centre along the wall from the optical axis
  vision::DoorMarkReading mark;   // the classified door's leaf mark (Table 6.8)
  int candidates = 0;             // candidate jamb pairs the detector offered
  int casings = 0;                // of those, recognised as a casing round an inner pair
  // The candidates handed to the classifier (after the width gate and the casing rule), in
  // the detector's order, and the pair widths the gate allowed.
  std::vector<sensing::JambCandidate> ranked;
  vision::PairWidthLimits width_limits;
  int pairs_before_cap = 0;  // pairs within the limits before the detector's max_pairs
};

// The width gate: pairs are kept only when some legal door class could be that wide in the
// image at the sonar's range and stare (Chapter 5: the Short Side's sdis and theta). The
// door may be anywhere wholly in view; the stare is known to half a sensor spacing (§5.3:
// "as great as 7.5°") and the range to range_tolerance.
struct WidthGate {
  bool enabled = true;
  double stare_tolerance_deg = 7.5;
  double range_tolerance = 0.15;  // share of the range: the sonar's error at oblique incidence
  // Added to the widest class on each side: the outer edges of a door's casing (the casing
  // rule needs that pair to find the opening inside it). 3 in is the rendered casing; ours.
  double casing_allowance_in = 4.0;
};

// Pair widths (px) that a door of [min_width_in, max_width_in] can have when the wall is
// sdis_in from the camera at theta_rad (optical axis to wall normal), give or take the
// tolerances of `gate`, with the door anywhere wholly in view.
vision::PairWidthLimits LegalPairWidths(const sensing::CameraModel& camera, double sdis_in,
                                        double theta_rad, double min_width_in,
                                        double max_width_in, const WidthGate& gate);

// The casing rule: how a door's frame is told apart from the door.
//
// A door in a painted frame shows four vertical edges, not two: wall -> casing, casing ->
// opening, opening -> casing, casing -> wall. The outer pair is often the most confident
// one (the wall-to-casing contrast is the stronger), and it is the opening plus two casing
// widths: 36 + 2 x 3 = 42 in, class 40 (and 30 + 6 = 36, class 36; 32 + 6 = 38, class 36).
// The class of a door is its opening (§4.1.2, the jambs), so the inner pair is the one to
// measure. The four edges are recognised from the image alone, without assuming a casing
// width: two footprint pairs nested with nothing between them, where
//  - each side band is bounded by edges of opposite polarity (a stripe, not a step),
//  - the two bands are mirror images (outer edges of opposite polarity, likewise the inner
//    edges: constraint C2 of §5.1, a face that contrasts with its surround on both sides),
//  - each band is narrow beside the opening and the two are of like width (a frame is the
//    same on both jambs; perspective may make one up to max_band_ratio wider).
// The outer pair and the two mixed pairs (outer edge with the far inner edge, e.g. 39 in)
// are then the same landmark measured wrongly: they are withdrawn and the inner pair takes
// the group's highest confidence. The rule applies outside in, so a frame within a frame
// resolves to the innermost opening.
struct CasingRule {
  bool enabled = true;
  // Each band at most this share of the opening's width: a 3 in casing is 4-10 % of a 30-72
  // in door; 0.25 admits casings up to 7.5 in on a 30 in door and rejects two doors side by
  // side (their "bands" are whole doors).
  double max_band_to_opening = 0.25;
  // Left and right band widths within this ratio: 1 square-on; at the 7.5° limit of the
  // navigation envelope (§6.4.2) and beyond, the near band looks wider.
  double max_band_ratio = 2.5;
  // Each of the four edges appears in at least this many of the processed rows: a casing
  // runs the door's full height. A clump in one row only is not a casing edge: at 6 ft and
  // 10° of roll (§4.1.1) a jamb crosses the outer rows ±30 px from where the centre rows
  // see it, and those strays would otherwise frame a "casing" round the true jamb.
  int min_rows_hit = 2;
};

// The landmark pipeline of §4.1 and Chapter 5 for one frame: the vertical edge ribbon
// detector (Figure 4.1) on rows chosen from the coaxial sonar range, the casing rule over
// its candidate pairs, then the sensing geometry (Short Side by default) and the Bayes door
// classes of Table 4.1 over the candidate pairs in order of confidence; last, the classified
// door's leaf mark (Table 6.8: a vision panel, a poster or a plain leaf).
class LandmarkPipeline {
 public:
  LandmarkPipeline(const sensing::RobotConfig& robot, vision::RibbonDetectorParams detector,
                   sensing::LandmarkEstimatorConfig estimator, CasingRule casing = {},
                   WidthGate gate = {});
  FrameOutcome Process(const vision::ImageView& frame, const sensing::SonarScan& scan) const;
  // The same, with the detector's own output (for drawing and measuring).
  FrameOutcome Process(const vision::ImageView& frame, const sensing::SonarScan& scan,
                       vision::RibbonDetection* detection) const;

 private:
  sensing::RobotConfig robot_;
  vision::RibbonDetector detector_;
  vision::DoorMarkParams marks_;  // the camera's height and focal length from the detector
  sensing::LandmarkEstimator estimator_;
  // The gate's limits for this scan: the Short Side stare from the nearest valid sensor.
  vision::PairWidthLimits GateLimits(const sensing::SonarScan& scan) const;

  CasingRule casing_;
  WidthGate gate_;
  double min_class_in_ = 0.0, max_class_in_ = 0.0;  // the classifier's outer boundaries
};

// The candidates handed to the classifier: the detector's pairs after the casing rule
// (withdrawn pairs left out), in the detector's order. `casings`, if given, receives the
// number of casing pairs recognised. Exposed for tests.
std::vector<sensing::JambCandidate> CandidatesAfterCasingRule(
    const vision::RibbonDetection& detection, const CasingRule& rule, int* casings = nullptr);

}  // namespace stickrep::landmark
