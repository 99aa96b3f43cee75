#pragma once

// The small test map's Where-am-I setup, shared by the run's and the batch tool's tests.

#include <string>

#include "whereami/whereami_run.h"

namespace stickrep::whereami::testing {

inline const std::string kSmallMap =
    std::string(STICKREP_SOURCE_DIR) + "/test/maps/wing1_corridor.yaml";

// Loaded once: the configs/ defaults on the small map.
inline const RunSetup& SmallMapSetup() {
  static const RunSetup setup = LoadRunSetup("", kSmallMap);
  return setup;
}

}  // namespace stickrep::whereami::testing
