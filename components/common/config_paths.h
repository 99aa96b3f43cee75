#pragma once

#include <string>

namespace stickrep {

// `path` made absolute against the directory of `relative_to_file` (unless already absolute
// or empty).
std::string ResolvePath(const std::string& path, const std::string& relative_to_file);

// Where StickRep's data (configs/, maps/, deploy/, idl/) is: $STICKREP_DATA_DIR if set;
// else, for a program installed under PREFIX/bin, PREFIX/share/stickrep; else (a program
// run from the build tree) the source tree.
std::string DataDir();

// The configs/ directory: $STICKREP_CONFIG_DIR if set, else DataDir()/configs.
std::string DefaultConfigDir();

}  // namespace stickrep
