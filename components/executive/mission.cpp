#include "executive/mission.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stickrep::executive {

const char* ToString(MissionState s) {
  switch (s) {
    case MissionState::kWaitingForComponents: return "WAITING_FOR_COMPONENTS";
    case MissionState::kAligning: return "ALIGNING";
    case MissionState::kRecoveringPose: return "RECOVERING_POSE";
    case MissionState::kLocalized: return "LOCALIZED";
    case MissionState::kExecutingGoal: return "EXECUTING_GOAL";
    case MissionState::kGoalReached: return "GOAL_REACHED";
    case MissionState::kStoppedFault: return "STOPPED_FAULT";
    case MissionState::kLinkLost: return "LINK_LOST";
  }
  return "?";
}

Mission::Mission(MissionConfig config) : config_(std::move(config)) {
  message_ = "waiting for " + std::to_string(config_.required_components.size()) + " processes";
}

void Mission::Enter(MissionState s, const std::string& message) {
  if (s == state_ && message == message_) return;
  transitions_.push_back(std::string(ToString(state_)) + " -> " + ToString(s) + ": " + message);
  state_ = s;
  message_ = message;
}

bool Mission::Required(const std::string& name) const {
  return std::find(config_.required_components.begin(), config_.required_components.end(),
                   name) != config_.required_components.end();
}

void Mission::OnComponentActive(const std::string& name) {
  active_.insert(name);
  if (state_ == MissionState::kStoppedFault && absent_.erase(name) > 0 && absent_.empty()) {
    ResumeWhenAtRest();
    return;
  }
  if (state_ != MissionState::kWaitingForComponents) return;
  const bool all = std::all_of(config_.required_components.begin(),
                               config_.required_components.end(),
                               [this](const std::string& c) { return active_.count(c) > 0; });
  if (!all) return;
  if (pose_while_waiting_) {
    // A restarted executive: the localizer kept the pose meanwhile.
    Enter(MissionState::kLocalized, "every process is active and the localizer holds the pose "
                                    "at " + *pose_while_waiting_ + ": holding, ready for a goal");
    return;
  }
  align_start_s_ = -1.0;
  in_envelope_since_s_ = -1.0;
  Enter(MissionState::kAligning,
        "every process is active: aligning with the hallway axis and centring");
}

std::vector<std::string> Mission::Missing() const {
  std::vector<std::string> out;
  for (const std::string& c : config_.required_components) {
    if (active_.count(c) == 0) out.push_back(c);
  }
  return out;
}

void Mission::OnMotionState(bool in_envelope, double now_s) {
  if (state_ != MissionState::kAligning) return;
  if (align_start_s_ < 0.0) align_start_s_ = now_s;
  if (!in_envelope) {
    in_envelope_since_s_ = -1.0;
  } else if (in_envelope_since_s_ < 0.0) {
    in_envelope_since_s_ = now_s;
  }
  if (in_envelope_since_s_ >= 0.0 && now_s - in_envelope_since_s_ >= config_.aligned_hold_s) {
    Enter(MissionState::kRecoveringPose,
          "inside the navigation envelope: travelling to recover the pose");
  } else if (now_s - align_start_s_ >= config_.align_timeout_s) {
    Enter(MissionState::kRecoveringPose,
          "not inside the navigation envelope after " + std::to_string(static_cast<int>(
              config_.align_timeout_s)) + " s: travelling to recover the pose anyway");
  }
}

void Mission::OnComponentGone(const std::string& name, const std::string& why) {
  active_.erase(name);
  // Before the mission starts, a process that goes is only waited for again.
  if (!Required(name) || state_ == MissionState::kWaitingForComponents) return;
  absent_.insert(name);
  if (name == config_.pose_component) pose_component_gone_ = true;
  if (state_ != MissionState::kStoppedFault) {
    fault_resume_state_ = state_ == MissionState::kLinkLost ? resume_state_ : state_;
  }
  std::string names;
  for (const std::string& n : absent_) names += (names.empty() ? "'" : ", '") + n + "'";
  Enter(MissionState::kStoppedFault, "process '" + name + "' is gone (" + why +
                                         "): robot stopped until " + names +
                                         (absent_.size() > 1 ? " are" : " is") + " back");
}

