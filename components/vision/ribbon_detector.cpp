#include "vision/ribbon_detector.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <utility>

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

// Step (1) on the processed rows: their scaled responses, row after row.
std::vector<int> FilterRows(const std::uint8_t* data, int width, std::size_t step,
                            const std::vector<int>& rows) {
  const int n_rows = static_cast<int>(rows.size());
  std::vector<int> response(static_cast<std::size_t>(n_rows) * width);
  std::vector<int> colsum(width);
  for (int i = 0; i < n_rows; ++i) {
    PrewittRowScaled(data, width, step, rows[i], colsum.data(),
                     response.data() + static_cast<std::size_t>(i) * width);
  }
  return response;
}

// Step (2), "thresholding to pass top 5%": the (1 - fraction) quantile of |response| over the
// processed pixels, found exactly from a histogram (responses are integers x15). Scaled x15.
int ThresholdScaled(const std::vector<int>& response, int n_rows, int width,
                    const RibbonDetectorParams& params) {
  std::vector<int> histogram(kMaxScaledResponse + 1, 0);
  for (int i = 0; i < n_rows; ++i) {
    const int* row = response.data() + static_cast<std::size_t>(i) * width;
    for (int c = kHalf; c < width - kHalf; ++c)
      ++histogram[std::min(std::abs(row[c]), kMaxScaledResponse)];
  }
  const long long total = static_cast<long long>(n_rows) * (width - 2 * kHalf);
  const long long pass_target =
      static_cast<long long>(std::ceil(params.threshold_fraction * static_cast<double>(total)));
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
      static_cast<int>(std::ceil(params.min_edge_level * kPrewittScale - 1e-9));
  threshold_scaled = std::max({threshold_scaled, floor_scaled, 1});
  return threshold_scaled;
}

// Step (3)'s output: per column bin, and which processed pixels passed the threshold.
struct Projection {
  std::vector<double> projection;         // V(c) = sum_r I(r, c), grey levels
  std::vector<double> signed_sum;         // the same with sign, for polarity
  std::vector<int> nonempty;              // 1 when some processed row passes in bin c
  std::vector<std::uint8_t> passed_mask;  // [row i * width + c]
};

// Step (3): vertical integral projection V(c) = sum_r I(r, c) of the thresholded response,
// plus the count of rows passing in each column bin and the signed sum for polarity.
Projection Project(const std::vector<int>& response, int n_rows, int width, int threshold_scaled) {
  Projection p;
  p.projection.assign(width, 0.0);
  p.signed_sum.assign(width, 0.0);
  p.nonempty.assign(width, 0);
  p.passed_mask.assign(static_cast<std::size_t>(n_rows) * width, 0);
  for (int i = 0; i < n_rows; ++i) {
    const int* row = response.data() + static_cast<std::size_t>(i) * width;
    std::uint8_t* mask = p.passed_mask.data() + static_cast<std::size_t>(i) * width;
    for (int c = kHalf; c < width - kHalf; ++c) {
      const int a = std::abs(row[c]);
      if (a < threshold_scaled) continue;
      mask[c] = 1;
      p.projection[c] += static_cast<double>(a) / kPrewittScale;
      p.signed_sum[c] += static_cast<double>(row[c]) / kPrewittScale;
      p.nonempty[c] = 1;
    }
  }
  return p;
}

// Step (4), which bins clump: a window of clump_window_bins bins holding at least
// clump_min_nonempty non-empty bins joins its non-empty bins into one clump (§4.1.1).
// member[c]: bin c is in a clump; linked[c]: bin c is joined to the next non-empty bin.
void MarkClumps(const std::vector<int>& nonempty, int width, const RibbonDetectorParams& params,
                std::vector<std::uint8_t>* member, std::vector<int>* linked) {
  const int win = params.clump_window_bins;
  int count = 0;
  for (int c = 0; c < std::min(win, width); ++c) count += nonempty[c];
  for (int s = 0; s + win <= width; ++s) {
    if (s > 0) count += nonempty[s + win - 1] - nonempty[s - 1];
    if (count < params.clump_min_nonempty) continue;
    int prev = -1;
    for (int c = s; c < s + win; ++c) {
      if (!nonempty[c]) continue;
      (*member)[c] = 1;
      if (prev >= 0) (*linked)[prev] = 1;
      prev = c;
    }
  }
}

