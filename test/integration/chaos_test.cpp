// Supervision under chaos: the all-in-one graph under stickrep-launch (restart: on-failure),
// the mission kept busy with goals, and every 10-20 s (seeded) one of the landmark, localizer
// and executive processes killed with SIGKILL, for two minutes of real time (the victims in a
// random order, each once per round of three, so each is killed at least twice). The
// device processes (sonar, camera, locomotion: each drives a device) and the virtual robot
// (the hardware and the world) are not killed. Asserted: every killed process is restarted
// and the mission resumes; the base is at rest within kMaxStopS of each kill and stays at
// rest until the process is back; a killed localizer makes the mission recover the pose again
// (RECOVERING_POSE); no collision; at the end the mission holds a LOCALIZED pose. Whether
// that pose names the true place is printed with the other figures for docs/reliability.md.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <optional>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "common/quantile.h"
#include "integration/process_fixture.h"
#include "localizationPubSubTypes.h"
#include "missionPubSubTypes.h"
#include "runtime/process.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

constexpr double kChaosS = 120.0;
// Kill to base at rest: the executive's 2 s heartbeat timeout (locomotion's 0.5 s command
// deadline when the executive itself dies), a 0.1 s tick and braking, on a loaded machine.
constexpr double kMaxStopS = 4.0;
constexpr int kGoalEdgesAhead = 6;
const char* const kVictims[] = {"landmark", "localizer", "executive"};

// Pid of the child of `parent` running build/bin/stickrep-NAME (/proc's comm is cut at 15).
std::optional<int> ChildPid(int parent, const std::string& name) {
  const std::string comm = ("stickrep-" + name).substr(0, 15);
  std::optional<int> found;
  DIR* proc = opendir("/proc");
  for (dirent* e; proc != nullptr && (e = readdir(proc)) != nullptr;) {
    const int pid = std::atoi(e->d_name);
    if (pid <= 0) continue;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) continue;
    const auto open = line.find('('), close = line.rfind(')');
    if (open == std::string::npos || close == std::string::npos) continue;
    int ppid = 0;
    std::sscanf(line.c_str() + close + 2, "%*c %d", &ppid);
    if (ppid == parent && line.substr(open + 1, close - open - 1) == comm) found = pid;
  }
  if (proc != nullptr) closedir(proc);
  return found;
}

struct Kill {
  std::string victim;
  int pid;
  double at_s;
  double restarted_s = -1.0;  // when the launcher's new process was first seen in /proc
};

struct StatusSample {
  double stamp_s;
  msgs::MissionState state;
};

const char* StateName(msgs::MissionState s) {
  static const char* const kNames[] = {"WAITING_FOR_COMPONENTS", "ALIGNING", "RECOVERING_POSE",
                                       "LOCALIZED", "EXECUTING_GOAL", "GOAL_REACHED",
                                       "STOPPED_FAULT", "LINK_LOST"};
  const auto i = static_cast<size_t>(s);
  return i < sizeof(kNames) / sizeof(kNames[0]) ? kNames[i] : "?";
}

struct MotionEvent {
  bool moving;
  double at_s;  // simulated time: the wall clock at real time
};

std::vector<MotionEvent> TruthEvents(const std::string& output) {
  static const std::regex truth(R"(truth: base (moving|at rest) at simulated time ([0-9.]+) s)");
  std::vector<MotionEvent> out;
  for (auto it = std::sregex_iterator(output.begin(), output.end(), truth);
       it != std::sregex_iterator(); ++it) {
    out.push_back({(*it)[1] == "moving", std::stod((*it)[2])});
  }
  return out;
}

bool MovingAt(const std::vector<MotionEvent>& events, double t) {
  bool moving = false;
  for (const auto& e : events) {
    if (e.at_s > t) break;
    moving = e.moving;
  }
  return moving;
}

class ChaosTest : public ProcessFixture {
 protected:
  ChaosTest() : ProcessFixture(63) {}

