// The whole Where-am-I run, every process on its own and faster than real time, on a small
// map (test/maps/wing1_corridor.yaml, one corridor of the Engineering Building): seeded
// random starts recover the true pose, and a kidnapped robot is noticed and recovers again.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "common/quantile.h"
#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/process.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

// Simulated seconds per wall second. The runs take 20-60 s simulated. 3x leaves the machine
// room for the other tests that ctest -j2 runs beside this one: starved of CPU, the landmark
// process misses frames, doors go unseen, and the matcher is given a sequence with more
// missed doors than its model expects.
constexpr const char* kRealTimeFactor = "3";

class WhereAmITest : public ProcessFixture {
 protected:
  explicit WhereAmITest(int domain = 25) : ProcessFixture(domain) {}

  void StartStack(const std::string& name, const std::map<std::string, std::string>& robot) {
    StartStackOn(SmallMapSystem(name + "_system.yaml"), name, robot);
  }

  void StartStackOn(const std::string& system, const std::string& name,
                    const std::map<std::string, std::string>& robot) {
    std::map<std::string, std::string> keys = {{"real_time_factor", kRealTimeFactor},
                                               {"summary_png", "\"\""}};
    for (const auto& [key, value] : robot) keys[key] = value;  // the test's own keys win
    Start("stickrep-virtual-robot",
          {"--system", system, "--config",
           WriteTempFile(name + "_vr.yaml", ConfigWith("virtual_robot.yaml", keys))});
    for (const char* exe : {"stickrep-sonar", "stickrep-camera", "stickrep-locomotion",
                            "stickrep-landmark", "stickrep-localizer", "stickrep-executive"}) {
      Start(exe, {"--system", system});
    }
  }

  // A goal a third of the small map's ring ahead of `from` in its direction of travel, as
  // `stickrep-whereami` sets: the shorter route to it keeps that direction. (Half the ring
  // ahead is as far either way, and the route may turn the travel round: kidnapped as it
  // turned at the next corner, seed 113 then circled the ring sensing almost no edges;
  // docs/whereami.md, "Noticed, left alone".)
  static std::string TargetAhead(const msgs::PoseHypothesis& from, int ring_edges = kSmallMapEdges,
                                 int ahead_edges = -1) {
    if (ahead_edges < 0) ahead_edges = ring_edges / 3;
    const int edge = static_cast<int>(from.edge_index());
    const int ahead = from.forward() ? edge + ahead_edges : edge - ahead_edges + ring_edges;
    return from.ring_id() + "/" + std::to_string(ahead % ring_edges);
  }

  // Publishes `goal` until the executive takes it: its status (`last_status`, kept by the
  // test's reader; cleared here before each try) names the goal and does not refuse it. The
  // pose and the goal travel on different topics, so a goal sent the moment the test sees the
  // first pose can reach the executive before that pose does, and is refused ("the pose is
  // not known yet"); it is sent again. A goal the executive refuses for good is not taken
  // within `timeout_s` either.
  bool SendGoalUntilTaken(runtime::Writer<msgs::MissionGoalPubSubType>& goals,
                          msgs::MissionGoal& goal, std::string& last_status,
                          double timeout_s) {
    const std::string named = "goal '" + goal.goal_id() + "'";
    const auto answered = [&] { return last_status.find(named) != std::string::npos; };
    return SpinUntil(
        [&] {
          last_status.clear();
          goals.Publish(goal, runtime::WallClockNowNs());
          return SpinUntil(answered, 0.5) && last_status.find("refused") == std::string::npos;
        },
        timeout_s);
  }

