#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::localizer {

// The localizer process: door observations and odometry in; the pose (RECOVERING /
// LOCALIZED / LOST with the candidate count), the top hypotheses and the map out.
std::unique_ptr<runtime::ProcessNode> MakeLocalizerNode();

}  // namespace stickrep::localizer
