// stickrep-replay: a recording's topics published again, at the recorded pace.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "console/console.h"
#include "recording/replay_session.h"
#include "runtime/process.h"
#include "runtime/system_config.h"

int main(int argc, char** argv) {
  CLI::App app{"Replay a StickRep recording: each topic with its recorded QoS at the recorded "
               "pace; payloads unchanged (header stamps as recorded)"};
  stickrep::recording::ReplayOptions o;
  std::string system_file = stickrep::runtime::DefaultConfigDir() + "/system.yaml";
  int domain_id = -1;
  stickrep::runtime::DeploymentOptions deployment;
  std::vector<std::string> remaps;
  app.add_option("file", o.file, "the recording")->required();
  app.add_option("--rate", o.rate, "recorded seconds per wall second (0.5 to 20)");
  app.add_option("--start", o.start_s, "skip this many seconds of the recording");
  app.add_option("--duration", o.duration_s, "replay this many seconds (default: to the end)");
  app.add_flag("--loop", o.loop, "start again at the end, until stopped");
  app.add_option("--topics", o.topics, "replay only these topics")->delimiter(',');
  app.add_option("--remap", remaps, "publish topic OLD as NEW (OLD:NEW, repeatable)");
  app.add_option("--wait", o.wait_for_readers_s,
                 "seconds to wait for a reader of every topic before starting (default 5)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--system", system_file, "deployment settings (domain, QoS file)");
  app.add_option("--domain", domain_id, "DDS domain id, overriding the system file")
      ->check(CLI::Range(0, 232));
  stickrep::runtime::AddDeploymentOptions(app, deployment);
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  stickrep::runtime::InstallSignalHandlers();
  return stickrep::RunTool("stickrep-replay", [&] {
    o.remap = stickrep::recording::ParseRemaps(remaps);
    stickrep::recording::ValidateReplayOptions(o);
    auto session = stickrep::console::JoinDomain(system_file, domain_id, deployment,
                                                 "stickrep-replay", 1.0);
    stickrep::runtime::Executor executor;
    stickrep::recording::ReplaySession replay(*session.participant, executor, o);
    fmt::print(stderr, "stickrep-replay: {} topics, {:.1f} s of recording at rate {:g}\n",
               replay.replayer().topics().size(), replay.replayer().span_s(), o.rate);
    replay.replayer().Start();
    while (stickrep::runtime::KeepRunning().load() && !replay.replayer().done()) {
      executor.SpinOnce(std::chrono::milliseconds(50));
    }
    replay.replayer().Stop();
    std::cout << replay.Summary() << '\n';
    return 0;
  });
}
