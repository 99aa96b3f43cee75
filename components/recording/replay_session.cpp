#include "recording/replay_session.h"

#include <fmt/format.h>


#include "basePubSubTypes.h"
#include "common/input_error.h"

namespace stickrep::recording {

namespace {
constexpr const char* kWheelTopic = "device/base/wheel_command";
}

std::map<std::string, std::string> ParseRemaps(const std::vector<std::string>& pairs) {
  std::map<std::string, std::string> out;
  for (const std::string& p : pairs) {
    const auto colon = p.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == p.size()) {
      throw InputError("--remap", 0, p, "expected OLD:NEW, e.g. device/sonar/echo:bench/sonar/echo");
    }
    out[p.substr(0, colon)] = p.substr(colon + 1);
  }
  return out;
}

ReplaySession::ReplaySession(runtime::Participant& participant, runtime::Executor& executor,
                             const ReplayOptions& options)
    : options_(options), replayer_(std::make_unique<Replayer>(participant, options)) {
  bool replays_wheels = false;
  for (const auto& [id, topic] : replayer_->topics()) replays_wheels |= topic == kWheelTopic;
  if (!replays_wheels) {
    wheels_ = std::make_unique<runtime::Reader<msgs::WheelCommandPubSubType>>(
        participant, executor, kWheelTopic, [this](const msgs::WheelCommand&) { wheel_commands_++; });
  }
}

std::string ReplaySession::Summary() const {
  return ReplayReportLine(replayer_->report(), options_.rate) +
         fmt::format("; open loop: {} wheel commands ignored (the recording's motion is "
                     "replayed, not the commands)", wheel_commands_);
}

}  // namespace stickrep::recording
