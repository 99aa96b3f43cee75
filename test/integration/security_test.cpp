// DDS Security on the whole stack: keys made by deploy/security/make-keys.sh, the all-in-one
// graph run by stickrep-launch --security-dir (the one switch), and the attacks of
// docs/security.md tried against it while the robot holds its recovered pose:
//  - a plain Fast DDS participant (no security) and an Eclipse Cyclone DDS participant
//    discover no topic of the stack, and their goals, motion and wheel commands move nothing;
//  - an authenticated identity without the permission (the camera's) cannot write
//    mission/goal or robot/motion/command; with a permissions document of its own making
//    that grants them (signed by a permissions CA the stack does not trust), the stack
//    matches none of its writers and its goals move nothing;
//  - an identity made by another CA (a forged "executive") is not authenticated: it
//    discovers no topic and moves nothing;
//  - the console's identity, allowed to, sends a goal and the executive answers it.
// The stack starts once for the suite (it takes about a minute) and runs alone (RUN_SERIAL).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "basePubSubTypes.h"
#include "integration/process_fixture.h"
#include "launch/child_process.h"
#include "missionPubSubTypes.h"
#include "runtime/executor.h"
#include "runtime/participant.h"
#include "runtime/process.h"
#include "sensorsPubSubTypes.h"
#include "systemPubSubTypes.h"

namespace stickrep::test {
namespace {

constexpr int kDomain = 60;          // the secured stack
constexpr int kControlDomain = 61;   // the Cyclone peer beside a plain reader, no stack
// Long enough for several discovery announcements (every 3 s in simple discovery) and
// dozens of goals and commands at 10 Hz.
constexpr double kAttackWindowS = 8.0;
constexpr const char* kGoalTarget = "wing1_corridor/60";
constexpr int kProcesses = 7;  // the all-in-one graph's
// As the launcher's handshake watch (launch::HandshakeWatch): a handshake not done this long
// after both participants started has stuck.
constexpr double kHandshakeTimeoutS = 20.0;

runtime::QosCatalog Catalog() { return runtime::QosCatalog::LoadFile(ConfigPath("qos.yaml")); }

runtime::ParticipantConfig Config(int domain, const std::string& name,
                                  const std::string& security_dir = "",
                                  const std::string& identity = "") {
  runtime::ParticipantConfig c{domain, name, "", "", {}};
  if (!security_dir.empty()) c.security = runtime::SecurityConfig{security_dir, identity};
  return c;
}

// The topics of the others' endpoints that a participant has discovered.
std::set<std::string> StackTopics(runtime::Participant& p) {
  const std::string own = runtime::GuidText(p.dds()->guid());
  const std::string own_prefix = own.substr(0, own.find('|') + 1);
  std::set<std::string> out;
  for (const auto& e : p.discovery().Endpoints()) {
    if (e.guid.rfind(own_prefix, 0) != 0) out.insert(e.topic);
  }
  return out;
}

std::string Join(const std::set<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
  return out.empty() ? "none" : out;
}

// Everything the suite shares: the keys, the stack under stickrep-launch, and an observer
// with the console's identity (allowed to read every topic).
struct Stack {
  std::string keys;
  std::string rogue_keys;  // another CA's: the same names, signed by nobody the stack trusts
  std::unique_ptr<launch::ChildProcess> launch;
  runtime::Executor executor;
  std::unique_ptr<runtime::Participant> observer;
  std::unique_ptr<runtime::Reader<msgs::MissionStatusPubSubType>> status;
  std::unique_ptr<runtime::Reader<msgs::MissionGoalResultPubSubType>> results;
  std::unique_ptr<runtime::Reader<msgs::GroundTruthPubSubType>> truth;
  std::string mission_state;
  std::vector<msgs::MissionGoalResult> goal_results;
  unsigned collisions = 0;
  struct Motion {
    bool moving;
    double read_at_s;  // when the test read the virtual robot's line (wall clock)
  };
  std::vector<Motion> motion;
};

Stack* g_stack = nullptr;

// The observer with the console's identity, and its readers: made again when its handshake
// with a process of the stack has stuck (SecuredStackRecoversACorrectPose joins it again).
void JoinObserver() {
  Stack& s = *g_stack;
  s.status.reset();
  s.results.reset();
  s.truth.reset();
  s.observer.reset();
  s.observer = std::make_unique<runtime::Participant>(
      Config(kDomain, "stickrep-console", s.keys, "console"), Catalog());
  s.status = std::make_unique<runtime::Reader<msgs::MissionStatusPubSubType>>(
      *s.observer, s.executor, "mission/status", [](const msgs::MissionStatus& m) {
        static const char* kNames[] = {"WAITING_FOR_COMPONENTS", "ALIGNING", "RECOVERING_POSE",
                                       "LOCALIZED", "EXECUTING_GOAL", "GOAL_REACHED",
                                       "STOPPED_FAULT", "LINK_LOST"};
        g_stack->mission_state = kNames[static_cast<int>(m.state())];
      });
  s.results = std::make_unique<runtime::Reader<msgs::MissionGoalResultPubSubType>>(
      *s.observer, s.executor, "mission/goal_result",
      [](const msgs::MissionGoalResult& r) { g_stack->goal_results.push_back(r); });
  s.truth = std::make_unique<runtime::Reader<msgs::GroundTruthPubSubType>>(
      *s.observer, s.executor, "sim/ground_truth",
      [](const msgs::GroundTruth& g) { g_stack->collisions = g.collisions(); });
}

class SecuredStackTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  static void TearDownTestSuite();

