#pragma once

// Hallway following from the sonar ring (§6.3 assumptions A3 and A4): estimate the hallway
// from one gated scan, then steer the base along the hallway axis and keep it inside the
// navigation envelope of §6.4.2 (within 1 ft of the axis, optical axis within 7.5° of the
// wall normal) without oscillating, stop before obstacles and report corners and hallway
// ends. Standard library only: the locomotion node feeds it scans and sends its set-points.
//
// Conventions (all in the base frame, seen from above):
//   - x is the base's forward axis, y its left; angles are radians, counter-clockwise
//     positive, 0 along +x.
//   - The camera looks sideways at the mapped wall, along +y (camera_yaw_deg = +90). Sensor
//     k points (k - coaxial_sensor) * spacing_deg toward the image's right, i.e. clockwise,
//     so its bearing is camera_yaw - (k - coaxial_sensor) * spacing: with the shipped
//     configs/robot.yaml sensor 0 looks left (+90°), 6 forward (0°), 12 right (-90°), 18
//     backward (180°).
//   - Ranges are reported from the transducer face, which sits head_radius_in from the ring
//     centre along the sensor's bearing; every distance this file returns is measured from
//     the ring centre (= the base centre).
//   - The "left wall" is the wall on +y (the mapped wall the camera looks at), the "right
//     wall" the one on -y.
//   - heading_error_rad: the angle of the base's forward axis relative to the hallway axis
//     (CCW positive). lateral_offset_in: the signed distance of the base centre from the
//     hallway axis (midway between the walls), positive when the base is left of the axis
//     (nearer the left wall).
//   - Travel is forward (positive speed, along +x) or backward (negative speed, along -x):
//     the robot travels a hallway either way with the camera kept on the wall (§6.3).

#include <limits>
#include <optional>
#include <vector>

namespace stickrep::locomotion {

// One transducer's reading after the sonar gate.
struct SonarRange {
  double range_in = 0.0;  // from the transducer face
  bool valid = false;     // false: no echo, out of range, outside the footprint, malformed
  // An echo in the measuring range that the gate set aside as outside the accurate
  // footprint (§4.3): its range is rough, but something is there.
  bool outside_footprint = false;
};

// Tuning of the hallway follower. The ring geometry defaults follow configs/robot.yaml
// (robot.sonar_ring, robot.camera.coaxial_sensor) and the node fills them from there; the
// rest are documented where they are declared.
struct HallwayFollowerConfig {
  // --- Ring geometry (configs/robot.yaml) ---
  int sensor_count = 24;
  double spacing_deg = 15.0;
  double head_radius_in = 7.5;
  double cone_deg = 23.6;  // §5.4: a sensor returns the nearest point inside this cone
  int coaxial_sensor = 0;
  double camera_yaw_deg = 90.0;  // the camera looks at the wall, 90° left of forward

  // --- Wall fit ---
  // Sensors within this angle of ±90° look at a side wall and take part in its fit: three
  // sensors either side of the normal, enough to see past a door recess.
  double side_half_angle_deg = 45.0;
  // Heading errors searched by the fit, and the grid step. A3 puts the robot within a few
  // degrees; the search covers 30° so the robot can also align after a turn.
  double max_heading_search_deg = 30.0;
  double heading_step_deg = 0.25;
  // A reading whose implied wall distance is farther than this from the side's consensus
  // is an outlier (a door recess, an open door, a person): the cost is truncated there so
  // outliers cannot pull the fit. Sonar on concrete and wood is good to about an inch in
  // the footprint (§4.3, Tables 4.2, 4.3); 3 in leaves room for the cone model.
  double inlier_band_in = 3.0;
  // Sides without any reading nearer than this are "open": the wall has disappeared (a
  // corner, a branch hallway). 7 ft: a side wall of an 8 ft hallway reads at most about
  // 5 ft from the centre (half the width, 1 ft off the axis, the cone's slant), while in a
  // crossing hallway of the same width the nearest walls are 8 ft or more away once the
  // base stands in the crossing.
  double side_open_range_in = 84.0;
  // Side sensors judged for openness: within this angle of the side's normal (three
  // sensors). A 36 in open door at hallway range fills only the middle cone, so the outer
  // two stay on the wall; a crossing hallway empties all three once the base is in it.
  double side_open_half_angle_deg = 15.0;

