#pragma once

#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::localizer {

// One classified door in one frame, placed along the wall.
struct DoorSighting {
  map::DoorClass door_class = map::DoorClass::k36;
  double width_in = 0.0;
  double confidence = 0.0;
  // Along-wall position of the door centre: the odometer reading at the frame plus the
  // centre's offset from the optical axis.
  double along_in = 0.0;
  // The leaf's mark as the frame showed it (Table 6.8's supplemental marks); kUnknown: not
  // read.
  map::DoorMark mark = map::DoorMark::kUnknown;
};

struct EdgeAssemblerConfig {
  // Sightings whose two jambs each lie within this of a track's are the same pair of
  // vertical edges seen again (jambs are placed to an inch or so frame to frame).
  double same_door_in = 4.0;
  // A door is complete once the optical axis is this far past its centre: then it cannot
  // be seen again and its frames are all in (half the field of view's footprint at the
  // usual range, plus margin).
  double out_of_view_in = 48.0;
  // A door whose near jamb is less than this behind the optical axis may not yet have been
  // seen whole (the widest single leaf, 40 in, and the frames' spacing): silent_in() leaves
  // that stretch out.
  double silent_margin_in = 48.0;
  // Doors seen in fewer frames are dropped as spurious (a 36 in door stays in view for
  // several frames at 6.24 in per frame, SPEC §8).
  int min_frames = 2;
  // Two doors whose facing jambs are closer than this have no wall between them
  // (Table 6.2's door-door adjacencies).
  double min_wall_in = 6.0;
  // Two tracks that overlap by more than this cannot both be doors: the one with more
  // support (summed detector confidence) is the door, the other the same landmark paired
  // wrongly (a casing edge, a leaf window's edge).
  double max_overlap_in = 3.0;
  // The two leaves of a double door share the meeting stile: their facing jambs lie within
  // this of each other (doors side by side, or a door and a wall panel, are a casing's
  // width apart), and together they span a 30/30 or 36/36 door to within
  // double_door_tolerance_in.
  double leaf_gap_in = 1.5;
  double double_door_tolerance_in = 6.0;
  // Leaves of one double door are alike and no wider than a 36 in leaf read a little wide
  // (a wall panel between two casings reads 40 in).
  double max_leaf_in = 38.5;
  double leaf_mismatch_in = 5.0;
  // A heading change this large is a corner of the hallway: the node between two walls,
  // sensed by odometry as the base turns in place (A3), a 90 or 270 degree node whatever
  // the turn (Table 6.1 and 6.3; a hallway that turns by 45 degrees is turned into the
  // same way). Smaller changes are a wall the follower bends along (the map's hallway view
  // merges bends up to map::HallwayViewConfig::max_bend_deg, 30 degrees).
  double corner_turn_deg = 30.0;
  // ... within this much travel: the base turns at a corner in place or within a few inches,
  // while along a curved wall (a radius of 50 ft turns 2.3 degrees in 24 in) or a bend it
  // steers through, the heading changes over many feet. A curve is the one wall the map's
  // hallway view merges its chords into, not a corner per 30 degrees of it.
  double corner_window_in = 24.0;
  // A turn is over once the base has travelled this far since it began (it turns in place,
  // then drives on): the heading then is the new wall's, and the wall range read then is
  // the one after the corner.
  double turn_settled_travel_in = 3.0;
  // Wall ranges are trusted while the heading is within this of the wall's.
  double turn_settled_deg = 10.0;
  // Without a wall range after the turn within this much travel, the range before the
  // turn stands in for it (a symmetric corner).
  double range_wait_in = 24.0;
  // The travel direction has reversed once the odometer is this far back from the farthest
  // point reached (more than a wheel's slip or the settling after a stop).
  double reverse_after_in = 12.0;
};