  void SetUp() override {
    if (g_stack == nullptr || g_stack->launch == nullptr) GTEST_SKIP() << "no stack";
  }

  // Reads the launcher's output (the virtual robot's truth lines) and spins the observer.
  static void Pump() {
    static const std::regex truth(R"(truth: base (moving|at rest) at simulated time)");
    for (const std::string& line : g_stack->launch->ReadLines()) {
      std::smatch m;
      if (std::regex_search(line, m, truth)) {
        g_stack->motion.push_back({m[1] == "moving", WallNowS()});
      }
    }
    g_stack->executor.SpinOnce(std::chrono::milliseconds(20));
  }

  static bool WaitFor(const std::function<bool()>& done, double timeout_s) {
    const double until = WallNowS() + timeout_s;
    while (!done()) {
      if (WallNowS() > until) return false;
      Pump();
    }
    return true;
  }

  // How many of the stack's processes (by participant name) the observer has authenticated
  // and still discovers.
  static size_t ObserverKnows() {
    const auto& d = g_stack->observer->discovery();
    std::set<std::string> names;
    for (const std::string& prefix : d.AuthenticatedPrefixes()) {
      const std::string name = d.NameOf(prefix);
      if (!name.empty()) names.insert(name);
    }
    return names.size();
  }

  static bool StackSaid(const std::string& text) {
    return g_stack->launch->output().find(text) != std::string::npos;
  }

  static std::string Output() {
    Pump();
    return g_stack->launch->output() + ObserverState();
  }

  // What the console-identity observer knows: which participants it discovered and
  // authenticated, which topics, and whether its readers matched a writer.
  static std::string ObserverState() {
    const auto& d = g_stack->observer->discovery();
    std::string participants;
    for (const auto& p : d.Participants()) participants += (participants.empty() ? "" : ", ") + p;
    return "\n[observer] participants: " + (participants.empty() ? "none" : participants) +
           "; authenticated: " + std::to_string(d.Authenticated()) +
           "; refused: " + std::to_string(d.Refused().size()) +
           "; topics: " + Join(StackTopics(*g_stack->observer)) +
           "; matched writers: status " + std::to_string(g_stack->status->counters().matched) +
           ", goal_result " + std::to_string(g_stack->results->counters().matched) +
           ", ground_truth " + std::to_string(g_stack->truth->counters().matched) +
           "; samples: status " + std::to_string(g_stack->status->counters().samples) + "\n";
  }

