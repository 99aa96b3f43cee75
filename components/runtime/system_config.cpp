#include "runtime/system_config.h"

#include <cstdlib>
#include <filesystem>

namespace stickrep::runtime {

SystemConfig SystemConfig::Load(const StrictYaml& root) {
  SystemConfig c;
  c.file = root.file();
  const StrictYaml s = root.Child("system");
  c.domain_id = s.Get<int>("domain_id", 0, 232);
  c.qos_file = ResolvePath(s.Get<std::string>("qos_file"), c.file);
  c.fastdds_profile_xml = ResolvePath(s.GetOr<std::string>("fastdds_profile_xml", ""), c.file);
  c.fastdds_profile_name = s.GetOr<std::string>("fastdds_profile_name", "");
  c.shared_memory = s.GetOr<bool>("shared_memory", false);
  c.robot_file = ResolvePath(s.Get<std::string>("robot_file"), c.file);
  c.map_file = ResolvePath(s.Get<std::string>("map_file"), c.file);
  c.log_level = s.GetOr<std::string>("log_level", "info");
  if (c.log_level != "trace" && c.log_level != "debug" && c.log_level != "info" &&
      c.log_level != "warn" && c.log_level != "error") {
    s.Fail("log_level", "'" + c.log_level + "' is not one of: trace, debug, info, warn, error");
  }
  if (c.fastdds_profile_xml.empty() && !c.fastdds_profile_name.empty()) {
    s.Fail("fastdds_profile_name", "a profile name needs fastdds_profile_xml");
  }
  s.Finish();
  root.Finish();
  return c;
}

SystemConfig SystemConfig::LoadFile(const std::string& path) {
  return Load(StrictYaml::LoadFile(path));
}

}  // namespace stickrep::runtime
