#pragma once

#include "common/strict_yaml.h"
#include "executive/mission.h"

namespace stickrep::executive {

// The executive process's settings (configs/executive.yaml).
struct ExecutiveConfig {
  MissionConfig mission;
  double command_rate_hz = 10.0;      // motion commands re-sent at this rate
  double heartbeat_timeout_s = 2.0;   // a process silent this long is suspected
  double link_settle_s = 1.0;         // then judged: its host unreachable, or it is dead
  bool exit_when_localized = false;   // end the process once the pose is recovered
};

// Reads the `executive` section; every key required, unknown keys rejected (InputError with
// file, line and key).
ExecutiveConfig LoadExecutiveConfig(const StrictYaml& section);

}  // namespace stickrep::executive
