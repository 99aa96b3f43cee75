#include "executive/mission.h"

#include <algorithm>
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

void Mission::OnComponentActive(const std::string& name) {
  active_.insert(name);
  if (state_ != MissionState::kWaitingForComponents) return;
  const bool all = std::all_of(config_.required_components.begin(),
                               config_.required_components.end(),
                               [this](const std::string& c) { return active_.count(c) > 0; });
  if (all) {
    align_start_s_ = -1.0;
    in_envelope_since_s_ = -1.0;
    Enter(MissionState::kAligning,
          "every process is active: aligning with the hallway axis and centring");
  }
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
  const bool required = std::find(config_.required_components.begin(),
                                  config_.required_components.end(),
                                  name) != config_.required_components.end();
  if (required && state_ != MissionState::kStoppedFault) {
    Enter(MissionState::kStoppedFault, "process '" + name + "' is gone (" + why + "): robot stopped");
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
      return "the robot is stopped after a fault";
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