  // The all-in-one graph on the small map at real time, the mission holding between goals.
  std::string Graph() {
    const std::string system = SmallMapSystem("chaos_system.yaml");
    const std::string robot = WriteTempFile(
        "chaos_vr.yaml",
        ConfigWith("virtual_robot.yaml", {{"seed", "3"}, {"summary_png", "\"\""}}));
    std::string g =
        "launch:\n  name: chaos\n  max_duration_s: 900\n"
        "  restart: {policy: on-failure, backoff_initial_s: 2, backoff_max_s: 8, "
        "max_restarts: 20}\n"
        "  common_args: [--system, \"" + system + "\"]\n  processes:\n"
        "    - name: virtual_robot\n      executable: stickrep-virtual-robot\n"
        "      restart: never\n      args: [--config, \"" + robot + "\"]\n";
    for (const char* name : {"sonar", "camera", "locomotion", "landmark", "localizer"}) {
      g += std::string("    - name: ") + name + "\n      executable: stickrep-" + name + "\n";
    }
    g += "    - name: executive\n      executable: stickrep-executive\n"
         "      args: [--config, \"" + ConfigPath("executive.yaml") + "\"]\n";
    return WriteTempFile("chaos.launch.yaml", g);
  }

  // When the victim of a kill was back, and the state the mission resumed in: the new
  // executive's first state past waiting for the processes, or the mission leaving the fault
  // the kill caused.
  std::optional<StatusSample> BackAt(const Kill& k) const {
    bool faulted = false;
    for (const auto& s : status_) {
      if (s.stamp_s <= k.at_s) continue;
      if (k.victim == "executive") {
        if (s.state != msgs::MISSION_WAITING_FOR_COMPONENTS) return s;
        continue;
      }
      if (s.state == msgs::MISSION_STOPPED_FAULT) faulted = true;
      if (faulted && s.state != msgs::MISSION_STOPPED_FAULT) return s;
    }
    return std::nullopt;
  }

  // Notes when each killed process's successor appears among the launcher's children.
  static void NoteRestarts(std::vector<Kill>& kills, int launcher) {
    for (Kill& k : kills) {
      if (k.restarted_s >= 0.0) continue;
      const auto pid = ChildPid(launcher, k.victim);
      if (pid && *pid != k.pid) k.restarted_s = WallNowS();
    }
  }

  // Sends a goal a few edges ahead when the mission holds, to keep the robot travelling.
  void KeepBusy(msgs::MissionGoal& goal, runtime::Writer<msgs::MissionGoalPubSubType>& goals) {
    const bool holding = !status_.empty() && (status_.back().state == msgs::MISSION_LOCALIZED ||
                                              status_.back().state == msgs::MISSION_GOAL_REACHED);
    if (!holding || !pose_ || pose_->status() != msgs::LOCALIZATION_LOCALIZED ||
        WallNowS() - last_goal_s_ < 3.0) {
      return;
    }
    const int edge = static_cast<int>(pose_->best().edge_index());
    const int target = pose_->best().forward() ? edge + kGoalEdgesAhead
                                               : edge - kGoalEdgesAhead + kSmallMapEdges;
    goal.goal_id("chaos" + std::to_string(++goals_sent_));
    goal.target(pose_->best().ring_id() + "/" + std::to_string(target % kSmallMapEdges));
    goals.Publish(goal, runtime::WallClockNowNs());
    last_goal_s_ = WallNowS();
  }

  std::vector<StatusSample> status_;
  std::optional<msgs::LocalizationPose> pose_;
  std::optional<msgs::GroundTruth> truth_;
  int goals_sent_ = 0;
  int goals_accepted_ = 0;
  double last_goal_s_ = 0.0;
};