  // Keeps the robot travelling until `done`: a goal `ahead_edges` ahead of the pose held
  // (`latest`, kept by the test's reader) and a new one each time one is reached (the robot
  // stops at a goal, and on a wrong pose that may be anywhere). Whether `done` held within
  // `timeout_s`.
  bool TravelOnUntil(const std::function<bool()>& done,
                     runtime::Writer<msgs::MissionGoalPubSubType>& goals,
                     const std::optional<msgs::LocalizationPose>& latest, std::string& last_status,
                     int ring_edges, int ahead_edges, double timeout_s) {
    int sent = 0;
    const auto send = [&] {
      msgs::MissionGoal goal;
      goal.goal_id("ahead" + std::to_string(++sent));
      goal.target(TargetAhead(latest->best(), ring_edges, ahead_edges));
      EXPECT_TRUE(SendGoalUntilTaken(goals, goal, last_status, 20.0))
          << "goal " << goal.goal_id() << " (" << goal.target() << ") not taken: " << last_status;
    };
    send();
    return SpinUntil(
        [&] {
          if (!done() && last_status.find("reached") != std::string::npos) send();
          return done();
        },
        timeout_s);
  }

  // Whether a localized pose names the true place: same ring and direction of travel, the
  // true edge or its neighbour (the robot may be crossing a node as the pose is published).
  static bool Matches(const msgs::PoseHypothesis& best, const msgs::GroundTruth& truth,
                      bool truth_forward, int ring_edges = kSmallMapEdges) {
    const int de =
        std::abs(static_cast<int>(best.edge_index()) - static_cast<int>(truth.edge_index()));
    return best.ring_id() == truth.ring_id() && best.forward() == truth_forward &&
           (de <= 1 || de == ring_edges - 1);
  }
};

TEST_F(WhereAmITest, SeededRandomStartsRecoverTheTruePose) {
  for (const char* seed : {"1", "2", "3"}) {
    SCOPED_TRACE(std::string("seed ") + seed);
    std::optional<msgs::GroundTruth> truth;
    std::optional<msgs::LocalizationPose> localized;
    std::vector<std::string> mission;
    runtime::Reader<msgs::GroundTruthPubSubType> truths(
        participant(), executor(), "sim/ground_truth",
        [&](const msgs::GroundTruth& g) { truth = g; });
    runtime::Reader<msgs::LocalizationPosePubSubType> poses(
        participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
          if (p.status() == msgs::LOCALIZATION_LOCALIZED && !localized) localized = p;
        });
    runtime::Reader<msgs::MissionStatusPubSubType> status(
        participant(), executor(), "mission/status", [&](const msgs::MissionStatus& s) {
          if (mission.empty() || mission.back() != s.message()) mission.push_back(s.message());
        });
    StartStack(std::string("seed") + seed, {{"seed", seed}});
    ASSERT_TRUE(SpinUntil([&] { return localized.has_value() && truth.has_value(); }, 150.0))
        << Outputs();
    // The truth of the moment the pose was published (ground truth comes at 20 Hz simulated).
    const msgs::GroundTruth at_pose = *truth;
    EXPECT_TRUE(Matches(localized->best(), at_pose, at_pose.forward_in_ring()))
        << "localized on ring " << localized->best().ring_id() << " edge "
        << localized->best().edge_index() << (localized->best().forward() ? " fwd" : " back")
        << ", truth ring " << at_pose.ring_id() << " edge " << at_pose.edge_index()
        << (at_pose.forward_in_ring() ? " fwd" : " back") << "\n"
        << Outputs();
    EXPECT_EQ(at_pose.collisions(), 0u);
    StopAllAndExpectCleanExit();
    // The mission aligned and centred before it travelled to recover the pose: the
    // executive's log has every transition. (mission/status is latched keep-last-1: a reader
    // matched after a short alignment sees only the state after it.)
    const std::string out = Outputs();
    const std::size_t aligning = out.find("-> ALIGNING: every process is active");
    const std::size_t travelling = out.find("ALIGNING -> RECOVERING_POSE");
    EXPECT_TRUE(aligning != std::string::npos && travelling != std::string::npos &&
                aligning < travelling)
        << "mission/status seen: " << ::testing::PrintToString(mission) << "\n"
        << out;
  }
}

