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

// The view of a single-channel 8-bit image, as a camera stream would deliver it.
ImageView Mono8View(const cv::Mat& image);

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
  // 0.45 (rows 132 and 348 at six feet) sees the door between 24 and 56 in above the floor
  // at the sonar range, and still between 8 and 72 in when the door is twice as far as the
  // range says (a coaxial echo off a nearer object, a camera looking down the hallway).
  // Rows at 0.75 landed on the ceiling light strips and the floor's reflections in real
  // hallway frames, and on the baseboard of a door farther than the range.
  double outer_row_fraction = 0.45;

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
  // Ours: a clump is at most this wide. Windows chain through anything that crosses the
  // processed rows at a slant (a baseboard's perspective line, a floor reflection); without
  // a bound, two jambs 10 px apart became one footprint, and clumps up to 151 px wide were
  // seen on real frames. 12 px holds a one-pixel edge bowed by the lens (seven pixels at
  // six feet, §4.1.1) and tilted 1.4 px by 10° of roll over the centre rows.
  int max_clump_width_px = 12;

  // Step (5), candidate pairs. Widths outside [min, max] pixels are not a door. These are
  // the bounds when the caller gives none; the landmark pipeline gives the widths a legal
  // door class can have at the sonar range and stare (Chapter 5 geometry). A door seen
  // obliquely can be 10 px wide.
  double min_pair_width_px = 8.0;
  double max_pair_width_px = 1e9;
  // Pairs of like polarity (both edges darkening, or both brightening, left to right) are
  // not the two sides of one face (constraint C2, §5.1: the landmark contrasts with its
  // surroundings) but are kept at this share of their confidence in case of clutter.
  double same_polarity_factor = 0.5;
  // A thin line (a double door's seam, a gap between two leaves) is one clump holding both
  // polarities, with the wall or leaf at one level on both sides. It bounds a face (each leaf
  // of a closed double door is framed by its casing and the seam), but it is not a step:
  // its polarity says nothing, and the face's flank on that side is the line itself, not
  // the other leaf beyond it. A footprint is such a line when the levels just either side
  // of its clump agree within line_side_agreement grey levels and the column of the clump's
  // core farthest from them differs from both, the same way, by at least min_edge_level (the
  // processed rows' mean smears a line a rolled camera sees slanted; its depth shows where
  // it is darkest). Off (the default, as shipped in configs/landmark.yaml): every footprint
  // is a step.
  bool seam_lines = false;
  double line_side_agreement = 12.0;
  int max_pairs = 32;

  // How a pair's confidence is formed.
  //  kAbsolute: from the edges' own contrast in grey levels, their persistence over the
  //    processed rows and the pair's appearance; comparable across frames.
  //  kEnergyShare: the geometric mean of the two footprints' shares of the frame's edge
  //    energy, times persistence and the polarity factor (the first detector: a door-free frame
  //    of posters scored above real doors, because a share is relative to its own frame).
  enum class Confidence { kAbsolute, kEnergyShare };
  // kAbsolute: an edge rolled by up to this much (§4.1.1: 10°) crosses a processed row
  // within tan(max_roll) times the row's distance from the centre row (plus 2 px) of the
  // footprint: it counts as hit there when a passed pixel of the edge's polarity lies in
  // that window. With the clump bounded, a rolled edge's outer-row hits are clumps of their
  // own; this keeps its persistence and contrast whole.
  double max_roll_deg = 10.0;
  Confidence confidence = Confidence::kAbsolute;
  // kAbsolute: an edge of this contrast (grey levels) scores one half; c / (c + half).
  double half_contrast = 20.0;
  // The appearance rule (kAbsolute only). A door is a face that contrasts with the wall on
  // both sides (C2, §5.1): its interior is darker than both flanks or lighter than both.
  // A light strip between two dark doors is such a face too, with the figure and the
  // ground swapped: its interior is like the wall round the group and its far flanks (the
  // doors) are not. The wall level is read at the two ends of the processed rows, beyond
  // the outermost edges; when the two ends disagree by more than ground_agreement grey
  // levels the frame gives no ground and no pair is marked down for it.
  bool appearance_rule = true;
  double ground_agreement = 25.0;
  double reversed_ground_factor = 0.3;  // a pair whose interior is the ground
  // One face: a persistent edge inside the pair (in all processed rows but one) that steps
  // between two levels by at least half the pair's weaker edge contrast means the pair
  // spans two faces (a door and the strip beside it, a casing and its opening). A thin
  // line (a double door's seam) has one level on both sides and is not such an edge.
  double two_faces_factor = 0.5;
  // Door height: a door's face ends at its head (a standard door is 80 in, its casing 3 in
  // more), while the wall between two doors and a pilaster go on to the ceiling. Where the
  // image shows the band from head_low_in to header_height_in above the floor (at the
  // coaxial range, camera_height_in up, focal_px), the pair's interior is read every few
  // rows up that band: a door's changes there by min_tall_contrast grey levels from its
  // level in the processed rows (its head casing, the wall above it); a face that does not
  // change is a full-height strip and is marked down.
  double head_low_in = 70.0;
  double header_height_in = 90.0;
  double camera_height_in = 40.0;  // not in the text; configs/robot.yaml's camera
  double focal_px = 483.3;         // 512 px over 55.817° (§5.4)
  double min_tall_contrast = 20.0;
  double tall_face_factor = 0.3;
  // A door reaches the floor: where the row at foot_height_in is in the image, a pair whose
  // face does not contrast with both flanks there (same sign, min_foot_contrast grey
  // levels) ends above the floor (a poster, a notice board, a window) and is marked down.
  double foot_height_in = 14.0;
  double min_foot_contrast = 8.0;
  double short_face_factor = 0.5;
};

