#include "whereami_tool/wall_residuals.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace stickrep::whereami {

namespace {

using End = EdgeErrorCounts::WallEnd;
using Residual = EdgeErrorCounts::WallResidual;

// The kinds of wall printed, in order: a wall counts in the first whose test it passes.
struct WallKind {
  const char* label;
  bool (*is)(const Residual&);
};

bool Has(const Residual& r, End e) { return r.start == e || r.end == e; }

constexpr WallKind kKinds[] = {
    {"over a missed door", [](const Residual& r) { return r.over_missed; }},
    {"beside a door read mis-sized", [](const Residual& r) { return Has(r, End::kDoorMissized); }},
    {"between two doors read right",
     [](const Residual& r) { return r.start == End::kDoorRight && r.end == End::kDoorRight; }},
    {"between a door read right and another node",
     [](const Residual& r) { return Has(r, End::kDoorRight); }},
    {"between two other nodes", [](const Residual&) { return true; }},
};

void PrintKind(const char* label, const std::vector<Residual>& walls,
               const recovery::SensingNoise& noise, std::ostream& out) {
  if (walls.empty()) {
    out << fmt::format("    {:<40} {:>5}\n", label, 0);
    return;
  }
  double mean = 0.0, z2 = 0.0;
  long over3 = 0, over6 = 0;
  std::vector<double> lengths;
  for (const Residual& r : walls) {
    mean += r.error_in;
    over3 += std::abs(r.error_in) > 3.0;
    over6 += std::abs(r.error_in) > 6.0;
    const double sigma = std::max(1.0, noise.WallSigmaIn(r.true_in));
    z2 += (r.error_in / sigma) * (r.error_in / sigma);
    lengths.push_back(r.true_in);
  }
  const double n = static_cast<double>(walls.size());
  mean /= n;
  double sq = 0.0;
  for (const Residual& r : walls) sq += (r.error_in - mean) * (r.error_in - mean);
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  out << fmt::format("    {:<40} {:>5} {:>+7.2f} {:>6.2f} {:>6.1f} {:>6.1f} {:>7.2f} {:>7.0f}\n",
                     label, walls.size(), mean, std::sqrt(sq / std::max(1.0, n - 1.0)),
                     100.0 * over3 / n, 100.0 * over6 / n, std::sqrt(z2 / n),
                     lengths[lengths.size() / 2]);
}

}  // namespace

void PrintWallResiduals(const EdgeErrorCounts& total, const recovery::SensingNoise& noise,
                        std::ostream& out) {
  out << fmt::format(
      "  sensed walls with both ends within {:g} in of a true node: {} ({} of {} wall ends "
      "farther from every node; {} walls at a corner left out); sensed - true length (in), by "
      "what bounds the wall:\n",
      EdgeErrorCounts::kNodeNearIn, total.wall_residuals.size(), total.wall_ends_off_node,
      total.wall_ends, total.walls_at_corners);
  out << fmt::format("    {:<40} {:>5} {:>7} {:>6} {:>6} {:>6} {:>7} {:>7}\n", "", "walls", "mean",
                     "sd", ">3in%", ">6in%", "rms z", "med in");
  std::vector<std::vector<Residual>> by_kind(std::size(kKinds));
  for (const Residual& r : total.wall_residuals) {
    for (std::size_t k = 0; k < std::size(kKinds); ++k) {
      if (kKinds[k].is(r)) {
        by_kind[k].push_back(r);
        break;
      }
    }
  }
  for (std::size_t k = 0; k < std::size(kKinds); ++k) {
    PrintKind(kKinds[k].label, by_kind[k], noise, out);
  }
  out << "  walls between two doors that held a false door, by the doors before and after them "
         "(in travel) missed or seen:\n";
  for (int w = 0; w < 2; ++w) {
    std::string line = w == 0 ? "    walls of 60 in or more:" : "    walls under 60 in:     ";
    for (int b = 0; b < 2; ++b) {
      for (int a = 0; a < 2; ++a) {
        const EdgeErrorCounts::WallTally& t = total.walls_by_missed[w][b][a];
        line +=
            fmt::format("  {}/{} {}/{} ({:.1f} %)", b ? "missed" : "seen", a ? "missed" : "seen",
                        t.false_doors, t.walls, 100.0 * t.false_doors / std::max<long>(1, t.walls));
      }
    }
    out << line << "\n";
  }
  out << "    (rms z: the errors in units of the matcher's sigma for each wall, "
         "SensingNoise::WallSigmaIn; 1 when walls are read as the matcher weighs them)\n";
}

}  // namespace stickrep::whereami
