#include "console/doctor.h"

#include <gtest/gtest.h>

namespace stickrep::console {
namespace {

TEST(DoctorTimelinessTest, NamesTheDeadlineAndEachWriterThatLapsed) {
  TimelinessWatch command{"robot/motion/command", 0.5, 0.0, 8.0, {"executive"}, 7, {}, 1};
  TimelinessWatch status{"system/status", 0.0, 1.0, 8.0, {"camera", "sonar"}, 0,
                         {"sonar", "camera", "sonar"}, 0};
  TimelinessWatch quiet{"robot/motion/command", 0.5, 0.0, 8.0, {"executive"}, 0, {}, 1};
  const auto f = DiagnoseTimeliness({command, status, quiet});
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].problem, "missed deadline");
  EXPECT_EQ(f[0].policy, "deadline");
  EXPECT_EQ(f[0].writer, "executive offers 0.5 s");
  EXPECT_EQ(f[0].detail,
            "robot/motion/command: 7 deadlines of 0.5 s passed with no sample in the 8 s watched");
  EXPECT_EQ(f[1].problem, "lost liveliness");
  EXPECT_EQ(f[1].writer, "camera (lease 1 s)");
  EXPECT_EQ(f[2].writer, "sonar (lease 1 s)");
  EXPECT_NE(f[2].detail.find("sonar lost its liveliness 2 time(s)"), std::string::npos) << f[2].detail;
  for (const Finding& x : f) EXPECT_TRUE(IsFault(x));
  EXPECT_FALSE(IsFault(Finding{"a", "no reader", "", "w", "", ""}));
}

}  // namespace
}  // namespace stickrep::console
