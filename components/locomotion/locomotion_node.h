#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::locomotion {

// The locomotion process: turns motion commands into wheel set-points for the base device,
// stops the base when commands stop arriving (the command stream's deadline), and
// publishes dead-reckoned odometry from the encoders.
std::unique_ptr<runtime::ProcessNode> MakeLocomotionNode();

}  // namespace stickrep::locomotion