// Location of the clump [first, last]: the centre of mass of the bins in its heaviest clump
// window (five bins). A clump can chain several windows (a rolled outer row landing next to
// the casing's other edge, §4.1.1 roll); the centre of mass of the whole chain would fall
// between edges, while the heaviest window holds the edge the centre rows agree on.
double HeaviestWindowColumn(const std::vector<double>& projection, int first, int last, int win) {
  int best_start = first;
  double best_mass = -1.0;
  for (int s0 = first; s0 <= std::max(first, last - win + 1); ++s0) {
    double m = 0.0;
    for (int k = s0; k < s0 + win && k <= last; ++k) m += projection[k];
    if (m > best_mass) {
      best_mass = m;
      best_start = s0;
    }
  }
  double moment = 0.0;
  double mass = 0.0;
  for (int k = best_start; k < best_start + win && k <= last; ++k) {
    moment += k * projection[k];
    mass += projection[k];
  }
  return moment / mass;
}

// Processed rows with a thresholded pixel in bins [first, last].
int RowsHit(const std::vector<std::uint8_t>& passed_mask, int n_rows, int width, int first,
            int last) {
  int rows_hit = 0;
  for (int i = 0; i < n_rows; ++i) {
    const std::uint8_t* mask = passed_mask.data() + static_cast<std::size_t>(i) * width;
    for (int k = first; k <= last; ++k) {
      if (mask[k]) {
        ++rows_hit;
        break;
      }
    }
  }
  return rows_hit;
}

// Mean over the processed rows that pass in bins [first, last] of each row's peak |response|,
// in grey levels: the edge's own contrast, whatever else the frame holds.
double ClumpContrast(const std::vector<int>& response, const std::vector<std::uint8_t>& passed_mask,
                     int n_rows, int width, int first, int last) {
  double sum = 0.0;
  int rows = 0;
  for (int i = 0; i < n_rows; ++i) {
    const std::size_t base = static_cast<std::size_t>(i) * width;
    int peak = 0;
    for (int k = first; k <= last; ++k) {
      if (passed_mask[base + k]) peak = std::max(peak, std::abs(response[base + k]));
    }
    if (peak > 0) {
      sum += static_cast<double>(peak) / kPrewittScale;
      ++rows;
    }
  }
  return rows > 0 ? sum / rows : 0.0;
}

// Persistence and contrast of the edge at fp over the processed rows, tolerant to roll
// (RibbonDetectorParams::max_roll_deg): per row, the peak passed response of the edge's
// polarity within the row's window round the footprint.
void RollTolerantHits(const std::vector<int>& response, const std::vector<std::uint8_t>& mask,
                      const std::vector<int>& rows, int width, int height,
                      const RibbonDetectorParams& params, Footprint* fp) {
  const double tan_roll = std::tan(params.max_roll_deg * 3.14159265358979323846 / 180.0);
  const double centre_row = (height - 1) / 2.0;
  int hit = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double tol = 2.0 + tan_roll * std::abs(rows[i] - centre_row);
    const int lo = std::max(0, static_cast<int>(std::floor(fp->column_px - tol)));
    const int hi = std::min(width - 1, static_cast<int>(std::ceil(fp->column_px + tol)));
    const std::size_t base = i * static_cast<std::size_t>(width);
    int peak = 0;
    for (int k = lo; k <= hi; ++k) {
      const int v = response[base + k];
      if (mask[base + k] && (v > 0) == (fp->polarity > 0)) peak = std::max(peak, std::abs(v));
    }
    if (peak > 0) {
      ++hit;
      sum += static_cast<double>(peak) / kPrewittScale;
    }
  }
  fp->rows_hit = std::max(fp->rows_hit, hit);
  if (hit > 0) fp->contrast = sum / hit;
}

