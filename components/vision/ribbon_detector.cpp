#include "vision/ribbon_detector.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stickrep::vision {
namespace {

// The 5x5 vertical Prewitt kernel used here: every row is [-2 -1 0 1 2] (a horizontal
// central difference averaged over five rows, so it "rejected horizontal features" and
// "averaged vertical features", §4.1.1). An ideal step of N grey levels gives 3N per row,
// 15N over the kernel; dividing by 15 makes the response read in grey levels.
constexpr int kPrewittScale = 15;
constexpr int kHalf = 2;  // kernel half size
// Largest scaled |response|: five rows of 2 * 255 + 1 * 255 = 3825 = 255 * 15.
constexpr int kMaxScaledResponse = 255 * kPrewittScale;
// Largest frame side accepted; guards the size arithmetic against absurd headers.
constexpr int kMaxSidePx = 1 << 15;

DetectResult Error(DetectStatus status, std::string message) {
  DetectResult r;
  r.status = status;
  r.message = std::move(message);
  return r;
}

// Scaled (x15) response of one row into `out`; border columns are 0.
void PrewittRowScaled(const std::uint8_t* data, int width, std::size_t step, int row, int* colsum,
                      int* out) {
  const std::uint8_t* r0 = data + static_cast<std::size_t>(row - 2) * step;
  const std::uint8_t* r1 = r0 + step;
  const std::uint8_t* r2 = r1 + step;
  const std::uint8_t* r3 = r2 + step;
  const std::uint8_t* r4 = r3 + step;
  for (int c = 0; c < width; ++c) {
    colsum[c] = r0[c] + r1[c] + r2[c] + r3[c] + r4[c];
  }
  for (int c = 0; c < kHalf && c < width; ++c) out[c] = 0;
  for (int c = std::max(0, width - kHalf); c < width; ++c) out[c] = 0;
  for (int c = kHalf; c < width - kHalf; ++c) {
    out[c] = 2 * (colsum[c + 2] - colsum[c - 2]) + (colsum[c + 1] - colsum[c - 1]);
  }
}

}  // namespace

const char* ToString(DetectStatus status) {
  switch (status) {
    case DetectStatus::kOk:
      return "ok";
    case DetectStatus::kEmptyFrame:
      return "empty_frame";
    case DetectStatus::kSizeMismatch:
      return "size_mismatch";
    case DetectStatus::kUnknownEncoding:
      return "unknown_encoding";
    case DetectStatus::kBadRange:
      return "bad_range";
    case DetectStatus::kTooSmall:
      return "too_small";
  }
  return "unknown";
}

void PrewittRow(const std::uint8_t* data, int width, std::size_t step, int row, float* out) {
  std::vector<int> colsum(width);
  std::vector<int> scaled(width);
  PrewittRowScaled(data, width, step, row, colsum.data(), scaled.data());
  for (int c = 0; c < width; ++c) out[c] = static_cast<float>(scaled[c]) / kPrewittScale;
}

RibbonDetector::RibbonDetector(RibbonDetectorParams params) : params_(params) {
  const RibbonDetectorParams& p = params_;
  if (!(p.threshold_fraction > 0.0 && p.threshold_fraction < 1.0)) {
    throw std::invalid_argument("ribbon detector: threshold_fraction must be in (0, 1)");
  }
  if (p.clump_window_bins < 1 || p.clump_min_nonempty < 1 ||
      p.clump_min_nonempty > p.clump_window_bins) {
    throw std::invalid_argument(
        "ribbon detector: need 1 <= clump_min_nonempty <= clump_window_bins");
  }
  if (!(p.near_range_in > 0.0) || p.center_row_spacing_px < 1 ||
      !(p.outer_row_fraction > 0.0 && p.outer_row_fraction <= 1.0)) {
    throw std::invalid_argument(
        "ribbon detector: need near_range_in > 0 in, center_row_spacing_px >= 1, "
        "0 < outer_row_fraction <= 1");
  }
  if (!(p.min_edge_level >= 0.0) || !(p.min_pair_width_px >= 0.0) ||
      !(p.max_pair_width_px > p.min_pair_width_px) ||
      !(p.same_polarity_factor >= 0.0 && p.same_polarity_factor <= 1.0) || p.max_pairs < 0) {
    throw std::invalid_argument(
        "ribbon detector: need min_edge_level >= 0, 0 <= min_pair_width_px < "
        "max_pair_width_px, same_polarity_factor in [0, 1], max_pairs >= 0");
  }
}