// Assembles per-frame door sightings and the odometer into the sensed sequence of StickRep
// edges (§6.3, Figure 6.2 steps 3-4): a door edge per tracked door (class by
// confidence-weighted vote, width by median, the leaf's mark by vote), and between consecutive
// doors a wall edge whose length is the odometry distance between their facing jambs. The wall the
// robot started in is only partly seen: its length is a lower bound.
//
// The detector pairs any two strong vertical edges (Figure 4.1), so one door gives several
// pairs: the opening, the opening plus a casing, a casing to a leaf window's edge. Each pair
// is tracked by its two jambs; of tracks that overlap only the best supported is a door.
// A wall panel between two doors, framed by their casings, is a pair too: a "door" whose
// jambs touch doors on both sides is that panel and is left out. Which track of a row is its
// first door decides that phase for the whole row, so a door that begins one waits for the
// track after it: of the two, the better supported is the door (a panel seen first, by the
// casings of the door beside the robot's start, would otherwise make every door of the row
// a panel and every panel a 40 in door). The two leaves of a double
// door (the meeting stile is a jamb to the detector; a 72 in door never fits in the view
// from the hallway axis) are two tracks that share the stile: they become one 30/30 or
// 36/36 edge by their span, as the map has them (Table 4.1's double-door classes).
class EdgeAssembler {
 public:
  explicit EdgeAssembler(EdgeAssemblerConfig config = {}) : config_(config) {}

  void AddSighting(const DoorSighting& s);
  // The perpendicular distance from the base centre to the wall the camera looks at (the
  // coaxial sonar), for placing corners: see EmitCorner. Non-finite or non-positive: none.
  void SetWallRange(double range_in);
  // Advances the odometer (and the odometry heading, radians CCW); returns the edges
  // completed by this step, in travel order.
  std::vector<map::SensedEdge> Advance(double odometer_in, double heading_rad = 0.0);
  // Forgets everything: the next edges start a new sequence (deterministic recovery, §6.7).
  // The robot is then inside a wall or door again, so the next wall is a lower bound.
  void Restart();
  // Whether the travel direction reversed since the last call (a goal behind, a hallway
  // end): the odometer ran reverse_after_in back from the farthest point reached. The
  // assembler has then restarted, travelling the other way.
  bool TakeReversal() {
    const bool r = reversed_;
    reversed_ = false;
    return r;
  }
  // At the last reversal: how far the robot went past the far end of the last emitted
  // edge before it turned back (NaN when no edge had been emitted, or in a turn).
  double reversal_travel_in() const { return reversal_travel_in_; }
  int travel_direction() const { return direction_; }
  // The last odometer reading given to Advance.
  double odometer_in() const { return odometer_in_; }
  // How far past the far end of the last emitted edge the pipeline has seen nothing: no
  // door emitted, none in view waiting to be decided, up to silent_margin_in behind the
  // optical axis. A door the map has within that stretch was missed (or the map place is
  // wrong). Empty before the first edge and while a corner is being turned or placed.
  std::optional<double> silent_in() const;
  // Odometer reading at the far end of the last emitted door; empty before the first.
  std::optional<double> last_edge_end_in() const { return last_jamb_in_; }
  // Edges emitted since the last Restart(), in order.
  const std::vector<map::SensedEdge>& sequence() const { return sequence_; }
  // Where each edge of sequence() began and ended: odometer readings, in travel order.
  struct Span {
    double from_in = 0.0;
    double to_in = 0.0;
  };
  const std::vector<Span>& spans() const { return spans_; }