// Step (4): the clumps of the projection as footprints, left to right, each weighted by its
// share of the frame's thresholded edge response. A chain of windows is cut where it would
// grow wider than max_clump_width_px.
void ClumpFootprints(const Projection& proj, const std::vector<int>& response, int n_rows,
                     int width, const RibbonDetectorParams& params,
                     std::vector<Footprint>* footprints) {
  const std::vector<int>& nonempty = proj.nonempty;
  std::vector<int> next_nonempty_linked(width, 0);  // bin c is joined to the next non-empty
  std::vector<std::uint8_t> member(width, 0);
  MarkClumps(nonempty, width, params, &member, &next_nonempty_linked);
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
      if (k - c >= params.max_clump_width_px) break;
      fp.strength += proj.projection[k];
      polarity += proj.signed_sum[k];
      last = k;
    }
    fp.last_bin = last;
    fp.polarity = polarity >= 0.0 ? 1 : -1;
    fp.column_px =
        HeaviestWindowColumn(proj.projection, fp.first_bin, fp.last_bin, params.clump_window_bins);
    fp.rows_hit = RowsHit(proj.passed_mask, n_rows, width, fp.first_bin, fp.last_bin);
    fp.contrast =
        ClumpContrast(response, proj.passed_mask, n_rows, width, fp.first_bin, fp.last_bin);
    total_strength += fp.strength;
    footprints->push_back(fp);
    c = last + 1;
  }
  for (Footprint& fp : *footprints) fp.weight = fp.strength / total_strength;
}

// The processed rows' mean grey level per column, as prefix sums: the appearance rule
// reads band means from it in O(1).
class RowProfile {
 public:
  RowProfile(const std::uint8_t* data, int width, std::size_t step, const std::vector<int>& rows)
      : prefix_(width + 1, 0.0) {
    std::vector<double> col(width, 0.0);
    for (int r : rows) {
      const std::uint8_t* row = data + static_cast<std::size_t>(r) * step;
      for (int c = 0; c < width; ++c) col[c] += row[c];
    }
    const double n = rows.empty() ? 1.0 : static_cast<double>(rows.size());
    for (int c = 0; c < width; ++c) prefix_[c + 1] = prefix_[c] + col[c] / n;
  }
  int width() const { return static_cast<int>(prefix_.size()) - 1; }
  // Mean over columns [a, b] clipped to the image; NaN when nothing is left.
  double Mean(double a, double b) const {
    const int lo = std::max(0, static_cast<int>(std::ceil(a)));
    const int hi = std::min(width() - 1, static_cast<int>(std::floor(b)));
    if (hi < lo) return std::nan("");
    return (prefix_[hi + 1] - prefix_[lo]) / (hi - lo + 1);
  }

 private:
  std::vector<double> prefix_;
};

// The wall level round everything the frame shows: the row ends beyond the outermost
// persistent edges, when both ends are there and agree; -1 otherwise.
double GroundLevel(const RowProfile& profile, const std::vector<Footprint>& footprints, int n_rows,
                   const RibbonDetectorParams& params) {
  constexpr int kMinBandPx = 6;
  int first = -1, last = -1;
  for (const Footprint& fp : footprints) {
    if (2 * fp.rows_hit < n_rows) continue;
    if (first < 0) first = fp.first_bin;
    last = fp.last_bin;
  }
  if (first < 0) return -1.0;
  const int w = profile.width();
  const double left_end = first - 3, right_start = last + 3;
  if (left_end - kHalf + 1 < kMinBandPx || (w - 1 - kHalf) - right_start + 1 < kMinBandPx) {
    return -1.0;
  }
  const double l = profile.Mean(kHalf, left_end);
  const double r = profile.Mean(right_start, w - 1 - kHalf);
  if (!(std::abs(l - r) <= params.ground_agreement)) return -1.0;
  return 0.5 * (l + r);
}

// Where the appearance rule reads a pair (columns): its interior, the near flanks just
// outside each edge (up to the next footprint outside, so a narrow casing is its own flank)
// and the far flanks beyond them (past that footprint, or past a casing's width).
struct PairBands {
  double interior_lo, interior_hi;
  double near_l_lo, near_l_hi, near_r_lo, near_r_hi;
  double far_l_lo, far_l_hi, far_r_lo, far_r_hi;
};

