#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "basePubSubTypes.h"
#include "recording/replayer.h"
#include "runtime/endpoint.h"

namespace stickrep::recording {

// "old:new" pairs of --remap; throws InputError for one without a colon or with an empty side.
std::map<std::string, std::string> ParseRemaps(const std::vector<std::string>& pairs);

// A replay as the robot's stand-in: the Replayer, plus the wheel commands the stack sends
// meanwhile, which a recording cannot obey — they are ignored and counted (open loop).
// stickrep-replay and the virtual robot's `source: replay` both run one.
class ReplaySession {
 public:
  ReplaySession(runtime::Participant& participant, runtime::Executor& executor,
                const ReplayOptions& options);

  Replayer& replayer() { return *replayer_; }
  std::uint64_t wheel_commands_ignored() const { return wheel_commands_; }
  // The replay report and the open-loop count, in one line.
  std::string Summary() const;

 private:
  ReplayOptions options_;
  std::unique_ptr<Replayer> replayer_;
  std::unique_ptr<runtime::Reader<msgs::WheelCommandPubSubType>> wheels_;
  std::uint64_t wheel_commands_ = 0;
};

}  // namespace stickrep::recording
