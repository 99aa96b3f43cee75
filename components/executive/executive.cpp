#include "executive/executive.h"

namespace stickrep::executive {

Executive::Executive(const map::Map& map, MissionConfig config)
    : mission_(config), planner_(map), travel_direction_(config.travel_direction) {}

void Executive::OnLocalized(const MapPose& pose, const std::string& where) {
  pose_ = pose;
  mission_.OnLocalized(where);
  // The maintained pose re-anchors the goal: odometry alone misjudges the distance round
  // corners, where the base turns in place.
  if (mission_.state() == MissionState::kExecutingGoal) {
    const RouteResult route = planner_.Plan(pose, goal_target_);
    if (route && !route.route->legs.empty()) {
      // Still ahead along the way the robot is being driven, or behind it (overshot).
      const bool ahead = route.route->initial_travel_sign == 0 ||
                         route.route->legs.front().dir == goal_ring_dir_;
      mission_.UpdateGoal(ahead ? route.route->distance_in : -route.route->distance_in,
                          odometer_in_);
    }
  }
}

void Executive::OnLost() {
  pose_.reset();
  mission_.OnLost();
}

void Executive::OnOdometer(double odometer_in) {
  odometer_in_ = odometer_in;
  mission_.OnOdometer(odometer_in);
}

std::optional<std::string> Executive::OnGoal(const std::string& goal_id,
                                             const std::string& target) {
  if (const auto why = mission_.CanTakeGoal()) return why;
  if (!pose_) return "the pose is not known yet";
  const RouteResult route = planner_.Plan(*pose_, target);
  if (!route) return route.error;
  if (!route.route->crossings.empty()) {
    return "the route crosses into another hallway, and turning at a join is not built yet";
  }
  // Keep going means the direction the base travelled while localizing.
  const int sign = route.route->initial_travel_sign >= 0 ? travel_direction_ : -travel_direction_;
  goal_target_ = target;
  goal_ring_dir_ = route.route->legs.empty() ? pose_->dir : route.route->legs.front().dir;
  mission_.StartGoal(
      GoalPlan{goal_id, planner_.Describe(*route.route), sign, route.route->distance_in},
      odometer_in_);
  return std::nullopt;
}

}  // namespace stickrep::executive
