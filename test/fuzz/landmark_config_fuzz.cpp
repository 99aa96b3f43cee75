// The landmark process's section (landmark/landmark_config.h, configs/landmark.yaml),
// read as the process reads it: the document's `landmark:` mapping.
#include "landmark/landmark_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const StrictYaml section = fuzz::Root(text).Child("landmark");
    landmark::LoadLandmarkConfig(section);
    return true;
  });
  return 0;
}
