#include "executive/link_monitor.h"

#include <gtest/gtest.h>

namespace stickrep::executive {
namespace {

using Kind = LinkMonitor::Event::Kind;

// Heartbeats at 1 Hz from sonar and camera on "robot" and localizer on "base" (the
// executive's own host), from t0 to t1 inclusive.
void Beat(LinkMonitor& m, const std::vector<std::string>& robot, double t0, double t1) {
  for (double t = t0; t <= t1 + 1e-9; t += 1.0) {
    for (const auto& n : robot) m.OnHeartbeat(n, "robot", t);
    m.OnHeartbeat("localizer", "base", t + 0.3);
  }
}

std::vector<LinkMonitor::Event> TickUntil(LinkMonitor& m, double t0, double t1) {
  std::vector<LinkMonitor::Event> all;
  for (double t = t0; t <= t1 + 1e-9; t += 0.1) {
    for (auto& e : m.Tick(t)) all.push_back(e);
  }
  return all;
}

TEST(LinkMonitorTest, EveryProcessOfAHostSilentIsALostHostNotDeadProcesses) {
  LinkMonitor m("base", 3.0, 2.0);
  Beat(m, {"sonar", "camera"}, 0.0, 10.0);
  // The link goes at 10.5: robot processes fall silent, the base's localizer goes on.
  for (double t = 11.0; t <= 16.0; t += 1.0) m.OnHeartbeat("localizer", "base", t + 0.3);
  m.OnSilent("sonar", "liveliness lost", 12.0);
  const auto events = TickUntil(m, 10.6, 16.0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, Kind::kHostLost);
  EXPECT_EQ(events[0].host, "robot");
  EXPECT_EQ(events[0].processes, (std::vector<std::string>{"camera", "sonar"}));
  EXPECT_TRUE(m.HostLost("robot"));
}

TEST(LinkMonitorTest, TheHostIsBackWhenEachOfItsProcessesIsHeardAgain) {
  LinkMonitor m("base", 3.0, 2.0);
  Beat(m, {"sonar", "camera"}, 0.0, 10.0);
  TickUntil(m, 10.1, 16.0);
  ASSERT_TRUE(m.HostLost("robot"));
  EXPECT_TRUE(m.OnHeartbeat("sonar", "robot", 20.0).empty());
  const auto back = m.OnHeartbeat("camera", "robot", 20.2);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].kind, Kind::kHostBack);
  EXPECT_NEAR(back[0].outage_s, 10.2, 1e-9);
  EXPECT_FALSE(m.HostLost("robot"));
}

TEST(LinkMonitorTest, OneSilentProcessAmongLiveOnesIsDead) {
  LinkMonitor m("base", 3.0, 2.0);
  Beat(m, {"sonar", "camera"}, 0.0, 10.0);
  Beat(m, {"camera"}, 11.0, 20.0);  // sonar died after its beat at 10
  m.OnSilent("sonar", "its heartbeat's liveliness was lost", 11.5);
  const auto events = TickUntil(m, 10.1, 20.0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, Kind::kProcessGone);
  EXPECT_EQ(events[0].processes.front(), "sonar");
  EXPECT_EQ(events[0].why, "its heartbeat's liveliness was lost");
  EXPECT_FALSE(m.HostLost("robot"));
}

TEST(LinkMonitorTest, OnTheExecutivesOwnHostSilenceIsAlwaysDeath) {
  LinkMonitor m("robot", 3.0, 2.0);
  Beat(m, {"sonar"}, 0.0, 10.0);
  for (double t = 11.0; t <= 16.0; t += 1.0) m.OnHeartbeat("localizer", "base", t + 0.3);
  const auto events = TickUntil(m, 10.1, 16.0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, Kind::kProcessGone);
  EXPECT_EQ(events[0].why, "no heartbeat for 3.0 s");  // the monitor built with 3 s
}

TEST(LinkMonitorTest, OnTheExecutivesOwnHostASuspectIsDeadWithoutSettling) {
  LinkMonitor m("robot", 3.0, 2.0);
  for (double t = 0.0; t <= 10.0; t += 1.0) m.OnHeartbeat("sonar", "robot", t);
  m.OnSilent("sonar", "its heartbeat's liveliness was lost", 11.0);
  const auto events = m.Tick(11.05);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, Kind::kProcessGone);
}

TEST(LinkMonitorTest, ADeadProcessHeardAgainIsAliveAndCanDieAgain) {
  LinkMonitor m("robot", 3.0, 2.0);
  for (double t = 0.0; t <= 10.0; t += 1.0) m.OnHeartbeat("sonar", "robot", t);
  m.OnSilent("sonar", "liveliness lost", 11.0);
  ASSERT_EQ(m.Tick(11.1).size(), 1u);
  EXPECT_TRUE(m.OnHeartbeat("sonar", "robot", 14.0).empty());  // restarted
  for (double t = 14.5; t <= 16.0; t += 0.5) m.OnHeartbeat("sonar", "robot", t);
  EXPECT_TRUE(TickUntil(m, 14.1, 16.0).empty());
  m.OnSilent("sonar", "liveliness lost", 16.5);
  const auto again = m.Tick(16.6);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].kind, Kind::kProcessGone);
}

TEST(LinkMonitorTest, AProcessThatDoesNotComeBackWithItsHostIsDead) {
  LinkMonitor m("base", 3.0, 2.0);
  Beat(m, {"sonar", "camera"}, 0.0, 10.0);
  TickUntil(m, 10.1, 16.0);
  m.OnHeartbeat("camera", "robot", 20.0);
  const auto events = TickUntil(m, 20.1, 23.0);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, Kind::kProcessGone);
  EXPECT_EQ(events[0].processes.front(), "sonar");
  EXPECT_EQ(events[1].kind, Kind::kHostBack);
}

TEST(LinkMonitorTest, AStoppedProcessIsGoneAtOnceAndOnlyOnce) {
  LinkMonitor m("base", 3.0, 2.0);
  m.OnHeartbeat("sonar", "robot", 0.0);
  ASSERT_EQ(m.OnStopped("sonar").size(), 1u);
  EXPECT_TRUE(m.OnStopped("sonar").empty());
  EXPECT_TRUE(TickUntil(m, 0.1, 10.0).empty());
}

}  // namespace
}  // namespace stickrep::executive
