// stickrep-bag: look inside a StickRep recording.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "recording/bag_inspect.h"

int main(int argc, char** argv) {
  CLI::App app{"Inspect a StickRep recording: info, export, check"};
  app.require_subcommand(1);
  std::string file, topic;
  bool json = false;
  CLI::App* info = app.add_subcommand("info", "topics, types, counts, rates, duration, size");
  info->add_option("file", file, "the recording")->required();
  info->add_flag("--json", json, "JSON instead of a table");
  CLI::App* exporter = app.add_subcommand("export", "a topic's samples as JSON lines");
  exporter->add_option("file", file, "the recording")->required();
  exporter->add_option("--topic", topic, "the topic to export")->required();
  CLI::App* check = app.add_subcommand("check", "every payload deserializes to its type");
  check->add_option("file", file, "the recording")->required();
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  return stickrep::RunTool("stickrep-bag", [&] {
    using namespace stickrep::recording;
    if (*info) {
      const BagInfo i = InspectBag(file);
      json ? PrintBagInfoJson(i, std::cout) : PrintBagInfo(i, std::cout);
      return 0;
    }
    if (*exporter) return ExportTopic(file, topic, std::cout, std::cerr) == 0 ? 0 : stickrep::kExitBadInput;
    return CheckBag(file, std::cout) == 0 ? 0 : stickrep::kExitBadInput;
  });
}
