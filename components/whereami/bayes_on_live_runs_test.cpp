// The Bayes matcher, as the localizer process configures it (configs/localizer.yaml, the
// hallway view of the map, the measured error model), on sensed sequences that live runs
// of the deployed processes produced.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "localizer/localizer_config.h"
#include "recovery/bayes_localizer.h"
#include "stickrep/hallway_view.h"
#include "stickrep/sequence_matcher.h"
#include "whereami/whereami_run.h"

namespace stickrep::whereami {
namespace {

map::SensedEdge Wall(double in, double angle_deg = std::nan("")) {
  map::SensedEdge e;
  e.code = map::kWallCode;
  e.metric_in = in;
  e.angle_deg = angle_deg;
  return e;
}

map::SensedEdge Door(map::DoorClass c) {
  map::SensedEdge e;
  e.code = map::DoorCode(c);
  return e;
}

class BayesOnLiveRunsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setup_ = std::make_unique<RunSetup>(LoadRunSetup(""));
    localizer::LocalizerSettings s = setup_->localizer;
    s.view.camera_fov_deg = setup_->robot.camera.fov_deg;
    view_ = std::make_unique<map::HallwayView>(*setup_->map, s.view);
    config_ = localizer::MakeLocalizerConfig(s, view_->view());
    index_ = std::make_unique<map::MatchIndex>(view_->view());
  }
  // The global index of the view edge that original edge `edge` of ring `ring_id` became.
  int ViewEdge(const std::string& ring_id, int edge) const {
    const int r = setup_->map->FindRing(ring_id);
    return index_->RingOffset(r) + view_->ViewEdge(r, edge);
  }

  std::unique_ptr<RunSetup> setup_;
  std::unique_ptr<map::HallwayView> view_;
  localizer::LocalizerConfig config_;
  std::unique_ptr<map::MatchIndex> index_;
};

// A two-host run of the main job's seed (20261121) with its link cut for 3 s: the robot
// stood before the 36/36 double door at wing1_corridor edge 59 (walking backward) and read
// its first leaf into the wall before it (46 in + 36 in = 82 in) and the second as a 36 in
// door. The same stretch read as a single door fits wing3_corridor edge 39 exactly; the
// filter must not be sure of that place after these five edges.
TEST_F(BayesOnLiveRunsTest, ADoubleDoorsFirstLeafReadIntoTheWallBeforeItIsNotTakenForASingleDoor) {
  recovery::BayesLocalizer bayes(*index_, config_.bayes);
  const std::vector<map::SensedEdge> sensed = {
      Wall(71), Wall(132, 270), Door(map::DoorClass::k36), Wall(82), Door(map::DoorClass::k36)};
  for (const map::SensedEdge& e : sensed) bayes.Add(e);
  EXPECT_LT(bayes.best().probability, config_.bayes.settings.threshold);
  EXPECT_NE(bayes.status(), recovery::RecoveryStatus::kLocalized);
  // The true place keeps some of the belief.
  double truth = 0.0;
  for (int e : {58, 59, 60}) truth += bayes.PoseProbability(ViewEdge("wing1_corridor", e), -1);
  EXPECT_GT(truth, 0.001);
}

}  // namespace
}  // namespace stickrep::whereami
