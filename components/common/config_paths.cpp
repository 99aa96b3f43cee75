#include "common/config_paths.h"

#include <cstdlib>
#include <filesystem>

namespace stickrep {

std::string ResolvePath(const std::string& path, const std::string& relative_to_file) {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  const std::filesystem::path base = std::filesystem::path(relative_to_file).parent_path();
  return (base / p).lexically_normal().string();
}

std::string DefaultConfigDir() {
  if (const char* env = std::getenv("STICKREP_CONFIG_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return std::string(STICKREP_SOURCE_DIR) + "/configs";
}

}  // namespace stickrep
