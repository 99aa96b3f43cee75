#pragma once

#include <unistd.h>

namespace stickrep::runtime {

// A DDS domain id for an in-process test: derived from the process id so that tests that
// ctest runs in parallel (each in its own process) do not see each other's samples.
// Integration tests that start processes get fixed, distinct ids from CMake instead.
inline int TestDomainId() { return 100 + static_cast<int>(getpid() % 120); }

}  // namespace stickrep::runtime
