#include "camera/frame_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace stickrep::camera {
namespace {

using ::testing::HasSubstr;
using ::testing::Optional;

FrameShape Good() { return FrameShape{512, 480, 512, "mono8", 512u * 480u}; }

TEST(FrameCheckTest, WellFormedFrameOfTheCameraSizePasses) {
  EXPECT_EQ(CheckFrame(Good(), 512, 480), std::nullopt);
}

TEST(FrameCheckTest, ZeroSizedFrameIsRejected) {
  FrameShape f = Good();
  f.height_px = 0;
  EXPECT_THAT(CheckFrame(f, 0, 0), Optional(HasSubstr("empty frame")));
}

TEST(FrameCheckTest, DataLengthNotMatchingHeightTimesStepIsRejected) {
  FrameShape f = Good();
  f.data_bytes -= 1;
  EXPECT_THAT(CheckFrame(f, 0, 0), Optional(HasSubstr("need 245760")));
}

TEST(FrameCheckTest, UnknownEncodingIsRejected) {
  FrameShape f = Good();
  f.encoding = "rgb8";
  EXPECT_THAT(CheckFrame(f, 0, 0), Optional(HasSubstr("unknown encoding 'rgb8'")));
}

TEST(FrameCheckTest, StepShorterThanARowIsRejected) {
  FrameShape f = Good();
  f.step_bytes = 100;
  f.data_bytes = 100u * 480u;
  EXPECT_THAT(CheckFrame(f, 0, 0), Optional(HasSubstr("shorter than")));
}

TEST(FrameCheckTest, FrameOfAnotherSizeThanTheCameraIsRejected) {
  EXPECT_THAT(CheckFrame(Good(), 640, 480), Optional(HasSubstr("the camera is 640 x 480")));
}

}  // namespace
}  // namespace stickrep::camera