// Image widths a door can have in this frame (the landmark pipeline computes them from the
// sonar range, the stare and the legal door classes).
struct PairWidthLimits {
  double min_px = 0.0;
  double max_px = 1e9;
};

// A clumped vertical ribbon footprint: "the center of mass of the bins" (§4.1.1).
struct Footprint {
  double column_px = 0.0;  // sub-pixel column, pixel centres at integers
  double weight = 0.0;     // share of all thresholded edge response in the frame, 0..1
  double strength = 0.0;   // summed thresholded response (grey levels) in the clump
  int rows_hit = 0;        // processed rows with a thresholded pixel in the clump
  int polarity = 0;        // +1 brightening left to right, -1 darkening
  bool line = false;       // a thin line, not a step (RibbonDetectorParams::seam_lines)
  double contrast = 0.0;   // mean over the rows hit of the row's peak |response|, grey levels
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
  // The appearance rule's readings (grey levels over the processed rows): interior, the
  // near flanks just outside each edge, and the far flanks beyond a casing's width.
  double interior = 0.0;
  double left_flank = 0.0, right_flank = 0.0;
  double far_flank = 0.0;
  bool ground_reversed = false;  // the interior looks like the wall, the flanks do not
  bool two_faces = false;        // a persistent step inside the pair
  bool tall_face = false;        // the face goes on above door height (no head seen)
  bool short_face = false;       // the face ends above the floor
  int left_index = -1;  // into RibbonDetection::footprints
  int right_index = -1;
};

struct RibbonDetection {
  std::vector<int> rows;              // processed rows, top to bottom
  double threshold = 0.0;             // edge level used, grey levels
  double ground = -1.0;               // wall level at the row ends, -1: none (appearance rule)
  PairWidthLimits width_limits;       // pair widths kept
  int pairs_before_cap = 0;           // pairs within the width limits, before max_pairs
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
// Whether a frame's fields are consistent (mono8, sizes, step, data length): kOk, or why
// not in `why` (if given). Detect() and every other reader of an ImageView check with it.
DetectStatus CheckFrame(const ImageView& image, std::string* why);

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
  // The same, keeping only pairs within `limits` (and within the parameters' bounds).
  DetectResult Detect(const cv::Mat& image, double coaxial_range_in,
                      const PairWidthLimits& limits) const;
  DetectResult Detect(const ImageView& image, double coaxial_range_in,
                      const PairWidthLimits& limits) const;

  // The five rows processed for a frame of `height_px` rows at this range, top to bottom
  // (step 0). Each row is at least 2 from the border so the 5x5 filter stays inside.
  std::vector<int> SampledRows(int height_px, double coaxial_range_in) const;

 private:
  DetectResult Run(const std::uint8_t* data, int width, int height, std::size_t step,
                   double coaxial_range_in, const PairWidthLimits& limits) const;

  RibbonDetectorParams params_;
};

// Step (1) on one row: the vertical 5x5 Prewitt response at every column of `row`
// (columns 0, 1, width-2, width-1 are 0), normalised so that an ideal step of N grey
// levels peaks at N. Positive where the image brightens to the right. Exposed for tests.
void PrewittRow(const std::uint8_t* data, int width, std::size_t step, int row, float* out);

}  // namespace stickrep::vision
