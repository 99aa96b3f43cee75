// The virtual robot's section (virtual_robot/virtual_robot_config.h,
// configs/virtual_robot.yaml), read as the process reads it: the document's `virtual_robot:`
// mapping.
#include "virtual_robot/virtual_robot_config.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const StrictYaml section = fuzz::Root(text).Child("virtual_robot");
    virtual_robot::LoadVirtualRobotConfig(section);
    return true;
  });
  return 0;
}