std::vector<int> RibbonDetector::SampledRows(int height_px, double coaxial_range_in) const {
  const int lo = kHalf;
  const int hi = height_px - 1 - kHalf;
  if (hi < lo) return {};
  const double center = (height_px - 1) / 2.0;
  // The door's image height falls as 1/range beyond six feet; the outer rows follow it.
  double scale = 1.0;
  if (std::isfinite(coaxial_range_in) && coaxial_range_in > params_.near_range_in) {
    scale = params_.near_range_in / coaxial_range_in;
  }
  const double outer = params_.outer_row_fraction * (height_px / 2.0) * scale;
  const double inner = params_.center_row_spacing_px;
  const double offsets[5] = {-std::max(outer, 2.0 * inner), -inner, 0.0, inner,
                             std::max(outer, 2.0 * inner)};
  std::vector<int> rows;
  for (double off : offsets) {
    const int r = std::clamp(static_cast<int>(std::lround(center + off)), lo, hi);
    if (rows.empty() || rows.back() != r) rows.push_back(r);
  }
  return rows;
}

DetectResult RibbonDetector::Detect(const cv::Mat& image, double coaxial_range_in) const {
  if (image.empty() || image.cols <= 0 || image.rows <= 0) {
    return Error(DetectStatus::kEmptyFrame, "empty frame");
  }
  if (image.type() != CV_8UC1 || image.dims != 2) {
    return Error(DetectStatus::kUnknownEncoding,
                 "frame type " + std::to_string(image.type()) + " is not CV_8UC1 (mono8)");
  }
  return Run(image.data, image.cols, image.rows, image.step[0], coaxial_range_in);
}

DetectResult RibbonDetector::Detect(const ImageView& image, double coaxial_range_in) const {
  if (image.width_px <= 0 || image.height_px <= 0 || image.data == nullptr ||
      image.size_bytes == 0) {
    return Error(DetectStatus::kEmptyFrame, "empty frame (" + std::to_string(image.width_px) +
                                                " x " + std::to_string(image.height_px) + " px, " +
                                                std::to_string(image.size_bytes) + " bytes)");
  }
  if (image.encoding != "mono8") {
    return Error(DetectStatus::kUnknownEncoding, "encoding '" + image.encoding + "' is not mono8");
  }
  if (image.width_px > kMaxSidePx || image.height_px > kMaxSidePx ||
      image.step_bytes < image.width_px) {
    return Error(DetectStatus::kSizeMismatch,
                 "step " + std::to_string(image.step_bytes) + " bytes is below width " +
                     std::to_string(image.width_px) + " px or the frame exceeds " +
                     std::to_string(kMaxSidePx) + " px");
  }
  const std::size_t expected =
      static_cast<std::size_t>(image.step_bytes) * static_cast<std::size_t>(image.height_px);
  if (image.size_bytes != expected) {
    return Error(DetectStatus::kSizeMismatch,
                 "data length " + std::to_string(image.size_bytes) + " bytes does not match " +
                     std::to_string(image.height_px) + " rows x step " +
                     std::to_string(image.step_bytes) + " = " + std::to_string(expected));
  }
  return Run(image.data, image.width_px, image.height_px,
             static_cast<std::size_t>(image.step_bytes), coaxial_range_in);
}

