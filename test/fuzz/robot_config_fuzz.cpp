// The robot's geometry (sensing/robot_config.h, configs/robot.yaml).
#include "sensing/robot_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    sensing::LoadRobotConfig(fuzz::Root(text));
    return true;
  });
  return 0;
}
