#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::virtual_robot {

// The virtual robot: stands in for the hardware and the world. It takes wheel commands on
// the base's device topic and serves encoder readings, sonar echoes and camera frames
// simulated in a hallway built from the map, plus sim/ground_truth.
std::unique_ptr<runtime::ProcessNode> MakeVirtualRobotNode();

}  // namespace stickrep::virtual_robot