TEST_F(ChaosTest, RandomKillsForTwoMinutesTheMissionEndsLocalizedAndTheBaseStopsEachTime) {
  const char* env_seed = std::getenv("STICKREP_CHAOS_SEED");
  const uint64_t seed = env_seed != nullptr ? std::strtoull(env_seed, nullptr, 10) : 20240515;
  std::printf("[chaos] seed %llu (STICKREP_CHAOS_SEED to change it)\n",
              static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  runtime::Reader<msgs::MissionStatusPubSubType> status(
      participant(), executor(), "mission/status", [&](const msgs::MissionStatus& s) {
        status_.push_back({s.header().stamp_ns() * 1e-9, s.state()});
      });
  runtime::Reader<msgs::LocalizationPosePubSubType> poses(
      participant(), executor(), "localization/pose",
      [&](const msgs::LocalizationPose& p) { pose_ = p; });
  runtime::Reader<msgs::GroundTruthPubSubType> truths(
      participant(), executor(), "sim/ground_truth", [&](const msgs::GroundTruth& g) { truth_ = g; });
  runtime::Reader<msgs::MissionGoalResultPubSubType> results(
      participant(), executor(), "mission/goal_result",
      [&](const msgs::MissionGoalResult& r) { goals_accepted_ += r.accepted() ? 1 : 0; });
  runtime::Writer<msgs::MissionGoalPubSubType> goals(participant(), "mission/goal");
  msgs::MissionGoal goal;

  launch::ChildProcess& launch = Start("stickrep-launch", {Graph()});
  const auto localized = [&] {
    return !status_.empty() && status_.back().state == msgs::MISSION_LOCALIZED;
  };
  ASSERT_TRUE(SpinUntil(localized, 240.0)) << Outputs();
  std::printf("[chaos] first pose recovered; killing for %.0f s\n", kChaosS);

  // Kill, every 10-20 s, one of the victims.
  std::vector<Kill> kills;
  const double chaos_end = WallNowS() + kChaosS;
  std::uniform_real_distribution<double> interval(10.0, 20.0);
  std::vector<std::string> round;  // the victims not yet killed in this round
  for (double next = WallNowS() + interval(rng); next < chaos_end; next += interval(rng)) {
    SpinUntil([&] {
      KeepBusy(goal, goals);
      NoteRestarts(kills, launch.pid());
      return WallNowS() >= next;
    }, next - WallNowS() + 60.0);
    if (round.empty()) {
      round.assign(std::begin(kVictims), std::end(kVictims));
      std::shuffle(round.begin(), round.end(), rng);
    }
    const std::string victim = round.back();
    round.pop_back();
    const auto pid = ChildPid(launch.pid(), victim);
    ASSERT_TRUE(pid.has_value()) << victim << " is not running\n" << Outputs();
    kills.push_back({victim, *pid, WallNowS()});
    ASSERT_EQ(kill(*pid, SIGKILL), 0);
    std::printf("[chaos] %.1f s: killed %s (pid %d)\n", kills.back().at_s - kills.front().at_s,
                victim.c_str(), *pid);
  }
  SpinUntil([&] {
    KeepBusy(goal, goals);
    NoteRestarts(kills, launch.pid());
    return WallNowS() >= chaos_end;
  }, 60.0);

  // No more goals: the mission must end holding a pose that names the true place.
  const auto settled = [&] {
    const bool holding = !status_.empty() && (status_.back().state == msgs::MISSION_LOCALIZED ||
                                              status_.back().state == msgs::MISSION_GOAL_REACHED);
    NoteRestarts(kills, launch.pid());
    return holding && pose_ && pose_->status() == msgs::LOCALIZATION_LOCALIZED;
  };
  // A localizer restarted late in the chaos recovers from scratch at real time: on the marked
  // map's bar the in-process runs of seeds 2301-3000 took 71 s to a pose at the median, 157 s
  // at the 95th percentile and 337 s at most (docs/whereami.md, "The panels of a row").
  ASSERT_TRUE(SpinUntil(settled, 360.0)) << Outputs();
  SpinUntil([] { return false; }, 2.0);  // the base's last truth lines and samples
  ASSERT_TRUE(truth_.has_value());
  const auto& best = pose_->best();
  const int de = std::abs(static_cast<int>(best.edge_index()) -
                          static_cast<int>(truth_->edge_index()));
  // Whether the held pose is right is the localizer's integrity, measured by
  // stickrep-whereami over hundreds of runs (docs/whereami.md), not a pass condition here:
  // each kill of the localizer costs a recovery, and one run in a few tens ends on a wrong one.
  const bool final_right = best.ring_id() == truth_->ring_id() &&
                           best.forward() == truth_->forward_in_ring() &&
                           (de <= 1 || de == kSmallMapEdges - 1);
  EXPECT_EQ(truth_->collisions(), 0u);

  // Each kill: the base at rest within kMaxStopS, and at rest until the process was back.
  launch.ReadLines();
  const std::string out = launch.output();
  const std::string log_path = WriteTempFile("chaos_launch.log", out);
  std::printf("[chaos] the launcher's output: %s\n", log_path.c_str());
  const auto events = TruthEvents(out);
  std::vector<double> stop_times;
  int moving_kills = 0, survived = 0;
  for (const Kill& k : kills) {
    const auto resumed = BackAt(k);
    EXPECT_TRUE(resumed.has_value()) << k.victim << " killed at " << k.at_s << " never came back";
    const double back = resumed ? resumed->stamp_s : -1.0;
    if (resumed) survived++;
    if (resumed && k.victim == "localizer") {
      // A new localizer has no pose: the mission recovers it again.
      EXPECT_EQ(resumed->state, msgs::MISSION_RECOVERING_POSE)
          << "after the localizer's restart the mission resumed in " << StateName(resumed->state);
    }
    // The base comes to rest, and stays at rest until the process is back: the last motion
    // change before `back` is a stop, less than kMaxStopS after the kill. Stops and starts
    // before it are locomotion's own (a bend, a reversal) while the death is noticed. A new
    // executive is back when it runs: this test hears its first state only once it has
    // discovered the new process, which on a loaded machine can be after it has set off.
    const double until = k.victim == "executive" && k.restarted_s > 0.0 && back > 0.0
                             ? std::min(back, k.restarted_s)
                             : back;
    double rest = k.at_s;  // already at rest at the kill, and no change since
    for (const auto& e : events) {
      if (until > 0.0 && e.at_s > k.at_s && e.at_s < until) rest = e.moving ? -1.0 : e.at_s;
    }
    if (until > 0.0) {
      ASSERT_GT(rest, 0.0) << "the base was moving when " << k.victim << " came back ("
                           << k.at_s << " to " << until << ")";
      ASSERT_FALSE(rest == k.at_s && MovingAt(events, k.at_s))
          << "the base never stopped while " << k.victim << " was absent";
    }
    if (MovingAt(events, k.at_s)) {
      moving_kills++;
      stop_times.push_back(rest - k.at_s);
      EXPECT_LT(rest - k.at_s, kMaxStopS) << k.victim << " killed";
    }
    std::printf("[chaos] %-9s killed: %s, restarted %.1f s and back (mission resumed in %s) "
                "%.1f s after the kill\n",
                k.victim.c_str(),
                rest > k.at_s ? ("base at rest " + std::to_string(rest - k.at_s).substr(0, 5) +
                                 " s after it").c_str()
                              : "base already at rest",
                k.restarted_s > 0.0 ? k.restarted_s - k.at_s : -1.0,
                resumed ? StateName(resumed->state) : "-", back - k.at_s);
  }
  const auto count = [&out](const char* pattern) {
    const std::regex re(pattern);
    return static_cast<long>(
        std::distance(std::sregex_iterator(out.begin(), out.end(), re), std::sregex_iterator()));
  };
  const long restarts = count(R"(launch: (\w+) restarted)");
  EXPECT_EQ(restarts, static_cast<long>(kills.size()));
  const long correct = count(R"(: CORRECT)");
  const long incorrect = count(R"(: INCORRECT)");
  std::printf("[chaos] seed %llu: %zu kills (%d while moving), %d survived, %ld restarts; stop "
              "times median %.2f s, max %.2f s; %d goals sent, %d accepted; poses recovered %ld "
              "CORRECT, %ld INCORRECT; final pose ring %s edge %u (truth edge %u): %s; %u "
              "collisions\n",
              static_cast<unsigned long long>(seed), kills.size(), moving_kills, survived,
              restarts, stop_times.empty() ? 0.0 : Median(stop_times),
              stop_times.empty() ? 0.0 : *std::max_element(stop_times.begin(), stop_times.end()),
              goals_sent_, goals_accepted_, correct, incorrect, best.ring_id().c_str(),
              best.edge_index(), truth_->edge_index(), final_right ? "right" : "WRONG",
              truth_->collisions());
  EXPECT_GE(kills.size(), 6u);
  // The launcher ends with code 1: processes failed (and were restarted) during the run.
  launch.Signal(SIGINT);
  ASSERT_TRUE(launch.WaitExit(40.0)) << Outputs();
  EXPECT_EQ(launch.exit_code(), 1) << launch.output().substr(launch.output().size() - 3000);
  const std::string& end = launch.output();
  const auto table = end.find("\nPROCESS ");
  if (table != std::string::npos) std::printf("[chaos] %s\n", end.substr(table + 1).c_str());
}

// Restarts in a row on one host: round after round the executive killed and, 4 s later while
// it is being restarted, the landmark; each round the new executive must hear every process
// (the new landmark too) and the mission leave waiting and the fault. The scenario in which
// Fast DDS 2.9's shared memory left new executives deaf for good (docs/reliability.md,
// "Supervision"); this test did not reproduce that fault in a run over shared memory, so it
// guards the restarts, not the transport.
TEST_F(ChaosTest, ExecutiveAndLandmarkKilledInTurnSixTimesAreHeardAgainEachTime) {
  constexpr int kRounds = 6;
  runtime::Reader<msgs::MissionStatusPubSubType> status(
      participant(), executor(), "mission/status", [&](const msgs::MissionStatus& s) {
        status_.push_back({s.header().stamp_ns() * 1e-9, s.state()});
      });
  launch::ChildProcess& launch = Start("stickrep-launch", {Graph()});
  // Every required process heard, and none absent: the mission runs.
  const auto running_since = [&](double t_s) {
    return [&, t_s] {
      return !status_.empty() && status_.back().stamp_s > t_s &&
             status_.back().state != msgs::MISSION_WAITING_FOR_COMPONENTS &&
             status_.back().state != msgs::MISSION_STOPPED_FAULT;
    };
  };
  ASSERT_TRUE(SpinUntil(running_since(0.0), 60.0)) << Outputs();
  std::vector<double> back_s;
  for (int round = 1; round <= kRounds; ++round) {
    double last_kill = 0.0;
    for (const char* victim : {"executive", "landmark"}) {
      const auto pid = ChildPid(launch.pid(), victim);
      ASSERT_TRUE(pid.has_value()) << victim << " is not running\n" << Outputs();
      last_kill = WallNowS();
      ASSERT_EQ(kill(*pid, SIGKILL), 0);
      if (std::string(victim) == "executive") SpinUntil([] { return false; }, 4.0);
    }
    // Both restarted after 2-8 s of back-off; the new executive hears them all.
    ASSERT_TRUE(SpinUntil(running_since(last_kill), 45.0))
        << "round " << round << ": the mission did not run again\n" << Outputs();
    back_s.push_back(status_.back().stamp_s - last_kill);
  }
  std::printf("[chaos] %d rounds of an executive and a landmark kill: every new process heard, "
              "the mission running again %.1f s (median) and %.1f s (max) after the second "
              "kill\n",
              kRounds, Median(back_s), *std::max_element(back_s.begin(), back_s.end()));
  launch.Signal(SIGINT);
  ASSERT_TRUE(launch.WaitExit(40.0)) << Outputs();
}

}  // namespace
}  // namespace stickrep::test
