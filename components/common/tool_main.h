#pragma once

#include <functional>
#include <string>

namespace stickrep {

// The body of a tool's main() after its command line is parsed: bad input (InputError)
// is printed as "NAME: file:line: key 'k': reason" and ends with kExitBadInput, any other
// failure is printed and ends with 1; otherwise the body's own exit code.
int RunTool(const std::string& name, const std::function<int()>& body);

}  // namespace stickrep