// The columns of a line footprint's own level: its clump less the filter's spread on
// either side, at least the pixel under its column.
std::pair<double, double> LineCore(const Footprint& fp) {
  const double lo = std::min<double>(fp.first_bin + kHalf, std::floor(fp.column_px));
  const double hi = std::max<double>(fp.last_bin - kHalf, std::ceil(fp.column_px));
  return {lo, hi};
}

PairBands Bands(const CandidatePair& pair, const std::vector<Footprint>& footprints) {
  constexpr double kEdgeGapPx = 2.0;  // the edge's own blur
  const double lj = pair.left_px, rj = pair.right_px, w = pair.width_px;
  const double near = std::clamp(0.15 * w, 3.0, 12.0);
  const double far = std::clamp(0.35 * w, 4.0, 40.0);
  const double inset = std::min(kEdgeGapPx, 0.25 * w);
  const Footprint& left = footprints[pair.left_index];
  const Footprint& right = footprints[pair.right_index];
  PairBands b;
  b.interior_lo = left.line ? std::max(lj + inset, left.last_bin + 1.0) : lj + inset;
  b.interior_hi = right.line ? std::min(rj - inset, right.first_bin - 1.0) : rj - inset;
  b.near_l_hi = lj - kEdgeGapPx;
  b.near_l_lo = lj - kEdgeGapPx - near;
  b.far_l_hi = b.near_l_lo;
  if (pair.left_index > 0) {
    const double prev = footprints[pair.left_index - 1].column_px;
    if (prev + kEdgeGapPx > b.near_l_lo) {
      b.near_l_lo = std::min(prev + kEdgeGapPx, b.near_l_hi - 1.0);
      b.far_l_hi = prev - kEdgeGapPx;
    }
  }
  if (left.line) std::tie(b.near_l_lo, b.near_l_hi) = LineCore(left);  // the face's flank
  b.far_l_lo = b.far_l_hi - far;
  b.near_r_lo = rj + kEdgeGapPx;
  b.near_r_hi = rj + kEdgeGapPx + near;
  b.far_r_lo = b.near_r_hi;
  if (pair.right_index + 1 < static_cast<int>(footprints.size())) {
    const double next = footprints[pair.right_index + 1].column_px;
    if (next - kEdgeGapPx < b.near_r_hi) {
      b.near_r_hi = std::max(next - kEdgeGapPx, b.near_r_lo + 1.0);
      b.far_r_lo = next + kEdgeGapPx;
    }
  }
  if (right.line) std::tie(b.near_r_lo, b.near_r_hi) = LineCore(right);
  b.far_r_hi = b.far_r_lo + far;
  return b;
}

// RibbonDetectorParams::seam_lines: marks the footprints that are thin lines (like levels
// just either side of the clump, its core darker or lighter than both).
void MarkLines(const RowProfile& profile, const RibbonDetectorParams& params,
               std::vector<Footprint>* footprints) {
  constexpr double kSidePx = 6.0;
  for (Footprint& fp : *footprints) {
    const auto [core_lo, core_hi] = LineCore(fp);
    const double left = profile.Mean(fp.first_bin - kHalf - kSidePx, fp.first_bin - kHalf);
    const double right = profile.Mean(fp.last_bin + kHalf, fp.last_bin + kHalf + kSidePx);
    if (std::isnan(left) || std::isnan(right)) continue;
    // The line's own level: the core's column farthest from the sides' level. The processed
    // rows' mean smears a thin line that crosses them slanted (a rolled camera) over the
    // whole core, whose mean would then take in its shoulders; its depth shows where it is
    // darkest (or lightest).
    const double sides = 0.5 * (left + right);
    double core = std::nan("");
    for (int c = static_cast<int>(core_lo); c <= static_cast<int>(core_hi); ++c) {
      const double level = profile.Mean(c, c);
      if (std::isnan(core) || std::abs(level - sides) > std::abs(core - sides)) core = level;
    }
    if (std::isnan(core)) continue;
    const double dl = core - left, dr = core - right;
    fp.line = std::abs(left - right) <= params.line_side_agreement && dl * dr > 0.0 &&
              std::min(std::abs(dl), std::abs(dr)) >= params.min_edge_level;
  }
}

