// The map loader (stickrep/map_io.h) on arbitrary text. A map that loads must also survive
// the writer: its YAML loads again and writes the same bytes (the map tools save maps they
// loaded).
#include "stickrep/map_io.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const map::Map m = map::ParseMap(text, fuzz::kFuzzFileName);
    const std::string written = map::WriteMapYaml(m);
    map::Map again;
    try {
      again = map::ParseMap(written, "written.yaml");
    } catch (const InputError& e) {
      fuzz::FuzzFail(std::string("a loaded map, written, does not load again: ") + e.what());
    }
    if (map::WriteMapYaml(again) != written) {
      fuzz::FuzzFail("a loaded map, written and loaded again, writes different text");
    }
    return true;
  });
  return 0;
}