  // Runs `attack` every 0.1 s for the attack window; then the base must not have moved
  // since the window opened, and the executive must have answered no goal.
  static void ExpectNothingMovesDuring(const std::function<void()>& attack) {
    const double start = WallNowS();
    const size_t results_before = g_stack->goal_results.size();
    WaitFor([&] {
      attack();
      WaitFor([] { return false; }, 0.1);
      return WallNowS() - start >= kAttackWindowS;
    }, kAttackWindowS + 10.0);
    for (const auto& m : g_stack->motion) {
      EXPECT_FALSE(m.moving && m.read_at_s >= start) << "the base moved during the attack";
    }
    EXPECT_EQ(g_stack->goal_results.size(), results_before)
        << "the executive answered a goal of the attacker";
    EXPECT_EQ(g_stack->mission_state, "LOCALIZED");
  }

  // From `who`: goals and motion commands for the attack window; nothing may move, no topic
  // of the stack may be discovered and no reader may match. Prints what was tried.
  static void AttackWithGoalsAndCommands(runtime::Participant& who, const std::string& goal_id,
                                         const std::string& label) {
    runtime::Writer<msgs::MissionGoalPubSubType> goals(who, "mission/goal");
    runtime::Writer<msgs::MotionCommandPubSubType> commands(who, "robot/motion/command");
    msgs::MissionGoal goal;
    goal.goal_id(goal_id);
    goal.target(kGoalTarget);
    msgs::MotionCommand command;
    command.mode(msgs::MOTION_FOLLOW_HALLWAY);
    command.linear_speed_ftps(2.6);
    ExpectNothingMovesDuring([&] {
      goals.Publish(goal, runtime::WallClockNowNs());
      commands.Publish(command, runtime::WallClockNowNs());
    });
    const auto topics = StackTopics(who);
    EXPECT_TRUE(topics.empty()) << "discovered: " << Join(topics);
    EXPECT_EQ(goals.counters().matched.load(), 0);
    EXPECT_EQ(commands.counters().matched.load(), 0);
    std::printf("[security] %s: %llu goals and %llu motion commands written; topics "
                "discovered: %s; readers matched: %d\n",
                label.c_str(), static_cast<unsigned long long>(goals.counters().samples.load()),
                static_cast<unsigned long long>(commands.counters().samples.load()),
                Join(topics).c_str(), goals.counters().matched.load());
  }
};

void SecuredStackTest::SetUpTestSuite() {
  g_stack = new Stack;
  Stack& s = *g_stack;
  const std::string tmp = ::testing::TempDir() + "/stickrep_security_" + std::to_string(getpid());
  s.keys = tmp + "/keys";
  s.rogue_keys = tmp + "/rogue";
  const std::string script = "bash " + SourcePath("deploy/security/make-keys.sh") + " ";
  const auto [rc, out] = Shell(script + s.keys);
  ASSERT_EQ(rc, 0) << out;
  const auto [rogue_rc, rogue_out] = Shell(script + s.rogue_keys);
  ASSERT_EQ(rogue_rc, 0) << rogue_out;

  JoinObserver();

  // The all-in-one graph on the small map, the mission holding at the recovered pose. At
  // real time: at twice real time, with the realistic camera frames, on a loaded 2-core
  // machine, not one encrypted 250 kB frame reached its reader (docs/security.md).
  const std::string system = SmallMapSystem("security_system.yaml");
  const std::string robot = WriteTempFile(
      "security_vr.yaml",
      ConfigWith("virtual_robot.yaml", {{"seed", "2"}, {"summary_png", "\"\""}}));
  std::string graph =
      "launch:\n  name: secured all-in-one\n  max_duration_s: 900\n"
      "  common_args: [--system, \"" + system + "\"]\n  processes:\n"
      "    - name: virtual_robot\n      executable: stickrep-virtual-robot\n"
      "      args: [--config, \"" + robot + "\"]\n";
  for (const char* name : {"sonar", "camera", "locomotion", "landmark", "localizer"}) {
    graph += std::string("    - name: ") + name + "\n      executable: stickrep-" + name + "\n";
  }
  graph += "    - name: executive\n      executable: stickrep-executive\n"
           "      args: [--config, \"" + ConfigPath("executive.yaml") + "\"]\n";
  s.launch = std::make_unique<launch::ChildProcess>(
      "launch", std::vector<std::string>{BinPath("stickrep-launch"),
                                         WriteTempFile("security.launch.yaml", graph), "--domain",
                                         std::to_string(kDomain), "--security-dir", s.keys});
}

void SecuredStackTest::TearDownTestSuite() {
  if (g_stack == nullptr) return;
  if (g_stack->launch != nullptr && !g_stack->launch->Exited()) {
    g_stack->launch->Signal(SIGINT);
    if (!g_stack->launch->WaitExit(30.0)) g_stack->launch->Signal(SIGKILL);
    g_stack->launch->WaitExit(5.0);
    g_stack->launch->ReadLines(true);
    const std::string& out = g_stack->launch->output();
    // The launcher's own lines: a process restarted for a stuck handshake says so.
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("launch: ", 0) == 0) std::printf("[security] %s\n", line.c_str());
    }
    const auto table = out.find("\nPROCESS ");
    if (table != std::string::npos) std::printf("[security] %s\n", out.substr(table + 1).c_str());
  }
  g_stack->results.reset();
  g_stack->status.reset();
  g_stack->truth.reset();
  g_stack->observer.reset();
  delete g_stack;
  g_stack = nullptr;
}

