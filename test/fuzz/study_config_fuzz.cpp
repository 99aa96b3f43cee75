// The simulation study's settings (recovery/error_model.h, configs/study.yaml).
#include "recovery/error_model.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    recovery::ParseStudyConfig(text, fuzz::kFuzzFileName);
    return true;
  });
  return 0;
}