// The appearance rule's readings for a pair, and its factor on the confidence.
double Appearance(const RowProfile& profile, const std::vector<Footprint>& footprints,
                  double ground, const RibbonDetectorParams& params, CandidatePair* pair) {
  const PairBands b = Bands(*pair, footprints);
  pair->interior = profile.Mean(b.interior_lo, b.interior_hi);
  pair->left_flank = profile.Mean(b.near_l_lo, b.near_l_hi);
  pair->right_flank = profile.Mean(b.near_r_lo, b.near_r_hi);
  const double far_l = profile.Mean(b.far_l_lo, b.far_l_hi);
  const double far_r = profile.Mean(b.far_r_lo, b.far_r_hi);
  pair->far_flank = std::isnan(far_l) ? far_r : std::isnan(far_r) ? far_l : 0.5 * (far_l + far_r);
  double factor = 0.5;
  const double dl = pair->interior - pair->left_flank;
  const double dr = pair->interior - pair->right_flank;
  if (std::isnan(dl) || std::isnan(dr)) {
    factor = 0.75;  // a flank outside the image: no evidence either way
  } else if (dl * dr > 0.0) {
    // A face against both flanks; balanced contrast scores highest.
    factor = 0.5 + 0.5 * std::min(std::abs(dl), std::abs(dr)) /
                       std::max(std::abs(dl), std::abs(dr));
  }
  if (ground >= 0.0 && !std::isnan(pair->far_flank) && !std::isnan(pair->interior) &&
      std::abs(pair->interior - ground) + 0.5 * params.ground_agreement <
          std::abs(pair->far_flank - ground)) {
    pair->ground_reversed = true;
    factor *= params.reversed_ground_factor;
  }
  return factor;
}

// Whether a persistent footprint strictly inside the pair steps between two levels by at
// least half the pair's weaker edge contrast (RibbonDetectorParams::two_faces_factor).
bool SpansTwoFaces(const RowProfile& profile, const std::vector<Footprint>& footprints,
                   int n_rows, const CandidatePair& pair) {
  constexpr double kGapPx = 3.0, kBandPx = 8.0;
  const double weaker = std::min(std::abs(pair.interior - pair.left_flank),
                                 std::abs(pair.interior - pair.right_flank));
  if (std::isnan(weaker)) return false;
  for (int k = pair.left_index + 1; k < pair.right_index; ++k) {
    const Footprint& f = footprints[k];
    if (f.rows_hit < n_rows - 1 || f.column_px - pair.left_px < 4.0 ||
        pair.right_px - f.column_px < 4.0) {
      continue;
    }
    const double left = profile.Mean(std::max(pair.left_px + 2.0, f.column_px - kGapPx - kBandPx),
                                      f.column_px - kGapPx);
    const double right = profile.Mean(
        f.column_px + kGapPx, std::min(pair.right_px - 2.0, f.column_px + kGapPx + kBandPx));
    if (!std::isnan(left) && !std::isnan(right) && std::abs(left - right) >= 0.5 * weaker &&
        std::abs(left - right) >= 10.0) {
      return true;
    }
  }
  return false;
}

// Whether the pair's face still contrasts with both flanks by min_contrast at the rows of
// `rows` (the foot rows, RibbonDetectorParams), with the sign it has in the processed rows.
bool FaceContinuesAt(const RowProfile* rows, const std::vector<Footprint>& footprints,
                     const CandidatePair& pair, double min_contrast) {
  if (rows == nullptr) return false;
  const PairBands b = Bands(pair, footprints);
  const double i = rows->Mean(b.interior_lo, b.interior_hi);
  const double l = rows->Mean(b.near_l_lo, b.near_l_hi);
  const double r = rows->Mean(b.near_r_lo, b.near_r_hi);
  const double sign = pair.interior - 0.5 * (pair.left_flank + pair.right_flank);
  if (std::isnan(i) || std::isnan(l) || std::isnan(r) || std::isnan(sign)) return false;
  const double dl = i - l, dr = i - r;
  // A line's foot may lie off its column at the processed rows (roll, lens): its side is not
  // read there, the face's other side decides.
  const bool left_ok =
      footprints[pair.left_index].line || (dl * sign > 0.0 && std::abs(dl) >= min_contrast);
  const bool right_ok =
      footprints[pair.right_index].line || (dr * sign > 0.0 && std::abs(dr) >= min_contrast);
  return left_ok && right_ok;
}

