// The launch graph (launch/launch_graph.h, deploy/*.launch.yaml): a graph that loads has
// placeholder values for every argument, as stickrep-launch computes them.
#include "launch/launch_graph.h"
#include "yaml_fuzz.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickrep;
  fuzz::RunLoader(data, size, [](const std::string& text) {
    const launch::LaunchGraph g = launch::LaunchGraph::Load(fuzz::Root(text));
    try {
      const auto values = launch::PlaceholderValues(g, "/config", {});
      for (const std::string& a : g.common_args) launch::SubstitutePlaceholders(a, values);
      for (const launch::ProcessSpec& p : g.processes) {
        for (const std::string& a : p.args) launch::SubstitutePlaceholders(a, values);
      }
    } catch (const InputError& e) {
      fuzz::FuzzFail(std::string("a graph that loaded has an argument that does not resolve: ") +
                     e.what());
    }
    return true;
  });
  return 0;
}
