#pragma once

// Hallway following with turns: what the locomotion process does in MOTION_FOLLOW_HALLWAY.
// Owns a HallwayFollower (wall fit and PD steering, hallway_follower.h) and the state
// machine around it:
//
//   FOLLOWING  steer along the hallway axis on the newest gated sonar scan. A wall across
//              the hallway ahead caps the speed so that the base comes to rest with its
//              centre half the measured hallway width from that wall, i.e. on the axis of
//              the hallway it turns into. There DetectTurn decides:
//                corner       one side open: rotate in place toward it (TURNING);
//                junction     both sides open: rotate toward the camera side (left, where
//                             the mapped wall is), so the wall the camera watches is kept —
//                             a left-hand rule; the mission plans routes, not this class;
//                hallway end  neither side open: reverse the travel direction (the base
//                             drives backward with the camera still on the wall, §6.3).
//              A side that opens with no wall ahead (a branch hallway, a crossing) is
//              passed straight: the hallway continues and the walls on both sides return.
//   STOPPING   braking (at brake_decel_ftps2) before a turn decided at speed.
//   TURNING    rotating in place by the decided angle, measured with the odometry heading,
//              the rate ramped up and down (turn_accel_radps2) and capped (turn_rate_radps);
//              then FOLLOWING again with the follower reset.
//   OBSTACLE   stopped: something is within the follower's stop distance in the direction
//              of travel, or what looked like a wall ahead does not reach across the
//              hallway (the sensors 30° either side of travel read the side walls past
//              it). Following resumes by itself when it clears; after
//              obstacle_patience_s unmoved it is taken for a wall (turn or reverse).
//   NO_SCAN    the newest scan is older than scan_timeout_s (or none came yet): the base is
//              held, as steering blind is unsafe.
//
// Standard library only; the node feeds scans and odometry and sends the set-points.

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "locomotion/hallway_follower.h"

namespace stickrep::locomotion {

// Noise figures of HallwayTracker.
struct HallwayTrackerNoise {
  double offset_sigma_in = 0.5;     // one scan's offset (the fit is good to ~0.2 in)
  double heading_sigma_deg = 8.0;   // one scan's heading
  double initial_heading_sigma_deg = 10.0;
  // Odometry: heading random walk per inch travelled (wheel slip, and the hallway's own
  // bending: a corridor curving at a radius of 50 ft turns its axis 0.17 rad in 100 in,
  // which a filter sure of a straight hallway lags until the base meets the outer wall),
  // per radian turned, and a lateral wander per inch (a hallway is not a perfect line).
  double heading_walk_rad_per_sqrt_in = 0.004;
  double turn_scale_error = 0.02;
  double offset_walk_in_per_sqrt_in = 0.05;
  // A measurement this many standard deviations off the prediction is an outlier (a door
  // recess taken for the wall, a pilaster's face); after `reinit_after` of them in a row
  // the track restarts (0.8 s of scans: a track gone wrong is not kept long).
  double gate_sigmas = 4.0;
  int reinit_after = 8;
  // Outliers that put the wall farther than predicted (a door alcove, a recess, a room
  // opening off the corridor) restart the track only after this much travel: a recess as
  // long as a corridor is wide is passed on the track, and holding it never brings the base
  // nearer a wall. (Counted in scans, 0.8 s, a slow base took a long alcove for the wall.)
  double reinit_recess_in = 96.0;
  // A recess has a back parallel to the wall: once a run of such outliers is twice this
  // long, the outliers over its last `recess_window_in` of travel must lie on a line within
  // `recess_max_slope_deg` of the track. Readings that keep drifting farther are not a
  // recess but a track gone wrong, its heading off, steering the base away from the only
  // wall it has (across an open hall): the track restarts then, not 96 in later.
  double recess_window_in = 24.0;
  double recess_max_slope_deg = 10.0;
  // Reported as known below these standard deviations.
  double known_offset_sigma_in = 3.0;
  double known_heading_sigma_deg = 4.0;
};

// Lateral offset and heading error of the base in the hallway, tracked between scans with
// odometry: a two-state Kalman filter. One scan's wall fit gives the offset to a fraction of
// an inch but the heading only to several degrees (sonar off real surfaces, §4.3); how the
// offset changes as the base travels tells the heading far better, and odometry carries
// both across scans and across stretches where the walls cannot be fitted (a side open, a
// wall ahead). Conventions as in hallway_follower.h.
class HallwayTracker {
 public:
  explicit HallwayTracker(HallwayTrackerNoise noise = {}) : noise_(noise) {}

