#include "sonar/sonar_component.h"

#include <fmt/format.h>

namespace stickrep::sonar {

void SonarComponent::OnEcho(const message::SonarEcho& echo) {
  if (echo.header.stamp_ns < last_stamp_ns_) {
    ctx_.counters.Drop("device/sonar/echo", "time went backwards");
    return;
  }
  last_stamp_ns_ = echo.header.stamp_ns;
  const GatedScan g = GateScan(echo.range_in, gate_);
  message::SonarScan scan;
  scan.header.stamp_ns = echo.header.stamp_ns;  // the scan describes the echo's instant
  scan.range_in = g.range_in;
  scan.state = g.state;
  scan.valid_count = g.valid_count;
  for (const ReadingState s : g.state) outside_footprint_ += s == ReadingState::kOutsideFootprint;
  valid_ += g.valid_count;
  scans_served_++;
  scans_.Publish(scan);
}

std::string SonarComponent::Summary() const {
  return fmt::format("{} scans gated, {} readings valid, {} outside the footprint", scans_served_,
                     valid_, outside_footprint_);
}

}  // namespace stickrep::sonar
