// The floor plan compiler's loader (tools/map_tool/floor_plan.h, maps/sources/*.floor.yaml)
// on arbitrary text; a plan that compiles gives a map the writer can write.
#include "map_tool/floor_plan.h"
#include "stickrep/map_io.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const map::Map m = map::ParseFloorPlan(text, fuzz::kFuzzFileName);
    map::WriteMapYaml(m);
    return true;
  });
  return 0;
}