  // The base moved ds_in along its forward axis and turned dtheta_rad (odometry).
  void Predict(double ds_in, double dtheta_rad);
  // False when the measurement is set aside as an outlier. `recess`: the measurement puts
  // no wall nearer than the track does (an outlier of that kind is held off longer).
  bool UpdateOffset(double offset_in, bool recess = false);
  // One scan's fit of both walls: its offset as UpdateOffset, and its heading whenever the
  // offset is taken (NaN: the scan fitted none). So a track that the offset restarts (a new
  // stretch round a bend, a base pushed aside) starts again from the scan's heading, not
  // from heading 0 with only odometry and later offsets to find it.
  bool UpdateScan(double offset_in, double heading_rad, bool recess = false);
  // Whether a measurement would pass the gate (no side effects).
  bool Consistent(double offset_in) const;
  void UpdateHeading(double heading_rad);
  // After an in-place turn of `rad` (already predicted from odometry): the hallway's axis
  // turned with the base, so the heading error drops by `rad`; the offset in the new
  // hallway is not known yet.
  void TurnedOnto(double rad);
  void Reset() {
    initialised_ = false;
    rejected_ = 0;
    EndRecessRun();
  }

  bool offset_known() const;
  bool heading_known() const;
  double offset_in() const { return y_; }
  double heading_rad() const { return psi_; }

 private:
  HallwayTrackerNoise noise_;
  bool initialised_ = false;
  double y_ = 0.0, psi_ = 0.0;
  double pyy_ = 0.0, pyp_ = 0.0, ppp_ = 0.0;  // covariance
  int rejected_ = 0;
  // Travel since the first of a run of recess outliers; < 0 outside such a run.
  double recess_travel_in_ = -1.0;
  // The run's outliers: travel since its first, and the offset each put the base at.
  struct RecessSample {
    double travel_in;
    double offset_in;
  };
  std::vector<RecessSample> recess_run_;
  void EndRecessRun() {
    recess_travel_in_ = -1.0;
    recess_run_.clear();
  }
  // Whether the run's latest outliers drift (see HallwayTrackerNoise::recess_window_in).
  bool RecessDrifts() const;
  void Correct(double h_y, double h_psi, double v, double s);
};

enum class BehaviourState { kNoScan, kFollowing, kStopping, kTurning, kObstacle };
const char* ToString(BehaviourState state);

struct HallwayBehaviourConfig {
  HallwayFollowerConfig follower;
  // In-place turns: peak rate and ramp. 0.6 rad/s turns 90° in about 3 s; the ramp keeps
  // the wheels from slipping at the start and the end of a turn.
  double turn_rate_radps = 0.6;
  double turn_accel_radps2 = 1.0;
  // A turn is complete within this of the target heading; the follower corrects the rest.
  double turn_tolerance_deg = 1.0;
  // The base is held when the newest scan is older than this (scans come every 0.1 s).
  double scan_timeout_s = 0.5;
  // A wall ahead seen by one scan is kept (dead-reckoned by odometry) for this long when
  // the next scans miss it (the front sensors are gated out near a corner's edges).
  double wall_memory_s = 1.0;
  // The turn is taken once the base is within this of its stopping point.
  double stop_tolerance_in = 2.0;
  // Something in the way that does not move for this long is no person: it is taken for
  // a corner or the end of the way (DetectTurn on the sides), as if it spanned the hallway.
  double obstacle_patience_s = 5.0;
  // The hallway width assumed until a scan has measured one.
  double default_hallway_width_in = 120.0;
  // A stalled base: driven at stall_speed_ftps or more for stall_time_s while its odometer
  // moved less than stall_travel_in. The base is against something the sonar does not see
  // (glass, a low step, a corner nearer than the sonar's 1 ft minimum range); travel
  // reverses at once, as at a hallway end. The encoders are the only witness: wheels that
  // spin on the floor against the obstacle would need the motors' current, which the
  // LabMate's driver does not report here.
  double stall_speed_ftps = 0.25;
  double stall_time_s = 1.0;
  double stall_travel_in = 0.5;
  // The navigation envelope of §6.4.2: within 1 ft of the axis and 7.5° of its direction.
  double envelope_offset_in = 12.0;
  double envelope_heading_deg = 7.5;
  // Pace in the camera's view. A door is measured from a frame that shows both its jambs
  // (§4.1), and the camera stares at the mapped wall, so the base moves slowly enough that
  // the widest single door stays whole in view for `frames_per_door` frames at the wall's
  // range r: v <= (2 r tan(FOV/2) - door) / (frames_per_door x frame period). At the text's
  // 60 in from the wall (120 in hallways) that allows more than the LabMate's 2.6 ft/s; at
  // 44-48 in (88-96 in corridors) about half of it. 0 frames: no pacing.
  int frames_per_door = 0;
  double camera_fov_deg = 55.817;    // configs/robot.yaml
  double camera_frame_period_s = 0.2;  // §6.3
  double door_in_view_in = 40.0;     // the widest single door class (Table 4.1)
  // Never slower than this, however near the wall (the base must still get somewhere).
  double min_view_speed_ftps = 0.5;
  // Riding off the axis for the camera. In a hallway too narrow for the pacing above to
  // allow the top speed on its axis, the base is steered up to this far from the axis,
  // away from the mapped wall, toward the range at which it does (55.4 in with the
  // values above), and never nearer the far wall than the follower's stop distance; with
  // a wall ahead in sight (a corner, a hallway end) it steers back to the axis. The
  // envelope of §6.4.2 is judged about the line steered to. 0: the base keeps to the axis.
  double max_view_offset_in = 0.0;
  // A hallway is taken for narrow (or wide again) only once every width measured over this
  // much travel says so: a wall that juts out for a few feet, or an alcove, changes nothing.
  double view_offset_after_in = 240.0;
};

// The speed cap of the camera-view pacing above at `range_in` from the mapped wall
// (unbounded when frames_per_door is 0).
double ViewPacedSpeedFtps(const HallwayBehaviourConfig& config, double range_in);

// The lateral offset the base is steered to in a hallway `width_in` wide (the sign of
// BehaviourOutput::lateral_offset_in: negative, away from the mapped wall; 0 on the axis):
// see max_view_offset_in.
double ViewOffsetIn(const HallwayBehaviourConfig& config, double width_in);

// What the behaviour wants from the base this step, and why.
struct BehaviourOutput {
  double linear_ftps = 0.0;
  double angular_radps = 0.0;
  BehaviourState state = BehaviourState::kNoScan;
  std::string reason;  // a sentence for the status message and the log
  // Events of this step (for counting and logging).
  bool turn_started = false;
  bool reversed = false;
  bool obstacle_stop_started = false;
  bool stalled = false;                  // the base did not move while driven (see stall_time_s)
  TurnKind turn_kind = TurnKind::kNone;  // the decision taken this step
  int travel_sign = +1;  // +1 forward, -1 backward
  // The newest scan's view of the hallway.
  bool offset_valid = false;
  double lateral_offset_in = 0.0;  // from the axis, + nearer the left (mapped) wall
  double target_offset_in = 0.0;   // the line steered to (ViewOffsetIn), the same sign
  bool heading_valid = false;
  double heading_error_rad = 0.0;  // forward axis vs the hallway axis, CCW +
  bool in_envelope = false;        // following, and inside the §6.4.2 envelope about that line
};

class HallwayBehaviour {
 public:
  // Throws std::invalid_argument when a value is out of range (set-up only).
  explicit HallwayBehaviour(HallwayBehaviourConfig config = {});

