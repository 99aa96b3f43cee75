#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace stickrep::executive {

enum class MissionState {
  kWaitingForComponents,
  kAligning,        // following the hallway slowly until inside the envelope (A3, A4)
  kRecoveringPose,
  kLocalized,       // pose recovered; holding until a goal arrives
  kExecutingGoal,   // travelling along the ring to the goal
  kGoalReached,
  kStoppedFault,     // a required process is absent: stopped until every one is back
  kLinkLost,        // every process of another host went silent: stopped until it is back
};
const char* ToString(MissionState s);

// What the mission wants the base to do now: follow the hallway at a signed speed
// (negative: backward), or stand still.
struct MotionRequest {
  bool move = false;
  double linear_speed_ftps = 0.0;
};

// A goal the route planner has turned into travel along the current ring.
struct GoalPlan {
  std::string goal_id;
  std::string description;
  int travel_sign = +1;      // +1: the base's forward direction; -1: backward
  double distance_in = 0.0;  // along the hallway
};

struct MissionConfig {
  std::vector<std::string> required_components;
  double travel_speed_ftps = 2.6;  // the base's top speed (§6.3): recovery is travel-bound
  int travel_direction = +1;       // +1: toward the image's right; -1: the other way
  // Aligning and centring (A3, A4 of §6.3) before recovery: follow the hallway at this
  // speed until locomotion has reported the robot inside the navigation envelope (§6.4.2)
  // for aligned_hold_s; after align_timeout_s recovery starts anyway, and says so.
  double align_speed_ftps = 1.3;
  double aligned_hold_s = 1.0;
  double align_timeout_s = 30.0;
  // The process that holds the pose: when it was absent and is back, it is a new process
  // without the pose, so the mission recovers the pose again.
  std::string pose_component = "localizer";
};

// The executive's state machine, free of DDS: waits until every required process is
// active, aligns with the hallway and centres (A3, A4), travels to recover the pose until
// the localizer reports LOCALIZED, holds there until a goal arrives, travels to it, recovers
// again when the pose is lost, and stops the robot while a required process is absent
// (STOPPED_FAULT). When every absent process is back (restarted), the mission resumes where
// it was, keeping the pose, unless the localizer was among them: then it recovers the pose
// again. Every transition is recorded. Times are seconds on any one clock the caller keeps.
class Mission {
 public:
  explicit Mission(MissionConfig config);

  // A process reported itself active (again, after a restart: the mission may resume).
  void OnComponentActive(const std::string& name);
  // Locomotion's report: whether the robot is inside the navigation envelope at `now_s`
  // (the base's clock); aligning is timed from the first report.
  void OnMotionState(bool in_envelope, double now_s);
  // A process stopped or its liveliness was lost; a required one stops the robot until it
  // is active again.
  void OnComponentGone(const std::string& name, const std::string& why);
  // The required processes absent now (gone and not back).
  const std::set<std::string>& Absent() const { return absent_; }
  // Every process on `host` went silent (a link or host loss): the robot is stopped and the
  // mission waits. Back after `outage_s`: the mission continues where it was, keeping the
  // pose if `localized` (the localizer still reports one), else recovering it again.
  void OnLinkLost(const std::string& host, const std::string& why);
  void OnLinkBack(const std::string& host, double outage_s, bool localized);
  void OnLocalized(const std::string& where);
  void OnLost();
  // Why a goal cannot be taken now (nothing if it can).
  std::optional<std::string> CanTakeGoal() const;
  // Starts travelling to the goal; the odometer is the base's current reading.
  void StartGoal(const GoalPlan& plan, double odometer_in);
  // The localized pose says the goal is `remaining_in` further along (0: here), at
  // odometer reading `odometer_in`: the goal's odometer reading is set afresh from it.
  void UpdateGoal(double remaining_in, double odometer_in);
  // Progress toward the goal.
  void OnOdometer(double odometer_in);
  // The base's measured speed (odometry) at `now_s` on the base's clock. A fault stop is a
  // full stop: once every absent process is back, the mission resumes only after the base
  // has been at rest for kFaultRestHoldS, so a process restarted faster than the base can
  // brake still leaves the robot stopped while it was absent. Until the base first reports,
  // it is taken to be at rest.
  void OnBaseSpeed(double speed_ftps, double now_s);
  static constexpr double kAtRestFtps = 0.01;
  static constexpr double kFaultRestHoldS = 0.2;
  const std::string& goal_id() const { return goal_.goal_id; }

  MissionState state() const { return state_; }
  // The required processes not heard from as active yet.
  std::vector<std::string> Missing() const;
  const std::string& last_message() const { return message_; }
  MotionRequest Motion() const;
  // Transitions since the last call, oldest first.
  std::vector<std::string> TakeTransitions();

 private:
  void Enter(MissionState s, const std::string& message);
  bool Required(const std::string& name) const;
  // Every absent process is back: continue where the fault stopped the mission.
  void ResumeAfterFault();
  // Every absent process is back: resume once the base is held at rest.
  void ResumeWhenAtRest();
  bool BaseHeldAtRest() const;

  MissionConfig config_;
  MissionState state_ = MissionState::kWaitingForComponents;
  GoalPlan goal_;
  double goal_odometer_in_ = 0.0;  // odometer reading at which the goal is reached
  std::set<std::string> active_;
  MissionState resume_state_ = MissionState::kWaitingForComponents;  // after a link loss
  MissionState fault_resume_state_ = MissionState::kWaitingForComponents;  // after a fault
  std::set<std::string> absent_;     // required processes gone and not back
  // A pose the localizer already holds when this executive starts (it was restarted).
  std::optional<std::string> pose_while_waiting_;
  bool pose_component_gone_ = false;  // the localizer was among them
  double align_start_s_ = -1.0;
  double in_envelope_since_s_ = -1.0;
  bool base_reported_ = false;
  double base_at_rest_since_s_ = -1.0;  // -1: moving
  double base_report_s_ = 0.0;
  std::string message_;
  std::vector<std::string> transitions_;
};

}  // namespace stickrep::executive