class KidnapTest : public WhereAmITest {
 protected:
  KidnapTest() : WhereAmITest(26) {}
};

TEST_F(KidnapTest, KidnappedRobotIsNoticedAndRecoversTheNewPose) {
  std::optional<msgs::GroundTruth> truth;
  // The kidnap is noticed when the pose stops being LOCALIZED: LOST (the evidence is against
  // it) or RECOVERING (no longer sure of it).
  bool noticed = false;
  std::optional<msgs::LocalizationPose> first, second;
  std::optional<msgs::GroundTruth> truth_at_second;
  std::string last_status;
  // The kidnap, seen in the ground truth: the base jumps far between two samples (20 Hz).
  bool kidnapped = false;
  runtime::Reader<msgs::GroundTruthPubSubType> truths(
      participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) {
        if (truth && std::hypot(g.pose().x_in() - truth->pose().x_in(),
                                g.pose().y_in() - truth->pose().y_in()) > 120.0) {
          kidnapped = true;
        }
        truth = g;
      });
  runtime::Reader<msgs::LocalizationPosePubSubType> poses(
      participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
        if (p.status() != msgs::LOCALIZATION_LOCALIZED) {
          noticed = noticed || kidnapped;
          return;
        }
        if (!first) first = p;
        if (noticed && !second) {
          second = p;
          truth_at_second = truth;
        }
      });
  runtime::Reader<msgs::MissionStatusPubSubType> status(
      participant(), executor(), "mission/status",
      [&](const msgs::MissionStatus& s) { last_status = s.message(); });
  runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
  StartStack("kidnap",
             {{"seed", "4"}, {"kidnap_after_localized_s", "4"}, {"kidnap_jump_in", "2500"}});
  ASSERT_TRUE(SpinUntil([&] { return first.has_value(); }, 150.0)) << Outputs();
  // A goal ahead keeps the robot travelling, so the kidnap shows.
  msgs::MissionGoal goal;
  goal.goal_id("far");
  goal.target(TargetAhead(first->best()));
  ASSERT_TRUE(SendGoalUntilTaken(goals, goal, last_status, 20.0)) << last_status;
  ASSERT_TRUE(SpinUntil([&] { return noticed; }, 120.0)) << last_status << "\n" << Outputs();
  ASSERT_TRUE(SpinUntil([&] { return second.has_value(); }, 150.0)) << Outputs();
  ASSERT_TRUE(truth_at_second.has_value());
  EXPECT_TRUE(Matches(second->best(), *truth_at_second, truth_at_second->forward_in_ring()))
      << "recovered on ring " << second->best().ring_id() << " edge " << second->best().edge_index()
      << ", truth ring " << truth_at_second->ring_id() << " edge " << truth_at_second->edge_index()
      << "\n"
      << Outputs();
  StopAllAndExpectCleanExit();
}

// A wrong pose's spell on the deployed stack: from the moment the robot is known to hold a
// wrong LOCALIZED pose (a kidnap seen in the ground truth, or a first pose that does not name
// the true place) to the first published pose that is not LOCALIZED (LOST or RECOVERING) or
// names the true place (corrected). Its edges are the edges the robot entered meanwhile (the
// distinct edges of the truth after the one it held when the spell opened: the truth's edge
// flickers at a boundary; the localizer's own count of edges sensed is not published while it
// tracks), its feet the truth's travel.
struct WrongPoseSpell {
  bool open = false;
  bool done = false;
  long edges = 0;
  double feet = 0.0;
  std::string ended_by = "never";
  double from_in = 0.0;
  std::set<uint32_t> entered;

