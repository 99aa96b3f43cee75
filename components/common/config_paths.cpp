#include "common/config_paths.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace stickrep {

std::string ResolvePath(const std::string& path, const std::string& relative_to_file) {
  if (path.empty()) return path;
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  const std::filesystem::path base = std::filesystem::path(relative_to_file).parent_path();
  return (base / p).lexically_normal().string();
}

namespace {

// PREFIX/share/stickrep when this program runs from PREFIX/bin and the data is installed.
std::string InstalledDataDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::canonical("/proc/self/exe", ec);
  if (ec) return "";
  const std::filesystem::path share = exe.parent_path().parent_path() / "share" / "stickrep";
  if (!std::filesystem::is_directory(share / "configs", ec)) return "";
  return share.string();
}

}  // namespace

std::string DataDir() {
  if (const char* env = std::getenv("STICKREP_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  static const std::string installed = InstalledDataDir();
  if (!installed.empty()) return installed;
  return STICKREP_SOURCE_DIR;
}

std::string DefaultConfigDir() {
  if (const char* env = std::getenv("STICKREP_CONFIG_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return DataDir() + "/configs";
}

}  // namespace stickrep
