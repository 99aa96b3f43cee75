#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::camera {

// The camera process: takes frames from its device (the virtual robot's device topic, or
// V4L2 on the real robot), drops frames that are malformed or of the wrong size, and
// publishes robot/camera/image.
std::unique_ptr<runtime::ProcessNode> MakeCameraNode();

}  // namespace stickrep::camera
