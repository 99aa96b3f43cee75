// stickrep-console: the base station's view of a StickRep domain.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <iostream>
#include <optional>

#include "common/input_error.h"
#include "common/tool_main.h"
#include "console/console.h"
#include "runtime/process.h"
#include "runtime/system_config.h"

namespace {
constexpr const char* kWaitHelp =
    "seconds to listen to discovery (default 4: a process announces itself every 3 s)";
}  // namespace

int main(int argc, char** argv) {
  using stickrep::console::ConsoleOptions;
  CLI::App app{"StickRep remote console: list the topics of a domain, echo a topic, show the "
               "robot's pose on the map, send a goal"};
  ConsoleOptions o;
  o.system_file = stickrep::runtime::DefaultConfigDir() + "/system.yaml";
  app.add_option("--system", o.system_file, "deployment settings (domain, QoS file)");
  app.add_option("--domain", o.domain_id, "DDS domain id, overriding the system file")
      ->check(CLI::Range(0, 232));
  stickrep::runtime::AddDeploymentOptions(app, o.deployment);
  app.require_subcommand(1);
  CLI::App* list = app.add_subcommand("list", "every topic on the domain with its QoS");
  list->add_option("--wait", o.wait_s, kWaitHelp)->check(CLI::PositiveNumber);
  list->add_flag("--json", o.json, "JSON instead of a table");
  CLI::App* echo = app.add_subcommand("echo", "print the samples of a topic as JSON lines");
  std::string topic;
  echo->add_option("topic", topic, "e.g. robot/sonar")->required();
  echo->add_option("--count", o.count, "stop after this many samples")->check(CLI::NonNegativeNumber);
  echo->add_option("--timeout", o.timeout_s, "give up after this many seconds")
      ->check(CLI::NonNegativeNumber);
  echo->add_flag_callback("--once", [&o] { o.count = 1; }, "print one sample and exit");
  echo->add_option("--field", o.field, "print only this member (a.b, array indices as numbers)");
  CLI::App* hz = app.add_subcommand("hz", "rate of a topic: mean, and min/max/std of the period");
  CLI::App* delay = app.add_subcommand(
      "delay", "delay of a topic from the writer's source timestamp to reception");
  for (CLI::App* watch : {hz, delay}) {
    watch->add_option("topic", topic, "e.g. robot/sonar")->required();
    watch->add_option("--window", o.window, "samples in the sliding window (default 50)")
        ->check(CLI::Range(2, 100000));
    watch->add_option("--duration", o.duration_s, "stop after this many seconds (default: Ctrl-C)")
        ->check(CLI::NonNegativeNumber);
    watch->add_option("--timeout", o.timeout_s,
                      "give up when no writer or no sample comes within this many seconds "
                      "(default 10)")
        ->check(CLI::NonNegativeNumber);
    watch->add_flag("--json", o.json, "one JSON object per report");
  }
  CLI::App* info = app.add_subcommand("info", "every writer and reader of a topic, with QoS");
  bool verbose = false;
  info->add_option("topic", topic, "e.g. robot/sonar")->required();
  info->add_flag("-v,--verbose", verbose, "add GUIDs and types");
  info->add_option("--wait", o.wait_s, kWaitHelp)->check(CLI::PositiveNumber);
  info->add_flag("--json", o.json, "JSON instead of a table");
  CLI::App* status = app.add_subcommand(
      "status", "one line per process from its heartbeat, refreshing (Ctrl-C ends)");
  status->add_flag_callback("--once", [&o] { o.count = 1; }, "print once and exit");
  status->add_option("--duration", o.duration_s, "stop after this many seconds")
      ->check(CLI::NonNegativeNumber);
  status->add_option("--timeout", o.timeout_s, "exit 1 when no heartbeat comes in this long")
      ->check(CLI::NonNegativeNumber);
  status->add_flag("--json", o.json, "one JSON array per refresh");
  CLI::App* doctor = app.add_subcommand(
      "doctor", "QoS that do not match, type mismatches, readers without writers and writers "
                "without readers, missed deadlines and lost liveliness");
  doctor->add_option("--wait", o.wait_s, kWaitHelp)
      ->check(CLI::PositiveNumber);
  doctor->add_option("--watch", o.duration_s,
                     "seconds to read the topics with a deadline or a liveliness lease "
                     "(default 3)")
      ->check(CLI::PositiveNumber);
  doctor->add_flag("--json", o.json, "JSON instead of lines");
  CLI::App* bw = app.add_subcommand(
      "bw", "samples, rate and serialized bytes/s of every topic that has a writer");
  bw->add_option("--wait", o.wait_s, "seconds to listen to discovery first (default 4)")
      ->check(CLI::PositiveNumber);
  bw->add_option("--duration", o.timeout_s, "seconds to measure (default 10)")
      ->check(CLI::PositiveNumber);
  bw->add_flag("--json", o.json, "one JSON object instead of the table");
  CLI::App* goal = app.add_subcommand(
      "goal", "send a goal on mission/goal and print the executive's answer");
  std::string target, goal_id = "console";
  goal->add_option("target", target, "RING/EDGE, RING/node/N or pattern:NAME")->required();
  goal->add_option("--id", goal_id, "goal id (default 'console')");
  goal->add_flag("--json", o.json, "the executive's answer as JSON");
  goal->add_option("--timeout", o.timeout_s, "give up after this many seconds (default 10)")
      ->check(CLI::NonNegativeNumber);
  CLI::App* pose = app.add_subcommand(
      "pose", "the map with the robot's pose (an arrow) and the other hypotheses (digits by "
              "rank), refreshing every second (Ctrl-C ends)");
  pose->add_flag_callback("--once", [&o] { o.count = 1; },
                          "print one frame once the map and a pose are in, and exit");
  pose->add_option("--duration", o.duration_s, "stop after this many seconds")
      ->check(CLI::NonNegativeNumber);
  pose->add_option("--timeout", o.timeout_s,
                   "exit 1 when the map or a pose does not come in this long (default 10)")
      ->check(CLI::NonNegativeNumber);
  pose->add_option("--cols", o.cols, "width of the map in characters (default 100)")
      ->check(CLI::Range(10, 1000));
  pose->add_flag("--json", o.json,
                 "one JSON object per refresh (status, confidence, best, hypotheses) instead of "
                 "the map");
  pose->add_option("--png", o.png, "write the map to scale with the pose to this PNG and exit");
  if (const std::optional<int> rc = stickrep::ParseCommandLine(app, argc, argv)) return *rc;
  stickrep::runtime::InstallSignalHandlers();
  return stickrep::RunTool("stickrep-console", [&] {
    if (*list) return stickrep::console::ListTopics(o, std::cout);
    if (*bw) return stickrep::console::MeasureBandwidth(o, std::cout);
    if (*goal) return stickrep::console::SendGoal(o, goal_id, target, std::cout);
    if (*info) return stickrep::console::InfoTopic(o, topic, verbose, std::cout);
    if (*status) return stickrep::console::ShowStatus(o, std::cout);
    if (*doctor) return stickrep::console::Doctor(o, std::cout);
    if (*pose) return stickrep::console::ShowPose(o, std::cout);
    if (*hz) return stickrep::console::WatchTopic(o, topic, stickrep::console::TopicStat::kRate, std::cout);
    if (*delay) {
      return stickrep::console::WatchTopic(o, topic, stickrep::console::TopicStat::kDelay, std::cout);
    }
    return stickrep::console::EchoTopic(o, topic, std::cout);
  });
}
