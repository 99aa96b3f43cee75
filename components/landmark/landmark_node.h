#pragma once

#include <memory>

#include "runtime/process.h"

namespace stickrep::landmark {

// The landmark process: pairs each camera frame with the sonar scan taken nearest to it,
// runs the landmark pipeline and publishes classified doors on perception/landmark with the
// odometry distance at which they were seen.
std::unique_ptr<runtime::ProcessNode> MakeLandmarkNode();

}  // namespace stickrep::landmark
