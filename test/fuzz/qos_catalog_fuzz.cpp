// The QoS catalog (runtime/qos_catalog.h, configs/qos.yaml): every stream it names must
// resolve to a profile.
#include "runtime/qos_catalog.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    runtime::QosCatalog::Load(fuzz::Root(text));
    return true;
  });
  return 0;
}
