#pragma once

// What the assembled edges of a run were, held against the edges the robot truly passed:
// the live counterpart of Table 6.10, per sensed edge rather than per frame. Doors are
// matched by where their centre was; a true door with no sensed door there is missed, a
// sensed door on a wall is a false door. The counts become an error model in the schema of
// configs/error_model_paper.yaml, for the Bayes matcher.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "localizer/edge_assembler.h"
#include "recovery/error_model.h"
#include "stickrep/map.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::whereami {

// Where the optical axis met the wall at one odometer reading: a view edge (the map as the
// hallway follower senses it, map::HallwayView), or -1 when it met no mapped wall.
struct TruthSample {
  double odometer_in = 0.0;
  int view_edge = -1;
};

struct EdgeErrorCounts {
  long true_doors = 0, correct = 0, missized = 0, missed = 0;
  long true_walls = 0, false_doors = 0;
  // [true class][sensed class] of mis-sized doors; classes of false doors.
  std::array<std::array<long, map::kDoorClassCount>, map::kDoorClassCount> missized_to{};
  std::array<long, map::kDoorClassCount> false_class{};
  // Sensed minus true length of walls between two doors that were both sensed correctly.
  std::vector<double> wall_error_in;
  // Every sensed wall (but a run's first edge, and walls that begin or end at a sensed
  // corner: `walls_at_corners`) whose two ends lie within kNodeNearIn of a true node: sensed
  // minus true length (the true edges between the two nodes), by what bounds it. Each end
  // is a jamb of a door read with its class, of a door read mis-sized, or another node (a
  // step, a join, a door missed); `over_missed` when a true door between the ends went
  // unseen. The Bayes matcher weighs a wall by a normal error about its length
  // (SensingNoise::WallSigmaIn): these show whether the live walls are read so.
  enum class WallEnd : std::uint8_t { kDoorRight, kDoorMissized, kOther };
  struct WallResidual {
    double error_in = 0.0;
    double true_in = 0.0;
    WallEnd start = WallEnd::kOther, end = WallEnd::kOther;
    bool over_missed = false;
    int missed_doors = 0;  // the true doors between the ends that went unseen
  };
  static constexpr double kNodeNearIn = 8.0;
  std::vector<WallResidual> wall_residuals;
  // Sensed wall ends (as above) and those farther than kNodeNearIn from every true node.
  long wall_ends = 0, wall_ends_off_node = 0, walls_at_corners = 0;
  // Mis-sized doors read at least recovery::kLeafDeficitIn narrower than they are (a double
  // door read as one leaf), and where the rest of the width went: the other leaf read as a
  // second door (right after, or after a sliver of wall: the slivers' sensed lengths), or
  // the sensed wall just before or just after longer by more than half the missing width.
  long leaf_reads = 0, leaf_split = 0, leaf_wall_before = 0, leaf_wall_after = 0;
  std::vector<double> leaf_sliver_in;
  // The true doors by their width (inches, rounded): passed, sensed with their class,
  // mis-sized, missed. A door wider than the camera's view at the wall's range is never
  // whole in one frame; this shows which widths the pipeline sees.
  struct DoorTally {
    long passed = 0, correct = 0, missized = 0, missed = 0;
  };
  std::map<int, DoorTally> by_width;
  // The same by the door's class: the error model's per-class rates.
  std::array<DoorTally, map::kDoorClassCount> by_class{};
  // Doors in a row and doors alone, by class ([1][class]: map::InDoorRow), and the walls
  // shorter than map::kRowWallIn between two doors against every other wall ([1]: those
  // short walls), with the false doors sensed on them: the error model's in-row rates.
  std::array<std::array<DoorTally, map::kDoorClassCount>, 2> by_row{};
  struct WallTally {
    long walls = 0, false_doors = 0;
    double wall_in = 0.0;  // the walls' lengths summed
    void Add(const WallTally& o) {
      walls += o.walls;
      false_doors += o.false_doors;
      wall_in += o.wall_in;
    }
  };
  std::array<WallTally, 2> walls_by_row{};
  // The doors of a row by the door before them across the short wall between
  // ([before missed][class]): the in-row missed rates after a missed and after a seen door
  // (ErrorModel::InRow::door_missed_after_missed, _after_seen).
  std::array<std::array<DoorTally, map::kDoorClassCount>, 2> row_by_before{};
  // The true walls between two true doors ([0]: at least map::kRowWallIn long, [1]: shorter)
  // by whether the door before them (in the direction of travel) and the door after them
  // were missed ([before missed][after missed]), with the walls that held a false door (a
  // wall counts once, however many it held): the in-row rates after a missed and after a
  // seen door (ErrorModel::InRow::wall_false_door_after_missed, _after_seen).
  std::array<std::array<std::array<WallTally, 2>, 2>, 2> walls_by_missed{};
  // The true walls and the false doors sensed on them by the wall's length (its view edge's
  // metric): bin b holds lengths in [kWallLengthBinsIn[b], kWallLengthBinsIn[b + 1]), the
  // last bin every longer wall. A false door is read on a stretch of wall, so a rate per
  // wall hides how it grows with the wall's length.
  static constexpr std::array<double, 6> kWallLengthBinsIn{0.0, 60.0, 120.0, 240.0, 480.0, 960.0};
  std::array<WallTally, kWallLengthBinsIn.size()> walls_by_length{};
  // The walls outside rows by how many false doors each held: 0, 1, 2 and kMostCounted or
  // more (ErrorModel::wall_false_doors_max).
  static constexpr int kMostCounted = 4;
  std::array<long, kMostCounted + 1> walls_by_false_doors{};
  // How the leaves' marks were read (Table 6.8): [true mark][read mark] over the sensed doors
  // on a true door, sensed with their class and mis-sized (both leaves of a split double
  // door), and the reads of false doors.
  using MarkCounts = std::array<long, map::kDoorMarkCount>;
  std::array<MarkCounts, map::kDoorMarkCount> mark_read{}, mark_read_missized{};
  MarkCounts false_mark{};

