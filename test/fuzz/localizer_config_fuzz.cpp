// The localizer process's section (localizer/localizer_config.h, configs/localizer.yaml),
// read as the process reads it: the document's `localizer:` mapping.
#include "localizer/localizer_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const StrictYaml section = fuzz::Root(text).Child("localizer");
    localizer::LoadLocalizerSettings(section);
    return true;
  });
  return 0;
}
