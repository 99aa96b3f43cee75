#include "common/tool_main.h"

#include <cstdio>
#include <exception>

#include "common/input_error.h"

namespace stickrep {

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
