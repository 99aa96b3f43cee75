#include "executive/executive_config.h"

namespace stickrep::executive {

ExecutiveConfig LoadExecutiveConfig(const StrictYaml& c) {
  ExecutiveConfig out;
  MissionConfig& mission = out.mission;
  for (const StrictYaml& name : c.Sequence("required_components")) {
    mission.required_components.push_back(name.As<std::string>());
  }
  mission.travel_speed_ftps = c.Get<double>("travel_speed_ftps", 0.1, 2.6, "ft/s");
  mission.travel_direction = c.Get<int>("travel_direction", -1, 1);
  if (mission.travel_direction == 0) c.Fail("travel_direction", "must be +1 or -1");
  mission.align_speed_ftps = c.Get<double>("align_speed_ftps", 0.1, 2.6, "ft/s");
  mission.aligned_hold_s = c.Get<double>("aligned_hold_s", 0.0, 60.0, "s");
  mission.align_timeout_s = c.Get<double>("align_timeout_s", 1.0, 600.0, "s");
  out.command_rate_hz = c.Get<double>("command_rate_hz", 2.0, 100.0, "Hz");
  out.heartbeat_timeout_s = c.Get<double>("heartbeat_timeout_s", 0.5, 60.0, "s");
  out.link_settle_s = c.Get<double>("link_settle_s", 0.6, 30.0, "s");
  out.exit_when_localized = c.Get<bool>("exit_when_localized");
  c.Finish();
  return out;
}

}  // namespace stickrep::executive
