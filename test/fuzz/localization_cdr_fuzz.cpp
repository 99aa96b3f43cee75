// localization.idl as the executive, the virtual robot and the console read it; the map
// message (map/stickrep) is rebuilt into a map as the console's pose view does
// (localizer/map_msg.h), which refuses an invalid one with std::invalid_argument.
#include <stdexcept>

#include "cdr_fuzz.h"
#include "localizationPubSubTypes.h"
#include "localizer/map_msg.h"
#include "stickrep/map_io.h"

namespace {

using namespace stickrep;

message::PoseHypothesis Hypothesis(int edge, double p) {
  return {"wing1_corridor", edge, true, 12.5, 100.0, -40.0, 1.5708, p};
}

void FeedMap(const std::uint8_t* data, std::size_t size) {
  msgs::StickRepMap m;
  if (!fuzz::Deserialize<msgs::StickRepMapPubSubType>(data, size, &m)) return;
  try {
    localizer::FromMsg(m);
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).empty()) fuzz::FuzzFail("FromMsg refused a map without a reason");
  }
}

std::vector<fuzz::CdrType> Types() {
  return {
      {"LocalizationPose", &fuzz::FeedChecked<msgs::LocalizationPosePubSubType>,
       [] {
         message::LocalizationPose p;
         p.header = {6'000'000'000, 21};
         p.status = message::LocalizationStatus::kLocalized;
         p.candidate_count = 1;
         p.best = Hypothesis(59, 0.997);
         p.confidence = 0.997;
         p.edges_sensed = 5;
         p.message = "pose recovered";
         return fuzz::Serialize<msgs::LocalizationPosePubSubType>(convert::ToIdl(p));
       }},
      {"PoseHypotheses", &fuzz::FeedChecked<msgs::PoseHypothesesPubSubType>,
       [] {
         message::PoseHypotheses h;
         h.header = {6'000'000'000, 22};
         h.hypotheses = {Hypothesis(59, 0.6), Hypothesis(12, 0.3)};
         return fuzz::Serialize<msgs::PoseHypothesesPubSubType>(convert::ToIdl(h));
       }},
      {"StickRepMap", &FeedMap,
       [] {
         return fuzz::Serialize<msgs::StickRepMapPubSubType>(localizer::ToMsg(
             map::LoadMap(STICKREP_SOURCE_DIR "/test/maps/wing1_corridor.yaml")));
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
