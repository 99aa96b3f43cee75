// The locomotion process's section (locomotion/locomotion_config.h, configs/locomotion.yaml),
// read as the process reads it: the document's `locomotion:` mapping, with the shipped robot.
#include "locomotion/locomotion_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  static const sensing::RobotConfig robot =
      sensing::LoadRobotConfigFile(STICKREP_SOURCE_DIR "/configs/robot.yaml");
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const StrictYaml section = fuzz::Root(text).Child("locomotion");
    locomotion::LoadLocomotionConfig(section, robot);
    return true;
  });
  return 0;
}
