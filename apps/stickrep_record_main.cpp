// stickrep-record: the streams of a StickRep domain into one SQLite recording.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "recording/recorder.h"
#include "runtime/process.h"
#include "runtime/system_config.h"

int main(int argc, char** argv) {
  CLI::App app{"Record StickRep topics (serialized CDR, source and reception times) into an "
               "SQLite file; SIGINT/SIGTERM end it with everything committed"};
  stickrep::recording::RecordOptions o;
  o.system_file = stickrep::runtime::DefaultConfigDir() + "/system.yaml";
  app.add_option("-o,--output", o.output, "the recording to create (never overwritten)")->required();
  app.add_option("--topics", o.topics, "record only these topics (default: every topic)")
      ->delimiter(',');
  app.add_option("--system", o.system_file, "deployment settings (domain, QoS, robot and map files)");
  app.add_option("--domain", o.domain_id, "DDS domain id, overriding the system file")
      ->check(CLI::Range(0, 232));
  app.add_option("--duration", o.duration_s, "stop after this many seconds (default: on SIGINT)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-bytes", o.max_bytes,
                 "cap the file's size (a full disk); what was committed before stays")
      ->check(CLI::NonNegativeNumber);
  stickrep::runtime::AddDeploymentOptions(app, o.deployment);
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  stickrep::runtime::InstallSignalHandlers();
  return stickrep::RunTool("stickrep-record", [&] {
    const auto report = stickrep::recording::Record(o, std::cerr);
    stickrep::recording::PrintRecordReport(report, std::cout);
    return report.failure.empty() ? 0 : stickrep::kExitBadInput;
  });
}
