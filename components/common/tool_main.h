#pragma once

#include <functional>
#include <optional>
#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace stickrep {

// Parses a program's command line; every program parses through this. Empty: go on.
// Otherwise the program's exit code: 0 after --help (the help printed), kExitBadInput for a
// bad command line (an unknown option, a missing value or required option, a value out of
// range), with CLI11's message and "Run with --help" on stderr.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv);

// The body of a tool's main() after its command line is parsed: bad input (InputError)
// is printed as "NAME: file:line: key 'k': reason" and ends with kExitBadInput, any other
// failure is printed and ends with 1; otherwise the body's own exit code.
int RunTool(const std::string& name, const std::function<int()>& body);

}  // namespace stickrep
