#include "console/topic_stats.h"

#include <algorithm>
#include <cmath>

namespace stickrep::console {

Spread SpreadOf(const std::vector<double>& v) {
  Spread s;
  s.n = v.size();
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  double sq = 0.0;
  for (double x : v) sq += (x - s.mean) * (x - s.mean);
  s.stddev = std::sqrt(sq / v.size());
  return s;
}

void TopicWindow::Add(std::int64_t source_ns, std::int64_t reception_ns, std::size_t bytes) {
  samples_.push_back({source_ns, reception_ns, bytes});
  if (samples_.size() > window_) samples_.pop_front();
  total_++;
}

Spread TopicWindow::Period() const {
  std::vector<double> periods;
  for (std::size_t k = 1; k < samples_.size(); ++k) {
    periods.push_back((samples_[k].reception_ns - samples_[k - 1].reception_ns) * 1e-9);
  }
  return SpreadOf(periods);
}

Spread TopicWindow::DelayMs() const {
  std::vector<double> delays;
  for (const Sample& s : samples_) delays.push_back((s.reception_ns - s.source_ns) * 1e-6);
  return SpreadOf(delays);
}

double TopicWindow::MeanBytes() const {
  if (samples_.empty()) return 0.0;
  double sum = 0.0;
  for (const Sample& s : samples_) sum += s.bytes;
  return sum / samples_.size();
}

namespace {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::vector<std::string> CloseNames(const std::string& name, const std::vector<std::string>& known) {
  const std::size_t limit = std::max<std::size_t>(3, name.size() / 3);
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const std::string& k : known) {
    const std::size_t d = EditDistance(name, k);
    if (d <= limit) scored.push_back({d, k});
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& [d, k] : scored) out.push_back(k);
  return out;
}

}  // namespace stickrep::console
