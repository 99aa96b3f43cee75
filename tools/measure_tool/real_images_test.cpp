// The detector on image files: annotations, unreadable files, the frame size, precision.
#include "measure_tool/real_images.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "common/input_error.h"
#include "sensing/robot_config.h"

namespace stickrep::measure {
namespace {

using ::testing::HasSubstr;

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/real_images_test_" + name;
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

// A 640 x 480 hallway-like frame: a light wall and a dark door 100 px wide at columns
// 270-370 (of 640), the size the webcam gives before it is made 512 x 480.
std::string DoorImage(const std::string& name) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(190));
  img(cv::Rect(270, 60, 100, 420)).setTo(60);
  const std::string path = TempPath(name);
  cv::imwrite(path, img);
  return path;
}

TEST(AnnotationsTest, ReadsPairsAndDoorFreeLinesAndComments) {
  const auto a = LoadAnnotations(
      Write("ok.txt", "# jambs in source pixels\nhall1.png: 270 370  # a door\n\nwall.jpg: -\n"));
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(a.at("hall1.png").size(), 1u);
  EXPECT_EQ(a.at("hall1.png")[0].first, 270.0);
  EXPECT_TRUE(a.at("wall.jpg").empty());
}

TEST(AnnotationsTest, ABadLineNamesTheFileAndTheLine) {
  const std::string path = Write("bad.txt", "a.png: 10 20\nb.png: 30 x\n");
  try {
    LoadAnnotations(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(e.file(), path);
    EXPECT_THAT(e.reason(), HasSubstr("'x'"));
  }
  EXPECT_THROW(LoadAnnotations(Write("odd.txt", "a.png: 10 20 30\n")), InputError);
  EXPECT_THROW(LoadAnnotations(Write("order.txt", "a.png: 20 10\n")), InputError);
  EXPECT_THROW(LoadAnnotations(Write("nocolon.txt", "a.png 10 20\n")), InputError);
  EXPECT_THROW(LoadAnnotations(Write("twice.txt", "a.png: -\na.png: -\n")), InputError);
  EXPECT_THROW(LoadAnnotations(TempPath("missing.txt")), InputError);
}

TEST(LoadFrameTest, AnyImageBecomes512By480GreyAndAnUnreadableFileIsBadInput) {
  int width = 0;
  const cv::Mat frame = LoadFrame(DoorImage("door.png"), &width);
  EXPECT_EQ(width, 640);
  EXPECT_EQ(frame.cols, 512);
  EXPECT_EQ(frame.rows, 480);
  EXPECT_EQ(frame.type(), CV_8UC1);
  EXPECT_THROW(LoadFrame(Write("not_an_image.png", "hello")), InputError);
}

TEST(RunOnImagesTest, FindsTheAnnotatedDoorFirst) {
  ImageRunConfig config;
  config.files = {DoorImage("door_run.png")};
  config.annotations = Write("door_run.txt", "real_images_test_door_run.png: 270 370\n");
  config.range_in = 120.0;
  const std::string report = RunOnImages(config, sensing::RobotConfig{});
  EXPECT_THAT(report, HasSubstr("annotated door: pair 0"));
  EXPECT_THAT(report, HasSubstr("precision of the first pair 100.0 %"));
}

}  // namespace
}  // namespace stickrep::measure
