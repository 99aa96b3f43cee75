#pragma once

#include <string>

namespace stickrep {

// `path` made absolute against the directory of `relative_to_file` (unless already absolute
// or empty).
std::string ResolvePath(const std::string& path, const std::string& relative_to_file);

// The configs/ directory: $STICKREP_CONFIG_DIR if set, else the source tree's configs/.
std::string DefaultConfigDir();

}  // namespace stickrep