bool Mission::BaseHeldAtRest() const {
  return !base_reported_ || (base_at_rest_since_s_ >= 0.0 &&
                             base_report_s_ - base_at_rest_since_s_ >= kFaultRestHoldS - 1e-9);
}

void Mission::ResumeWhenAtRest() {
  if (BaseHeldAtRest()) {
    ResumeAfterFault();
    return;
  }
  Enter(MissionState::kStoppedFault,
        "every required process is back: waiting for the base to come to rest");
}

void Mission::OnBaseSpeed(double speed_ftps, double now_s) {
  base_reported_ = true;
  base_report_s_ = now_s;
  if (std::abs(speed_ftps) > kAtRestFtps) {
    base_at_rest_since_s_ = -1.0;
  } else if (base_at_rest_since_s_ < 0.0 || now_s < base_at_rest_since_s_) {
    base_at_rest_since_s_ = now_s;
  }
  if (state_ == MissionState::kStoppedFault && absent_.empty() && BaseHeldAtRest()) {
    ResumeAfterFault();
  }
}

void Mission::ResumeAfterFault() {
  const std::string back = "every required process is back";
  const bool had_pose = fault_resume_state_ == MissionState::kLocalized ||
                        fault_resume_state_ == MissionState::kExecutingGoal ||
                        fault_resume_state_ == MissionState::kGoalReached;
  const bool new_localizer = pose_component_gone_;
  pose_component_gone_ = false;
  switch (fault_resume_state_) {
    case MissionState::kAligning:
      align_start_s_ = -1.0;
      in_envelope_since_s_ = -1.0;
      Enter(MissionState::kAligning, back + ": aligning again");
      return;
    case MissionState::kLocalized:
    case MissionState::kExecutingGoal:
    case MissionState::kGoalReached:
    case MissionState::kRecoveringPose:
      if (new_localizer || !had_pose) {
        Enter(MissionState::kRecoveringPose,
              back + (new_localizer ? ": the localizer restarted without the pose: travelling "
                                      "to recover it again"
                                    : ": no pose yet: travelling to recover it"));
      } else {
        Enter(fault_resume_state_,
              back + ": pose kept; " + ToString(fault_resume_state_) + " continues");
      }
      return;
    default:
      Enter(MissionState::kWaitingForComponents, back + ": waiting for the processes");
      if (!active_.empty()) OnComponentActive(*active_.begin());
      return;
  }
}

void Mission::OnLinkLost(const std::string& host, const std::string& why) {
  if (state_ == MissionState::kStoppedFault || state_ == MissionState::kLinkLost) return;
  resume_state_ = state_;
  Enter(MissionState::kLinkLost, "link to host '" + host + "' lost (" + why +
                                     "): robot stopped, waiting for the link");
}

void Mission::OnLinkBack(const std::string& host, double outage_s, bool localized) {
  if (state_ != MissionState::kLinkLost) return;
  char after[64];
  std::snprintf(after, sizeof(after), "link to host '%s' back after %.1f s", host.c_str(),
                outage_s);
  switch (resume_state_) {
    case MissionState::kLocalized:
    case MissionState::kExecutingGoal:
    case MissionState::kGoalReached:
      if (localized) {
        Enter(resume_state_, std::string(after) + ": pose kept; " + ToString(resume_state_) +
                                 " continues");
      } else {
        Enter(MissionState::kRecoveringPose,
              std::string(after) + ": pose not kept: travelling to re-acquire it");
      }
      return;
    case MissionState::kAligning:
      align_start_s_ = -1.0;
      in_envelope_since_s_ = -1.0;
      Enter(MissionState::kAligning, std::string(after) + ": aligning again");
      return;
    case MissionState::kRecoveringPose:
      Enter(MissionState::kRecoveringPose,
            std::string(after) + ": no pose yet: travelling to recover it");
      return;
    default:
      Enter(resume_state_, std::string(after));
      return;
  }
}

