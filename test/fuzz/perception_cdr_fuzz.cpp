// perception.idl as the localizer process reads it.
#include "cdr_fuzz.h"
#include "perceptionPubSubTypes.h"

namespace {

using namespace stickrep;

std::vector<fuzz::CdrType> Types() {
  return {
      {"LandmarkObservation", &fuzz::FeedChecked<msgs::LandmarkObservationPubSubType>,
       [] {
         message::LandmarkObservation o;
         o.header = {3'000'000'000, 5};
         o.door_class = sensing::DoorClass::k36;
         o.width_in = 35.5;
         o.confidence = 0.9;
         o.left_jamb_px = 120.25;
         o.right_jamb_px = 380.5;
         o.range_in = 60.0;
         o.in_envelope = true;
         o.odometry_distance_in = 144.0;
         o.image_stamp_ns = 2'950'000'000;
         return fuzz::Serialize<msgs::LandmarkObservationPubSubType>(convert::ToIdl(o));
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