  const HallwayBehaviourConfig& config() const { return config_; }

  // A gated scan (sensor_count readings, ranges from the transducer faces), received at
  // now_s on the clock Step is given.
  void OnScan(const std::vector<SonarRange>& scan, double now_s);

  // One control step: the mission's speed (signed: negative travels backward; the sign
  // sets the travel direction until a hallway end reverses it), the odometry heading and
  // odometer reading (drive.h), the time now and since the last step. Never throws.
  BehaviourOutput Step(double commanded_speed_ftps, double odometry_heading_rad,
                       double odometer_in, double now_s, double dt_s);

  // Forgets speed, travel direction, turn and wall memory (after a stop or a plain velocity
  // command): the next Step starts afresh. The newest scan is kept.
  void Reset();

  BehaviourState state() const { return state_; }
  int travel_sign() const { return travel_sign_; }

 private:
  void Report(BehaviourOutput& out) const;
  // The steps of Step(), each filling `out`; a true return means `out` is final.
  // Rotating in place toward turn_target_rad_.
  bool TurnInPlace(double odometry_heading_rad, double dt_s, BehaviourOutput& out);
  // At the stopping point before a wall ahead: waits for an obstacle, or sets the turn.
  bool ActAtWall(double wall_in, double wall_normal, double stop_at_in, bool was_obstacle,
                 double now_s, BehaviourOutput& out);
  // Braking before the pending turn, then reversing or starting the turn.
  bool BrakeAndAct(double wall_in, double odometry_heading_rad, double dt_s, BehaviourOutput& out);
  // Following at up to `speed` (ft/s, unsigned): capped before the wall ahead and for the
  // camera, steered on the track; fills and reports `out`.
  void Follow(double speed, double width_in, double wall_in, double stop_at_in, bool was_obstacle,
              double odometer_in, double now_s, double dt_s, BehaviourOutput& out);
  // The follower stopped for something close: waits, or reverses after the patience.
  void Blocked(double odometer_in, double now_s, BehaviourOutput& out);
  // At the first stop of a blocked spell: when a side wall the base heads into stopped it,
  // starts an in-place turn onto that wall's direction (true; `out` then says so).
  bool SquareUp(double free_in, BehaviourOutput& out);
  // Travel reverses (a hallway end, §6.3 A4).
  void Reverse(BehaviourOutput& out);
  // Whether the base has stalled while driven (stall_time_s): then travel reverses and
  // `out` is final.
  bool Stalled(double odometer_in, double now_s, BehaviourOutput& out);
  // Updates the track from the fresh scan (`width_in`: the hallway's).
  void UpdateTrack(double width_in);
  // Whether `wall` on `side` (+1 left, -1 right) is no nearer than the track puts it (a
  // recess, not a wall that came closer), in a hallway `half_width_in` either side.
  bool NotNearer(const WallLine& wall, int side, double half_width_in) const;
  // ... from a scan with both walls in range.
  void TrackBothWalls(double width_in);
  // A width measured on a plain stretch, for the narrow-hallway state.
  void NoteWidth(double width_in);
  // Whether a wall ahead at wall_in spans the hallway (an end, a corner, a junction) rather
  // than standing in it (an obstacle): judged on the newest scan.
  // `wall_in` is along the travel direction, `normal_rad` the wall's angle from across.
  bool WallSpansHallway(double wall_in, double normal_rad) const;