  // --- Free space and hallway end ---
  // Sensors within this angle of the travel direction look ahead (three sensors).
  double front_half_angle_deg = 22.5;
  // A front echo within this much of the range the fitted side walls explain is the side
  // wall seen at the edge of the cone, not an obstacle.
  double side_echo_margin_in = 6.0;
  // All front sensors agreeing on one plane across the travel direction to within this
  // much make a wall ahead (the hallway's end or a corner), not a narrow obstacle.
  double wall_ahead_spread_in = 8.0;
  // A wall ahead that is not across the hallway (a corner at another angle than 90°: the
  // hallway turns by less than a right angle) is searched for with its normal up to this
  // far off the hallway axis, among the sensors within oblique_half_angle_deg of the travel
  // direction; it takes three of them agreeing. Walls turned less than
  // min_oblique_wall_deg count as across.
  double max_oblique_wall_deg = 60.0;
  double oblique_half_angle_deg = 45.0;
  double min_oblique_wall_deg = 15.0;
  // EmptySectorTurnRad: an empty sector at least this wide from the travel axis is a turn.
  double min_free_sector_deg = 75.0;

  // --- Control ---
  double max_speed_ftps = 2.6;  // §6.3: the LabMate's rated speed
  double max_angular_radps = 1.0;
  // Speeding up is limited to this (slowing down is not: stopping is never delayed).
  double max_accel_ftps2 = 1.5;
  // Deceleration the speed ramp plans with when an obstacle is ahead: 1.5 ft/s^2 brakes
  // from 2.6 ft/s in 27 in.
  double brake_decel_ftps2 = 1.5;
  // Stop when an obstacle ahead is this close to the base centre: the 7.5 in head radius
  // plus 16.5 in of clearance for the base's corners and the sonar's minimum range of 1 ft.
  double stop_distance_in = 24.0;
  // Echoes off the front fan that no side wall explains stop the base too when they lie
  // within its radius plus this much of the travel line (a corner passed at a slant).
  double swept_clearance_in = 4.0;
  // PD gains, spatial (per inch travelled rather than per second, so the path is the same
  // at every speed): the lateral offset y obeys y'' + 2 zeta/L y' + y/L^2 = 0 along the
  // distance travelled, critically damped (zeta = 1) with a length scale L of 36 in. The
  // offset then settles in about 5 L = 15 ft with no overshoot from rest; from 10 in off
  // the axis heading 10° toward it the crossing stays below 1 in (see the test).
  double length_scale_in = 36.0;
  double damping_ratio = 1.0;
  // The offset term alone never asks for more than this heading toward the axis, so a large
  // offset is corrected without leaving the 7.5° envelope of §6.4.2.
  double max_correction_heading_deg = 5.0;
  // Turns are requested once a wall ahead is this close (a corner or the hallway's end):
  // far enough to stop at the configured deceleration from full speed before the stop
  // distance, with a foot to spare.
  double turn_wall_ahead_in = 66.0;
};

// One fitted side wall.
struct WallLine {
  bool valid = false;
  double distance_in = 0.0;  // perpendicular distance from the base centre
  double normal_rad = 0.0;   // direction of the perpendicular from the base to the wall
  int inliers = 0;           // readings within the inlier band
  int outliers = 0;          // readings beyond it (door recesses, open doors, obstacles)
};

inline constexpr double kNoObstacle = std::numeric_limits<double>::infinity();

// What one scan says about the hallway.
struct HallwayEstimate {
  WallLine left;   // +y, the mapped wall
  WallLine right;  // -y
  // Valid when both walls are fitted.
  bool offset_valid = false;
  double lateral_offset_in = 0.0;
  double hallway_width_in = 0.0;
  // Valid when the fit had readings that carry heading information: at least three inliers
  // with at least one outside the central part of its cone (a reading with the wall normal
  // inside the cone returns the perpendicular distance whatever the heading, §5.4.1 Case 1).
  bool heading_valid = false;
  double heading_error_rad = 0.0;
  // Distance from the base centre to the nearest obstacle in the direction of travel,
  // forward (+x) and backward (-x); kNoObstacle when the way is clear.
  double free_forward_in = kNoObstacle;
  double free_backward_in = kNoObstacle;
  // A wall ahead / behind (the front sensors agree on one plane): its distance along the
  // direction of travel, kNoObstacle when there is none, and the angle of its normal from
  // the hallway axis in that direction (0: across the hallway, a square corner or end;
  // CCW positive, so a wall ahead on the right is negative).
  double wall_forward_in = kNoObstacle;
  double wall_backward_in = kNoObstacle;
  double wall_forward_normal_rad = 0.0;
  double wall_backward_normal_rad = 0.0;
  // No reading within side_open_range_in on that side: the wall has disappeared.
  bool left_open = false;
  bool right_open = false;
  int valid_readings = 0;
};

// What the robot should do at the end of a straight run.
enum class TurnKind {
  kNone,
  kCorner,      // the wall ahead is close and one side is open: turn into it
  kJunction,    // the wall ahead is close and both sides are open: the mission chooses
  kHallwayEnd,  // the wall ahead is close and both sides are closed: reverse the travel
};
const char* ToString(TurnKind kind);

struct TurnRequest {
  TurnKind kind = TurnKind::kNone;
  // In-place rotation that lines the travel direction up with the open side (+pi/2 CCW,
  // -pi/2 CW), or with the wall ahead when it is oblique (the hallway turns by less than a
  // right angle: pi/2 less the wall's angle, away from its normal). 0 for a junction
  // (either way) and a hallway end (travel reverses: the base drives backward with the
  // camera still on the wall, no rotation needed).
  double rotate_rad = 0.0;
  double wall_ahead_in = kNoObstacle;
};

// The set-points for the base.
struct SteerCommand {
  double linear_ftps = 0.0;
  double angular_radps = 0.0;
  // The speed is held below the command by an obstacle ahead (true also when stopped).
  bool limited_by_obstacle = false;
  bool stopped_for_obstacle = false;
  TurnRequest turn;
};

// Estimates the hallway from one sonar scan. The sonar returns the nearest surface point
// inside its 23.6° cone (§5.4.1): against a wall whose normal lies inside the cone it
// reports the perpendicular distance (Case 1), otherwise the distance along the cone's edge
// nearest the normal (Cases 2 and 3). Placing echoes along the sensor axes and fitting
// lines to them would therefore bend every wall into an arc and bias the heading, so each
// side is fitted with that model instead: for each heading error on a grid, every side
// reading implies a wall distance, the side's wall is their median (doors and open doors
// are recesses that only some sensors see), and the heading whose implied distances agree
// best (truncated squared residuals, both walls parallel) wins.
HallwayEstimate EstimateHallway(const std::vector<SonarRange>& scan,
                                const HallwayFollowerConfig& config);

// The range a sensor at `bearing_rad` reports against a wall whose perpendicular from the
// base centre points along `normal_rad` at `distance_in` (§5.4.1 Cases 1-3); kNoObstacle
// when the wall is outside the cone. Exposed for tests and the free-space check.
double PredictedWallRangeIn(double bearing_rad, double normal_rad, double distance_in,
                            const HallwayFollowerConfig& config);

// A side wall whose normal points more than this into the travel direction is headed into:
// far beyond the 7.5° envelope steering keeps (§6.4.2).
inline constexpr double kHeadedIntoDeg = 10.0;

// How far the base can travel along `travel_rad` (0 forward, pi backward) before a fitted
// side wall it is headed into (see kHeadedIntoDeg) meets it: where the travel line meets the
// wall, less the base's radius; kNoObstacle when it heads into neither. The wall's echoes
// are explained by its fit, so the free-space check would not stop the base otherwise.
double SideWallsHeadedIntoIn(const HallwayEstimate& walls, double travel_rad,
                             const HallwayFollowerConfig& config);

// Bearing of sensor k from the base's forward axis (see the conventions above), in
// (-pi, pi].
double SensorBearingRad(int k, const HallwayFollowerConfig& config);

// Where a hallway end was judged from the front sensors: a turn after all when, on one side,
// every sensor from the first off the travel axis to at least min_free_sector_deg returns no
// echo or one beyond side_open_range_in (the next stretch's walls meet them too steeply, or
// one looks straight down it at a far wall: a bend of 30-75 deg, whose side is
// not "open" abeam because the sensors behind abeam still read the wall passed) while the
// other side answers. Returns the rotation onto the middle of that empty sector (CCW +),
// or nullopt. An open door cannot empty a sector that wide at the stopping point.
std::optional<double> EmptySectorTurnRad(const std::vector<SonarRange>& scan, int travel_sign,
                                         const HallwayFollowerConfig& config);

// The corner / hallway-end rule: a wall ahead (in the travel direction, travel_sign = +1
// forward, -1 backward) closer than turn_wall_ahead_in, and which sides are open.
TurnRequest DetectTurn(const HallwayEstimate& estimate, int travel_sign,
                       const HallwayFollowerConfig& config);

// The hallway-following controller: PD on lateral offset and heading, speed limited and
// ramped, stopped before obstacles. Holds the last speed for the acceleration limit, so one
// instance per base.
class HallwayFollower {
 public:
  // Throws std::invalid_argument when a value is out of range (set-up only).
  explicit HallwayFollower(HallwayFollowerConfig config = {});