// Whether the pair's interior keeps its level over every row of the head band (no head:
// RibbonDetectorParams::head_low_in).
bool NoHead(const std::vector<RowProfile>& head_band, const CandidatePair& pair,
            double min_contrast) {
  if (head_band.size() < 3 || std::isnan(pair.interior)) return false;
  const double inset = std::min(2.0, 0.25 * pair.width_px);
  for (const RowProfile& row : head_band) {
    const double level = row.Mean(pair.left_px + inset, pair.right_px - inset);
    if (std::isnan(level) || std::abs(level - pair.interior) >= min_contrast) return false;
  }
  return true;
}

// Confidence of the pair of footprints l, r (see RibbonDetectorParams::Confidence).
double PairConfidence(const Footprint& l, const Footprint& r, int n_rows,
                      const RibbonDetectorParams& params) {
  const double persistence = (static_cast<double>(l.rows_hit) / n_rows) *
                             (static_cast<double>(r.rows_hit) / n_rows);
  // A line has both polarities: it bounds a face whichever way the other edge steps.
  const double polarity =
      l.line || r.line || l.polarity != r.polarity ? 1.0 : params.same_polarity_factor;
  if (params.confidence == RibbonDetectorParams::Confidence::kEnergyShare) {
    return std::sqrt(l.weight * r.weight) * persistence * polarity;
  }
  auto score = [&](double c) { return c / (c + params.half_contrast); };
  return std::sqrt(score(l.contrast) * score(r.contrast)) * persistence * polarity;
}

// Step (5), candidate pairs within the width limits, highest confidence first, at most
// max_pairs. Confidence: PairConfidence, times the appearance rule's factor when it is on.
void PairFootprints(const std::vector<Footprint>& footprints, int n_rows,
                    const RibbonDetectorParams& params, const RowProfile& profile,
                    const std::vector<RowProfile>& head_band, const RowProfile* foot,
                    RibbonDetection* det) {
  const int n_fp = static_cast<int>(footprints.size());
  const bool appearance = params.appearance_rule &&
                          params.confidence == RibbonDetectorParams::Confidence::kAbsolute;
  det->ground = appearance ? GroundLevel(profile, footprints, n_rows, params) : -1.0;
  const double min_w = std::max(params.min_pair_width_px, det->width_limits.min_px);
  const double max_w = std::min(params.max_pair_width_px, det->width_limits.max_px);
  std::vector<CandidatePair>* pairs = &det->pairs;
  for (int i = 0; i < n_fp; ++i) {
    const Footprint& l = footprints[i];
    for (int j = i + 1; j < n_fp; ++j) {
      const Footprint& r = footprints[j];
      const double w = r.column_px - l.column_px;
      if (w < min_w || w > max_w) continue;
      CandidatePair pair;
      pair.left_px = l.column_px;
      pair.right_px = r.column_px;
      pair.width_px = w;
      pair.left_index = i;
      pair.right_index = j;
      pair.confidence = PairConfidence(l, r, n_rows, params);
      if (appearance) {
        pair.confidence *= Appearance(profile, footprints, det->ground, params, &pair);
        pair.two_faces = SpansTwoFaces(profile, footprints, n_rows, pair);
        if (pair.two_faces) pair.confidence *= params.two_faces_factor;
        pair.tall_face = NoHead(head_band, pair, params.min_tall_contrast);
        if (pair.tall_face) pair.confidence *= params.tall_face_factor;
        pair.short_face =
            foot != nullptr && !FaceContinuesAt(foot, footprints, pair, params.min_foot_contrast);
        if (pair.short_face) pair.confidence *= params.short_face_factor;
      }
      pairs->push_back(pair);
    }
  }
  det->pairs_before_cap = static_cast<int>(pairs->size());
  std::stable_sort(
      pairs->begin(), pairs->end(),
      [](const CandidatePair& a, const CandidatePair& b) { return a.confidence > b.confidence; });
  if (static_cast<int>(pairs->size()) > params.max_pairs) {
    pairs->resize(params.max_pairs);
  }
}

