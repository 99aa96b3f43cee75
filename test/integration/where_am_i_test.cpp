// The whole Where-am-I run, every process on its own, faster than real time: seeded random
// starts recover the true pose, and a kidnapped robot is noticed and recovers again.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/process.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

// The shipped virtual-robot config with some keys replaced.
std::string VirtualRobotConfig(const std::map<std::string, std::string>& overrides) {
  std::ifstream in(ConfigPath("virtual_robot.yaml"));
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    for (const auto& [key, value] : overrides) {
      if (line.rfind("  " + key + ":", 0) == 0) line = "  " + key + ": " + value;
    }
    out << line << "\n";
  }
  return out.str();
}

class WhereAmITest : public ProcessFixture {
 protected:
  explicit WhereAmITest(int domain = 25) : ProcessFixture(domain) {}

  void StartStack(const std::string& virtual_robot_config) {
    Start("stickrep-virtual-robot", {"--config", virtual_robot_config});
    for (const char* exe : {"stickrep-sonar", "stickrep-camera", "stickrep-locomotion",
                            "stickrep-landmark", "stickrep-localizer", "stickrep-executive"}) {
      Start(exe);
    }
  }

  // Whether a localized pose names the true place: same ring, the true edge or its
  // neighbour (the robot may be crossing a node as the pose is published).
  static bool Matches(const msgs::PoseHypothesis& best, const msgs::GroundTruth& truth) {
    const int de = std::abs(static_cast<int>(best.edge_index()) -
                            static_cast<int>(truth.edge_index()));
    return best.ring_id() == truth.ring_id() && de <= 1;
  }
};

TEST_F(WhereAmITest, SeededRandomStartsRecoverTheTruePose) {
  for (const char* seed : {"11", "22", "33"}) {
    SCOPED_TRACE(std::string("seed ") + seed);
    msgs::GroundTruth truth;
    bool have_truth = false;
    std::optional<msgs::LocalizationPose> localized;
    runtime::Reader<msgs::GroundTruthPubSubType> truths(
        participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) {
          truth = g;
          have_truth = true;
        });
    runtime::Reader<msgs::LocalizationPosePubSubType> poses(
        participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
          if (p.status() == msgs::LOCALIZATION_LOCALIZED && !localized) localized = p;
        });
    StartStack(WriteTempFile(std::string("vr_") + seed + ".yaml",
                             VirtualRobotConfig({{"seed", seed}, {"real_time_factor", "4"}})));
    ASSERT_TRUE(SpinUntil([&] { return localized.has_value() && have_truth; }, 180.0))
        << Outputs();
    // Let the newest ground truth arrive (it is published at 20 Hz simulated).
    SpinUntil([] { return false; }, 0.3);
    EXPECT_TRUE(Matches(localized->best(), truth))
        << "localized on ring " << localized->best().ring_id() << " edge "
        << localized->best().edge_index() << ", truth ring " << truth.ring_id() << " edge "
        << truth.edge_index();
    StopAllAndExpectCleanExit();
  }
}

class KidnapTest : public WhereAmITest {
 protected:
  KidnapTest() : WhereAmITest(26) {}
};

TEST_F(KidnapTest, KidnappedRobotIsNoticedAndRecoversTheNewPose) {
  msgs::GroundTruth truth;
  int localized_count = 0;
  bool lost = false;
  std::optional<msgs::LocalizationPose> first, second;
  std::string last_status;
  runtime::Reader<msgs::GroundTruthPubSubType> truths(
      participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) { truth = g; });
  runtime::Reader<msgs::LocalizationPosePubSubType> poses(
      participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
        if (p.status() == msgs::LOCALIZATION_LOST) lost = true;
        if (p.status() != msgs::LOCALIZATION_LOCALIZED) return;
        if (!first) first = p;
        if (lost && !second) second = p;
      });
  runtime::Reader<msgs::MissionStatusPubSubType> status(
      participant(), executor(), "mission/status",
      [&](const msgs::MissionStatus& s) { last_status = s.message(); });
  runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
  StartStack(WriteTempFile("vr_kidnap.yaml",
                           VirtualRobotConfig({{"seed", "44"},
                                               {"real_time_factor", "4"},
                                               {"kidnap_after_localized_s", "2"},
                                               {"kidnap_jump_in", "2500"}})));
  ASSERT_TRUE(SpinUntil([&] { return first.has_value(); }, 180.0)) << Outputs();
  // A goal far along the ring keeps the robot travelling, so the kidnap shows.
  msgs::MissionGoal goal;
  goal.goal_id("far");
  const map::Map map =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  const int ring_edges = map.ring(map.FindRing(first->best().ring_id())).EdgeCount();
  goal.target(first->best().ring_id() + "/" +
              std::to_string((first->best().edge_index() + ring_edges / 2) % ring_edges));
  goals.Publish(goal, runtime::WallClockNowNs());
  ASSERT_TRUE(SpinUntil([&] { return lost; }, 120.0)) << last_status << "\n" << Outputs();
  ASSERT_TRUE(SpinUntil([&] { return second.has_value(); }, 180.0)) << Outputs();
  SpinUntil([] { return false; }, 0.3);
  EXPECT_TRUE(Matches(second->best(), truth))
      << "recovered on ring " << second->best().ring_id() << " edge "
      << second->best().edge_index() << ", truth ring " << truth.ring_id() << " edge "
      << truth.edge_index();
  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
