#pragma once

#include "component/component.h"
#include "messages/messages.h"
#include "sonar/sonar_gate.h"

namespace stickrep::sonar {

// The sonar process's logic: every ring of echoes from the device is gated (range limits,
// malformed values, the accurate footprint of §4.3) and published as robot/sonar, keeping the
// device's time stamp.
class SonarComponent : public component::Component {
 public:
  SonarComponent(component::Context& ctx, SonarGateConfig gate,
                 component::Publisher<message::SonarScan>& scans)
      : ctx_(ctx), gate_(gate), scans_(scans) {}

  void OnEcho(const message::SonarEcho& echo);
  std::string Summary() const override;

 private:
  component::Context& ctx_;
  SonarGateConfig gate_;
  component::Publisher<message::SonarScan>& scans_;
  int64_t last_stamp_ns_ = 0;
  uint64_t scans_served_ = 0, valid_ = 0, outside_footprint_ = 0;
};

}  // namespace stickrep::sonar
