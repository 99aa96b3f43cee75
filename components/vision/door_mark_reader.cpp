#include "vision/door_mark_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace stickrep::vision {
namespace {

DoorMarkReading Unknown(std::string why) {
  DoorMarkReading r;
  r.why_unknown = std::move(why);
  return r;
}

// Why the parameters cannot be used, or "".
std::string ParamsProblem(const DoorMarkParams& p) {
  if (!(p.focal_px > 0.0) || !std::isfinite(p.focal_px) || !std::isfinite(p.camera_height_in)) {
    return "camera focal length or height is not a positive finite number";
  }
  if (!(p.mark_low_in < p.mark_high_in) || !(p.face_low_in < p.face_high_in)) {
    return "a band's low edge is not below its high edge";
  }
  if (p.row_step_px < 1 || p.min_columns < 1 || !(p.jamb_margin >= 0.0 && p.jamb_margin < 0.5)) {
    return "row step, minimum columns or jamb margin out of range";
  }
  return "";
}

// The rows of the band [low_in, high_in] above the floor on a wall range_in away, every
// step rows from its top; empty when the band is not wholly in a frame of `height` rows.
std::vector<int> BandRows(double low_in, double high_in, double range_in, int height,
                          const DoorMarkParams& p) {
  const double centre = (height - 1) / 2.0;
  const double top = centre - p.focal_px * (high_in - p.camera_height_in) / range_in;
  const double bottom = centre - p.focal_px * (low_in - p.camera_height_in) / range_in;
  std::vector<int> rows;
  if (!(top >= 0.0 && bottom <= height - 1.0)) return rows;
  for (int r = static_cast<int>(std::ceil(top)); r <= bottom; r += p.row_step_px) {
    rows.push_back(r);
  }
  return rows;
}

// Median grey of the pixels of `rows` in columns [c0, c1], from a histogram.
double MedianLevel(const ImageView& f, const std::vector<int>& rows, int c0, int c1) {
  std::array<long long, 256> histogram{};
  for (int r : rows) {
    const std::uint8_t* row = f.data + static_cast<std::size_t>(r) * f.step_bytes;
    for (int c = c0; c <= c1; ++c) ++histogram[row[c]];
  }
  const long long half = static_cast<long long>(rows.size()) * (c1 - c0 + 1) / 2;
  long long seen = 0;
  for (int level = 0; level < 256; ++level) {
    seen += histogram[level];
    if (seen > half) return level;
  }
  return 255.0;
}

// Mean grey of column c over `rows`.
double ColumnMean(const ImageView& f, const std::vector<int>& rows, int c) {
  double sum = 0.0;
  for (int r : rows) sum += f.data[static_cast<std::size_t>(r) * f.step_bytes + c];
  return sum / static_cast<double>(rows.size());
}

// Why the call cannot be read at all, or "": the frame, the parameters, the range, the jambs.
std::string InputProblem(const ImageView& frame, double left_px, double right_px, double range_in,
                         const DoorMarkParams& params) {
  if (std::string why; CheckFrame(frame, &why) != DetectStatus::kOk) return why;
  if (std::string why = ParamsProblem(params); !why.empty()) return why;
  if (!(std::isfinite(range_in) && range_in > 0.0)) {
    return "range " + std::to_string(range_in) + " in is not a positive finite number";
  }
  if (!(std::isfinite(left_px) && std::isfinite(right_px) && left_px < right_px)) {
    return "jambs " + std::to_string(left_px) + ", " + std::to_string(right_px) +
           " px are not finite with left < right";
  }
  return "";
}

// Table 6.8's marks told apart by their width on the leaf: a vision panel is narrow (a fifth
// of each leaf, about 0.23 of the columns read), a poster half of it (about 0.57).
map::DoorMark MarkOfShare(double share, const DoorMarkParams& params) {
  if (share < params.window_min_share) return map::DoorMark::kPlain;
  if (share >= params.poster_min_share) return map::DoorMark::kPoster;
  return map::DoorMark::kWindow;
}

}  // namespace

DoorMarkReading ReadDoorMark(const ImageView& frame, double left_px, double right_px,
                             double range_in, const DoorMarkParams& params) {
  if (std::string why = InputProblem(frame, left_px, right_px, range_in, params); !why.empty()) {
    return Unknown(std::move(why));
  }
  // Leave the jamb edges and the casing's shadow out. A door cut by the frame's edge may
  // hide its mark: it is not read at all.
  const double margin = params.jamb_margin * (right_px - left_px);
  const double first = std::ceil(left_px + margin);
  const double last = std::floor(right_px - margin);
  if (!(first >= 0.0 && last <= frame.width_px - 1.0)) {
    return Unknown("door not wholly in the frame");
  }
  const int c0 = static_cast<int>(first);
  const int c1 = static_cast<int>(last);
  DoorMarkReading reading;
  reading.columns = std::max(0, c1 - c0 + 1);
  if (reading.columns < params.min_columns) {
    reading.why_unknown = std::to_string(reading.columns) + " columns between the jambs, below " +
                          std::to_string(params.min_columns);
    return reading;
  }
  const int h = frame.height_px;
  const std::vector<int> mark_rows =
      BandRows(params.mark_low_in, params.mark_high_in, range_in, h, params);
  const std::vector<int> face_rows =
      BandRows(params.face_low_in, params.face_high_in, range_in, h, params);
  if (mark_rows.empty() || face_rows.empty()) {
    reading.why_unknown = "mark or face band not wholly in the frame (or under a row) at range " +
                          std::to_string(range_in) + " in";
    return reading;
  }
  reading.face_level = MedianLevel(frame, face_rows, c0, c1);
  // A pale mark on a leaf already within min_mark_contrast of white cannot show: the leaf
  // is unread rather than called plain.
  if (reading.face_level + params.min_mark_contrast > 255.0) {
    reading.why_unknown = "leaf level " + std::to_string(reading.face_level) +
                          " leaves no room for a brighter mark";
    return reading;
  }
  int mark_columns = 0;
  for (int c = c0; c <= c1; ++c) {
    if (ColumnMean(frame, mark_rows, c) - reading.face_level >= params.min_mark_contrast) {
      ++mark_columns;
    }
  }
  reading.mark_share = static_cast<double>(mark_columns) / reading.columns;
  reading.mark = MarkOfShare(reading.mark_share, params);
  return reading;
}

}  // namespace stickrep::vision
