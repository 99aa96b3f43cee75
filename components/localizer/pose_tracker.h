#pragma once

// Pose maintenance after localization (§3.3): "If a high confidence match is made between
// sensed data and the next anticipated edge on the graph, within its current uncertainty
// circle, the current pose estimate can be updated to this edge. If not, the robot will
// continue searching for the anticipated feature edge until it reaches a tolerance limit
// that initiates complete pose recovery." Map and edges in, pose and status out; no DDS.

#include <optional>
#include <string>
#include <vector>

#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::localizer {

enum class TrackStatus {
  kIdle,      // not started: no localized pose yet
  kTracking,  // the pose is maintained
  kLost,      // too many consecutive misses: the localizer starts a full recovery
};
const char* ToString(TrackStatus s);

// A pose on the map: inside edge `edge` of ring `ring`, travelling in ring order (dir = +1)
// or against it (dir = -1), offset_in past the edge's start in the travel direction. The
// same meaning as localizer::Hypothesis.
struct TrackedPose {
  int ring = 0;
  int edge = 0;
  int dir = +1;
  double offset_in = 0.0;
};

struct PoseTrackerConfig {
  // Radius of the uncertainty circle (§3.3, Brooks' uncertainty cylinder of §3.1): a base
  // for the jamb placement of the landmark pipeline (doors are placed to a few inches;
  // a door's jambs to an inch or two frame to frame) plus a share of the distance travelled
  // since the last confirmation for wheel slip (a few per cent on a LabMate, §3.1).
  double uncertainty_base_in = 12.0;
  double uncertainty_per_travel = 0.05;
  // How walls are compared (their length is the odometer distance between two jambs): the
  // localizer's tolerance, 10 % or 6 in.
  double wall_tolerance_rel = 0.10;
  double wall_tolerance_abs_in = 6.0;
  // How far past a door's centre the edge stream reports it: EdgeAssemblerConfig::
  // out_of_view_in. An anticipated door is missed once the odometer is this far past its
  // centre plus the uncertainty radius.
  double report_delay_in = 48.0;
  // More than this many consecutive misses: LOST. Table 6.10's fused error model has one
  // door in six false and one in sixteen missed, so single misses are common and two in a
  // row happen; three in a row are rare on the right track and quick to come when the
  // robot is somewhere else.
  int max_consecutive_misses = 2;
  // How many edges past the next anticipated one a sensed edge may be matched to (after
  // missed doors the next confirmation is further along).
  int lookahead_edges = 8;
};

// Maintains a localized pose along the rings from the odometer and the sensed edges (the
// EdgeAssembler's output). The next anticipated edges are predicted from the odometer,
// measured from an anchor: the last confirmed edge's end as sensed, so every confirmation
// flushes the accumulated dead-reckoning error (§3.1: "the accumulated dead-reckoning error
// determining the radius of the uncertainty region can be briefly reset").
//
// - A sensed door whose far jamb lies within the uncertainty radius of an anticipated map
//   door's far end, of the same class, confirms it: the pose is re-anchored there, the
//   uncertainty and the miss count reset. Anticipated doors passed over on the way count
//   as misses (missed doors).
// - A sensed door near a map door of another class (a mis-sized door) or near no map door
//   at all (a false door) is a miss.
// - An anticipated door not reported by the time the odometer is report_delay_in plus the
//   uncertainty radius past its centre is a miss.
// - A sensed wall of matching length ending where a map wall ends confirms it. A wall that
//   does not match is not counted: its length comes from the jambs of the doors on either
//   side, so whatever made it wrong (a false or missed door) is already counted once.
// - More than max_consecutive_misses consecutive misses: LOST (a kidnapped robot sees doors
//   where the map has none and misses those it anticipates). Nothing changes until Start().
//
// Holds a reference to `map`, which must outlive it. Never throws after construction.
class PoseTracker {
 public:
  explicit PoseTracker(const map::Map& map, PoseTrackerConfig config = {});

  // Starts tracking from a localized pose at odometer reading `odometer_in`.
  // `odometer_sign` is +1 when the odometer increases as the robot moves along pose.dir,
  // -1 when it decreases (the base drives backward): the EdgeAssembler's
  // travel_direction(). Returns false (and stays or becomes IDLE) for a pose not on the map.
  bool Start(const TrackedPose& pose, double odometer_in, int odometer_sign);

  // Stops tracking (IDLE): the pose was found wrong elsewhere.
  void Stop(const std::string& why) {
    status_ = TrackStatus::kIdle;
    message_ = why;
  }

  // Dead reckoning: a new odometer reading. Counts anticipated doors that were not seen.
  void Advance(double odometer_in);
  // One sensed edge whose far end (in the travel direction) was at odometer reading
  // `end_odometer_in`.
  void OnEdge(const map::SensedEdge& edge, double end_odometer_in);
  // The edges one EdgeAssembler::Advance() returned, in travel order, and the odometer
  // reading at the far end of the last one: EdgeAssembler::last_edge_end_in() when the
  // batch ends with a door, the reading where the base turned when it ends with a wall at
  // a corner. The ends of the earlier edges follow from the later edges' metrics (doors
  // without a measured width: their class width).
  void OnEdges(const std::vector<map::SensedEdge>& edges, double last_end_odometer_in);

  TrackStatus status() const { return status_; }
  // The pose at the last odometer reading (dead-reckoned from the last confirmation).
  TrackedPose pose() const;
  // Radius of the uncertainty circle at the last odometer reading.
  double uncertainty_in() const;
  // The next map edge the robot expects to sense; empty when not tracking or past the end
  // of an open ring.
  std::optional<map::Cursor> anticipated() const;

  int consecutive_misses() const { return consecutive_misses_; }
  int confirmations() const { return confirmations_; }
  int misses() const { return misses_; }
  // What happened last, for the status topic ("confirmed door36 at hall/5", ...).
  const std::string& message() const { return message_; }

 private:
  // An edge `steps` edges past the anchor: where it starts, in inches of travel past the
  // anchor; empty past the end of an open ring.
  struct Ahead {
    map::Cursor cursor;
    double start_in = 0.0;
    const map::Edge* edge = nullptr;
  };
  std::optional<Ahead> EdgeAhead(int steps) const;
  double TravelPastAnchor(double odometer_in) const {
    return odometer_sign_ * (odometer_in - anchor_odometer_in_);
  }
  double UncertaintyAt(double odometer_in) const;
  void Confirm(const Ahead& a, int steps, double end_odometer_in, const std::string& what);
  void Miss(const std::string& why);
  std::string Where(const map::Cursor& c) const;

  const map::Map& map_;
  PoseTrackerConfig config_;
  TrackStatus status_ = TrackStatus::kIdle;
  map::Cursor anchor_;               // the edge that starts at the anchor
  double anchor_odometer_in_ = 0.0;  // odometer where anchor_ starts
  int next_steps_ = 0;               // first unresolved edge, in edges past the anchor
  int odometer_sign_ = +1;
  double odometer_in_ = 0.0;
  double confirmed_odometer_in_ = 0.0;
  int consecutive_misses_ = 0;
  int confirmations_ = 0;
  int misses_ = 0;
  std::string message_;
};

}  // namespace stickrep::localizer
