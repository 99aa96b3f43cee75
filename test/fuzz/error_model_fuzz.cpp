// The error model loader (recovery/error_model.h, configs/error_model_*.yaml) on arbitrary
// text. A model that loads must also survive the writer: its YAML loads again.
#include "recovery/error_model.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const recovery::ErrorModel m = recovery::ParseErrorModel(text, fuzz::kFuzzFileName);
    const std::string written = recovery::FormatErrorModelYaml(m, "");
    try {
      recovery::ParseErrorModel(written, "written.yaml");
    } catch (const InputError& e) {
      fuzz::FuzzFail(std::string("a loaded error model, written, does not load again: ") +
                     e.what());
    }
    return true;
  });
  return 0;
}
