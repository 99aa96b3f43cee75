// The executive process's section (executive/executive_config.h, configs/executive.yaml),
// read as the process reads it: the document's `executive:` mapping.
#include "executive/executive_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const StrictYaml section = fuzz::Root(text).Child("executive");
    executive::LoadExecutiveConfig(section);
    return true;
  });
  return 0;
}
