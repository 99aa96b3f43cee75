#pragma once

#include <optional>

#include "sensing/result.h"
#include "sensing/robot_config.h"

namespace stickrep::sensing {

// The sonar ring as the geometry sees it (§4.3, §5.4): sensor bearings, head radius, cone.
struct SonarRingModel {
  int count = 24;
  double spacing_rad = 0.0;
  double head_radius_in = 7.5;
  double half_cone_rad = 0.0;
  double min_range_in = 12.0;
  double max_range_in = 420.0;
  double footprint_rad = 0.0;
  int coaxial_sensor = 0;

  static SonarRingModel FromConfig(const RobotConfig& c);
  // Bearing of sensor k from the optical axis, in (-pi, pi], positive toward image right.
  double BearingOf(int k) const;
  // Whether a range is a plausible reading: finite and within [min, max].
  bool InRange(double range_in) const;
};

// Which of the three cases of §5.4.1 a sensor is in, from its axis' angle to the wall
// normal (the paper's cases are written for the sensor two spacings off the optical axis).
enum class ReturnCase {
  kNormalInsideCone,   // Case 1: the perpendicular from the sensor lies inside the cone
  kNormalOutsideCone,  // Cases 2 and 3: the echo comes from the cone limit nearest the normal
  kNoEcho,             // the whole cone points away from the wall (|incidence| - half cone >= 90°)
};

ReturnCase ClassifyReturn(const SonarRingModel& ring, double incidence_rad);

// §5.4.1, forward: the range a sensor returns from a plane at perpendicular distance
// `wall_distance_in` from the ring centre when its axis makes `incidence_rad` with the wall
// normal. The sensor sits head_radius_in out along its axis; the first echo comes from the
// point of the plane nearest the sensor within its cone.
Result<double> ReturnedRange(const SonarRingModel& ring, double wall_distance_in,
                             double incidence_rad);

// §5.4.1, inverse (the "actual geometric definition" of RL and RR): the range from the ring
// centre along a ray at `ray_incidence_rad` to the normal, given the range `returned_in` of a
// sensor whose axis is at `sensor_incidence_rad`. The incidences must be known (the stare).
Result<double> RangeAlongRay(const SonarRingModel& ring, double returned_in,
                             double sensor_incidence_rad, double ray_incidence_rad);

// The formulas of §5.4.1 exactly as printed, angles in degrees, for checking. In the
// printed formulas L is the side whose sensor is nearer the normal for delta < 90°.
// Case 1 uses d_R as a perpendicular range and the printed Case 3 right formula does not
// reproduce the geometry (see docs/sensing.md); RangeAlongRay is what the code uses.
struct PrintedCaseRanges {
  int case_number = 0;
  double rl_in = 0.0;
  double rr_in = 0.0;
};
PrintedCaseRanges PrintedExactRanges(double d_l_in, double d_r_in, double delta_deg, double fov_deg,
                                     double head_radius_in);

// The three surfaces of the ultrasound studies (§4.3).
enum class Surface { kCloth, kWood, kConcrete };
const char* ToString(Surface s);
std::optional<Surface> SurfaceFromString(const std::string& name);

// Which repetition of the ultrasound study to read.
enum class UltrasoundExperiment { kTable42, kTable43, kWorseOfBoth };

// Percent range error (mean and standard deviation) of Tables 4.2 / 4.3.
struct PercentRangeError {
  double mean_pct = 0.0;
  double sigma_pct = 0.0;
};

// Tables 4.2 and 4.3: percent range error at incidence phi. The tables give phi = 0, 15,
// 30, 45°; between them we interpolate linearly (a few discrete, near-deterministic values
// per cell, Appendix A). Beyond 45°, and where a cell reads "++", the reading is gross:
// std::nullopt.
std::optional<PercentRangeError> SurfaceRangeError(Surface s, double phi_rad,
                                                   UltrasoundExperiment which);

// Whether a reading at incidence phi lies in the accurate footprint of §4.3: concrete and
// wood for phi <= footprint (15°), cloth only head-on (phi = 0 within 1°).
bool InAccurateFootprint(const SonarRingModel& ring, Surface s, double phi_rad);

}  // namespace stickrep::sensing
