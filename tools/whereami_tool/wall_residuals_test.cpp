// The measured walls' length errors beside the Bayes matcher's wall model.
#include "whereami_tool/wall_residuals.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace stickrep::whereami {
namespace {

using End = EdgeErrorCounts::WallEnd;

EdgeErrorCounts::WallResidual Residual(double error_in, End start, End end, bool over_missed) {
  EdgeErrorCounts::WallResidual r;
  r.error_in = error_in;
  r.true_in = 82.0;
  r.start = start;
  r.end = end;
  r.over_missed = over_missed;
  return r;
}

// The line of `label` in `text`.
std::string LineOf(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  if (at == std::string::npos) return "";
  return text.substr(at, text.find('\n', at) - at);
}

TEST(WallResidualsTest, EachWallCountsOnceUnderTheFirstKindItIsAndInUnitsOfTheMatchersSigma) {
  EdgeErrorCounts c;
  // Over a missed door (though beside a mis-sized one too), beside a mis-sized door, two
  // between doors read right.
  c.wall_residuals = {Residual(4.0, End::kDoorMissized, End::kDoorRight, true),
                      Residual(-2.0, End::kDoorRight, End::kDoorMissized, false),
                      Residual(1.0, End::kDoorRight, End::kDoorRight, false),
                      Residual(-1.0, End::kDoorRight, End::kDoorRight, false)};
  c.wall_ends = 10;
  c.wall_ends_off_node = 2;
  c.walls_by_missed[1][1][0] = {4, 3, 184.0};
  recovery::SensingNoise noise;
  noise.jamb_sigma_in = 1.0;
  noise.wheel_scale_sigma_rel = 0.0;
  noise.wheel_walk_sigma_in_per_sqrt_in = 0.0;  // sigma sqrt(2) in for every wall
  std::ostringstream out;
  PrintWallResiduals(c, noise, out);
  const std::string text = out.str();
  EXPECT_NE(text.find("4 (2 of 10 wall ends"), std::string::npos) << text;
  // Over the missed door: one wall, +4 in, over 3 in, rms z 4 / sqrt(2).
  EXPECT_NE(LineOf(text, "over a missed door").find("1   +4.00"), std::string::npos) << text;
  EXPECT_NE(LineOf(text, "over a missed door").find("2.83"), std::string::npos) << text;
  EXPECT_NE(LineOf(text, "beside a door read mis-sized").find("1   -2.00"), std::string::npos)
      << text;
  // Between doors read right: +1 and -1, mean 0, sd sqrt(2), none over 3 in, rms z 1/sqrt(2).
  const std::string right = LineOf(text, "between two doors read right");
  EXPECT_NE(right.find("2   +0.00   1.41    0.0    0.0    0.71"), std::string::npos) << text;
  EXPECT_NE(LineOf(text, "walls under 60 in").find("missed/seen 3/4 (75.0 %)"), std::string::npos)
      << text;
}

}  // namespace
}  // namespace stickrep::whereami