  void Open(const msgs::GroundTruth& truth) {
    open = true;
    from_in = truth.distance_in();
    entered = {truth.edge_index()};
  }
  void OnTruth(const msgs::GroundTruth& truth) {
    if (open) entered.insert(truth.edge_index());
  }
  // A pose published while the spell is open (`right`: it is LOCALIZED and names the true
  // place) ends it unless it still holds a wrong place.
  void OnPose(const msgs::LocalizationPose& p, bool right, const msgs::GroundTruth& truth) {
    if (!open || (p.status() == msgs::LOCALIZATION_LOCALIZED && !right)) return;
    edges = std::max(0L, static_cast<long>(entered.size()) - 1);
    feet = (truth.distance_in() - from_in) / 12.0;
    ended_by = right ? "corrected" : p.status() == msgs::LOCALIZATION_LOST ? "LOST" : "RECOVERING";
    open = false;
    done = true;
  }
};

// A batch of kidnaps over DDS: a measurement, not run by ctest unless asked for
// (STICKREP_KIDNAP_BATCH=N, optionally STICKREP_KIDNAP_SEED=first seed, default 101). Each
// run is a seeded start on the small map at 3x real time; 4 s after the first pose the robot
// is carried a seeded fraction (0.1-0.9) of the ring ahead, as `stickrep-whereami
// --kidnap-jump-random` does in process; the wrong pose's spell opens at the jump. Asserted
// for each run: the spell ends and a pose is recovered again. Printed: one line per kidnap and the
// median, 95th percentile and maximum.
struct DeployedKidnap {
  WrongPoseSpell spell;
  bool recovered_right = false;
};

class KidnapBatchTest : public WhereAmITest {
 protected:
  KidnapBatchTest() : WhereAmITest(64) {}

  // Wall seconds for each step (the first pose, the spell's end, the pose recovered): 600 s
  // simulated at 3x, the bound of the in-process runs (`stickrep-whereami --max-sim-s`). On a
  // map with surveyed marks the bar takes about 26 edges, 85 s simulated on average and
  // several times that in the tail.
  static constexpr double kStepBoundS = 200.0;

  DeployedKidnap RunOne(int seed, double jump_in) {
    DeployedKidnap k;
    std::optional<msgs::GroundTruth> truth;
    std::optional<msgs::LocalizationPose> first, again, latest;
    std::optional<msgs::GroundTruth> truth_again;
    bool kidnapped = false;
    std::string last_status;
    runtime::Reader<msgs::GroundTruthPubSubType> truths(
        participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) {
          // Carried: far in the building, or (a ring of one corridor goes down one side and
          // back the other) to the other side of the hallway, far along the ring.
          const int de = truth ? std::abs(static_cast<int>(g.edge_index()) -
                                          static_cast<int>(truth->edge_index()))
                               : 0;
          if (truth && !kidnapped &&
              (std::hypot(g.pose().x_in() - truth->pose().x_in(),
                          g.pose().y_in() - truth->pose().y_in()) > 120.0 ||
               std::min(de, kSmallMapEdges - de) > 2)) {
            kidnapped = true;
            k.spell.Open(g);
          }
          k.spell.OnTruth(g);
          truth = g;
        });
    runtime::Reader<msgs::LocalizationPosePubSubType> poses(
        participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
          const bool localized = p.status() == msgs::LOCALIZATION_LOCALIZED;
          if (localized && !first) first = p;
          if (localized) latest = p;
          if (k.spell.open) {
            k.spell.OnPose(p, localized && Matches(p.best(), *truth, truth->forward_in_ring()),
                           *truth);
          } else if (k.spell.done && localized && !again) {
            again = p;
            truth_again = truth;
          }
        });
    runtime::Reader<msgs::MissionStatusPubSubType> status(
        participant(), executor(), "mission/status",
        [&](const msgs::MissionStatus& s) { last_status = s.message(); });
    runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
    const std::string name = "kidnap_batch" + std::to_string(seed);
    StartStack(name, {{"seed", std::to_string(seed)},
                      {"kidnap_after_localized_s", "4"},
                      {"kidnap_jump_in", std::to_string(jump_in)}});
    EXPECT_TRUE(SpinUntil([&] { return first.has_value(); }, kStepBoundS)) << Outputs();
    if (!first) return k;
    // Goals a third of the ring ahead keep the robot travelling through and after the kidnap.
    EXPECT_TRUE(TravelOnUntil([&] { return k.spell.done; }, goals, latest, last_status,
                              kSmallMapEdges, kSmallMapEdges / 3, kStepBoundS))
        << "seed " << seed << ": the wrong pose was never given up; " << last_status << "\n"
        << Outputs();
    EXPECT_TRUE(SpinUntil([&] { return again.has_value(); }, kStepBoundS))
        << "seed " << seed << ": no pose recovered after the kidnap; " << last_status << "\n"
        << Outputs();
    if (again) {
      k.recovered_right = Matches(again->best(), *truth_again, truth_again->forward_in_ring());
    }
    StopAllAndExpectCleanExit();
    return k;
  }
};