  void Add(const EdgeErrorCounts& other);
  // The rates as an error model (door rates per true door, false doors per true wall). Each
  // class's own rates are shrunk towards the overall ones by kClassPriorDoors doors' worth,
  // so a class seen a few times, all correct, is not made certain. Where doors in a row or
  // short walls between doors were passed, the rates are split (ErrorModel::in_row): each
  // class's doors alone and in a row, shrunk likewise towards the class's rates, and the
  // false doors of those short walls and of the other walls, shrunk towards all walls'
  // by as many walls' worth; the false doors per inch of the walls not in a row
  // (ErrorModel::wall_false_door_per_in) are their count over those walls' length. The
  // mark rows are the
  // read shares of each true mark seen (mis-sized reads shrunk likewise towards the reads
  // with the class right), and of the false doors.
  // With the matcher's `noise`, the walls over missed doors (wall_residuals) also give
  // ErrorModel::wall_over_missed_door, where at least kMinMissedWalls were measured: the
  // mean error per missed door, and the spread per missed door beyond the matcher's own
  // sigma of each wall (SensingNoise::WallSigmaIn).
  static constexpr double kClassPriorDoors = 20.0;
  static constexpr int kMinMissedWalls = 20;
  recovery::ErrorModel ToModel(const std::string& source,
                               const recovery::SensingNoise* noise = nullptr) const;
};

// Compares the sensed edges (with the odometer readings they spanned) with the true view
// edges passed, counting only true edges passed whole between `from_in` and `to_in`
// (odometer readings; either order).
EdgeErrorCounts CompareWithTruth(const map::Ring& view_ring,
                                 const std::vector<map::SensedEdge>& sensed,
                                 const std::vector<localizer::EdgeAssembler::Span>& spans,
                                 const std::vector<TruthSample>& truth, double from_in,
                                 double to_in);

// Measures one run's assembled edges against the truth, one travel direction at a time. A
// reversal (a hallway end, a dead-end corridor) restarts the assembly and so forgets the
// sequence sensed so far (EdgeAssembler::Restart); each direction's sequence is compared
// with the truth passed during it, before it is forgotten.
class EdgeErrorMeter {
 public:
  // Odometer travel at the start skipped (aligning, the partial first edges).
  EdgeErrorMeter(const map::Ring& view_ring, localizer::EdgeAssembler& assembler,
                 double skip_in);
  // One encoder reading: advances the assembler and records where the optical axis met the
  // wall (a view edge, or -1).
  void Advance(double odometer_in, double heading_rad, int view_edge);
  // The counts over every direction travelled, the one under way included.
  EdgeErrorCounts Finish();
  // Travel directions measured (1 + reversals).
  int directions() const { return directions_; }

 private:
  void CompareDirection(const std::vector<map::SensedEdge>& sensed,
                        const std::vector<localizer::EdgeAssembler::Span>& spans);

  const map::Ring& view_ring_;
  localizer::EdgeAssembler& assembler_;
  double skip_in_;
  int directions_ = 1;
  std::vector<TruthSample> truth_;  // this direction's
  std::vector<map::SensedEdge> sequence_;  // the assembler's, as of the last reading
  std::vector<localizer::EdgeAssembler::Span> spans_;
  EdgeErrorCounts counts_;
};

}  // namespace stickrep::whereami
