#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::executive {

// The mission executive: watches every process's heartbeat, drives the robot while the pose
// is being recovered, stops it when a required process dies, and publishes each state and
// transition on mission/status.
std::unique_ptr<runtime::ProcessNode> MakeExecutiveNode();

}  // namespace stickrep::executive
