#include "locomotion/locomotion_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/config_paths.h"
#include "common/input_error.h"

namespace stickrep::locomotion {
namespace {

using ::testing::HasSubstr;

std::string Shipped() { return ReadYamlText(DefaultConfigDir() + "/locomotion.yaml"); }

LocomotionConfig Load(const std::string& text) {
  return LoadLocomotionConfig(StrictYaml::LoadString(text, "locomotion.yaml").Child("locomotion"),
                              sensing::RobotConfig{});
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(LocomotionConfigTest, ShippedFileLoadsWithTheRobotsRing) {
  const LocomotionConfig c = Load(Shipped());
  EXPECT_EQ(c.device, "virtual");
  EXPECT_DOUBLE_EQ(c.behaviour.follower.max_speed_ftps, sensing::RobotConfig{}.base.max_speed_ftps);
  EXPECT_EQ(c.behaviour.follower.sensor_count, sensing::RobotConfig{}.sonar_ring.count);
  EXPECT_DOUBLE_EQ(c.behaviour.follower.length_scale_in, 36.0);
  EXPECT_DOUBLE_EQ(c.behaviour.envelope_offset_in, 12.0);
}

// The message loading `text` is refused with; a failure (and "") when it loads.
std::string Refusal(const std::string& text, const char* accepted) {
  try {
    Load(text);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted " << accepted;
  return "";
}

TEST(LocomotionConfigTest, UnknownHallwayKeyNamesFileLineAndKey) {
  const std::string why =
      Refusal(Replace(Shipped(), "    turn_rate_radps:", "    turn_speed: 1\n    turn_rate_radps:"),
              "an unknown key");
  EXPECT_THAT(why, HasSubstr("locomotion.yaml:"));
  EXPECT_THAT(why, HasSubstr("locomotion.hallway.turn_speed"));
}

TEST(LocomotionConfigTest, OutOfRangeValueStatesTheRangeAndUnit) {
  const std::string why = Refusal(Replace(Shipped(), "stop_distance_in: 24", "stop_distance_in: 2"),
                                  "a stop distance inside the sonar's minimum range");
  EXPECT_THAT(why, HasSubstr("stop_distance_in"));
  EXPECT_THAT(why, HasSubstr("in"));
}

TEST(LocomotionConfigTest, AStallTravelTheStallSpeedCoversInTheStallTimeIsRefused) {
  // 0.25 ft/s for 1 s is 3 in: a stall bar of 4 in would stop every slow start.
  const std::string why = Refusal(Replace(Shipped(), "stall_travel_in: 0.5", "stall_travel_in: 4"),
                                  "a stall bar the stall speed cannot clear");
  EXPECT_THAT(why, HasSubstr("locomotion.yaml:"));
  EXPECT_THAT(why, HasSubstr("stall_travel_in"));
  EXPECT_THAT(why, HasSubstr("must be less than"));
  const LocomotionConfig c = Load(Shipped());
  EXPECT_DOUBLE_EQ(c.behaviour.stall_speed_ftps, 0.25);
  EXPECT_DOUBLE_EQ(c.behaviour.stall_time_s, 1.0);
  EXPECT_DOUBLE_EQ(c.behaviour.stall_travel_in, 0.5);
}

TEST(LocomotionConfigTest, AViewOffsetReachingTheEnvelopeIsRefused) {
  const std::string why =
      Refusal(Replace(Shipped(), "max_view_offset_in: 0", "max_view_offset_in: 12"),
              "a line on the envelope's edge");
  EXPECT_THAT(why, HasSubstr("locomotion.yaml:"));
  EXPECT_THAT(why, HasSubstr("max_view_offset_in"));
  EXPECT_THAT(why, HasSubstr("must be less than envelope_offset_in"));
  EXPECT_DOUBLE_EQ(Load(Shipped()).behaviour.max_view_offset_in, 0.0);  // on the axis, as shipped
  EXPECT_DOUBLE_EQ(Load(Shipped()).behaviour.view_offset_after_in, 240.0);
}

// The shipped text with `block` (lines indented for a map's block) under the map `name` in an
// on_maps block of its own, in place of the shipped one where there is one.
std::string WithOwnBlock(const std::string& name, const std::string& block) {
  std::string text = Shipped();
  const auto at = text.find("  on_maps:");
  if (at != std::string::npos) text.erase(at);
  return text + "  on_maps:\n    " + name + ":\n" + block;
}

TEST(LocomotionConfigTest, AFloorsOwnBlockReplacesOnlyTheKeysItGives) {
  const LocomotionConfig c =
      Load(WithOwnBlock("hall", "      max_view_offset_in: 10\n      turn_rate_radps: 0.4\n"));
  ASSERT_EQ(c.on_maps.count("hall"), 1U);
  const HallwayBehaviourConfig& own = c.on_maps.at("hall");
  EXPECT_DOUBLE_EQ(own.max_view_offset_in, 10.0);
  EXPECT_DOUBLE_EQ(own.turn_rate_radps, 0.4);
  EXPECT_DOUBLE_EQ(own.follower.length_scale_in, c.behaviour.follower.length_scale_in);
  EXPECT_DOUBLE_EQ(own.view_offset_after_in, c.behaviour.view_offset_after_in);
  EXPECT_EQ(own.follower.sensor_count, c.behaviour.follower.sensor_count);  // the robot's ring
  EXPECT_DOUBLE_EQ(c.behaviour.max_view_offset_in, 0.0);

  const LocomotionConfig on_hall = ForMap(c, "hall");
  EXPECT_DOUBLE_EQ(on_hall.behaviour.max_view_offset_in, 10.0);
  EXPECT_DOUBLE_EQ(on_hall.behaviour.turn_rate_radps, 0.4);
  EXPECT_TRUE(on_hall.on_maps.empty());
  const LocomotionConfig elsewhere = ForMap(c, "another_floor");
  EXPECT_DOUBLE_EQ(elsewhere.behaviour.max_view_offset_in, 0.0);
  EXPECT_DOUBLE_EQ(elsewhere.behaviour.turn_rate_radps, c.behaviour.turn_rate_radps);
}

TEST(LocomotionConfigTest, AFloorsOwnBlockIsCheckedAsTheHallwayBlockIs) {
  std::string why = Refusal(WithOwnBlock("hall", "      turn_speed: 1\n"), "an unknown key");
  EXPECT_THAT(why, HasSubstr("locomotion.yaml:"));
  EXPECT_THAT(why, HasSubstr("locomotion.on_maps.hall.turn_speed"));
  why = Refusal(WithOwnBlock("hall", "      stop_distance_in: 2\n"), "a value out of range");
  EXPECT_THAT(why, HasSubstr("locomotion.on_maps.hall.stop_distance_in"));
  // The checks between keys hold with the defaults the block does not replace.
  why = Refusal(WithOwnBlock("hall", "      envelope_offset_in: 8\n      max_view_offset_in: 10\n"),
                "a line outside the floor's envelope");
  EXPECT_THAT(why, HasSubstr("locomotion.on_maps.hall.max_view_offset_in"));
  EXPECT_THAT(why, HasSubstr("must be less than envelope_offset_in"));
  why = Refusal(WithOwnBlock("hall", "      stall_time_s: 0.1\n"), "a stall bar out of reach");
  EXPECT_THAT(why, HasSubstr("locomotion.on_maps.hall.stall_time_s"));
  EXPECT_THAT(why, HasSubstr("must be less than"));
}

TEST(LocomotionConfigTest, OnlyTheScienceHallRidesTheCameraLineAsShipped) {
  // The line off the axis: the science hall's narrow corridor rides it; the teaching
  // building's declared wrong poses more often on it (configs/locomotion.yaml), and the
  // Engineering Building's 120 in hallways never need it.
  const LocomotionConfig c = Load(Shipped());
  EXPECT_EQ(c.on_maps.size(), 1u);
  EXPECT_DOUBLE_EQ(ForMap(c, "science_hall_2f").behaviour.max_view_offset_in, 10.0);
  EXPECT_EQ(ForMap(c, "science_hall_2f").behaviour.frames_per_door, c.behaviour.frames_per_door);
  for (const char* floor : {"teaching_building_1f", "engineering_building_3f"}) {
    EXPECT_DOUBLE_EQ(ForMap(c, floor).behaviour.max_view_offset_in, 0.0) << floor;
  }
}

TEST(LocomotionConfigTest, SerialDeviceIsRefusedAsNotBuilt) {
  EXPECT_THROW(Load(Replace(Shipped(), "device: virtual", "device: serial")), InputError);
}

}  // namespace
}  // namespace stickrep::locomotion
