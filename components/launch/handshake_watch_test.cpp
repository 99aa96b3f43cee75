#include "launch/handshake_watch.h"

#include <gtest/gtest.h>

#include <string>

namespace stickrep::launch {
namespace {

std::string Identity(const std::string& name) {
  return "08:26:28.565 [" + name + "] info secured: identity '" + name +
         "' of /tmp/keys (participant stickrep-" + name + ")";
}

std::string Authenticated(const std::string& name) {
  return "08:34:32.697 [x] info DDS Security: participant b9.d2.9f.69.a0.5e.f0.15.78.d0.f1.58 "
         "(stickrep-" + name + ") authenticated";
}

// Three secured processes started together; sonar and camera authenticate each other (one
// side is enough), camera and locomotion too, sonar and locomotion never do.
class HandshakeWatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* p : {"sonar", "camera", "locomotion"}) {
      watch_.Started(p, 0.0);
      watch_.Line(p, Identity(p));
    }
    watch_.Line("sonar", Authenticated("camera"));
    watch_.Line("locomotion", Authenticated("camera"));
    watch_.Line("camera", Authenticated("locomotion"));
  }
  HandshakeWatch watch_{20.0, 2};
};

TEST_F(HandshakeWatchTest, APairIsNotStuckBeforeTheTimeout) {
  EXPECT_TRUE(watch_.Check(19.9).empty());
}

TEST_F(HandshakeWatchTest, APairThatNeverAuthenticatedIsStuckAndTheLaterStartedIsRestarted) {
  watch_.Started("locomotion", 1.0);  // started a second after the others
  watch_.Line("locomotion", Identity("locomotion"));
  watch_.Line("locomotion", Authenticated("camera"));
  const auto stuck = watch_.Check(21.5);
  ASSERT_EQ(stuck.size(), 1u);
  EXPECT_EQ(stuck[0].restart, "locomotion");
  EXPECT_EQ(stuck[0].other, "sonar");
  EXPECT_DOUBLE_EQ(stuck[0].together_s, 20.5);
  // Reported once: the process is being restarted.
  EXPECT_TRUE(watch_.Check(22.0).empty());
}

TEST_F(HandshakeWatchTest, ARestartedProcessStartsItsClockAgainAndIsHealedWhenItAuthenticates) {
  const auto stuck = watch_.Check(25.0);
  ASSERT_EQ(stuck.size(), 1u);
  const std::string restarted = stuck[0].restart;
  watch_.Stopped(restarted);
  watch_.Started(restarted, 26.0);
  watch_.Line(restarted, Identity(restarted));
  EXPECT_TRUE(watch_.Check(45.0).empty());  // 19 s together
  watch_.Line(restarted, Authenticated("sonar"));
  EXPECT_TRUE(watch_.Check(100.0).empty());
}

TEST_F(HandshakeWatchTest, APairStillStuckAfterItsHealsIsLeftAlone) {
  for (int i = 0; i < 2; ++i) {
    const double t = 30.0 * (i + 1);
    ASSERT_EQ(watch_.Check(t).size(), 1u) << "heal " << i + 1;
    watch_.Stopped("locomotion");
    watch_.Started("locomotion", t);
    watch_.Line("locomotion", Identity("locomotion"));
    watch_.Line("locomotion", Authenticated("camera"));
  }
  EXPECT_TRUE(watch_.Check(1000.0).empty());
}

TEST_F(HandshakeWatchTest, AStoppedProcessOrOneNotYetNamedIsNotJudged) {
  watch_.Stopped("sonar");
  EXPECT_TRUE(watch_.Check(100.0).empty());
  HandshakeWatch fresh(20.0, 2);
  fresh.Started("a", 0.0);
  fresh.Started("b", 0.0);
  fresh.Line("a", Identity("a"));  // b never said which participant it is (not secured)
  EXPECT_TRUE(fresh.Check(100.0).empty());
}

TEST_F(HandshakeWatchTest, ATimeoutOfZeroNeverReports) {
  HandshakeWatch off(0.0, 2);
  off.Started("a", 0.0);
  off.Started("b", 0.0);
  off.Line("a", Identity("a"));
  off.Line("b", Identity("b"));
  EXPECT_TRUE(off.Check(1000.0).empty());
}

}  // namespace
}  // namespace stickrep::launch