 private:
  // One pair of vertical edges seen in one or more frames: its jambs in odometer
  // coordinates (lo < hi), the detector's confidence summed over the frames, and the
  // classifier's votes.
  struct Track {
    double lo_sum = 0.0, hi_sum = 0.0;
    int frames = 0;
    double support = 0.0;
    double class_weight[map::kDoorClassCount] = {};
    double mark_weight[map::kDoorMarkCount] = {};  // confidence-weighted reads, by mark
    // Set when this track is the second leaf of a double door: the double door's class
    // and the first leaf's near jamb, where the double door begins.
    std::optional<map::DoorClass> double_class;
    double double_near_jamb_in = 0.0;
    double lo() const { return lo_sum / frames; }
    double hi() const { return hi_sum / frames; }
    double along() const { return 0.5 * (lo() + hi()); }
    double width() const { return hi() - lo(); }
    map::DoorClass VotedClass() const;
    // The mark most read, unknown reads left out; kUnknown when every read was.
    map::DoorMark VotedMark() const;
  };
  double Near(const Track& t) const { return direction_ >= 0 ? t.lo() : t.hi(); }
  double Far(const Track& t) const { return direction_ >= 0 ? t.hi() : t.lo(); }
  // Decides what the front track (complete) is: false when it is left out.
  bool Decide(Track& t);
  // Whether a track in view begins within min_wall_in of t's far jamb. One frame is enough:
  // it says only that something frames t on its far side, as a door's casing frames a panel.
  bool TouchesOneInView(const Track& t) const;
  // Decides the front track and emits it, or holds it (held_) while it may be a row's first
  // wall panel, or settles the held one against it.
  void Complete(Track t, std::vector<map::SensedEdge>& out);
  // The track in view that is t's next leaf: it begins at t's far jamb (the meeting stile),
  // alike, the two seen in min_frames together and spanning a double door (its class in
  // `door_class`); null when none is.
  Track* NextLeaf(const Track& t, map::DoorClass* door_class);
  // The double door whose two leaves span `span_in` jamb to jamb, if any.
  std::optional<map::DoorClass> DoubleDoorClass(double span_in) const;
  void Emit(const Track& t, std::vector<map::SensedEdge>& out);
  void EmitEdges(double near_jamb_in, double far_jamb_in, map::DoorClass door_class,
                 map::DoorMark mark, std::vector<map::SensedEdge>& out);

  EdgeAssemblerConfig config_;
  std::vector<Track> open_;
  // A complete door that touches the next track in view and follows no door: the first
  // door of a row, or the row's first wall panel, until the next track is complete.
  std::optional<Track> held_;
  std::vector<map::SensedEdge> sequence_;
  std::vector<Span> spans_;
  double odometer_in_ = 0.0;
  bool have_odometer_ = false;
  double start_in_ = 0.0;             // odometer where the current sequence began
  int direction_ = 0;                 // +1 / -1 once the robot has moved
  double farthest_in_ = 0.0;          // odometer farthest along the travel direction
  bool reversed_ = false;
  double reversal_travel_in_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<double> last_jamb_in_;  // trailing jamb of the last emitted door (or corner)
  std::optional<double> last_door_end_in_;  // trailing jamb of the last emitted door
  // Headings over the last corner_window_in of travel, oldest first: the oldest is the
  // reference a turn is measured from.
  struct HeadingSample {
    double odometer_in;
    double heading_rad;
  };
  std::deque<HeadingSample> headings_;
  // The heading change from the reference, after adding the newest sample.
  double TurnOverWindow(double heading_rad);
  double pending_angle_deg_ = std::numeric_limits<double>::quiet_NaN();  // node before next edge
  // A corner begun (heading past corner_turn_deg) and not yet placed: the base is turning
  // in place, or has just turned and waits for the wall range on its new side.
  struct PendingCorner {
    double odometer_in = 0.0;
    double turn_rad = 0.0;           // when it began: only its sign is used
    double range_before_in = 0.0;    // NaN when no range was read before the turn
    bool settled = false;            // the base drives on along the new wall
    double settled_odometer_in = 0.0;
  };
  std::optional<PendingCorner> corner_;
  std::vector<map::SensedEdge> placed_;  // placed by SetWallRange, handed out by Advance
  double wall_range_in_ = std::numeric_limits<double>::quiet_NaN();  // newest, heading steady
  double unconfirmed_range_in_ = std::numeric_limits<double>::quiet_NaN();  // since Advance
  void BeginCorner(double turn_rad, std::vector<map::SensedEdge>& out);
  void PlaceCorner(double range_after_in, std::vector<map::SensedEdge>& out);
  // The wall from the last door's far jamb (or the sequence start) to `end_in`, if any.
  void EmitWallUpTo(double end_in, std::vector<map::SensedEdge>& out);
};

}  // namespace stickrep::localizer
