#pragma once

// Reads a door's supplemental mark (Table 6.8: a glazed vision panel, a poster, or a plain
// leaf) from one frame, given the door's jambs as the ribbon detector found them and the
// range to the wall. The marks are pale against the leaf at chest height; the leaf's own
// level is read lower down, below every mark, between the same jambs.
//
// Geometry: the camera looks at the wall from camera_height_in above the floor with focal
// length focal_px; a point h inches above the floor at range r is on row
// (height - 1) / 2 - focal_px * (h - camera_height_in) / r.

#include <string>

#include "stickrep/map.h"
#include "vision/ribbon_detector.h"

namespace stickrep::vision {

struct DoorMarkParams {
  double camera_height_in = 40.0;  // configs/robot.yaml's camera
  double focal_px = 483.3;         // 512 px over 55.817° (§5.4)
  // The band read for a mark: every mark of the renderer and of the Engineering Building's
  // doors covers it (a vision panel 40-72 in, a poster 46-66 in above the floor).
  double mark_low_in = 50.0;
  double mark_high_in = 62.0;
  // The band read for the leaf's own level: below every mark, above the kick plate. At 20 in
  // its low edge stays in a 480-row frame down to a 40 in range (at 16 in it left the frame
  // nearer than 48 in, the four feet the reader must work at); the mark band's top then
  // limits the reader to 44 in and farther.
  double face_low_in = 20.0;
  double face_high_in = 32.0;
  int row_step_px = 3;  // every few rows of each band
  // Share of the door's width left out beside each jamb (the jamb edge, the casing's shadow).
  double jamb_margin = 0.06;
  // A column is part of a mark when its mark band is this many grey levels brighter than
  // the leaf.
  double min_mark_contrast = 25.0;
  // The share of the door's columns that are mark: below window_min_share the leaf is
  // plain, from poster_min_share on a poster, between a window.
  double window_min_share = 0.08;
  double poster_min_share = 0.35;
  // The leaf is unreadable (kUnknown) when fewer than min_columns columns lie between the
  // jambs, or when either band is not wholly in the frame.
  int min_columns = 12;
};

struct DoorMarkReading {
  map::DoorMark mark = map::DoorMark::kUnknown;
  double mark_share = 0.0;   // share of the door's columns read as mark, 0..1
  double face_level = 0.0;   // median grey level of the leaf band
  int columns = 0;           // columns read
  std::string why_unknown;   // set when mark == kUnknown
};

// The mark of the door whose jambs are at columns left_px < right_px (sub-pixel), on a wall
// range_in inches from the camera. Never throws; a frame or jamb pair it cannot read gives
// kUnknown with the reason.
DoorMarkReading ReadDoorMark(const ImageView& frame, double left_px, double right_px,
                             double range_in, const DoorMarkParams& params);

}  // namespace stickrep::vision
