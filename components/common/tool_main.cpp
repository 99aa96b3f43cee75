#include "common/tool_main.h"

#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "common/input_error.h"

namespace stickrep {

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's own codes (106 for an unknown option, 114 for a missing value, ...) are not
    // ours: help is 0, every mistake kExitBadInput.
    return app.exit(e) == 0 ? 0 : kExitBadInput;
  }
  return std::nullopt;
}

int RunTool(const std::string& name, const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return 1;
  }
}

}  // namespace stickrep
