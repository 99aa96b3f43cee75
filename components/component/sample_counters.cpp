#include "component/sample_counters.h"

namespace stickrep::component {

void SampleCounters::Drop(const std::string& topic, const std::string& reason) {
  dropped_++;
  const uint64_t n = ++by_reason_[topic + ": " + reason];
  last_warning_ = "dropped a sample on " + topic + ": " + reason;
  if (n <= 3 || n % 100 == 0) {
    log_->warn("dropped a sample on {}: {} ({} so far for this reason)", topic, reason, n);
  }
}

}  // namespace stickrep::component
