#pragma once

// The map as a robot that follows the hallway senses it. A hallway follower (§6.3, A3/A4)
// turns only where a wall blocks its way; a shallow step of the wall (a pilaster, a
// recessed alcove: two opposite corners joined by a short wall across the hallway) is
// passed straight, and odometry sees one wall where the map has three or more edges. The
// view removes those steps: the step's edge and its two corners go, the coplanar walls
// either side merge into one (lengths along the hallway add), and the localizer matches
// sensed edges against the view. Likewise walls joined at shallow bends (curved walls as
// chords) merge, openings (map format 2) are passed as wall (but a corridor's open end,
// through which the robot leaves the ring: map::IsOpenEnd), and corners of any other angle
// become the 90° or 270° turn the follower makes there. A door too wide for the camera to
// see whole from the hallway's axis is passed as wall too. Positions in the view map back
// to the map's own edges.

#include <functional>
#include <optional>
#include <vector>

#include "stickrep/map.h"

namespace stickrep::map {

struct HallwayViewConfig {
  // A wall edge between two opposite corners (90 then 270, or 270 then 90) shorter than
  // this is a step the follower passes straight. 0 keeps every corner.
  double max_step_in = 36.0;
  // A node between two walls (or openings) whose angle lies within this of 180° is a bend
  // the follower follows without turning: a coplanar joint, a curved wall written as chords,
  // a shallow corner. The walls either side are sensed as one, lengths along the wall add.
  // A node bent further is a corner the follower turns at in place, left or right: it is
  // sensed as 90° (convex) or 270° (concave) whatever its angle, and the view says so.
  double max_bend_deg = 30.0;
  // The class the robot's detector reports for a door of a given opening width, nullopt
  // when it rejects the width. When set, every door is matched as that class (a door of
  // measured width, map format 2, is what the robot will call it), or as wall. Empty: the
  // map's classes as they are.
  std::function<std::optional<DoorClass>(double width_in)> sensed_door_class;
  // The camera stares at the wall the robot follows from the hallway's axis, half the
  // hallway's width away, where its horizontal field of view covers 2 r tan(fov / 2) of wall
  // (46.6 in in an 88 in corridor, 63.6 in in the text's 120 in hallways). The detector
  // pairs two jambs seen in one frame (Figure 4.1), so a door (a double door: each leaf)
  // whose opening plus door_view_margin_in is wider than that is never reported: the view
  // has it as wall. 0: every door is seen.
  double camera_fov_deg = 0.0;
  // The casings either side (the casing rule needs all four edges in the frame) and the
  // travel over the frames a door must be seen in. Measured per door width with
  // stickrep-whereami --measure-ft (docs/whereami.md): at 44 in from the wall 36 in doors
  // are seen and 40-48 in ones never; at 48 in, 38 in seen, 40 in half the time, 42 and 44 in
  // never; at 60 in, 40 in doors are seen.
  double door_view_margin_in = 10.0;
  // The hallway's width along rings whose map gives none (Ring::width_in).
  double hallway_width_in = 120.0;
  // A recess of the wall (an alcove: the wall turns away from the hallway, runs on, and
  // turns back by the same depth) whose back, doors included, is at most this long is
  // passed straight at any depth under the hallway's width: the follower holds its track
  // across it (locomotion's reinit_recess_in, 96 in), and odometry sees one wall with the
  // doors at its back. Both sides go as steps do. 0: only max_step_in steps.
  double max_recess_in = 96.0;
};

class HallwayView {
 public:
  // Throws std::invalid_argument when the collapsed map is not a valid map (it always is
  // for a valid input; the check stays as a guard).
  HallwayView(const Map& map, HallwayViewConfig config = {});

  // The collapsed map: same rings (ids, order, closedness), fewer edges.
  const Map& view() const { return view_; }
  const Map& original() const { return original_; }

  // Original edges that make up view edge `edge` of ring `ring`, in ring order (steps
  // included).
  const std::vector<int>& OriginalEdges(int ring, int edge) const {
    return members_[ring][edge];
  }
  // The view edge that contains original edge `edge` of ring `ring`.
  int ViewEdge(int ring, int edge) const { return view_of_[ring][edge]; }

  // A place `offset_in` into view edge `edge` (measured from the node behind, travelling
  // `dir`: +1 ring order) as a place on the original map: the original edge and the
  // offset into it from its node behind. Steps across the hallway take no length; the
  // travel a bend adds (odometer length) is spread over the wall in proportion.
  struct Place {
    int edge = 0;
    double offset_in = 0.0;
  };
  Place ToOriginal(int ring, int edge, int dir, double offset_in) const;

  // Edges removed as steps, over all rings.
  int steps_removed() const { return steps_removed_; }

 private:
  // Whether original edge `e` of ring `r` is a step.
  bool IsStep(int r, int e) const;
  // Whether original edge `e` of ring `r` is a side of a recess the follower passes
  // straight (HallwayViewConfig::max_recess_in).
  bool IsRecessSide(int r, int e) const;
  // Edge `index` of ring `r` as the follower and the detector sense it: an opening as wall
  // (a corridor's open end stays an opening: IsOpenEnd), a door as the class the detector
  // reports for its width, or as wall when the camera cannot see it whole.
  Edge Sensed(int r, int index) const;
  bool WallLike(int r, int index) const;
  // The hallway's width along ring r: the map's, else the settings'.
  double HallwayWidthIn(int r) const;
  // The widest door opening (one leaf of a double door) the camera sees whole along ring r.
  double WidestSeenDoorIn(int r) const;
  // What the base's odometer travels beyond the wall's length at bend `bend` of ring r.
  double BendTravelIn(int r, const Node& bend) const;
  // Whether each original edge of ring r is a step (or a recess side) the follower passes.
  std::vector<bool> StepEdges(int r) const;
  // Whether kept edge e of ring r continues the view edge of the kept edge before it: only
  // steps lie between them and both are walls.
  bool Merges(int r, const std::vector<bool>& step, int e) const;
  // The edge of ring r its view starts at: a kept edge that begins a view edge (edge 0 of an
  // open ring). Throws std::invalid_argument when the ring has only steps.
  int StartEdge(int r, const std::vector<bool>& step) const;
  // The node of ring r that begins the view edge of kept edge e, as the follower senses it.
  Node ViewNode(int r, const std::vector<bool>& step, int e) const;
  // Ring r of the view; records its members, view edges and steps. node_of: [original node]
  // -> view node, for the joins.
  Ring CollapseRing(int r, std::vector<int>* node_of);

  HallwayViewConfig config_;
  Map original_;
  Map view_;
  std::vector<std::vector<std::vector<int>>> members_;  // [ring][view edge] -> originals
  std::vector<std::vector<int>> view_of_;               // [ring][original edge] -> view edge
  std::vector<std::vector<bool>> step_;                 // [ring][original edge]
  int steps_removed_ = 0;
};

}  // namespace stickrep::map
