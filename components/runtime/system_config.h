#pragma once

#include <string>

#include "common/config_paths.h"
#include "common/strict_yaml.h"

namespace stickrep::runtime {

// The deployment-wide settings every process shares (configs/system.yaml): the domain,
// the QoS catalogue, an optional Fast DDS XML profile, the robot description and the map.
// Relative paths are resolved against the directory of the file they appear in.
struct SystemConfig {
  std::string file;
  int domain_id = 0;
  std::string qos_file;
  std::string fastdds_profile_xml;   // empty: Fast DDS defaults, UDP only unless shared_memory
  std::string fastdds_profile_name;  // empty: the XML file's default participant profile
  // Fast DDS's shared-memory transport beside UDP (a profile that names its own transports
  // keeps them). Off by default: see runtime::ParticipantConfig::shared_memory.
  bool shared_memory = false;
  std::string robot_file;
  std::string map_file;
  std::string log_level = "info";

  static SystemConfig Load(const StrictYaml& root);
  static SystemConfig LoadFile(const std::string& path);
};

using stickrep::DefaultConfigDir;
using stickrep::ResolvePath;

}  // namespace stickrep::runtime