void Mission::OnLocalized(const std::string& where) {
  if (state_ == MissionState::kWaitingForComponents) {
    pose_while_waiting_ = where;
    return;
  }
  if (state_ == MissionState::kStoppedFault &&
      (fault_resume_state_ == MissionState::kRecoveringPose ||
       fault_resume_state_ == MissionState::kAligning) &&
      !pose_component_gone_) {
    fault_resume_state_ = MissionState::kLocalized;  // from what arrived before the fault
    return;
  }
  if (state_ == MissionState::kLinkLost && (resume_state_ == MissionState::kRecoveringPose ||
                                            resume_state_ == MissionState::kAligning)) {
    resume_state_ = MissionState::kLocalized;  // recovered from what arrived before the loss
    message_ = "link lost; pose recovered at " + where + " meanwhile: robot stopped";
    return;
  }
  if (state_ == MissionState::kRecoveringPose || state_ == MissionState::kAligning) {
    Enter(MissionState::kLocalized, "pose recovered at " + where + ": holding, ready for a goal");
  }
}

void Mission::OnLost() {
  if (state_ == MissionState::kWaitingForComponents) pose_while_waiting_.reset();
  if (state_ == MissionState::kStoppedFault) {
    if (fault_resume_state_ == MissionState::kLocalized ||
        fault_resume_state_ == MissionState::kExecutingGoal ||
        fault_resume_state_ == MissionState::kGoalReached) {
      fault_resume_state_ = MissionState::kRecoveringPose;
    }
    return;
  }
  if (state_ == MissionState::kLinkLost && resume_state_ != MissionState::kWaitingForComponents) {
    resume_state_ = MissionState::kRecoveringPose;
    return;
  }
  if (state_ == MissionState::kLocalized || state_ == MissionState::kExecutingGoal ||
      state_ == MissionState::kGoalReached) {
    Enter(MissionState::kRecoveringPose, "pose lost: travelling to recover it again");
  }
}

std::optional<std::string> Mission::CanTakeGoal() const {
  switch (state_) {
    case MissionState::kLocalized:
    case MissionState::kGoalReached:
    case MissionState::kExecutingGoal:
      return std::nullopt;
    case MissionState::kStoppedFault:
      return "the robot is stopped while a required process is absent";
    case MissionState::kLinkLost:
      return "the link to the robot is lost";
    default:
      return "the pose is not known yet";
  }
}

void Mission::StartGoal(const GoalPlan& plan, double odometer_in) {
  goal_ = plan;
  goal_odometer_in_ = odometer_in + plan.travel_sign * plan.distance_in;
  Enter(MissionState::kExecutingGoal, "goal '" + plan.goal_id + "': " + plan.description);
}

void Mission::UpdateGoal(double remaining_in, double odometer_in) {
  if (state_ != MissionState::kExecutingGoal) return;
  goal_odometer_in_ = odometer_in + goal_.travel_sign * remaining_in;
  OnOdometer(odometer_in);
}

void Mission::OnOdometer(double odometer_in) {
  if (state_ == MissionState::kExecutingGoal &&
      goal_.travel_sign * (odometer_in - goal_odometer_in_) >= 0.0) {
    Enter(MissionState::kGoalReached, "goal '" + goal_.goal_id + "' reached");
  }
}

MotionRequest Mission::Motion() const {
  switch (state_) {
    case MissionState::kAligning:
      return {true, config_.travel_direction * config_.align_speed_ftps};
    case MissionState::kRecoveringPose:
      return {true, config_.travel_direction * config_.travel_speed_ftps};
    case MissionState::kExecutingGoal:
      return {true, goal_.travel_sign * config_.travel_speed_ftps};
    default:
      return {};
  }
}

std::vector<std::string> Mission::TakeTransitions() {
  std::vector<std::string> out;
  out.swap(transitions_);
  return out;
}

}  // namespace stickrep::executive
