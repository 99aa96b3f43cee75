#pragma once

#include <optional>
#include <vector>

#include "sensing/door_classifier.h"
#include "sensing/error_analysis.h"
#include "sensing/result.h"
#include "sensing/robot_config.h"
#include "sensing/sensing_geometry.h"
#include "sensing/sonar_model.h"

namespace stickrep::sensing {

// One sonar sweep: a range per sensor (inches from the sensor face) and whether the sonar
// process judged it usable (footprint gate). Sensor k is the ring's k-th transducer.
struct SonarScan {
  std::vector<double> ranges_in;
  std::vector<bool> valid;
};

// A candidate vertical edge ribbon from the detector (§4.1.1): jamb columns and weight.
struct JambCandidate {
  Footprints footprints;
  double confidence = 0.0;
};

// Tunables of the landmark stage; defaults from the text where it gives them.
struct LandmarkEstimatorConfig {
  Geometry geometry = Geometry::kShortSide;  // §5.5: the Short Side is the better one
  ShortSideEdges short_side_edges = ShortSideEdges::kPaperSensorRays;
  double min_confidence = 0.0;  // §4.1.2 "a preset confidence threshold"
  std::vector<ClassBoundary> classes = DefaultBoundaries();  // Table 4.1 + door30
  // A sensor inside the door's bearing span that differs from both flanks by more than
  // this is a depth edge (an open door, §4.1.2). A door leaf is under 2 in thick and a
  // frame recess about 4 in; an open leaf moves the echo by tens of inches.
  double open_door_depth_edge_in = 8.0;
  // Navigation envelope, §6.4.2: optical axis within 7.5° of the wall normal, robot within
  // 1 ft of the hallway axis (when the caller knows its offset).
  double envelope_axis_angle_rad = 7.5 * kPi / 180.0;
  double envelope_lateral_in = 12.0;
};

// What the landmark stage reports for one frame.
struct LandmarkObservation {
  DoorClass door_class = DoorClass::k36;
  double width_in = 0.0;
  double confidence = 0.0;
  Footprints footprints;
  int candidate_index = 0;      // index into the caller's candidate list
  double range_in = 0.0;        // perpendicular range camera -> wall (sdis, §5.3)
  double theta_rad = 0.0;       // optical axis to wall normal, as the sonar saw it
  double look_angle_rad = 0.0;  // stare delta = theta + 90°
  bool in_envelope = false;
  bool open_door = false;  // flank line fit used (§4.1.2)
};

// The landmark classification stage (§4.1.2 with the geometries of §5.2/§5.3): fuses one
// sonar scan with the candidate jamb pairs of one frame and returns the classified door, or
// why there is none. Pure algorithm; the landmark process wraps it.
class LandmarkEstimator {
 public:
  explicit LandmarkEstimator(const RobotConfig& robot, LandmarkEstimatorConfig config = {});

  // Candidates are tried in decreasing confidence; the first whose width falls in a class
  // wins. `lateral_offset_in`: distance from the hallway axis, if known (envelope check).
  // Errors: kBadSonarRange (wrong count, or a valid-flagged NaN/negative/out-of-range
  // range), kBadFootprint (any malformed candidate), kNoValidSonar, kNoCandidate,
  // kStareOutOfRange, kOpenDoorUnresolved, kOutsideEveryClass.
  Result<LandmarkObservation> Estimate(
      const SonarScan& scan, const std::vector<JambCandidate>& candidates,
      std::optional<double> lateral_offset_in = std::nullopt) const;

  const CameraModel& camera() const { return camera_; }
  const SonarRingModel& ring() const { return ring_; }

 private:
  struct Ranges;  // the sonar readings the geometries use, referred to the camera
  Result<Ranges> ShortSideRanges(const std::vector<double>& ranges,
                                 const std::vector<bool>& valid) const;
  // Replaces readings inside the door's bearing span by the flank wall fit when a depth
  // edge is there. Returns whether it did; fails if a fit is needed but impossible.
  Result<bool> FillOpenDoor(const Footprints& fp, std::vector<double>* ranges,
                            std::vector<bool>* valid) const;
  // FillOpenDoor() once it found a depth edge: fits the wall through the `flank` sensors'
  // readings and puts its echoes in place of the `inside` ones.
  Result<bool> FillFromFlankWall(const std::vector<int>& flank, const std::vector<int>& inside,
                                 std::vector<double>* ranges, std::vector<bool>* valid) const;
  // The observation of the winning candidate c (index idx in the caller's list).
  LandmarkObservation Observation(const JambCandidate& c, std::size_t idx, DoorClass door_class,
                                  double width_in, const Ranges& rs, bool open_door,
                                  std::optional<double> lateral_offset_in) const;

  CameraModel camera_;
  SonarRingModel ring_;
  double camera_offset_in_ = 0.0;
  LandmarkEstimatorConfig config_;
};

}  // namespace stickrep::sensing
