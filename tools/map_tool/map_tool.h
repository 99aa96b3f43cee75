#pragma once

// The commands of the stickrep-map tool, callable from tests. Each returns the process exit
// code: 0 on success, kExitBadInput (2) for a bad map file (the message, "file:line: key
// 'k': reason", goes to `err`), 1 for other failures such as an unwritable output file.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stickrep/ambiguity.h"

namespace stickrep::map::tool {

int Validate(const std::vector<std::string>& paths, std::ostream& out, std::ostream& err);

// `compare`: print the paper's Engineering Building numbers beside ours; by default on for
// the map named engineering_building_3f.
int Census(const std::string& path, bool json, std::optional<bool> compare, std::ostream& out,
           std::ostream& err);

struct AmbiguityCommand {
  AmbiguityOptions analysis;
  bool json = false;
  std::string png;  // histogram file, empty for none
  int worst = 10;
};
int Ambiguity(const std::string& path, const AmbiguityCommand& command, std::ostream& out,
              std::ostream& err);

int Render(const std::string& path, const std::string& png, std::ostream& out, std::ostream& err);

// Builds the map of a floor plan source (floor_plan.h) into `out_path`.
int Floor(const std::string& source, const std::string& out_path, std::ostream& out,
          std::ostream& err);

// Generates a domain (seed defaults to the one its committed map was made with) into `out_path`.
int Generate(const std::string& domain, std::optional<std::uint64_t> seed,
             const std::string& out_path, std::ostream& out, std::ostream& err);

}  // namespace stickrep::map::tool
