// mission.idl as the executive process and the console read it.
#include "cdr_fuzz.h"
#include "missionPubSubTypes.h"

namespace {

using namespace stickrep;

message::Header Stamp() { return {4'000'000'000, 3}; }

std::vector<fuzz::CdrType> Types() {
  return {
      {"MissionGoal", &fuzz::FeedChecked<msgs::MissionGoalPubSubType>,
       [] {
         return fuzz::Serialize<msgs::MissionGoalPubSubType>(
             convert::ToIdl(message::MissionGoal{Stamp(), "goal-1", "wing1_corridor:12"}));
       }},
      {"MissionStatus", &fuzz::FeedChecked<msgs::MissionStatusPubSubType>,
       [] {
         return fuzz::Serialize<msgs::MissionStatusPubSubType>(convert::ToIdl(
             message::MissionStatus{Stamp(), message::MissionState::kExecutingGoal, "goal-1",
                                    "driving to edge 12"}));
       }},
      {"MissionGoalResult", &fuzz::FeedChecked<msgs::MissionGoalResultPubSubType>,
       [] {
         return fuzz::Serialize<msgs::MissionGoalResultPubSubType>(convert::ToIdl(
             message::MissionGoalResult{Stamp(), "goal-1", "wing1_corridor:12", true, "plan"}));
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
