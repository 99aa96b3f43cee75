#pragma once

// Order statistics of a sample, for the figures the processes and tools print.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace stickrep {

// The q-quantile (0 <= q <= 1) by the nearest rank of (n - 1) q; 0 for an empty sample.
inline double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const double r = std::clamp(q, 0.0, 1.0) * static_cast<double>(v.size() - 1);
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(r + 0.5));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The median; the mean of the two middle values of an even sample; 0 for an empty one.
inline double Median(std::vector<double> v) {
  const std::size_t n = v.size();
  if (n == 0) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2), v.end());
  const double upper = v[n / 2];
  if (n % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2)));
}

}  // namespace stickrep
