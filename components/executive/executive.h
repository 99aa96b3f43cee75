#pragma once

#include <optional>
#include <string>

#include "executive/mission.h"
#include "executive/route.h"
#include "stickrep/map.h"

namespace stickrep::executive {

// The mission executive's logic without middleware: the mission state machine, the pose it
// last heard of, and goals turned into travel along the rings. The executive process feeds
// it heartbeats, poses, goals, locomotion's state and odometry; the closed-loop run does the
// same in simulated time. Its route planner holds a reference to `map`, which must outlive
// it.
class Executive {
 public:
  Executive(const map::Map& map, MissionConfig config);

  Mission& mission() { return mission_; }
  const Mission& mission() const { return mission_; }

  // A localized pose on the map (ring index, edge, direction, offset into the edge); `where`
  // describes it for the status. Re-anchors a goal in progress.
  void OnLocalized(const MapPose& pose, const std::string& where);
  void OnLost();
  void OnOdometer(double odometer_in);

  // A goal named on mission/goal; the reason it is refused, or nothing when it is taken.
  std::optional<std::string> OnGoal(const std::string& goal_id, const std::string& target);

 private:
  Mission mission_;
  RoutePlanner planner_;
  int travel_direction_ = +1;
  std::optional<MapPose> pose_;
  std::string goal_target_;
  int goal_ring_dir_ = +1;  // the goal is driven to in this ring direction (+1: ring order)
  double odometer_in_ = 0.0;
};

}  // namespace stickrep::executive
