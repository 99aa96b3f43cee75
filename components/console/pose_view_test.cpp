#include "console/pose_view.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "plot/map_render.h"

namespace stickrep::console {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A hallway outline 990 in x 400 in, walked clockwise from its north-west corner: a 36 in
// door 400 in along the north wall. 100 columns make a cell 10 in wide and 20 in tall.
map::Map Hall() {
  map::Ring ring;
  ring.id = "hall";
  const auto node = [](double angle, double x, double y) {
    map::Node n;
    n.angle_deg = angle;
    n.x_in = x;
    n.y_in = y;
    return n;
  };
  ring.nodes = {node(90, 0, 400),   node(180, 400, 400), node(180, 436, 400),
                node(90, 990, 400), node(90, 990, 0),    node(90, 0, 0)};
  ring.edges = {map::Edge::Wall(400), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(554), map::Edge::Wall(400),
                map::Edge::Wall(990), map::Edge::Wall(400)};
  map::MapInfo info;
  info.name = "hall";
  return map::Map(info, {ring});
}

PoseMark Mark(int edge, double x, double y, double heading, double p) {
  PoseMark m;
  m.ring_id = "hall";
  m.edge = edge;
  m.forward = true;
  m.offset_in = 12.5;
  m.x_in = x;
  m.y_in = y;
  m.heading_rad = heading;
  m.probability = p;
  return m;
}

PoseFrame Localized(double heading) {
  PoseFrame f;
  f.status = "LOCALIZED";
  f.confidence = 0.9;
  f.candidates = 3;
  f.edges_sensed = 17;
  f.best = Mark(2, 500, 200, heading, 0.9);
  f.hypotheses = {*f.best, Mark(4, 200, 100, 0.0, 0.07), Mark(1, 800, 300, M_PI, 0.03)};
  f.age_s = 0.25;
  return f;
}

TEST(PoseViewTest, TheArrowLandsInThePosesCellAndPointsAlongItsHeading) {
  const map::Map hall = Hall();
  const std::vector<std::pair<double, char>> cases = {
      {0.0, '>'}, {M_PI / 2, '^'}, {M_PI, '<'}, {-M_PI / 2, 'v'}, {3 * M_PI / 2, 'v'}};
  for (const auto& [heading, arrow] : cases) {
    const CharGrid grid = DrawPoseGrid(hall, Localized(heading), 100);
    ASSERT_EQ(grid.CellOf(500, 200), std::make_pair(10, 50));
    EXPECT_EQ(grid.rows[10][50], arrow) << "heading " << heading;
  }
}

TEST(PoseViewTest, AHeadingTakesTheNearestOfTheFourArrows) {
  EXPECT_EQ(HeadingArrow(44.0 * M_PI / 180), '>');
  EXPECT_EQ(HeadingArrow(46.0 * M_PI / 180), '^');
  EXPECT_EQ(HeadingArrow(359.0 * M_PI / 180), '>');
  EXPECT_EQ(HeadingArrow(-100.0 * M_PI / 180), 'v');
  EXPECT_EQ(HeadingArrow(200.0 * M_PI / 180), '<');
  EXPECT_EQ(HeadingArrow(4 * M_PI + 0.1), '>');
}

TEST(PoseViewTest, TheOtherHypothesesAreDigitsByRank) {
  const CharGrid grid = DrawPoseGrid(Hall(), Localized(0.0), 100);
  EXPECT_EQ(grid.rows[15][20], '1');  // (200, 100)
  EXPECT_EQ(grid.rows[5][80], '2');   // (800, 300)
  // The best is not drawn again as a digit; no digit beyond the two others.
  std::string all;
  for (const auto& row : grid.rows) all += row;
  EXPECT_EQ(all.find('3'), std::string::npos);
  EXPECT_EQ(std::count(all.begin(), all.end(), '1'), 1);
}

TEST(PoseViewTest, NoMoreThanNineHypothesesAreDrawnAndRankOneIsOnTop) {
  PoseFrame f = Localized(0.0);
  f.hypotheses.resize(1);
  // Rank 2 on rank 1's cell, the others 50 in apart.
  for (int k = 1; k <= 12; ++k) {
    f.hypotheses.push_back(Mark(10 + k, k == 2 ? 150.0 : 100.0 + 50 * k, 100, 0, 0.01));
  }
  const CharGrid grid = DrawPoseGrid(Hall(), f, 100);
  EXPECT_EQ(grid.rows[15][15], '1');
  EXPECT_EQ(grid.rows[15][25], '3');
  EXPECT_EQ(grid.rows[15][55], '9');
  EXPECT_EQ(grid.rows[15][60], ' ');  // the tenth is left out
}

TEST(PoseViewTest, WallsFollowTheirDirectionAndDoorsArePlus) {
  const CharGrid grid = DrawPoseGrid(Hall(), PoseFrame{}, 100);
  ASSERT_EQ(grid.rows.size(), 21u);
  EXPECT_EQ(grid.cols(), 100);
  EXPECT_EQ(grid.rows[0].substr(40, 5), "+++++");  // x 400 to 436
  EXPECT_EQ(grid.rows[0][20], '-');
  EXPECT_EQ(grid.rows[0][60], '-');
  EXPECT_EQ(grid.rows[20][50], '-');
  EXPECT_EQ(grid.rows[10][0], '|');
  EXPECT_EQ(grid.rows[10][99], '|');
  EXPECT_EQ(grid.rows[10][50], ' ');
}

TEST(PoseViewTest, TheGridIsColsWideWithRowsTwiceAsTall) {
  for (int cols : {10, 40, 100, 250}) {
    const CharGrid grid = DrawPoseGrid(Hall(), Localized(0.0), cols);
    EXPECT_EQ(grid.cols(), cols);
    EXPECT_DOUBLE_EQ(grid.cell_in, 990.0 / (cols - 1));
    EXPECT_EQ(static_cast<int>(grid.rows.size()),
              static_cast<int>(std::lround(400.0 / (2 * grid.cell_in))) + 1);
    for (const auto& row : grid.rows) EXPECT_EQ(static_cast<int>(row.size()), cols);
    EXPECT_NE(grid.rows.front().find('+'), std::string::npos) << cols;
    const auto best = grid.CellOf(500, 200);
    EXPECT_EQ(grid.rows[best.first][best.second], '>') << cols;
  }
}

TEST(PoseViewTest, TheTextFrameHasTheHeaderTheMapAndALegend) {
  const std::string text = RenderPoseText(Hall(), Localized(M_PI / 2), 100);
  EXPECT_THAT(text, HasSubstr("LOCALIZED  confidence 0.90  candidates 3  edges sensed 17  best "
                              "hall/2 forward +12.5 in (x 500.0, y 200.0 in, heading 90 deg)  "
                              "pose age 0.2 s\n"));
  EXPECT_THAT(text, HasSubstr("^ best pose  1-9 other hypotheses by rank"));
  EXPECT_THAT(text, HasSubstr("1 column = 10 in, 1 row = 20 in"));
  EXPECT_THAT(text, Not(HasSubstr(" \n")));  // no trailing blanks
  PoseFrame none;
  none.status = "RECOVERING";
  EXPECT_THAT(PoseHeader(none), HasSubstr("RECOVERING  confidence 0.00  candidates 0"));
  EXPECT_THAT(PoseHeader(none), HasSubstr("best -"));
}

TEST(PoseViewTest, TheJsonHasTheStatusTheBestAndEveryHypothesis) {
  const nlohmann::json j = PoseJson(Localized(M_PI));
  EXPECT_EQ(j["status"], "LOCALIZED");
  EXPECT_DOUBLE_EQ(j["confidence"].get<double>(), 0.9);
  EXPECT_EQ(j["candidates"], 3);
  EXPECT_EQ(j["edges_sensed"], 17);
  const auto& best = j["best"];
  EXPECT_EQ(best["ring"], "hall");
  EXPECT_EQ(best["edge"], 2);
  EXPECT_EQ(best["forward"], true);
  EXPECT_DOUBLE_EQ(best["offset_in"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(best["x_in"].get<double>(), 500.0);
  EXPECT_DOUBLE_EQ(best["y_in"].get<double>(), 200.0);
  EXPECT_DOUBLE_EQ(best["heading_rad"].get<double>(), M_PI);
  EXPECT_DOUBLE_EQ(best["probability"].get<double>(), 0.9);
  ASSERT_EQ(j["hypotheses"].size(), 3u);
  EXPECT_EQ(j["hypotheses"][1]["edge"], 4);
  EXPECT_TRUE(PoseJson(PoseFrame{})["best"].is_null());
}

TEST(PoseViewTest, ThePngShowsThePoseWhereItIs) {
  const std::string dir = ::testing::TempDir() + "pose_view_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  const map::Map hall = Hall();
  WritePosePng(hall, Localized(M_PI), dir + "/pose.png");  // heading west
  map::RenderMapPng(hall, dir + "/plain.png");
  const cv::Mat pose = cv::imread(dir + "/pose.png");
  const cv::Mat plain = cv::imread(dir + "/plain.png");
  ASSERT_FALSE(pose.empty());
  ASSERT_EQ(pose.size(), plain.size());
  // map_render.cpp's layout: 40 px margins, a 70 px legend under the map, 1800 px wide.
  const double scale = (1800 - 80) / 990.0;
  const cv::Point at(static_cast<int>(std::lround(40 + 500 * scale)),
                     static_cast<int>(std::lround(pose.rows - 70 - 40 - 200 * scale)));
  const cv::Vec3b white(255, 255, 255);
  EXPECT_EQ(plain.at<cv::Vec3b>(at), white);
  EXPECT_NE(pose.at<cv::Vec3b>(at), white);
  // The arrow's shaft runs west of the dot.
  EXPECT_NE(pose.at<cv::Vec3b>(at + cv::Point(-20, 0)), white);
  EXPECT_EQ(plain.at<cv::Vec3b>(at + cv::Point(-20, 0)), white);
  EXPECT_EQ(pose.at<cv::Vec3b>(at + cv::Point(0, 20)), white);
  std::filesystem::remove_all(dir);
  EXPECT_THROW(WritePosePng(hall, Localized(0.0), dir + "/no/such/dir/pose.png"), std::exception);
}

}  // namespace
}  // namespace stickrep::console
