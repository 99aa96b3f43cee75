// system.idl: the component status every process and the console read, and the ground
// truth the replayed robot reads (deserialized only: it has no FromIdl).
#include "cdr_fuzz.h"
#include "systemPubSubTypes.h"

namespace {

using namespace stickrep;

void FeedGroundTruth(const std::uint8_t* data, std::size_t size) {
  msgs::GroundTruth m;
  fuzz::Deserialize<msgs::GroundTruthPubSubType>(data, size, &m);
}

std::vector<fuzz::CdrType> Types() {
  return {
      {"ComponentStatus", &fuzz::FeedChecked<msgs::ComponentStatusPubSubType>,
       [] {
         message::ComponentStatus s;
         s.header = {5'000'000'000, 9};
         s.component_name = "localizer";
         s.state = message::ComponentState::kActive;
         s.samples_in = 484;
         s.samples_out = 70;
         s.message = "recovering";
         s.host = "robot";
         return fuzz::Serialize<msgs::ComponentStatusPubSubType>(convert::ToIdl(s));
       }},
      {"GroundTruth", &FeedGroundTruth,
       [] {
         msgs::GroundTruth t;
         t.ring_id("wing1_corridor");
         t.edge_index(59);
         t.offset_in(60.8);
         t.distance_in(272.6);
         t.forward_in_ring(true);
         return fuzz::Serialize<msgs::GroundTruthPubSubType>(t);
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