TEST_F(KidnapBatchTest, DeployedKidnapsAreGivenUpAndRecovered) {
  const char* runs_text = std::getenv("STICKREP_KIDNAP_BATCH");
  if (runs_text == nullptr) {
    GTEST_SKIP() << "a measurement: STICKREP_KIDNAP_BATCH=N runs N kidnaps (docs/whereami.md)";
  }
  const int runs = std::atoi(runs_text);
  const char* seed_text = std::getenv("STICKREP_KIDNAP_SEED");
  const int first_seed = seed_text != nullptr ? std::atoi(seed_text) : 101;
  const double ring_in = map::LoadMap(kSmallMap).ring(0).LengthIn();
  std::printf("[kidnap batch] seeds %d-%d, small map ring %.0f in, 3x real time\n", first_seed,
              first_seed + runs - 1, ring_in);
  std::vector<double> edges, feet;
  std::map<std::string, int> ended_by;
  int right = 0;
  for (int seed = first_seed; seed < first_seed + runs; ++seed) {
    std::mt19937_64 rng(static_cast<uint64_t>(seed));
    const double jump_in = std::uniform_real_distribution<double>(0.1, 0.9)(rng) * ring_in;
    const DeployedKidnap k = RunOne(seed, jump_in);
    std::printf(
        "[kidnap batch] seed %d jump %.0f in: wrong pose LOCALIZED over %ld edges, "
        "%.1f ft, ended by %s; recovered %s\n",
        seed, jump_in, k.spell.edges, k.spell.feet, k.spell.ended_by.c_str(),
        k.recovered_right ? "right" : "wrong or not");
    std::fflush(stdout);
    if (!k.spell.done) continue;
    edges.push_back(static_cast<double>(k.spell.edges));
    feet.push_back(k.spell.feet);
    ended_by[k.spell.ended_by]++;
    right += k.recovered_right ? 1 : 0;
  }
  ASSERT_FALSE(edges.empty());
  std::printf("[kidnap batch] %zu kidnaps: edges median %.0f, p95 %.0f, max %.0f; feet median "
              "%.1f, p95 %.1f, max %.1f; ended by LOST %d, RECOVERING %d, corrected %d; %d "
              "recovered right\n",
              edges.size(), Median(edges), Quantile(edges, 0.95),
              *std::max_element(edges.begin(), edges.end()), Median(feet), Quantile(feet, 0.95),
              *std::max_element(feet.begin(), feet.end()), ended_by["LOST"],
              ended_by["RECOVERING"], ended_by["corrected"], right);
}

