#include "console/console.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "console/message_json.h"

namespace stickrep::console {
namespace {

using ::testing::HasSubstr;

TEST(ConsoleTest, SummaryCountsWritersAndReadersAndTakesHistoryFromUserData) {
  std::vector<runtime::DiscoveredEndpoint> eps;
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", true, "best_effort", "volatile", 0, 0,
                 "stickrep;profile=sensor;history=keep_last 5;publish_mode=synchronous"});
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", false, "best_effort", "volatile", 0,
                 0, "stickrep;profile=sensor;history=keep_last 5"});
  eps.push_back({"robot/sonar", "stickrep::msgs::SonarScan", false, "best_effort", "volatile", 0,
                 0, ""});
  const auto topics = runtime::Summarise(eps);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].writers, 1);
  EXPECT_EQ(topics[0].readers, 2);
  EXPECT_EQ(topics[0].history, "keep_last 5");
  EXPECT_EQ(topics[0].profile, "sensor");
}

TEST(ConsoleTest, TableShowsEveryColumn) {
  runtime::TopicSummary t;
  t.topic = "robot/motion/command";
  t.type = "stickrep::msgs::MotionCommand";
  t.writers = 1;
  t.readers = 1;
  t.reliability = "reliable";
  t.durability = "volatile";
  t.history = "keep_last 1";
  t.deadline_s = 0.5;
  std::ostringstream out;
  PrintTopicTable({t}, out);
  EXPECT_THAT(out.str(), HasSubstr("robot/motion/command"));
  EXPECT_THAT(out.str(), HasSubstr("reliable"));
  EXPECT_THAT(out.str(), HasSubstr("keep_last 1"));
  EXPECT_THAT(out.str(), HasSubstr("0.5 s"));
  EXPECT_THAT(out.str(), HasSubstr("1 topics"));
}

TEST(ConsoleTest, UserDataFieldReadsKeyValuePairs) {
  EXPECT_EQ(runtime::UserDataField("stickrep;profile=camera;history=keep_last 1", "history"),
            "keep_last 1");
  EXPECT_EQ(runtime::UserDataField("stickrep;profile=camera", "history"), "");
}

TEST(ConsoleTest, ImageJsonCarriesShapeNotPixels) {
  msgs::Image img;
  img.width_px(4);
  img.height_px(2);
  img.step_bytes(4);
  img.encoding("mono8");
  img.data(std::vector<uint8_t>(8, 7));
  const auto j = ToJson(img);
  EXPECT_EQ(j["data_bytes"], 8);
  EXPECT_FALSE(j.contains("data"));
}

}  // namespace
}  // namespace stickrep::console