// The head band (every few rows between head_low_in and header_height_in) and the foot
// rows near the floor at the coaxial range, where the image shows them (the appearance
// rule's head and foot tests).
void AppearanceBands(const std::uint8_t* data, int width, int height, std::size_t step,
                     const std::vector<int>& rows, double range_in,
                     const RibbonDetectorParams& params, std::vector<RowProfile>* head_band,
                     std::unique_ptr<RowProfile>* foot) {
  auto row_of = [&](double height_in) {
    return static_cast<int>(std::lround(
        (height - 1) / 2.0 - params.focal_px * (height_in - params.camera_height_in) / range_in));
  };
  constexpr int kHeadStepPx = 4;
  const int top = row_of(params.header_height_in);
  const int bottom = std::min(row_of(params.head_low_in), rows.front() - 4);
  if (top >= 1) {
    for (int r = top; r <= bottom; r += kHeadStepPx) {
      head_band->emplace_back(data, width, step, std::vector<int>{r});
    }
  }
  const int f = row_of(params.foot_height_in);
  if (f >= 1 && f <= height - 2 && f > rows.back() + 8) {
    *foot = std::make_unique<RowProfile>(data, width, step, std::vector<int>{f - 1, f, f + 1});
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
  if (p.max_clump_width_px < p.clump_window_bins || !(p.half_contrast > 0.0) ||
      !(p.max_roll_deg >= 0.0 && p.max_roll_deg < 45.0) ||
      !(p.ground_agreement >= 0.0) ||
      !(p.reversed_ground_factor >= 0.0 && p.reversed_ground_factor <= 1.0) ||
      !(p.two_faces_factor >= 0.0 && p.two_faces_factor <= 1.0) ||
      !(p.tall_face_factor >= 0.0 && p.tall_face_factor <= 1.0) || !(p.focal_px > 0.0) ||
      !(p.header_height_in > p.head_low_in) || !(p.head_low_in > p.camera_height_in) ||
      !(p.min_tall_contrast >= 0.0) ||
      !(p.foot_height_in < p.camera_height_in) || !(p.min_foot_contrast >= 0.0) ||
      !(p.short_face_factor >= 0.0 && p.short_face_factor <= 1.0)) {
    throw std::invalid_argument(
        "ribbon detector: need max_clump_width_px >= clump_window_bins, half_contrast > 0, "
        "ground_agreement >= 0, the appearance factors in [0, 1], focal_px > 0, "
        "header_height_in > head_low_in > camera_height_in, min_tall_contrast >= 0");
  }
  if (!(p.min_edge_level >= 0.0) || !(p.min_pair_width_px >= 0.0) ||
      !(p.max_pair_width_px > p.min_pair_width_px) ||
      !(p.same_polarity_factor >= 0.0 && p.same_polarity_factor <= 1.0) || p.max_pairs < 0 ||
      !(p.line_side_agreement >= 0.0)) {
    throw std::invalid_argument(
        "ribbon detector: need min_edge_level >= 0, 0 <= min_pair_width_px < "
        "max_pair_width_px, same_polarity_factor in [0, 1], max_pairs >= 0, "
        "line_side_agreement >= 0");
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
  return Detect(image, coaxial_range_in, PairWidthLimits{});
}

DetectResult RibbonDetector::Detect(const ImageView& image, double coaxial_range_in) const {
  return Detect(image, coaxial_range_in, PairWidthLimits{});
}

DetectResult RibbonDetector::Detect(const cv::Mat& image, double coaxial_range_in,
                                    const PairWidthLimits& limits) const {
  if (image.empty() || image.cols <= 0 || image.rows <= 0) {
    return Error(DetectStatus::kEmptyFrame, "empty frame");
  }
  if (image.type() != CV_8UC1 || image.dims != 2) {
    return Error(DetectStatus::kUnknownEncoding,
                 "frame type " + std::to_string(image.type()) + " is not CV_8UC1 (mono8)");
  }
  return Run(image.data, image.cols, image.rows, image.step[0], coaxial_range_in, limits);
}

DetectStatus CheckFrame(const ImageView& image, std::string* why) {
  const auto fail = [&](DetectStatus status, std::string message) {
    if (why) *why = std::move(message);
    return status;
  };
  if (image.width_px <= 0 || image.height_px <= 0 || image.data == nullptr ||
      image.size_bytes == 0) {
    return fail(DetectStatus::kEmptyFrame, "empty frame (" + std::to_string(image.width_px) +
                                               " x " + std::to_string(image.height_px) + " px, " +
                                               std::to_string(image.size_bytes) + " bytes)");
  }
  if (image.encoding != "mono8") {
    return fail(DetectStatus::kUnknownEncoding, "encoding '" + image.encoding + "' is not mono8");
  }
  if (image.width_px > kMaxSidePx || image.height_px > kMaxSidePx ||
      image.step_bytes < image.width_px) {
    return fail(DetectStatus::kSizeMismatch,
                "step " + std::to_string(image.step_bytes) + " bytes is below width " +
                    std::to_string(image.width_px) + " px or the frame exceeds " +
                    std::to_string(kMaxSidePx) + " px");
  }
  const std::size_t expected =
      static_cast<std::size_t>(image.step_bytes) * static_cast<std::size_t>(image.height_px);
  if (image.size_bytes != expected) {
    return fail(DetectStatus::kSizeMismatch,
                "data length " + std::to_string(image.size_bytes) + " bytes does not match " +
                    std::to_string(image.height_px) + " rows x step " +
                    std::to_string(image.step_bytes) + " = " + std::to_string(expected));
  }
  return DetectStatus::kOk;
}

DetectResult RibbonDetector::Detect(const ImageView& image, double coaxial_range_in,
                                    const PairWidthLimits& limits) const {
  std::string why;
  if (const DetectStatus status = CheckFrame(image, &why); status != DetectStatus::kOk) {
    return Error(status, why);
  }
  return Run(image.data, image.width_px, image.height_px,
             static_cast<std::size_t>(image.step_bytes), coaxial_range_in, limits);
}

DetectResult RibbonDetector::Run(const std::uint8_t* data, int width, int height, std::size_t step,
                                 double coaxial_range_in, const PairWidthLimits& limits) const {
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

  const std::vector<int> response = FilterRows(data, width, step, det.rows);
  const int threshold_scaled = ThresholdScaled(response, n_rows, width, params_);
  det.threshold = static_cast<double>(threshold_scaled) / kPrewittScale;
  const Projection proj = Project(response, n_rows, width, threshold_scaled);
  ClumpFootprints(proj, response, n_rows, width, params_, &det.footprints);
  if (params_.confidence == RibbonDetectorParams::Confidence::kAbsolute) {
    for (Footprint& fp : det.footprints) {
      RollTolerantHits(response, proj.passed_mask, det.rows, width, height, params_, &fp);
    }
  }
  det.width_limits = limits;
  const RowProfile profile(data, width, step, det.rows);
  if (params_.seam_lines) MarkLines(profile, params_, &det.footprints);
  std::vector<RowProfile> head_band;
  std::unique_ptr<RowProfile> foot;
  if (five_rows && params_.appearance_rule) {
    AppearanceBands(data, width, height, step, det.rows, coaxial_range_in, params_, &head_band,
                    &foot);
  }
  PairFootprints(det.footprints, n_rows, params_, profile, head_band, foot.get(), &det);
  return result;
}

ImageView Mono8View(const cv::Mat& image) {
  ImageView view;
  view.width_px = image.cols;
  view.height_px = image.rows;
  view.step_bytes = static_cast<int>(image.step[0]);
  view.encoding = "mono8";
  view.data = image.data;
  view.size_bytes = image.step[0] * static_cast<std::size_t>(image.rows);
  return view;
}

}  // namespace stickrep::vision