// Floors the generators did not make (maps/README.md, "Realistic floors"), every process on
// its own, at real time: at 3x, one CI run in three turned the other way at the teaching
// building's first junction and ended 4 edges off after 157 s; the processes then have the
// pace they have on the robot. Each start is one the in-process run recovers correctly in a
// few edges (`stickrep-whereami --map M --ring R --seed S -N 1`), but the deployed run is not
// the in-process one (frame and scan timing, discovery) and may take another route: teaching
// seed 28, 33 edges in process, ended 2 edges off in one CI run; seed 20 once went on for 36
// edges and declared edge 91 for 96. A declared pose on these floors carries a stated risk
// (in process, seeds 1-100: 3 of 88 declared poses wrong on the teaching building's main
// corridor, 4 of 78 on its science wing, 3 of 88 on the science hall; docs/whereami.md), so
// what is asserted is the promise that goes with it: the first pose names the true place, or the
// robot, sent on ahead, gives the wrong pose up within kWrongSpellEdges edges of the map and the
// next pose it declares names the true place.
class RealBuildingTest : public WhereAmITest {
 protected:
  explicit RealBuildingTest(int domain) : WhereAmITest(domain) {}

  // Edges of the map a wrong pose may stay LOCALIZED while the robot travels on. In process,
  // wrong spells on the teaching building lasted at most 4 sensed edges without a kidnap and
  // 6 after one (docs/whereami.md, "On the teaching building"); the edges the truth enters
  // are more than those sensed (missed doors, short wall steps passed straight).
  static constexpr int kWrongSpellEdges = 10;
  // How far ahead of the pose held each goal is: a few edges, so the route keeps the
  // direction of travel.
  static constexpr int kGoalAheadEdges = 6;
  // Real seconds allowed for a pose to be declared. Deployed, the teaching building's seed 12
  // took 89.6 s under the Engineering Building's calibration and 161 s and 413 s under the
  // floor's own with the direction of travel (a bar of the posterior 0.9992, not 0.9949),
  // where in process it takes 50.7 s either way: the deployed reads are not the in-process
  // ones, and a higher bar waits longer for reads that agree.
  static constexpr double kPoseTimeoutS = 900.0;

  void RecoversTheTruePose(const std::string& map_name, const std::string& ring,
                           const std::string& seed, int ring_edges) {
    std::optional<msgs::GroundTruth> truth, at_first, at_again;
    std::optional<msgs::LocalizationPose> first, again, latest;
    WrongPoseSpell spell;
    std::string last_status;
    const auto right = [&](const msgs::LocalizationPose& p) {
      return p.status() == msgs::LOCALIZATION_LOCALIZED &&
             Matches(p.best(), *truth, truth->forward_in_ring(), ring_edges);
    };
    runtime::Reader<msgs::GroundTruthPubSubType> truths(
        participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) {
          truth = g;
          spell.OnTruth(g);
        });
    runtime::Reader<msgs::LocalizationPosePubSubType> poses(
        participant(), executor(), "localization/pose", [&](const msgs::LocalizationPose& p) {
          const bool localized = p.status() == msgs::LOCALIZATION_LOCALIZED;
          if (!truth) return;
          if (localized) latest = p;
          if (localized && !first) {
            first = p;
            at_first = truth;
            if (!right(p)) spell.Open(*truth);
          } else if (spell.open) {
            spell.OnPose(p, right(p), *truth);
          } else if (spell.done && localized && !again) {
            again = p;
            at_again = truth;
          }
        });
    runtime::Reader<msgs::MissionStatusPubSubType> status(
        participant(), executor(), "mission/status",
        [&](const msgs::MissionStatus& s) { last_status = s.message(); });
    runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
    const std::string system = WriteTempFile(
        map_name + "_system.yaml",
        ConfigWith("system.yaml",
                   {{"qos_file", ConfigPath("qos.yaml")},
                    {"robot_file", ConfigPath("robot.yaml")},
                    {"map_file", STICKREP_SOURCE_DIR "/maps/" + map_name + ".yaml"}}));
    StartStackOn(system, map_name,
                 {{"seed", seed}, {"ring_id", ring}, {"real_time_factor", "1"}});
    ASSERT_TRUE(SpinUntil([&] { return first.has_value(); }, kPoseTimeoutS)) << Outputs();
    if (spell.open) {
      std::printf("[real building] the first pose is wrong (%s): sending the robot on\n",
                  Named(*first, *at_first).c_str());
      std::fflush(stdout);
      ASSERT_TRUE(TravelOnUntil([&] { return spell.done; }, goals, latest, last_status, ring_edges,
                                kGoalAheadEdges, kPoseTimeoutS))
          << "the wrong pose was never given up; " << last_status << "\n"
          << Outputs();
      std::printf("[real building] the wrong pose ended (%s) after %ld edges, %.1f ft\n",
                  spell.ended_by.c_str(), spell.edges, spell.feet);
      EXPECT_LE(spell.edges, kWrongSpellEdges) << Outputs();
      ASSERT_TRUE(SpinUntil([&] { return again.has_value(); }, kPoseTimeoutS)) << Outputs();
      EXPECT_TRUE(Matches(again->best(), *at_again, at_again->forward_in_ring(), ring_edges))
          << "after the wrong pose, " << Named(*again, *at_again) << "\n"
          << Outputs();
    }
    EXPECT_EQ(truth->collisions(), 0u);
    StopAllAndExpectCleanExit();
  }

  static std::string Named(const msgs::LocalizationPose& p, const msgs::GroundTruth& t) {
    return "localized on ring " + p.best().ring_id() + " edge " +
           std::to_string(p.best().edge_index()) + (p.best().forward() ? " fwd" : " back") +
           ", truth ring " + t.ring_id() + " edge " + std::to_string(t.edge_index()) +
           (t.forward_in_ring() ? " fwd" : " back");
  }
};

