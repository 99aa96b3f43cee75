// base.idl as the virtual robot, locomotion, landmark, localizer and executive processes
// read it.
#include "basePubSubTypes.h"
#include "cdr_fuzz.h"

namespace {

using namespace stickrep;

message::Header Stamp() { return {2'000'000'000, 11}; }

std::vector<fuzz::CdrType> Types() {
  return {
      {"WheelCommand", &fuzz::FeedChecked<msgs::WheelCommandPubSubType>,
       [] {
         return fuzz::Serialize<msgs::WheelCommandPubSubType>(
             convert::ToIdl(message::WheelCommand{Stamp(), 1.25, 1.5}));
       }},
      {"EncoderReading", &fuzz::FeedChecked<msgs::EncoderReadingPubSubType>,
       [] {
         return fuzz::Serialize<msgs::EncoderReadingPubSubType>(
             convert::ToIdl(message::EncoderReading{Stamp(), 120.5, 119.75}));
       }},
      {"MotionCommand", &fuzz::FeedChecked<msgs::MotionCommandPubSubType>,
       [] {
         return fuzz::Serialize<msgs::MotionCommandPubSubType>(convert::ToIdl(
             message::MotionCommand{Stamp(), message::MotionMode::kFollowHallway, 2.6, 0.0}));
       }},
      {"MotionState", &fuzz::FeedChecked<msgs::MotionStatePubSubType>,
       [] {
         message::MotionState s;
         s.header = Stamp();
         s.mode = message::MotionMode::kFollowHallway;
         s.state = message::LocomotionState::kFollowing;
         s.offset_valid = s.heading_valid = s.in_envelope = true;
         s.lateral_offset_in = 1.5;
         s.commanded_speed_ftps = s.linear_speed_ftps = 2.6;
         s.message = "following the hallway";
         return fuzz::Serialize<msgs::MotionStatePubSubType>(convert::ToIdl(s));
       }},
      {"Odometry", &fuzz::FeedChecked<msgs::OdometryPubSubType>,
       [] {
         return fuzz::Serialize<msgs::OdometryPubSubType>(convert::ToIdl(
             message::Odometry{Stamp(), 10.0, -2.0, 0.5, 272.5, 2.6, 0.01}));
       }},
  };
}

}  // namespace

STICKREP_CDR_FUZZ_TARGET(Types)