// First: the secured stack recovers the pose and the virtual robot judges it correct.
TEST_F(SecuredStackTest, SecuredStackRecoversACorrectPose) {
  const double t0 = WallNowS();
  // Every process authenticates every other (the launcher restarts one of a pair whose
  // handshake stuck) and the observer (the console's identity) every process: when its own
  // handshake with one has stuck, it joins again, as an operator would restart a console.
  int rejoins = 0;
  while (!WaitFor([] { return ObserverKnows() >= kProcesses; }, kHandshakeTimeoutS)) {
    ASSERT_LT(rejoins, 3) << "the observer authenticated " << ObserverKnows() << " of "
                          << kProcesses << " processes after joining 3 times" << Output();
    std::printf("[security] the observer authenticated %zu of %d processes in %.0f s: "
                "joining again\n", ObserverKnows(), kProcesses, kHandshakeTimeoutS);
    rejoins++;
    JoinObserver();
  }
  std::printf("[security] observer authenticated every process after %.1f s (%d rejoins)\n",
              WallNowS() - t0, rejoins);
  // The bound is a recovery's tail, not its median: a handshake the launcher heals restarts a
  // process mid-recovery (a restarted locomotion or localizer starts the recovery again), and
  // in process a recovery from scratch took 71 s at the median and up to 337 s on seeds
  // 2301-3000 (docs/whereami.md), slower still on a loaded machine.
  ASSERT_TRUE(
      WaitFor([] { return StackSaid("CORRECT") && g_stack->mission_state == "LOCALIZED"; }, 600.0))
      << Output();
  std::printf("[security] secured stack: pose recovered and judged in %.1f s of wall time\n",
              WallNowS() - t0);
  EXPECT_FALSE(StackSaid("INCORRECT")) << Output();
  EXPECT_EQ(g_stack->collisions, 0u);
  // The base comes to rest once the mission holds.
  ASSERT_TRUE(WaitFor([] { return !g_stack->motion.empty() && !g_stack->motion.back().moving; },
                      30.0))
      << Output();
  // Every topic is there for an allowed reader (secured endpoint discovery can still be
  // going on: one run had 16 of the 17 when the base came to rest).
  EXPECT_TRUE(WaitFor([] { return StackTopics(*g_stack->observer).size() >= 17u; }, 30.0))
      << Join(StackTopics(*g_stack->observer));
}

