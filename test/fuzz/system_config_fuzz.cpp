// The system file (runtime/system_config.h, configs/system.yaml).
#include "runtime/system_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    runtime::SystemConfig::Load(fuzz::Root(text));
    return true;
  });
  return 0;
}