DetectResult RibbonDetector::Run(const std::uint8_t* data, int width, int height, std::size_t step,
                                 double coaxial_range_in) const {
  if (width < 2 * kHalf + 1 || height < 2 * kHalf + 1) {
    return Error(DetectStatus::kTooSmall, "frame " + std::to_string(width) + " x " +
                                              std::to_string(height) +
                                              " px is smaller than the 5 x 5 filter");
  }
  const bool five_rows = params_.row_mode == RowMode::kFiveRows;
  if (five_rows && !(std::isfinite(coaxial_range_in) && coaxial_range_in > 0.0)) {
    return Error(DetectStatus::kBadRange, "coaxial range " + std::to_string(coaxial_range_in) +
                                              " in is not a positive finite number");
  }

  DetectResult result;
  RibbonDetection& det = result.detection;
  if (five_rows) {
    det.rows = SampledRows(height, coaxial_range_in);
  } else {
    det.rows.reserve(height - 2 * kHalf);
    for (int r = kHalf; r < height - kHalf; ++r) det.rows.push_back(r);
  }
  const int n_rows = static_cast<int>(det.rows.size());

  // (1) Filter the processed rows; keep the scaled responses.
  std::vector<int> response(static_cast<std::size_t>(n_rows) * width);
  std::vector<int> colsum(width);
  for (int i = 0; i < n_rows; ++i) {
    PrewittRowScaled(data, width, step, det.rows[i], colsum.data(),
                     response.data() + static_cast<std::size_t>(i) * width);
  }

  // (2) "Thresholding to pass top 5%": the (1 - fraction) quantile of |response| over the
  // processed pixels, found exactly from a histogram (responses are integers x15).
  std::vector<int> histogram(kMaxScaledResponse + 1, 0);
  for (int i = 0; i < n_rows; ++i) {
    const int* row = response.data() + static_cast<std::size_t>(i) * width;
    for (int c = kHalf; c < width - kHalf; ++c)
      ++histogram[std::min(std::abs(row[c]), kMaxScaledResponse)];
  }
  const long long total = static_cast<long long>(n_rows) * (width - 2 * kHalf);
  const long long pass_target =
      static_cast<long long>(std::ceil(params_.threshold_fraction * static_cast<double>(total)));
  int level_scaled = kMaxScaledResponse;
  long long passed = 0;
  while (level_scaled > 0 && passed + histogram[level_scaled] <= pass_target) {
    passed += histogram[level_scaled];
    --level_scaled;
  }
  // level_scaled is now the largest level whose inclusion would exceed the target; pass
  // only what is strictly above it, and never below the noise floor.
  int threshold_scaled = level_scaled + 1;
  const int floor_scaled =
      static_cast<int>(std::ceil(params_.min_edge_level * kPrewittScale - 1e-9));
  threshold_scaled = std::max({threshold_scaled, floor_scaled, 1});
  det.threshold = static_cast<double>(threshold_scaled) / kPrewittScale;

  // (3) Vertical integral projection V(c) = sum_r I(r, c) of the thresholded response, plus
  // the count of rows passing in each column bin and the signed sum for polarity.
  std::vector<double> projection(width, 0.0);
  std::vector<double> signed_sum(width, 0.0);
  std::vector<int> nonempty(width, 0);
  std::vector<std::uint8_t> passed_mask(static_cast<std::size_t>(n_rows) * width, 0);
  for (int i = 0; i < n_rows; ++i) {
    const int* row = response.data() + static_cast<std::size_t>(i) * width;
    std::uint8_t* mask = passed_mask.data() + static_cast<std::size_t>(i) * width;
    for (int c = kHalf; c < width - kHalf; ++c) {
      const int a = std::abs(row[c]);
      if (a < threshold_scaled) continue;
      mask[c] = 1;
      projection[c] += static_cast<double>(a) / kPrewittScale;
      signed_sum[c] += static_cast<double>(row[c]) / kPrewittScale;
      nonempty[c] = 1;
    }
  }

  // (4) Clumping: a window of clump_window_bins bins holding at least clump_min_nonempty
  // non-empty bins joins its non-empty bins into one clump (§4.1.1).
  const int win = params_.clump_window_bins;
  std::vector<int> next_nonempty_linked(width, 0);  // bin c is joined to the next non-empty
  std::vector<std::uint8_t> member(width, 0);
  {
    int count = 0;
    for (int c = 0; c < std::min(win, width); ++c) count += nonempty[c];
    for (int s = 0; s + win <= width; ++s) {
      if (s > 0) count += nonempty[s + win - 1] - nonempty[s - 1];
      if (count < params_.clump_min_nonempty) continue;
      int prev = -1;
      for (int c = s; c < s + win; ++c) {
        if (!nonempty[c]) continue;
        member[c] = 1;
        if (prev >= 0) next_nonempty_linked[prev] = 1;
        prev = c;
      }
    }
  }
  double total_strength = 0.0;
  for (int c = 0; c < width;) {
    if (!member[c]) {
      ++c;
      continue;
    }
    Footprint fp;
    fp.first_bin = c;
    double polarity = 0.0;
    int last = c;
    for (int k = c; k < width; ++k) {
      if (!nonempty[k]) continue;
      if (k != c && !next_nonempty_linked[last]) break;
      fp.strength += projection[k];
      polarity += signed_sum[k];
      last = k;
    }
    fp.last_bin = last;
    fp.polarity = polarity >= 0.0 ? 1 : -1;
    // Location: the centre of mass of the bins in the heaviest clump window (five bins). A
    // clump can chain several windows (a rolled outer row landing next to the casing's
    // other edge, §4.1.1 roll); the centre of mass of the whole chain would fall between
    // edges, while the heaviest window holds the edge the centre rows agree on.
    int best_start = fp.first_bin;
    double best_mass = -1.0;
    for (int s0 = fp.first_bin; s0 <= std::max(fp.first_bin, fp.last_bin - win + 1); ++s0) {
      double m = 0.0;
      for (int k = s0; k < s0 + win && k <= fp.last_bin; ++k) m += projection[k];
      if (m > best_mass) {
        best_mass = m;
        best_start = s0;
      }
    }
    double moment = 0.0;
    double mass = 0.0;
    for (int k = best_start; k < best_start + win && k <= fp.last_bin; ++k) {
      moment += k * projection[k];
      mass += projection[k];
    }
    fp.column_px = moment / mass;
    for (int i = 0; i < n_rows; ++i) {
      const std::uint8_t* mask = passed_mask.data() + static_cast<std::size_t>(i) * width;
      for (int k = fp.first_bin; k <= fp.last_bin; ++k) {
        if (mask[k]) {
          ++fp.rows_hit;
          break;
        }
      }
    }
    total_strength += fp.strength;
    det.footprints.push_back(fp);
    c = last + 1;
  }
  for (Footprint& fp : det.footprints) fp.weight = fp.strength / total_strength;

  // (5) Candidate pairs. Confidence: the geometric mean of the two footprint weights
  // (their share of the frame's edge energy), times each footprint's vertical persistence
  // (share of processed rows it appears in: "ribbon length is a strong indicator of a
  // large vertical feature", §4.1.1), times a penalty for like polarity.
  const int n_fp = static_cast<int>(det.footprints.size());
  for (int i = 0; i < n_fp; ++i) {
    const Footprint& l = det.footprints[i];
    for (int j = i + 1; j < n_fp; ++j) {
      const Footprint& r = det.footprints[j];
      const double w = r.column_px - l.column_px;
      if (w < params_.min_pair_width_px || w > params_.max_pair_width_px) continue;
      CandidatePair pair;
      pair.left_px = l.column_px;
      pair.right_px = r.column_px;
      pair.width_px = w;
      pair.left_index = i;
      pair.right_index = j;
      pair.confidence = std::sqrt(l.weight * r.weight) *
                        (static_cast<double>(l.rows_hit) / n_rows) *
                        (static_cast<double>(r.rows_hit) / n_rows) *
                        (l.polarity != r.polarity ? 1.0 : params_.same_polarity_factor);
      det.pairs.push_back(pair);
    }
  }
  std::stable_sort(
      det.pairs.begin(), det.pairs.end(),
      [](const CandidatePair& a, const CandidatePair& b) { return a.confidence > b.confidence; });
  if (static_cast<int>(det.pairs.size()) > params_.max_pairs) {
    det.pairs.resize(params_.max_pairs);
  }
  return result;
}

}  // namespace stickrep::vision