  HallwayBehaviourConfig config_;
  HallwayFollower follower_;
  HallwayTracker tracker_;
  BehaviourState state_ = BehaviourState::kNoScan;

  bool have_scan_ = false;
  bool scan_fresh_ = false;  // not yet used by a Step: its heading is a measurement
  double scan_time_s_ = 0.0;
  HallwayEstimate estimate_;
  std::vector<SonarRange> scan_;
  double hallway_width_in_ = 0.0;  // last measured, 0 until one is
  double target_offset_in_ = 0.0;  // the line Follow steers to (ViewOffsetIn)
  // The narrow-hallway state behind it: the travel so far (either way), whether the hallway
  // is narrow, the narrow widths measured over the last view_offset_after_in of travel (the
  // line is set by the least: an alcove's wider reading does not move it), and the travel
  // at which the widths began to say otherwise than the state (< 0: they agree).
  double travel_in_ = 0.0;
  bool narrow_ = false;
  std::deque<std::pair<double, double>> narrow_widths_;  // (travel, width) in
  double least_narrow_width_in_ = 0.0;                   // the least of them
  double narrow_disagree_since_in_ = -1.0;

  // Wall ahead in the travel direction, as last seen, and the odometer then.
  bool wall_known_ = false;
  double wall_ahead_in_ = 0.0;
  double wall_normal_rad_ = 0.0;  // 0: across the hallway; else an oblique corner
  int oblique_scans_ = 0;         // scans in a row that saw an oblique wall, at about
  double oblique_normal_rad_ = 0.0;  // this angle
  double wall_odometer_in_ = 0.0;
  double wall_time_s_ = 0.0;
  double obstacle_since_s_ = 0.0;
  // A spell of stops for something close ahead (the follower's stop distance).
  bool blocked_ = false;
  double blocked_since_s_ = 0.0;
  double blocked_odometer_in_ = 0.0;
  // Watching for a stall: since when the base has been driven, and the odometer then.
  bool driven_ = false;
  double driven_since_s_ = 0.0;
  double driven_odometer_in_ = 0.0;

  int commanded_sign_ = 0;
  int travel_sign_ = +1;
  double last_linear_ftps_ = 0.0;
  double last_angular_radps_ = 0.0;
  double turn_target_rad_ = 0.0;
  double turn_rad_ = 0.0;
  TurnKind pending_ = TurnKind::kNone;
  bool squaring_ = false;  // the turn squares up to this hallway (SquareUp), no corner
  bool squared_ = false;   // SquareUp has turned the base, at this odometer reading
  double squared_odometer_in_ = 0.0;
  double pending_rotate_rad_ = 0.0;
  double previous_odometer_in_ = 0.0;
  double previous_heading_rad_ = 0.0;
  bool have_odometer_ = false;
};

}  // namespace stickrep::locomotion
