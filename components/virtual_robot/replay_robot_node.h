#pragma once

#include <memory>

#include "runtime/process.h"
#include "virtual_robot/virtual_robot_config.h"

namespace stickrep::virtual_robot {

// The virtual robot with `source: replay`: the device streams and sim/ground_truth of a
// recording published again (recording/replay_session.h) instead of simulated ones. Wheel
// commands are ignored and counted (open loop). A recovered pose is judged against the
// replayed ground truth when the recording has it.
std::unique_ptr<runtime::ProcessNode> MakeReplayRobotNode(const VirtualRobotConfig& config);

}  // namespace stickrep::virtual_robot
