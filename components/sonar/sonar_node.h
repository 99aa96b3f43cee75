#pragma once

#include <memory>
#include <string>

#include "runtime/process.h"

namespace stickrep::sonar {

// The sonar process: reads the ring from its device (the virtual robot's device topic, or
// a serial driver on the real robot), gates every reading (range limits, malformed values,
// the accurate footprint of §4.3) and publishes robot/sonar.
std::unique_ptr<runtime::ProcessNode> MakeSonarNode();

}  // namespace stickrep::sonar