TEST_F(SecuredStackTest, PlainFastDdsParticipantDiscoversNoTopicAndMovesNothing) {
  runtime::Participant intruder(Config(kDomain, "stickrep-intruder"), Catalog());
  runtime::Writer<msgs::MissionGoalPubSubType> goals(intruder, "mission/goal");
  runtime::Writer<msgs::MotionCommandPubSubType> commands(intruder, "robot/motion/command");
  runtime::Writer<msgs::WheelCommandPubSubType> wheels(intruder, "device/base/wheel_command");
  msgs::MissionGoal goal;
  goal.goal_id("intruder");
  goal.target(kGoalTarget);
  msgs::MotionCommand command;
  command.mode(msgs::MOTION_FOLLOW_HALLWAY);
  command.linear_speed_ftps(2.6);
  msgs::WheelCommand wheel;
  wheel.left_speed_ftps(2.0);
  wheel.right_speed_ftps(2.0);
  ExpectNothingMovesDuring([&] {
    goals.Publish(goal, runtime::WallClockNowNs());
    commands.Publish(command, runtime::WallClockNowNs());
    wheels.Publish(wheel, runtime::WallClockNowNs());
  });
  const auto topics = StackTopics(intruder);
  EXPECT_TRUE(topics.empty()) << "discovered: " << Join(topics);
  EXPECT_EQ(goals.counters().matched.load(), 0);
  EXPECT_EQ(commands.counters().matched.load(), 0);
  EXPECT_EQ(wheels.counters().matched.load(), 0);
  std::printf("[security] plain Fast DDS participant: %llu goals, %llu motion and %llu wheel "
              "commands written; topics discovered: %s; readers matched: %d; participants "
              "announced to it: %zu\n",
              static_cast<unsigned long long>(goals.counters().samples.load()),
              static_cast<unsigned long long>(commands.counters().samples.load()),
              static_cast<unsigned long long>(wheels.counters().samples.load()),
              Join(topics).c_str(), goals.counters().matched.load(),
              intruder.discovery().Participants().size());
}

TEST_F(SecuredStackTest, CycloneDdsParticipantDiscoversNoTopicAndItsGoalMovesNothing) {
  if (std::string(STICKREP_CYCLONE_PEER).empty()) {
    GTEST_SKIP() << "built without Cyclone DDS (apt-get install cyclonedds-dev cyclonedds-tools)";
  }
  // Control: beside a plain Fast DDS reader of mission/goal, the peer's goals arrive; so
  // against the stack, nothing arriving is the security's doing.
  {
    runtime::Executor executor;
    runtime::Participant plain(Config(kControlDomain, "stickrep-plain-executive"), Catalog());
    int received = 0;
    runtime::Reader<msgs::MissionGoalPubSubType> reader(
        plain, executor, "mission/goal", [&](const msgs::MissionGoal& g) {
          if (g.goal_id() == "cyclone") received++;
        });
    launch::ChildProcess control("cyclone", {STICKREP_CYCLONE_PEER,
                                             std::to_string(kControlDomain), "8", kGoalTarget});
    const double until = WallNowS() + 30.0;
    while (!control.Exited() && WallNowS() < until) {
      executor.SpinOnce(std::chrono::milliseconds(20));
      control.ReadLines();
    }
    control.ReadLines(true);
    std::printf("[security] control, Cyclone DDS peer beside a plain reader: %s; %d goals "
                "received\n", control.output().c_str(), received);
    ASSERT_GT(received, 0) << "the Cyclone peer does not reach a plain Fast DDS reader here: "
                              "its result against the stack would prove nothing\n"
                           << control.output();
  }
  launch::ChildProcess peer("cyclone", {STICKREP_CYCLONE_PEER, std::to_string(kDomain),
                                        std::to_string(kAttackWindowS), kGoalTarget});
  ExpectNothingMovesDuring([&] { peer.ReadLines(); });
  ASSERT_TRUE(WaitFor([&] { return peer.Exited(); }, 20.0));
  peer.ReadLines(true);
  EXPECT_EQ(peer.exit_code(), 0) << peer.output();
  EXPECT_NE(peer.output().find("matched_readers=0 "), std::string::npos) << peer.output();
  EXPECT_NE(peer.output().find("topics=\n"), std::string::npos) << peer.output();
  std::printf("[security] Cyclone DDS peer against the secured stack: %s", peer.output().c_str());
}

