// `stickrep-console pose` against the localizer's three latched topics (map/stickrep,
// localization/pose, localization/hypotheses), written by this test on the catalogue's QoS
// before the console joins: the console prints the very pose written, draws it, writes the
// PNG, and names what did not come when the localizer is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "localizationPubSubTypes.h"
#include "localizer/map_msg.h"
#include "process_fixture.h"
#include "runtime/endpoint.h"
#include "stickrep/map_io.h"

namespace stickrep::test {
namespace {

constexpr int kDomainId = 53;

class ConsolePoseTest : public ProcessFixture {
 protected:
  ConsolePoseTest() : ProcessFixture(kDomainId) {}

  // Runs stickrep-console on the test's domain to its end (at most 60 s): exit code, output.
  std::pair<int, std::string> Console(const std::vector<std::string>& args) {
    std::vector<std::string> argv{BinPath("stickrep-console"), "--domain",
                                  std::to_string(kDomainId)};
    argv.insert(argv.end(), args.begin(), args.end());
    launch::ChildProcess console("stickrep-console", argv);
    const bool ended = console.WaitExit(60.0);
    if (!ended) console.Signal(SIGKILL);
    console.ReadLines(/*flush_partial=*/true);
    return {ended ? console.exit_code() : -1, console.output()};
  }
};

msgs::PoseHypothesis Hypothesis(const map::Map& m, int edge, bool forward, double offset_in,
                                double heading_rad, double probability) {
  const map::Node& node = m.ring(0).nodes[edge];
  msgs::PoseHypothesis h;
  h.ring_id(m.ring(0).id);
  h.edge_index(edge);
  h.forward(forward);
  h.offset_in(offset_in);
  h.pose().x_in(node.x_in);
  h.pose().y_in(node.y_in);
  h.pose().heading_rad(heading_rad);
  h.probability(probability);
  return h;
}

// The last line of `out` that holds a JSON object.
nlohmann::json LastJson(const std::string& out) {
  std::istringstream lines(out);
  std::string line, last;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.front() == '{') last = line;
  }
  return nlohmann::json::parse(last);
}

void ExpectSame(const nlohmann::json& printed, const msgs::PoseHypothesis& h) {
  EXPECT_EQ(printed.at("ring"), h.ring_id());
  EXPECT_EQ(printed.at("edge"), h.edge_index());
  EXPECT_EQ(printed.at("forward"), h.forward());
  EXPECT_DOUBLE_EQ(printed.at("offset_in").get<double>(), h.offset_in());
  EXPECT_DOUBLE_EQ(printed.at("x_in").get<double>(), h.pose().x_in());
  EXPECT_DOUBLE_EQ(printed.at("y_in").get<double>(), h.pose().y_in());
  EXPECT_DOUBLE_EQ(printed.at("heading_rad").get<double>(), h.pose().heading_rad());
  EXPECT_DOUBLE_EQ(printed.at("probability").get<double>(), h.probability());
}

TEST_F(ConsolePoseTest, NamesWhatDidNotComeWhenTheLocalizerIsMissing) {
  const auto [none_rc, none] = Console({"pose", "--once", "--timeout", "2"});
  EXPECT_EQ(none_rc, 1) << none;
  EXPECT_NE(none.find("no map on map/stickrep and no pose on localization/pose within 2 s: is "
                      "the localizer running?"),
            std::string::npos)
      << none;
  runtime::Writer<msgs::StickRepMapPubSubType> map_writer(participant(), "map/stickrep");
  msgs::StickRepMap map_msg = localizer::ToMsg(map::LoadMap(kSmallMap));
  ASSERT_TRUE(map_writer.Publish(map_msg, 1));
  const auto [pose_rc, no_pose] = Console({"pose", "--once", "--timeout", "5"});
  EXPECT_EQ(pose_rc, 1) << no_pose;
  EXPECT_NE(no_pose.find("no pose on localization/pose within 5 s"), std::string::npos) << no_pose;
  EXPECT_EQ(no_pose.find("no map"), std::string::npos) << no_pose;
}

TEST_F(ConsolePoseTest, PrintsDrawsAndPicturesThePoseThatWasPublished) {
  const map::Map small = map::LoadMap(kSmallMap);
  runtime::Writer<msgs::StickRepMapPubSubType> map_writer(participant(), "map/stickrep");
  runtime::Writer<msgs::LocalizationPosePubSubType> pose_writer(participant(), "localization/pose");
  runtime::Writer<msgs::PoseHypothesesPubSubType> hypotheses_writer(participant(),
                                                                    "localization/hypotheses");
  msgs::StickRepMap map_msg = localizer::ToMsg(small);
  msgs::PoseHypotheses hypotheses;
  hypotheses.hypotheses({Hypothesis(small, 17, true, 12.5, 0.0, 0.87),
                         Hypothesis(small, 40, false, 3.25, M_PI, 0.13)});
  msgs::LocalizationPose pose;
  pose.status(msgs::LOCALIZATION_LOCALIZED);
  pose.candidate_count(2);
  pose.confidence(0.87);
  pose.edges_sensed(14);
  pose.message("localized");
  pose.best(hypotheses.hypotheses()[0]);
  // Latched: written once, before the console joins.
  ASSERT_TRUE(map_writer.Publish(map_msg, 1));
  ASSERT_TRUE(pose_writer.Publish(pose, 1));
  ASSERT_TRUE(hypotheses_writer.Publish(hypotheses, 1));

  const auto [json_rc, json_out] = Console({"pose", "--once", "--json"});
  ASSERT_EQ(json_rc, 0) << json_out;
  const nlohmann::json printed = LastJson(json_out);
  EXPECT_EQ(printed.at("status"), "LOCALIZED");
  EXPECT_DOUBLE_EQ(printed.at("confidence").get<double>(), 0.87);
  EXPECT_EQ(printed.at("candidates"), 2);
  EXPECT_EQ(printed.at("edges_sensed"), 14);
  ExpectSame(printed.at("best"), pose.best());
  ASSERT_EQ(printed.at("hypotheses").size(), 2u) << json_out;
  ExpectSame(printed.at("hypotheses")[1], hypotheses.hypotheses()[1]);

  const auto [text_rc, text] = Console({"pose", "--once", "--cols", "80"});
  ASSERT_EQ(text_rc, 0) << text;
  EXPECT_NE(text.find("LOCALIZED  confidence 0.87  candidates 2  edges sensed 14  best "
                      "wing1_corridor/17 forward +12.5 in"),
            std::string::npos)
      << text;
  // The grid lies between the header and the legend: the arrow east and the runner-up.
  const std::string grid =
      text.substr(text.find('\n') + 1, text.rfind("> best pose") - text.find('\n') - 1);
  EXPECT_NE(grid.find('>'), std::string::npos) << text;
  EXPECT_NE(grid.find('1'), std::string::npos) << text;

  const std::string dir = ::testing::TempDir() + "/console_pose_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  const std::string png = dir + "/pose.png";
  const auto [png_rc, png_out] = Console({"pose", "--png", png});
  ASSERT_EQ(png_rc, 0) << png_out;
  EXPECT_NE(png_out.find("wrote " + png), std::string::npos) << png_out;
  const cv::Mat picture = cv::imread(png);
  EXPECT_FALSE(picture.empty()) << png;
  std::filesystem::remove_all(dir);
  const auto [bad_rc, bad] = Console({"pose", "--png", dir + "/no/such/dir/pose.png"});
  EXPECT_EQ(bad_rc, 2) << bad;
}

}  // namespace
}  // namespace stickrep::test
