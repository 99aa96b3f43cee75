#pragma once

#include <string>

#include "common/strict_yaml.h"

namespace stickrep::runtime {

// The deployment-wide settings every process shares (configs/system.yaml): the domain,
// the QoS catalogue, an optional Fast DDS XML profile, the robot description and the map.
// Relative paths are resolved against the directory of the file they appear in.
struct SystemConfig {
  std::string file;
  int domain_id = 0;
  std::string qos_file;
  std::string fastdds_profile_xml;   // empty: Fast DDS defaults (UDP multicast + SHM)
  std::string fastdds_profile_name;  // empty: the XML file's default participant profile
  std::string robot_file;
  std::string map_file;
  std::string log_level = "info";

  static SystemConfig Load(const StrictYaml& root);
  static SystemConfig LoadFile(const std::string& path);
};

// `path` made absolute against the directory of `relative_to_file` (unless already absolute).
std::string ResolvePath(const std::string& path, const std::string& relative_to_file);

// The configs/ directory: $STICKREP_CONFIG_DIR if set, else the source tree's configs/.
std::string DefaultConfigDir();

}  // namespace stickrep::runtime