TEST_F(SecuredStackTest, CameraIdentityMayNotWriteGoalsOrMotionCommands) {
  runtime::Participant camera(Config(kDomain, "stickrep-camera-impostor", g_stack->keys, "camera"),
                              Catalog());
  // Its own stream is allowed (so the identity itself is good)...
  runtime::Writer<msgs::ImagePubSubType> images(camera, "robot/camera/image");
  // ...goals and motion commands are not: access control refuses the writers.
  try {
    runtime::Writer<msgs::MissionGoalPubSubType> goals(camera, "mission/goal");
    FAIL() << "the camera's identity got a writer on mission/goal";
  } catch (const std::runtime_error& e) {
    std::printf("[security] camera identity on mission/goal: refused (%s)\n", e.what());
  }
  EXPECT_THROW(runtime::Writer<msgs::MotionCommandPubSubType>(camera, "robot/motion/command"),
               std::runtime_error);
  EXPECT_THROW(runtime::Writer<msgs::WheelCommandPubSubType>(camera, "device/base/wheel_command"),
               std::runtime_error);
  EXPECT_EQ(g_stack->mission_state, "LOCALIZED");
}

TEST_F(SecuredStackTest, CameraIdentityWithSelfSignedPermissionsIsNotMatchedAndMovesNothing) {
  // The camera's genuine certificate and key, but the permissions CA, governance and a
  // permissions document granting mission/goal and robot/motion/command all from another
  // permissions CA: the camera's own plugin accepts them, the stack's must not.
  const std::string dir = g_stack->keys + "_forged_camera";
  const std::string& k = g_stack->keys;
  const std::string& r = g_stack->rogue_keys;
  const auto [rc, out] = Shell(
      "set -e; mkdir -p " + dir + "/camera; cp " + k + "/identity_ca.cert.pem " + dir +
      "/; cp " + k + "/camera/cert.pem " + k + "/camera/key.pem " + dir + "/camera/; cp " + r +
      "/permissions_ca.cert.pem " + r + "/governance.p7s " + dir + "/; sed s/CN=executive,/CN=camera,/ " +
      r + "/executive/permissions.xml > " + dir + "/camera/permissions.xml; openssl smime -sign "
      "-text -in " + dir + "/camera/permissions.xml -out " + dir + "/camera/permissions.p7s "
      "-signer " + r + "/permissions_ca.cert.pem -inkey " + r + "/private/permissions_ca.key.pem");
  ASSERT_EQ(rc, 0) << out;
  runtime::Participant camera(Config(kDomain, "stickrep-camera-impostor", dir, "camera"),
                              Catalog());
  AttackWithGoalsAndCommands(camera, "camera", "camera identity with self-signed permissions");
}

TEST_F(SecuredStackTest, IdentityOfAnotherCaIsNotAuthenticatedAndMovesNothing) {
  // A forged "executive": its certificate, key and permissions (which allow goals and motion
  // commands) are all genuine, but made by a CA the stack does not trust.
  runtime::Participant forged(
      Config(kDomain, "stickrep-executive", g_stack->rogue_keys, "executive"), Catalog());
  AttackWithGoalsAndCommands(forged, "forged", "forged executive (other CA)");
  // The stack's processes say so (WatchAuthentication, checked every second).
  EXPECT_TRUE(WaitFor([] { return StackSaid("failed authentication: ignored"); }, 5.0))
      << Output();
}

// Last, as it moves the robot: the console's identity may send goals, and the executive
// answers (the attackers' goals above would have been answered too, had they arrived).
TEST_F(SecuredStackTest, ConsoleIdentityGoalIsAnswered) {
  runtime::Writer<msgs::MissionGoalPubSubType> goals(*g_stack->observer, "mission/goal");
  msgs::MissionGoal goal;
  goal.goal_id("operator");
  goal.target(kGoalTarget);
  ASSERT_TRUE(WaitFor(
      [&] {
        goals.Publish(goal, runtime::WallClockNowNs());
        WaitFor([] { return !g_stack->goal_results.empty(); }, 0.5);
        return !g_stack->goal_results.empty();
      },
      30.0))
      << Output();
  const msgs::MissionGoalResult& r = g_stack->goal_results.front();
  EXPECT_EQ(r.goal_id(), "operator");
  std::printf("[security] console identity's goal: %s (%s)\n",
              r.accepted() ? "accepted" : "refused", r.reason().c_str());
}

}  // namespace
}  // namespace stickrep::test