// The teaching building's main corridor: a corridor outline 96 in wide with door alcoves, a
// lobby with two columns, a curved stretch and a 45 deg bend.
class TeachingBuildingTest : public RealBuildingTest {
 protected:
  TeachingBuildingTest() : RealBuildingTest(29) {}
};

TEST_F(TeachingBuildingTest, StartRecoversTheTruePose) {
  // Seed 12 (edge 24 + 106.2 in, in the corridor): correct in process after 8 edges, 78.0 ft,
  // 50.7 s (with the floor's own calibration and the direction of travel as before it), one
  // hallway end and no turn on the way, in the realistic hallways the virtual robot draws
  // (configs/virtual_robot.yaml, realism on); chosen on an earlier build as the quickest
  // corridor start of seeds 1-40 there. Seed 20, used before, took 27 edges and 286 ft in
  // process on that build (and 36 edges once deployed); seed 54 starts in the entrance lobby, which
  // the ring does not model as a hall (maps/README.md), and deployed it once took the lobby's
  // junction the other way and was sure (0.9992) of the right edge in the wrong direction
  // (docs/whereami.md). The ring has 98 edges.
  RecoversTheTruePose("teaching_building_1f", "main_corridor", "12", 98);
}

// The science hall's labs corridor: 88 in wide, pilasters, a quarter circle and a 25 deg
// bend, alcoves 24-48 in deep, a study hall with four columns, single doors of 40-48 in the
// camera never sees whole.
class ScienceHallTest : public RealBuildingTest {
 protected:
  ScienceHallTest() : RealBuildingTest(28) {}
};

TEST_F(ScienceHallTest, StartRecoversTheTruePose) {
  // Seed 34: correct in process after 6 edges, 64.1 ft, 54.7 s (realism on), with the
  // floor's own calibration and the direction of travel, the same as without the direction
  // (configs/localizer.yaml, on_maps), riding 10 in off the axis for the camera
  // (configs/locomotion.yaml, on_maps). Seed 46, used on the axis, takes 22 edges and 330 ft
  // on the line. The ring has 136 edges.
  RecoversTheTruePose("science_hall_2f", "labs_corridor", "34", 136);
}

}  // namespace
}  // namespace stickrep::test