  const HallwayFollowerConfig& config() const { return config_; }

  // One control step: the estimate of the newest scan, the speed the mission wants (signed:
  // negative travels backward) and the time since the previous step. Never throws;
  // non-finite inputs give a stop.
  //
  // Linear: |commanded| capped at max_speed_ftps, then at sqrt(2 brake_decel (free -
  // stop_distance)) for the free space in the travel direction, 0 inside the stop distance;
  // increases limited to max_accel_ftps2 * dt.
  // Angular: omega = -v a y - |v| b sin(psi), a = 1/L^2, b = 2 zeta/L (spatial PD, see the
  // config), written as -|v| b (sin psi - sin psi_ref) with psi_ref the heading the offset
  // asks for, capped at max_correction_heading_deg. Terms whose estimate is not valid are
  // left out (no walls: hold the heading). When a scan cannot observe the heading, the last
  // measured heading advanced by the commanded turn rate stands in for it.
  SteerCommand Steer(const HallwayEstimate& estimate, double commanded_speed_ftps, double dt_s);

  // Forgets the last speed and heading (after a stop commanded from elsewhere, a turn).
  void Reset() {
    last_speed_ftps_ = 0.0;
    last_angular_radps_ = 0.0;
    heading_known_ = false;
  }
  double last_speed_ftps() const { return last_speed_ftps_; }
  // The heading error the controller steers on: the last measured one carried forward with
  // the turn commanded since; only meaningful when heading_known().
  bool heading_known() const { return heading_known_; }
  double heading_error_rad() const { return heading_rad_; }

 private:
  HallwayFollowerConfig config_;
  double last_speed_ftps_ = 0.0;
  double last_angular_radps_ = 0.0;
  // Heading error carried between scans that cannot observe it: the last measured value
  // plus the turn commanded since.
  bool heading_known_ = false;
  double heading_rad_ = 0.0;
};

}  // namespace stickrep::locomotion
