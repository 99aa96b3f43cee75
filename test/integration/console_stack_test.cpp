// The console against live processes: `doctor` names a command stream that stops as a missed
// deadline and a process killed with SIGKILL as lost liveliness of its heartbeat; a console
// stopped with SIGSTOP for 10 s slows no stream of the whole stack.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "console/message_types.h"
#include "process_fixture.h"
#include "runtime/endpoint.h"
#include "runtime/raw_endpoint.h"
#include "basePubSubTypes.h"

namespace stickrep::test {
namespace {

constexpr int kDomainId = 37;

double SteadyNowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

class ConsoleStackTest : public ProcessFixture {
 protected:
  ConsoleStackTest() : ProcessFixture(kDomainId) {}
};

TEST_F(ConsoleStackTest, DoctorNamesAMissedDeadlineAndAKilledProcessesLostLiveliness) {
  launch::ChildProcess& camera = Start("stickrep-camera");
  // robot/motion/command (deadline 0.5 s) written at 10 Hz by this test until the kill.
  runtime::Writer<msgs::MotionCommandPubSubType> commands(participant(), "robot/motion/command");
  std::atomic<bool> writing{true};
  std::thread writer([&] {
    for (int k = 1; writing; ++k) {
      msgs::MotionCommand c;
      c.mode(msgs::MOTION_STOP);
      commands.Publish(c, k);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  });
  // The camera is up once its heartbeat is seen.
  ASSERT_TRUE(SpinUntil(
      [&] {
        for (const auto& t : Topics()) {
          if (t.topic == "system/status" && t.writers >= 1) return true;
        }
        return false;
      },
      20.0))
      << Outputs();
  // The doctor listens to discovery for 4 s (a process announces itself every 3 s), then
  // reads the timed topics for 8 s; the camera dies and the commands stop 7 s after it
  // started, inside that window.
  launch::ChildProcess doctor(
      "doctor", {BinPath("stickrep-console"), "--domain", std::to_string(kDomainId), "doctor",
                 "--wait", "4", "--watch", "8", "--json"});
  const double started = SteadyNowS();
  SpinUntil([&] { return SteadyNowS() - started >= 7.0 || doctor.Exited(); }, 15.0);
  writing = false;
  writer.join();
  camera.Signal(SIGKILL);
  ASSERT_TRUE(doctor.WaitExit(60.0)) << "the doctor did not end";
  doctor.ReadLines(/*flush_partial=*/true);
  const std::string out = doctor.output();
  EXPECT_EQ(doctor.exit_code(), 1) << out;  // faults found
  const auto report = nlohmann::json::parse(out.substr(out.find('{')));
  bool deadline = false, liveliness = false;
  for (const auto& f : report.at("findings")) {
    const std::string problem = f.at("problem"), topic = f.at("topic");
    if (problem == "missed deadline" && topic == "robot/motion/command") {
      deadline = true;
      EXPECT_EQ(f.at("policy"), "deadline");
      EXPECT_NE(f.at("writer").get<std::string>().find("stickrep-test offers 0.5 s"),
                std::string::npos) << f.dump();
    }
    if (problem == "lost liveliness" && topic == "system/status") {
      liveliness = true;
      EXPECT_EQ(f.at("policy"), "liveliness lease");
      EXPECT_NE(f.at("writer").get<std::string>().find("camera"), std::string::npos) << f.dump();
    }
  }
  EXPECT_TRUE(deadline) << out;
  EXPECT_TRUE(liveliness) << out;
}

}  // namespace
}  // namespace stickrep::test

namespace stickrep::test {
namespace {

int64_t WallNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// What this test's own reader of one topic received: DDS reception and source timestamps.
struct Arrival {
  int64_t reception_ns;
  int64_t source_ns;
};

// Rate and source-to-reception delay of the samples received in [from_ns, to_ns).
struct Window {
  std::size_t n = 0;
  double rate_hz = 0.0;
  double delay_p50_ms = 0.0;
  double delay_p99_ms = 0.0;
};

Window Measure(const std::vector<Arrival>& all, int64_t from_ns, int64_t to_ns) {
  std::vector<double> delays_ms;
  for (const Arrival& a : all) {
    if (a.reception_ns >= from_ns && a.reception_ns < to_ns) {
      delays_ms.push_back((a.reception_ns - a.source_ns) * 1e-6);
    }
  }
  Window w;
  w.n = delays_ms.size();
  w.rate_hz = w.n / ((to_ns - from_ns) * 1e-9);
  if (w.n == 0) return w;
  std::sort(delays_ms.begin(), delays_ms.end());
  w.delay_p50_ms = delays_ms[w.n / 2];
  w.delay_p99_ms = delays_ms[std::min(w.n - 1, w.n * 99 / 100)];
  return w;
}

// Runs `stickrep-console ARGS` on the test's domain to its end (bounded); exit code, output.
std::pair<int, std::string> RunConsole(const std::string& system, std::vector<std::string> args) {
  std::vector<std::string> argv{BinPath("stickrep-console"), "--domain", std::to_string(kDomainId),
                                "--system", system};
  argv.insert(argv.end(), args.begin(), args.end());
  launch::ChildProcess console("console", argv);
  if (!console.WaitExit(60.0)) {
    console.Signal(SIGKILL);
    console.WaitExit(5.0);
    return {-1, "did not end: " + console.output()};
  }
  console.ReadLines(/*flush_partial=*/true);
  return {console.exit_code(), console.output()};
}

// Every verb once against the running stack (the pose is recovered by now or soon).
void ExpectEveryVerbAnswers(const std::string& system) {
  const auto expect = [&](std::vector<std::string> args, const std::string& shows) {
    std::string line;
    for (const auto& a : args) line += a + " ";
    const auto [rc, out] = RunConsole(system, args);
    EXPECT_EQ(rc, 0) << line << "\n" << out;
    EXPECT_NE(out.find(shows), std::string::npos) << line << "\n" << out;
  };
  expect({"list"}, "robot/motion/command");
  expect({"info", "robot/motion/command"}, "stickrep-executive");
  expect({"echo", "robot/odometry", "--once", "--timeout", "10"}, "\"distance_in\"");
  expect({"echo", "system/status", "--once", "--field", "state", "--timeout", "10"}, "COMPONENT_");
  expect({"hz", "robot/sonar", "--duration", "2.5"}, "robot/sonar: average rate");
  expect({"delay", "robot/camera/image", "--duration", "2.5"}, "source timestamp to reception");
  expect({"bw", "--duration", "2", "--json"}, "\"topic\":\"robot/camera/image\"");
  expect({"status", "--once"}, "localizer");
  expect({"pose", "--once", "--json", "--timeout", "60"}, "\"wing1_corridor\"");
  // The goal's answer is structured; a goal before the pose is refused with a reason.
  const auto [goal_rc, goal] = RunConsole(system, {"goal", "wing1_corridor/50", "--timeout", "20"});
  EXPECT_NE(goal.find("goal 'console' (wing1_corridor/50): "), std::string::npos) << goal;
  EXPECT_TRUE(goal_rc == 0 || goal.find("refused") != std::string::npos) << goal;
}

// The stack on the small map at 1x real time; this test reads seven of its streams while a
// console reading every topic (`bw`) is stopped with SIGSTOP for 10 s. A writer that waited
// for the stopped reader (a full history, a full shared-memory port) would show as a rate
// drop or a delay during the stop.
TEST_F(ConsoleStackTest, AConsoleStoppedFor10sSlowsNoStreamAndEveryVerbAnswers) {
  const std::vector<std::string> probed = {"robot/camera/image", "robot/sonar",
                                           "robot/odometry",     "robot/motion/command",
                                           "robot/motion/state", "system/status",
                                           "localization/pose"};
  std::map<std::string, std::vector<Arrival>> arrivals;
  std::vector<std::unique_ptr<runtime::RawReader>> readers;
  for (const std::string& topic : probed) {
    const console::MessageType* type = console::TypeOfTopic(topic);
    ASSERT_NE(type, nullptr) << topic;
    auto& into = arrivals[topic];
    readers.push_back(std::make_unique<runtime::RawReader>(
        participant(), executor(), topic, type->make_support, participant().catalog().ForTopic(topic),
        [&into](const runtime::RawSample&, const runtime::RawSampleInfo& i) {
          into.push_back({i.reception_ns, i.source_ns});
        }));
  }
  const std::string system = SmallMapSystem("sigstop_system.yaml");
  Start("stickrep-virtual-robot",
        {"--system", system, "--config",
         WriteTempFile("sigstop_vr.yaml",
                       ConfigWith("virtual_robot.yaml",
                                  {{"real_time_factor", "1"}, {"summary_png", "\"\""}}))});
  for (const char* exe : {"stickrep-sonar", "stickrep-camera", "stickrep-locomotion",
                          "stickrep-landmark", "stickrep-localizer", "stickrep-executive"}) {
    Start(exe, {"--system", system});
  }
  ASSERT_TRUE(SpinUntil(
      [&] {
        return std::all_of(probed.begin(), probed.end(),
                           [&](const std::string& t) { return !arrivals[t].empty(); });
      },
      60.0))
      << Outputs();
  launch::ChildProcess& console =
      Start("stickrep-console", {"--system", system, "bw", "--wait", "5", "--duration", "300"});
  // The console's readers are on every probed topic.
  ASSERT_TRUE(SpinUntil(
      [&] {
        std::size_t seen = 0;
        for (const std::string& t : probed) {
          for (const auto& e : participant().discovery().Endpoints()) {
            if (e.topic == t && !e.is_writer && e.participant == "stickrep-console") {
              ++seen;
              break;
            }
          }
        }
        return seen == probed.size();
      },
      30.0))
      << [&] {
           std::string readers;
           for (const auto& e : participant().discovery().Endpoints()) {
             if (!e.is_writer) readers += e.topic + " <- " + e.participant + "\n";
           }
           return readers;
         }() << Outputs();
  const auto spin_for = [&](double s) {
    const int64_t until = WallNowNs() + static_cast<int64_t>(s * 1e9);
    SpinUntil([&] { return WallNowNs() >= until; }, s + 10.0);
  };
  spin_for(10.0);
  const int64_t stopped = WallNowNs();
  console.Signal(SIGSTOP);
  spin_for(10.0);
  const int64_t continued = WallNowNs();
  console.Signal(SIGCONT);
  spin_for(5.0);
  const int64_t end = WallNowNs();
  std::printf("[sigstop] %-22s %28s %28s %28s\n", "topic", "10 s before: Hz p50/p99 ms",
              "10 s stopped: Hz p50/p99 ms", "5 s after: Hz p50/p99 ms");
  for (const std::string& t : probed) {
    const Window before = Measure(arrivals[t], stopped - 10'000'000'000, stopped);
    const Window during = Measure(arrivals[t], stopped, continued);
    const Window after = Measure(arrivals[t], continued, end);
    const auto cell = [](const Window& w) {
      return fmt::format("{:6.1f} {:7.2f}/{:7.2f}", w.rate_hz, w.delay_p50_ms, w.delay_p99_ms);
    };
    std::printf("[sigstop] %-22s %28s %28s %28s\n", t.c_str(), cell(before).c_str(),
                cell(during).c_str(), cell(after).c_str());
    ASSERT_GT(before.n, 0u) << t;
    // Not held up: the samples while the console is stopped, and after, stay within 20 % of
    // the rate before (a writer blocked on the stopped reader would stall for whole
    // seconds), give or take the one sample a window's edge can cut off: the pose comes at
    // 2 Hz and on events, 9 or 10 periodic ones in 5 s.
    const auto enough = [&](const Window& w, double seconds) {
      return static_cast<double>(w.n + 1) >= 0.8 * before.rate_hz * seconds;
    };
    EXPECT_TRUE(enough(during, 10.0)) << t << ": " << during.n << " samples in 10 s";
    EXPECT_TRUE(enough(after, 5.0)) << t << ": " << after.n << " samples in 5 s";
  }
  // The stopped console itself carries on, and Ctrl-C ends it with 0.
  console.Signal(SIGINT);
  ASSERT_TRUE(console.WaitExit(30.0)) << Outputs();
  EXPECT_EQ(console.exit_code(), 0) << Outputs();
  ExpectEveryVerbAnswers(system);
  StopAllAndExpectCleanExit();
}

}  // namespace
}  // namespace stickrep::test
