#include "sensing/robot_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace stickrep::sensing {
namespace {

using ::testing::HasSubstr;

const char* kGood = R"(robot:
  sonar_ring:
    count: 24
    spacing_deg: 15
    head_radius_in: 7.5
    cone_deg: 23.6
    min_range_in: 12
    max_range_in: 420
    footprint_deg: 15
  camera:
    fov_deg: 55.817
    image_width_px: 512
    image_height_px: 480
    focal_length_mm: 6
    pixel_pitch_mm: 0.012414
    coaxial_sensor: 0
    offset_forward_in: 0
    radial_distortion_k1: 0.1
    frame_rate_hz: 5
  base:
    max_speed_ftps: 2.6
    wheel_base_in: 14
)";

InputError LoadError(const std::string& text) {
  try {
    LoadRobotConfig(StrictYaml::LoadString(text, "robot.yaml"));
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "", "");
}

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

TEST(RobotConfigTest, ShippedFileLoads) {
  const RobotConfig c = LoadRobotConfigFile(DefaultRobotConfigPath());
  EXPECT_EQ(c.sonar_ring.count, 24);
  EXPECT_DOUBLE_EQ(c.camera.fov_deg, 55.817);
  EXPECT_DOUBLE_EQ(c.base.max_speed_ftps, 2.6);
}

TEST(RobotConfigTest, ReadsEveryValue) {
  const RobotConfig c = LoadRobotConfig(StrictYaml::LoadString(kGood, "robot.yaml"));
  EXPECT_DOUBLE_EQ(c.sonar_ring.cone_deg, 23.6);
  EXPECT_EQ(c.camera.image_width_px, 512);
  EXPECT_DOUBLE_EQ(c.base.wheel_base_in, 14.0);
}

TEST(RobotConfigTest, UnknownKeyNamesLineAndKey) {
  const InputError e =
      LoadError(Replace(kGood, "    cone_deg: 23.6\n", "    cone_deg: 23.6\n    cone: 3\n"));
  EXPECT_EQ(e.line(), 7);
  EXPECT_THAT(e.key(), HasSubstr("robot.sonar_ring.cone"));
  EXPECT_THAT(e.reason(), HasSubstr("unknown key"));
}

TEST(RobotConfigTest, MissingKeyIsRejected) {
  const InputError e = LoadError(Replace(kGood, "    focal_length_mm: 6\n", ""));
  EXPECT_THAT(e.key(), HasSubstr("focal_length_mm"));
  EXPECT_THAT(e.reason(), HasSubstr("missing"));
  EXPECT_GT(e.line(), 0);
}

TEST(RobotConfigTest, OutOfRangeValueNamesUnitAndLine) {
  const InputError e = LoadError(Replace(kGood, "max_speed_ftps: 2.6", "max_speed_ftps: -1"));
  EXPECT_EQ(e.line(), 21);
  EXPECT_THAT(e.reason(), HasSubstr("ft/s"));
}

TEST(RobotConfigTest, PitchInconsistentWithFieldOfViewIsRejected) {
  const InputError e =
      LoadError(Replace(kGood, "pixel_pitch_mm: 0.012414", "pixel_pitch_mm: 0.02"));
  EXPECT_THAT(e.key(), HasSubstr("pixel_pitch_mm"));
  EXPECT_THAT(e.reason(), HasSubstr("field of view"));
}

TEST(RobotConfigTest, RingThatDoesNotCloseIsRejected) {
  const InputError e = LoadError(Replace(kGood, "spacing_deg: 15", "spacing_deg: 14"));
  EXPECT_THAT(e.key(), HasSubstr("spacing_deg"));
}

}  // namespace
}  // namespace stickrep::sensing
