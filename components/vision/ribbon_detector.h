#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace stickrep::vision {

// A frame as it arrives from a camera stream: raw bytes plus their layout. Nothing is
// trusted: RibbonDetector::Detect validates every field.
struct ImageView {
  int width_px = 0;
  int height_px = 0;
  int step_bytes = 0;    // bytes from one row to the next (>= width for mono8)
  std::string encoding;  // "mono8" is the only encoding accepted
  const std::uint8_t* data = nullptr;
  std::size_t size_bytes = 0;
};

// Which image rows the detector processes.
enum class RowMode {
  kFiveRows,   // Figure 4.1 step (0): five rows chosen from the coaxial sonar range
  kFullFrame,  // every row (for comparison and for frames without a range)
};

// Parameters of the vertical edge ribbon detector (Figure 4.1, §4.1.1). Defaults are the
// text's values where it gives one; the others are ours and say why.
struct RibbonDetectorParams {
  RowMode row_mode = RowMode::kFiveRows;

  // Step (0), dynamic row sampling. "Three of these sampled rows were near the vertical
  // image center, with the others toward the top and bottom" and "if the range to the door
  // is six feet or less, sampling these particular rows will always be sufficient".
  double near_range_in = 72.0;  // six feet (§4.1.1)
  // Spacing of the three centre rows. The text ties 10° roll tolerance at 12 ft to "the
  // maximum spread of the center three sampled rows": a vertical edge rolled 10° drifts
  // tan(10°) * 8 = 1.4 px over 8 rows, so the three rows still fall in one 5-bin window.
  int center_row_spacing_px = 8;
  // Offset of the outer rows from the centre row at ranges up to near_range_in, as a
  // fraction of half the image height. 0.75 puts them at rows 60 and 420 of a 480-row
  // frame: at six feet and a 40 in camera height these still cut an 80 in door. Beyond
  // near_range_in the offset shrinks as near_range_in / range (the door's image height
  // falls as 1/range): the text's "range-based scale factor".
  double outer_row_fraction = 0.75;

  // Step (2), "thresholding to pass top 5%": the level is the (1 - fraction) quantile of
  // the absolute filter response over the processed rows of this frame.
  double threshold_fraction = 0.05;
  // Ours: a floor on that level, in grey levels of edge contrast (the filter is normalised
  // so a step of N grey levels gives a peak response of N). Without it a blank wall passes
  // its top 5 % of sensor noise; 10 grey levels is about five times the renderer's default
  // noise and well under the 40+ level contrast of a door frame.
  double min_edge_level = 10.0;

  // Step (4), clumping: "three nonempty bins within a five bin window" (§4.1.1).
  int clump_window_bins = 5;
  int clump_min_nonempty = 3;

  // Step (5), candidate pairs. Widths outside [min, max] pixels are not a door: a 30 in
  // door at 35 ft (the sonar's range limit, §4.3) is about 34 px wide with the default
  // camera; 12 px leaves room for oblique views.
  double min_pair_width_px = 12.0;
  double max_pair_width_px = 1e9;
  // Pairs of like polarity (both edges darkening, or both brightening, left to right) are
  // not the two sides of one face (constraint C2, §5.1: the landmark contrasts with its
  // surroundings) but are kept at this share of their confidence in case of clutter.
  double same_polarity_factor = 0.5;
  int max_pairs = 32;
};

// A clumped vertical ribbon footprint: "the center of mass of the bins" (§4.1.1).
struct Footprint {
  double column_px = 0.0;  // sub-pixel column, pixel centres at integers
  double weight = 0.0;     // share of all thresholded edge response in the frame, 0..1
  double strength = 0.0;   // summed thresholded response (grey levels) in the clump
  int rows_hit = 0;        // processed rows with a thresholded pixel in the clump
  int polarity = 0;        // +1 brightening left to right, -1 darkening
  int first_bin = 0;       // column span of the clump
  int last_bin = 0;
};

// A candidate jamb pair: left jamb LJ, right jamb RJ (§5.2), with a confidence weight
// (§4.1.2: "candidate footprint pairs, with confidence weights").
struct CandidatePair {
  double left_px = 0.0;
  double right_px = 0.0;
  double width_px = 0.0;
  double confidence = 0.0;
  int left_index = -1;  // into RibbonDetection::footprints
  int right_index = -1;
};

struct RibbonDetection {
  std::vector<int> rows;              // processed rows, top to bottom
  double threshold = 0.0;             // edge level used, grey levels
  std::vector<Footprint> footprints;  // left to right
  std::vector<CandidatePair> pairs;   // highest confidence first
};

enum class DetectStatus {
  kOk,
  kEmptyFrame,       // zero width or height, or no data
  kSizeMismatch,     // data length or step does not match width x height
  kUnknownEncoding,  // anything but mono8 / CV_8UC1
  kBadRange,         // coaxial range NaN, infinite or not positive (five-row mode)
  kTooSmall,         // fewer than 5 rows or columns: the 5x5 filter has nothing to read
};

const char* ToString(DetectStatus status);

// Result of one detection: a status and, when ok, the detection. Bad input never throws.
struct DetectResult {
  DetectStatus status = DetectStatus::kOk;
  std::string message;
  RibbonDetection detection;

  bool ok() const { return status == DetectStatus::kOk; }
};

// The vertical edge ribbon detector of Figure 4.1 (§4.1.1):
//   (0) sample five rows chosen from the coaxial sonar range,
//   (1) vertical 5x5 Prewitt filter,
//   (2) threshold to pass the top 5 %,
//   (3) vertical integral projection,
//   (4) clump the projection (3 non-empty bins in a 5-bin window) into footprints at
//       sub-pixel accuracy (centre of mass),
//   (5) output candidate pairs with width and confidence.
// Stateless after construction; Detect is const and may run on several threads.
class RibbonDetector {
 public:
  // Throws std::invalid_argument on inconsistent parameters (set-up error).
  explicit RibbonDetector(RibbonDetectorParams params = {});

  const RibbonDetectorParams& params() const { return params_; }

  // `coaxial_range_in`: sonar range along the optical axis, inches (§4.1.1). Ignored in
  // full-frame mode.
  DetectResult Detect(const cv::Mat& image, double coaxial_range_in) const;
  DetectResult Detect(const ImageView& image, double coaxial_range_in) const;

  // The five rows processed for a frame of `height_px` rows at this range, top to bottom
  // (step 0). Each row is at least 2 from the border so the 5x5 filter stays inside.
  std::vector<int> SampledRows(int height_px, double coaxial_range_in) const;

 private:
  DetectResult Run(const std::uint8_t* data, int width, int height, std::size_t step,
                   double coaxial_range_in) const;

  RibbonDetectorParams params_;
};

// Step (1) on one row: the vertical 5x5 Prewitt response at every column of `row`
// (columns 0, 1, width-2, width-1 are 0), normalised so that an ideal step of N grey
// levels peaks at N. Positive where the image brightens to the right. Exposed for tests.
void PrewittRow(const std::uint8_t* data, int width, std::size_t step, int row, float* out);

}  // namespace stickrep::vision
