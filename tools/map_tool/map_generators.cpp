#include "map_tool/map_generators.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>

#include "stickrep/paper_reference.h"

namespace stickrep::map {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Portable sampling on top of std::mt19937_64 (whose output the standard fixes); the
// std:: distributions are implementation-defined and would break byte-for-byte output.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed) {}
  // Uniform integer in [0, n).
  std::uint64_t Below(std::uint64_t n) {
    assert(n > 0);
    const std::uint64_t limit =
        std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
    std::uint64_t v;
    do {
      v = gen_();
    } while (v >= limit);
    return v % n;
  }
  int Int(int lo, int hi) {
    return lo + static_cast<int>(Below(static_cast<std::uint64_t>(hi - lo + 1)));
  }
  double Uniform() { return static_cast<double>(gen_() >> 11) * (1.0 / 9007199254740992.0); }
  template <typename T>
  void Shuffle(std::vector<T>& v) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[Below(i)]);
  }

 private:
  std::mt19937_64 gen_;
};

// One edge of a ring under construction with the angle of the node before it.
struct Item {
  double angle_deg = 180.0;
  Edge edge;
  bool artificial = false;
};

// Lays the items out with a turtle: node 0 at (x0, y0), the first edge heading
// `heading0_deg`, turning by (angle - 180) at each node (the wall is on the walker's right,
// so a 90° convex corner is a right turn).
Ring BuildRing(const std::string& id, bool closed, const std::vector<Item>& items, double x0,
               double y0, double heading0_deg) {
  Ring ring;
  ring.id = id;
  ring.closed = closed;
  double x = x0, y = y0, h = heading0_deg;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) h += items[i].angle_deg - 180.0;
    Node n;
    n.angle_deg = items[i].angle_deg;
    n.x_in = x;
    n.y_in = y;
    n.gamma_deg = std::fmod(std::fmod(h, 360.0) + 360.0, 360.0);
    n.artificial = items[i].artificial;
    ring.nodes.push_back(n);
    ring.edges.push_back(items[i].edge);
    x += items[i].edge.metric_in * std::cos(h * kPi / 180.0);
    y += items[i].edge.metric_in * std::sin(h * kPi / 180.0);
  }
  if (!closed) {
    Node end;
    end.angle_deg = 180.0;
    end.x_in = x;
    end.y_in = y;
    ring.nodes.push_back(end);
  }
  // Rounded so that the file shows clean numbers and tiny drift never accumulates.
  for (Node& n : ring.nodes) {
    n.x_in = std::round(n.x_in * 1000.0) / 1000.0;
    n.y_in = std::round(n.y_in * 1000.0) / 1000.0;
    n.gamma_deg = std::round(n.gamma_deg * 1000.0) / 1000.0;
    if (n.gamma_deg >= 360.0) n.gamma_deg -= 360.0;
  }
  return ring;
}

int ArtificialNode(const Ring& ring) {
  for (int i = 0; i < ring.NodeCount(); ++i) {
    if (ring.nodes[i].artificial) return i;
  }
  return 0;
}

int NearestNode(const Ring& ring, const Node& to) {
  int best = 0;
  double best_d = std::numeric_limits<double>::max();
  for (int i = 0; i < ring.NodeCount(); ++i) {
    const double d = std::hypot(ring.nodes[i].x_in - to.x_in, ring.nodes[i].y_in - to.y_in);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

// ---------------------------------------------------------------------------------------
// Engineering Building, third floor.
//
// Structure derived from Tables 6.1-6.9 (see maps/README.md for the arithmetic):
// 431 walls; door edges 11 x 30/30, 4 x 32, 28 x 36/36, 156 x 36, 11 x 40 (249 leaves, the
// "blank" column of Table 6.8); 680 leaf edges in 10 closed rings with one artificial node
// each, so that 670 physical pairs remain (the sum of Tables 6.1-6.3). Rings are rectangles:
// 7 blocks of rooms seen from the corridor (4 convex corners) and 3 outer corridor walls
// (4 concave corners), with 43 pilasters/alcoves, one recessed door and one door in an
// alcove making up the corner counts of Tables 6.1 and 6.3.
// ---------------------------------------------------------------------------------------

// Wall lengths come from a small catalogue per Table 6.9 bin: a building's walls repeat a
// few standard lengths, which is what makes a sensed sequence ambiguous (§6.2). The number
// of distinct lengths per bin is the one free parameter; it is set so that the no-error
// ambiguity lands near Table 6.22's 5.28 edges.
constexpr int kEngineeringLengthsPerBin = 1;
constexpr double kHallwayWidthIn = 96.0;

enum class SlotRole { kBase, kDepth, kFace };

struct Slot {
  SlotRole role = SlotRole::kBase;
  int ring = 0;
  int side = 0;
  int pair = -1;  // depth walls of one pilaster/alcove share a pair id (equal lengths)
  int row = -1;   // single walls between doors in one unbroken run along a side
  bool is_long = false;
  double length = 0.0;
};

// An item whose wall length is filled in later from slot `slot` (-1 for doors).
struct PItem {
  double angle_deg = 180.0;
  bool artificial = false;
  int slot = -1;
  Edge door;
  int side = 0;
};

enum class DecoKind { kPilaster, kAlcove };
struct Event {
  int side = 0;
  int gap = 0;
  bool art_split = false;
  DecoKind deco = DecoKind::kPilaster;
};

struct PRing {
  std::string id;
  bool block = true;  // seen from outside (convex corners) vs an outer corridor wall
  int wing = 0;
  std::vector<Edge> doors;
  std::vector<Event> events;
  int art_corner = -1;     // main corner flagged artificial, or -1
  int art_door = -1;       // door whose preceding node is artificial, or -1
  int recessed_door = -1;  // door set back in a recess (270° both sides)
  int alcove_door = -1;    // door at the back of an alcove (270° before it)
  std::vector<PItem> items;
  std::array<int, 4> absorber{{-1, -1, -1, -1}};  // a long base slot per side
};

// The 11 bins of Table 6.9 as [lo, hi) with their counts; the last is open-ended.
struct Bin {
  int lo, hi, count;
};
std::vector<Bin> WallBins() {
  const auto& th = paper::kWallThresholdsIn;
  const auto& n = paper::kWallCensus;
  std::vector<Bin> bins;
  for (std::size_t i = 0; i + 1 < th.size(); ++i) {
    bins.push_back({static_cast<int>(th[i]), static_cast<int>(th[i + 1]), n[i] - n[i + 1]});
  }
  bins.push_back({static_cast<int>(th.back()), 100000, n.back()});
  return bins;
}

class EngineeringBuilder {
 public:
  explicit EngineeringBuilder(std::uint64_t seed) : rng_(seed) {}

  Map Build() {
    MakeRings();
    AssignDoors();
    AssignEvents();
    for (std::size_t r = 0; r < rings_.size(); ++r) EmitRing(static_cast<int>(r));
    AssignLengths();
    // Long walls are 160 in plus a random share of a common stretch; the stretch is found by
    // bisection so that the mean leaf metric is the text's 67.64 in (§6.4.1).
    const double target = paper::kEngineeringMeanEdgeMetricIn * 680.0;
    double lo = 0.0, hi = 4000.0;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (Layout(mid) < target ? lo : hi) = mid;
    }
    Layout(lo);
    return Finish();
  }

 private:
  void MakeRings() {
    // Three wings of 3, 2 and 2 blocks.
    const int blocks_per_wing[3] = {3, 2, 2};
    int b = 0;
    for (int w = 0; w < 3; ++w) {
      PRing outer;
      outer.id = "wing" + std::to_string(w + 1) + "_corridor";
      outer.block = false;
      outer.wing = w;
      rings_.push_back(outer);
      for (int k = 0; k < blocks_per_wing[w]; ++k, ++b) {
        PRing block;
        block.id = "wing" + std::to_string(w + 1) + "_block" + static_cast<char>('a' + k);
        block.block = true;
        block.wing = w;
        rings_.push_back(block);
      }
    }
  }

  std::vector<int> BlockRings() const {
    std::vector<int> out;
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      if (rings_[r].block) out.push_back(static_cast<int>(r));
    }
    return out;
  }
  std::vector<int> OuterRings() const {
    std::vector<int> out;
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      if (!rings_[r].block) out.push_back(static_cast<int>(r));
    }
    return out;
  }

  void AssignDoors() {
    // Door edges with the marks of Table 6.8: every 36/36 double door has two new windows
    // (one per leaf), the singles carry the rest; every 40 in door has an old window.
    std::vector<Edge> doors;
    for (int i = 0; i < 11; ++i) doors.push_back(Edge::Door(DoorClass::k30_30));
    for (int i = 0; i < 4; ++i) doors.push_back(Edge::Door(DoorClass::k32));
    for (int i = 0; i < 28; ++i) doors.push_back(Edge::Door(DoorClass::k36_36, "two_new_windows"));
    const std::pair<const char*, int> singles[] = {{"two_new_windows", 48}, {"old_window", 54},
                                                   {"no_window", 10},       {"new_window", 3},
                                                   {"poster", 29},          {"", 12}};
    for (const auto& [pattern, count] : singles) {
      for (int i = 0; i < count; ++i) doors.push_back(Edge::Door(DoorClass::k36, pattern));
    }
    for (int i = 0; i < 11; ++i) doors.push_back(Edge::Door(DoorClass::k40, "old_window"));
    rng_.Shuffle(doors);
    const std::vector<int> blocks = BlockRings();
    const std::vector<int> outers = OuterRings();
    // Two artificial nodes sit before a door (Table 6.2: one door30 and one door36 have no
    // wall before them): a 30/30 in one block and a single 36 in another.
    auto take = [&](DoorClass cls) {
      for (std::size_t i = 0; i < doors.size(); ++i) {
        if (doors[i].door_class == cls) {
          Edge e = doors[i];
          doors.erase(doors.begin() + static_cast<long>(i));
          return e;
        }
      }
      throw std::logic_error("door class exhausted");
    };
    rings_[blocks[5]].doors.push_back(take(DoorClass::k30_30));
    rings_[blocks[5]].art_door = 0;
    rings_[blocks[6]].doors.push_back(take(DoorClass::k36));
    rings_[blocks[6]].art_door = 0;
    // The recessed door and the door in an alcove (Table 6.3's three door-wall pairs).
    rings_[blocks[0]].doors.push_back(take(DoorClass::k36));
    rings_[blocks[0]].recessed_door = 0;
    rings_[blocks[0]].doors.push_back(take(DoorClass::k36));
    rings_[blocks[0]].alcove_door = 1;
    // The rest spread over all rings. Corridor walls take the larger share: offices line the
    // outside of the corridors, and a corridor wall long enough for its blocks needs no wall
    // added to fit round them.
    for (const Edge& d : doors) {
      const std::uint64_t pick = rng_.Below(16);
      const int r = pick < 7 ? blocks[pick] : outers[(pick - 7) / 3];
      rings_[r].doors.push_back(d);
    }
    // Shuffle each ring's doors but remember where the special ones went.
    for (PRing& ring : rings_) {
      std::vector<int> order(ring.doors.size());
      std::iota(order.begin(), order.end(), 0);
      rng_.Shuffle(order);
      std::vector<Edge> shuffled;
      int art = -1, rec = -1, alc = -1;
      for (std::size_t i = 0; i < order.size(); ++i) {
        shuffled.push_back(ring.doors[order[i]]);
        if (order[i] == ring.art_door) art = static_cast<int>(i);
        if (order[i] == ring.recessed_door) rec = static_cast<int>(i);
        if (order[i] == ring.alcove_door) alc = static_cast<int>(i);
      }
      ring.doors = shuffled;
      ring.art_door = art;
      ring.recessed_door = rec;
      ring.alcove_door = alc;
    }
  }

  // Doors per side, equal on opposite sides so that a ring closes with little added wall:
  // `short_share` of them on each of sides 1 and 3, the rest split between sides 0 and 2.
  static std::array<int, 4> SideSplit(int doors, double short_share) {
    std::array<int, 4> n{};
    n[1] = n[3] = static_cast<int>(std::lround(doors * short_share));
    n[0] = (doors - 2 * n[1] + 1) / 2;
    n[2] = doors - 2 * n[1] - n[0];
    return n;
  }

  void AssignEvents() {
    for (PRing& ring : rings_) ring.events.clear();
    side_doors_.assign(rings_.size(), {});
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      // Blocks are squarish; a corridor wall runs round a row of k blocks, so its ends are
      // short (about 1 / (2 (k + 2)) of its doors on each).
      const PRing& ring = rings_[r];
      int k = 0;
      for (const PRing& other : rings_) k += (other.block && other.wing == ring.wing) ? 1 : 0;
      const double short_share = ring.block ? 0.25 : 1.0 / (2.0 * (k + 2));
      side_doors_[r] = SideSplit(static_cast<int>(ring.doors.size()), short_share);
    }
    auto random_gap = [&](int r, Event e) {
      e.side = static_cast<int>(rng_.Below(4));
      e.gap = static_cast<int>(rng_.Below(side_doors_[r][e.side] + 1));
      rings_[r].events.push_back(e);
    };
    const std::vector<int> blocks = BlockRings();
    const std::vector<int> outers = OuterRings();
    // Artificial nodes: at a main corner in three blocks and one corridor wall; splitting a
    // wall in two blocks and two corridor walls; before a door in the remaining two blocks.
    for (int k = 0; k < 3; ++k) rings_[blocks[k]].art_corner = static_cast<int>(rng_.Below(4));
    rings_[outers[0]].art_corner = static_cast<int>(rng_.Below(4));
    for (int r : {blocks[3], blocks[4], outers[1], outers[2]}) {
      Event e;
      e.art_split = true;
      random_gap(r, e);
    }
    // 43 pilasters and alcoves anywhere.
    for (int i = 0; i < 43; ++i) {
      const int r = static_cast<int>(rng_.Below(rings_.size()));
      Event e;
      e.deco = rng_.Below(2) == 0 ? DecoKind::kPilaster : DecoKind::kAlcove;
      random_gap(r, e);
    }
    for (PRing& ring : rings_) {
      std::stable_sort(ring.events.begin(), ring.events.end(), [](const Event& a, const Event& b) {
        return a.side != b.side ? a.side < b.side : a.gap < b.gap;
      });
    }
  }

  int NewSlot(SlotRole role, int ring, int side, int pair = -1) {
    slots_.push_back(Slot{role, ring, side, pair, -1, false, 0.0});
    return static_cast<int>(slots_.size()) - 1;
  }

  void EmitRing(int r) {
    PRing& ring = rings_[r];
    ring.items.clear();
    double next_angle = 0;
    bool next_art = false;
    int side = 0;
    auto emit_wall = [&](SlotRole role, int pair = -1) {
      PItem it;
      it.angle_deg = next_angle;
      it.artificial = next_art;
      it.slot = NewSlot(role, r, side, pair);
      it.side = side;
      ring.items.push_back(it);
      next_angle = 180.0;
      next_art = false;
    };
    auto emit_door = [&](const Edge& d) {
      PItem it;
      it.angle_deg = next_angle;
      it.artificial = next_art;
      it.door = d;
      it.side = side;
      ring.items.push_back(it);
      next_angle = 180.0;
      next_art = false;
    };
    const double corner = ring.block ? 90.0 : 270.0;
    int door_index = 0;
    std::size_t ev = 0;
    for (side = 0; side < 4; ++side) {
      next_angle = corner;
      next_art = ring.art_corner == side;
      const int doors_here = side_doors_[r][side];
      int row = next_row_++;
      for (int gap = 0; gap <= doors_here; ++gap) {
        emit_wall(SlotRole::kBase);
        const bool has_events =
            ev < ring.events.size() && ring.events[ev].side == side && ring.events[ev].gap == gap;
        if (gap > 0 && gap < doors_here && !has_events) {
          slots_.back().row = row;
        } else {
          row = next_row_++;
        }
        while (ev < ring.events.size() && ring.events[ev].side == side &&
               ring.events[ev].gap == gap) {
          const Event& e = ring.events[ev++];
          if (e.art_split) {
            next_art = true;
            emit_wall(SlotRole::kBase);
            continue;
          }
          const int pair = next_pair_++;
          const bool pilaster = e.deco == DecoKind::kPilaster;
          // Pilaster: 270 depth 90 face 90 depth 270; alcove: 90 depth 270 face 270 depth 90.
          const double in = pilaster ? 270.0 : 90.0, out = pilaster ? 90.0 : 270.0;
          next_angle = in;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = out;
          emit_wall(SlotRole::kFace);
          next_angle = out;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = in;
          emit_wall(SlotRole::kBase);
        }
        if (gap == doors_here) break;
        const Edge& d = ring.doors[door_index];
        if (door_index == ring.recessed_door) {
          const int pair = next_pair_++;
          next_angle = 90.0;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = 270.0;
          emit_door(d);
          next_angle = 270.0;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = 90.0;
        } else if (door_index == ring.alcove_door) {
          const int pair = next_pair_++;
          next_angle = 90.0;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = 270.0;
          emit_door(d);
          emit_wall(SlotRole::kFace);
          next_angle = 270.0;
          emit_wall(SlotRole::kDepth, pair);
          next_angle = 90.0;
        } else {
          next_art = door_index == ring.art_door;
          emit_door(d);
        }
        ++door_index;
      }
    }
  }

  void AssignLengths() {
    const std::vector<Bin> bins = WallBins();
    // A few standard lengths per bin (see kEngineeringLengthsPerBin).
    std::vector<std::vector<int>> catalogue(bins.size());
    for (std::size_t b = 0; b + 1 < bins.size(); ++b) {
      std::vector<int> values;
      const int lo = std::max(bins[b].lo, 2);
      for (int v = lo; v < bins[b].hi; ++v) values.push_back(v);
      rng_.Shuffle(values);
      values.resize(std::min<std::size_t>(values.size(), kEngineeringLengthsPerBin));
      catalogue[b] = values;
    }
    auto draw = [&](int b) { return catalogue[b][rng_.Below(catalogue[b].size())]; };
    std::vector<int> remaining;
    for (const Bin& b : bins) remaining.push_back(b.count);

    // Depth walls in pairs from the shortest bins, faces from the next ones.
    std::vector<int> depth_slots, face_slots, base_slots;
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      (slots_[i].role == SlotRole::kDepth  ? depth_slots
       : slots_[i].role == SlotRole::kFace ? face_slots
                                           : base_slots)
          .push_back(static_cast<int>(i));
    }
    const int pairs = static_cast<int>(depth_slots.size() / 2);
    std::vector<int> pair_values;
    for (std::size_t b = 0; b < bins.size() && static_cast<int>(pair_values.size()) < pairs; ++b) {
      while (remaining[b] >= 2 && static_cast<int>(pair_values.size()) < pairs) {
        pair_values.push_back(draw(static_cast<int>(b)));
        remaining[b] -= 2;
      }
    }
    rng_.Shuffle(pair_values);
    for (int s : depth_slots) slots_[s].length = pair_values[slots_[s].pair % pairs];
    // Pair ids are dense, so `pair % pairs` gives each pair its own value; check it.
    std::vector<int> faces;
    for (std::size_t b = 0; b < bins.size() && faces.size() < face_slots.size(); ++b) {
      while (remaining[b] > 0 && faces.size() < face_slots.size()) {
        faces.push_back(draw(static_cast<int>(b)));
        --remaining[b];
      }
    }
    rng_.Shuffle(faces);
    for (std::size_t i = 0; i < face_slots.size(); ++i) slots_[face_slots[i]].length = faces[i];

    // Base walls: one long (>= 160 in) wall on every side absorbs the closure of its ring;
    // the other long walls go anywhere.
    std::vector<int> free_base;
    for (std::size_t r = 0; r < rings_.size(); ++r) {
      for (int side = 0; side < 4; ++side) {
        std::vector<int> candidates;
        for (int s : base_slots) {
          if (slots_[s].ring == static_cast<int>(r) && slots_[s].side == side) {
            candidates.push_back(s);
          }
        }
        const int pick = candidates[rng_.Below(candidates.size())];
        slots_[pick].is_long = true;
        rings_[r].absorber[side] = pick;
      }
    }
    for (int s : base_slots) {
      if (!slots_[s].is_long) free_base.push_back(s);
    }
    rng_.Shuffle(free_base);
    const int long_total = bins.back().count;
    int long_used = 4 * static_cast<int>(rings_.size());
    std::size_t next = 0;
    while (long_used < long_total) {
      slots_[free_base[next++]].is_long = true;
      ++long_used;
    }
    std::vector<int> base_values;
    for (std::size_t b = 0; b + 1 < bins.size(); ++b) {
      while (remaining[b] > 0) {
        base_values.push_back(draw(static_cast<int>(b)));
        --remaining[b];
      }
    }
    // Rows of offices: the walls between the doors of one run along a side repeat one length
    // (§6.2: "36 inch doors embedded in a highly regular metric feature sequence"). Each row,
    // longest first, takes the commonest length still in the pool; the values themselves are
    // the census pool, so Table 6.9 is untouched.
    std::map<int, std::vector<int>> rows;
    for (int s : base_slots) {
      if (!slots_[s].is_long && slots_[s].row >= 0) rows[slots_[s].row].push_back(s);
    }
    std::vector<std::vector<int>> row_list;
    for (auto& [id, members] : rows) {
      if (members.size() >= 2) row_list.push_back(members);
    }
    rng_.Shuffle(row_list);
    std::stable_sort(row_list.begin(), row_list.end(),
                     [](const auto& a, const auto& b) { return a.size() > b.size(); });
    std::map<int, int> pool;
    for (int value : base_values) ++pool[value];
    for (const auto& members : row_list) {
      int best = -1, best_n = 0;
      for (const auto& [value, n] : pool) {
        if (n > best_n) {
          best = value;
          best_n = n;
        }
      }
      for (std::size_t i = 0; i < members.size() && pool[best] > 0; ++i) {
        slots_[members[i]].length = best;
        --pool[best];
      }
    }
    base_values.clear();
    for (const auto& [value, n] : pool) base_values.insert(base_values.end(), n, value);
    rng_.Shuffle(base_values);
    std::size_t v = 0;
    for (int s : base_slots) {
      if (slots_[s].is_long) {
        long_share_.push_back({s, rng_.Uniform()});
      } else if (slots_[s].length == 0.0) {
        slots_[s].length = base_values.at(v++);
      }
    }
    if (v != base_values.size()) throw std::logic_error("wall census bookkeeping is off");
  }

  double ItemLength(const PItem& it) const {
    return it.slot >= 0 ? slots_[it.slot].length : it.door.metric_in;
  }

  // Along-side length of each side (depth walls cancel in pairs).
  std::array<double, 4> SideLengths(const PRing& ring) const {
    std::array<double, 4> len{};
    for (const PItem& it : ring.items) {
      if (it.slot >= 0 && slots_[it.slot].role == SlotRole::kDepth) continue;
      len[it.side] += ItemLength(it);
    }
    return len;
  }

  void Close(PRing& ring) {
    const std::array<double, 4> len = SideLengths(ring);
    for (int s = 0; s < 2; ++s) {
      const double d = len[s] - len[s + 2];
      if (d > 0) slots_[ring.absorber[s + 2]].length += d;
      if (d < 0) slots_[ring.absorber[s]].length -= d;
    }
  }

  // Sets long walls for stretch `stretch`, closes every ring, fits each wing's corridor
  // wall around its blocks and returns the total metric.
  double Layout(double stretch) {
    for (const auto& [s, share] : long_share_) {
      slots_[s].length = 160.0 + std::round(share * stretch);
    }
    for (PRing& ring : rings_) Close(ring);
    wing_gap_.assign(3, kHallwayWidthIn);
    wing_margin_.assign(3, kHallwayWidthIn);
    for (int w = 0; w < 3; ++w) {
      double width = 0, height = 0;
      int k = 0;
      PRing* outer = nullptr;
      for (PRing& ring : rings_) {
        if (ring.wing != w) continue;
        if (!ring.block) {
          outer = &ring;
          continue;
        }
        const auto len = SideLengths(ring);
        width += len[0];
        height = std::max(height, len[1]);
        ++k;
      }
      const auto olen = SideLengths(*outer);
      const double need_w = width + (k + 1) * kHallwayWidthIn;
      const double need_h = height + 2 * kHallwayWidthIn;
      if (olen[0] < need_w) {
        slots_[outer->absorber[0]].length += need_w - olen[0];
        slots_[outer->absorber[2]].length += need_w - olen[0];
      } else {
        wing_gap_[w] = kHallwayWidthIn + (olen[0] - need_w) / (k + 1);
      }
      if (olen[1] < need_h) {
        slots_[outer->absorber[1]].length += need_h - olen[1];
        slots_[outer->absorber[3]].length += need_h - olen[1];
      }
    }
    double total = 0;
    for (const PRing& ring : rings_) {
      for (const PItem& it : ring.items) total += ItemLength(it);
    }
    return total;
  }

  Map Finish() {
    std::vector<Ring> out;
    std::vector<Join> joins;
    double wing_x = 0;
    std::vector<int> outer_index(3, -1);
    for (int w = 0; w < 3; ++w) {
      int outer_r = -1;
      for (std::size_t r = 0; r < rings_.size(); ++r) {
        if (rings_[r].wing == w && !rings_[r].block) outer_r = static_cast<int>(r);
      }
      const auto olen = SideLengths(rings_[outer_r]);
      // The corridor wall is walked counter-clockwise from its south-west corner.
      out.push_back(Build(rings_[outer_r], wing_x, 0.0, 0.0));
      outer_index[w] = static_cast<int>(out.size()) - 1;
      double x = wing_x + wing_gap_[w];
      for (std::size_t r = 0; r < rings_.size(); ++r) {
        const PRing& ring = rings_[r];
        if (ring.wing != w || !ring.block) continue;
        const auto len = SideLengths(ring);
        const double y_top = 0.5 * (olen[1] + len[1]);
        // A block is walked clockwise from its north-west corner.
        out.push_back(Build(ring, x, y_top, 0.0));
        const Ring& built = out.back();
        const Ring& corridor = out[outer_index[w]];
        const int a = ArtificialNode(built);
        joins.push_back({built.id, a, corridor.id, NearestNode(corridor, built.nodes[a])});
        x += len[0] + wing_gap_[w];
      }
      wing_x += olen[0] + 4 * kHallwayWidthIn;
    }
    // The corridors of wings 2 and 3 join wing 1's corridor.
    for (int w = 1; w < 3; ++w) {
      const Ring& from = out[outer_index[w]];
      const Ring& to = out[outer_index[0]];
      const int a = ArtificialNode(from);
      joins.push_back({from.id, a, to.id, NearestNode(to, from.nodes[a])});
    }
    MapInfo info;
    info.name = "engineering_building_3f";
    info.description =
        "MSU Engineering Building, third floor (Sections 6.2, 6.8): synthetic floor built to "
        "the census of Tables 6.1-6.9, 3 wings, 7 blocks of rooms, mean edge metric 67.64 in.";
    return Map(info, std::move(out), std::move(joins));
  }

  Ring Build(const PRing& ring, double x0, double y0, double heading) const {
    std::vector<Item> items;
    for (const PItem& it : ring.items) {
      Item item;
      item.angle_deg = it.angle_deg;
      item.artificial = it.artificial;
      item.edge = it.slot >= 0 ? Edge::Wall(slots_[it.slot].length) : it.door;
      items.push_back(item);
    }
    return BuildRing(ring.id, true, items, x0, y0, heading);
  }

  Rng rng_;
  std::vector<PRing> rings_;
  std::vector<std::array<int, 4>> side_doors_;
  std::vector<Slot> slots_;
  std::vector<std::pair<int, double>> long_share_;
  std::vector<double> wing_gap_;
  std::vector<double> wing_margin_;
  int next_pair_ = 0;
  int next_row_ = 0;
};

// ---------------------------------------------------------------------------------------
// Wells Hall, seventh floor.
// ---------------------------------------------------------------------------------------

// The major ring's sides are numbered from 0 by the 270° corners that start them.
double WellsSideLength(const std::vector<Item>& major, int side) {
  double len = 0;
  int s = -1;
  for (std::size_t i = 0; i < major.size(); ++i) {
    if (major[i].angle_deg == 270.0) ++s;
    if (s == side) len += major[i].edge.metric_in;
  }
  return len;
}

std::size_t WellsLastOfSide(const std::vector<Item>& major, int side) {
  int s = -1;
  std::size_t last = 0;
  for (std::size_t i = 0; i < major.size(); ++i) {
    if (major[i].angle_deg == 270.0) ++s;
    if (s == side) last = i;
  }
  return last;
}

// The corridor loop's outer wall is the major ring: four sides of office modules (a 36 in
// door and an 84 in wall, 10 ft on centre), walked counter-clockwise (concave corners).
// The corner walls differ from corner to corner (the building is not symmetric), and one
// double door on a long side is the single reference landmark (§6.8).
std::vector<Item> WellsMajorRing(Rng& rng) {
  const int long_modules = 14, short_modules = 7;
  const double module_wall = 84.0;
  std::vector<Item> major;
  // Corner walls from a short list of standard returns, so that corners only partly tell
  // themselves apart (the regularity of §6.8).
  const std::vector<double> returns = {24, 36, 48};
  std::array<std::pair<double, double>, 4> corner_walls;
  for (auto& c : corner_walls) {
    c = {returns[rng.Below(returns.size())], returns[rng.Below(returns.size())]};
  }
  const int landmark_side = static_cast<int>(rng.Below(2)) * 2;  // a long side
  const int landmark_at = rng.Int(2, long_modules - 3);
  for (int side = 0; side < 4; ++side) {
    const int n = side % 2 == 0 ? long_modules : short_modules;
    // Side: corner wall, modules, corner wall; modules fill the side exactly.
    major.push_back({270.0, Edge::Wall(corner_walls[side].second), false});
    for (int m = 0; m < n; ++m) {
      const bool landmark = side == landmark_side && m == landmark_at;
      // The landmark is a 36/36 double door in place of a module's door and 36 in of wall.
      major.push_back({180.0, Edge::Door(landmark ? DoorClass::k36_36 : DoorClass::k36), false});
      major.push_back({180.0, Edge::Wall(landmark ? module_wall - 36.0 : module_wall), false});
    }
    major.back().edge.metric_in += corner_walls[(side + 1) % 4].first;
  }
  // Side lengths must close the rectangle: add the difference to the last wall of the
  // shorter side of each opposite pair.
  for (int s = 0; s < 2; ++s) {
    const double d = WellsSideLength(major, s) - WellsSideLength(major, s + 2);
    if (d > 0) major[WellsLastOfSide(major, s + 2)].edge.metric_in += d;
    if (d < 0) major[WellsLastOfSide(major, s)].edge.metric_in -= d;
  }
  return major;
}

// The core inside the loop: inner offices on the same kind of module (a 36 in door and a
// 96 in wall) with a few odd doors among them (toilets behind a 30/30 double door, a store
// room, a plant room); walked clockwise (convex corners). The first and last wall of each
// side take up what the modules leave.
std::vector<Item> WellsCore(Rng& rng, double core_w, double core_h) {
  const double core_module_wall = 96.0;
  std::vector<Item> core;
  const std::array<double, 4> core_sides = {core_w, core_h, core_w, core_h};
  const std::array<DoorClass, 4> odd_door = {DoorClass::k32, DoorClass::k40, DoorClass::k30_30,
                                             DoorClass::k32};
  for (int side = 0; side < 4; ++side) {
    const int modules = static_cast<int>((core_sides[side] - 2 * 48.0) / (36.0 + core_module_wall));
    const int odd_at = rng.Int(0, modules - 1);
    std::vector<DoorClass> doors;
    for (int m = 0; m < modules; ++m)
      doors.push_back(m == odd_at ? odd_door[side] : DoorClass::k36);
    double used = 0;
    for (DoorClass d : doors) used += DoorClassWidthIn(d);
    used += core_module_wall * (modules - 1);
    const double ends = core_sides[side] - used;
    const double first = std::floor(ends * (0.3 + 0.4 * rng.Uniform()));
    core.push_back({90.0, Edge::Wall(first), false});
    for (int m = 0; m < modules; ++m) {
      core.push_back({180.0, Edge::Door(doors[m]), false});
      core.push_back(
          {180.0, Edge::Wall(m + 1 == modules ? ends - first : core_module_wall), false});
    }
  }
  // The core is joined to the loop at an artificial node at its first corner.
  core[0].artificial = true;
  return core;
}

// The modified Wells Hall: one artificial ribbon at the major-ring edge farthest (along the
// ring) from the landmark: the wall there is split and a 24 in painted ribbon put in its
// middle.
void AddArtificialRibbon(std::vector<Item>& major) {
  std::size_t landmark = 0;
  for (std::size_t i = 0; i < major.size(); ++i) {
    if (major[i].edge.IsDoor() && *major[i].edge.door_class == DoorClass::k36_36) landmark = i;
  }
  double total = 0;
  for (const Item& it : major) total += it.edge.metric_in;
  std::vector<double> start(major.size());
  double acc = 0;
  for (std::size_t i = 0; i < major.size(); ++i) {
    start[i] = acc;
    acc += major[i].edge.metric_in;
  }
  const double landmark_mid = start[landmark] + 0.5 * major[landmark].edge.metric_in;
  std::size_t far = 0;
  double far_d = -1;
  for (std::size_t i = 0; i < major.size(); ++i) {
    if (!major[i].edge.IsWall() || major[i].edge.metric_in < 48.0) continue;
    const double mid = start[i] + 0.5 * major[i].edge.metric_in;
    const double d = std::min(std::abs(mid - landmark_mid), total - std::abs(mid - landmark_mid));
    if (d > far_d) {
      far_d = d;
      far = i;
    }
  }
  const double ribbon = 24.0;
  const double wall = major[far].edge.metric_in;
  const double left = std::floor((wall - ribbon) / 2);
  Item a = major[far], rib = major[far], b = major[far];
  a.edge = Edge::Wall(left);
  rib.angle_deg = 180.0;
  rib.edge = Edge{};
  rib.edge.type = EdgeType::kPattern;
  rib.edge.prototype = Prototype::kPattern;
  rib.edge.metric_in = ribbon;
  rib.edge.pattern = "artificial_ribbon";
  b.angle_deg = 180.0;
  b.edge = Edge::Wall(wall - ribbon - left);
  major[far] = a;
  major.insert(major.begin() + static_cast<long>(far) + 1, {rib, b});
}

}  // namespace

Map GenerateEngineeringBuilding(std::uint64_t seed) { return EngineeringBuilder(seed).Build(); }

Map GenerateWellsHall(std::uint64_t seed, bool modified) {
  Rng rng(seed);
  std::vector<Item> major = WellsMajorRing(rng);
  const double outer_w = WellsSideLength(major, 0), outer_h = WellsSideLength(major, 1);
  const double hall = 96.0;
  const double core_w = outer_w - 2 * hall, core_h = outer_h - 2 * hall;
  const std::vector<Item> core = WellsCore(rng, core_w, core_h);
  if (modified) AddArtificialRibbon(major);

  std::vector<Ring> rings;
  rings.push_back(BuildRing("corridor_outer", true, major, 0.0, 0.0, 0.0));
  rings.back().nodes[0].artificial = true;
  rings.push_back(BuildRing("core", true, core, hall, outer_h - hall, 0.0));
  std::vector<Join> joins = {
      {"core", 0, "corridor_outer", NearestNode(rings[0], rings[1].nodes[0])}};
  MapInfo info;
  info.name = modified ? "wells_hall_7f_modified" : "wells_hall_7f";
  info.description =
      modified ? "MSU Wells Hall, seventh floor, with one artificial vertical ribbon at the edge "
                 "farthest from the reference landmark (Section 6.8)."
               : "MSU Wells Hall, seventh floor (Section 6.8): synthetic corridor loop of regular "
                 "office modules around a core, one reference landmark in the major ring.";
  return Map(info, std::move(rings), std::move(joins));
}

Map GenerateRegularPolygon(std::uint64_t seed) {
  Rng rng(seed);
  // 46 walls of 100 in around a polygonal block (§6.8; 100 in is Table 6.22's distance per
  // edge, 383.33 ft / 46). The one unique feature is a 36 in door set off-centre in one side
  // (20-28 in of wall before it, the rest after; 32 in on both sides would make the ring
  // mirror-symmetric and never unique when both directions of travel are matched).
  constexpr int kSides = 46;
  const double turn = 360.0 / kSides;
  const int unique_side = static_cast<int>(rng.Below(kSides));
  std::vector<Item> items;
  for (int s = 0; s < kSides; ++s) {
    const double corner = 180.0 - turn;
    if (s == unique_side) {
      const double left = 20.0 + 4.0 * static_cast<double>(rng.Below(3));
      items.push_back({corner, Edge::Wall(left), false});
      items.push_back({180.0, Edge::Door(DoorClass::k36), false});
      items.push_back({180.0, Edge::Wall(100.0 - 36.0 - left), false});
    } else {
      items.push_back({corner, Edge::Wall(100.0), false});
    }
  }
  MapInfo info;
  info.name = "regular_polygon_46";
  info.description =
      "Synthetic regular polygon of 46 sides of 100 in with one unique feature, a door set "
      "off-centre in one side (Section 6.8).";
  return Map(info, {BuildRing("polygon", true, items, 0.0, 0.0, 0.0)});
}

Map GenerateStorefront(std::uint64_t seed) {
  Rng rng(seed);
  // A city block 1/10 mile round (four 1584 in faces), walked clockwise from the pavement
  // (convex corners). Shops are built from a few standard unit designs, as a street of
  // similar shops is: a pier, the shop door, a display window, the door to the flat above.
  // Walls between doors are pier + window lengths; designs repeat in runs.
  struct Unit {
    double pier, window_a, window_b;
    DoorClass shop, upstairs;
  };
  const std::vector<Unit> designs = {
      {18, 60, 96, DoorClass::k36, DoorClass::k32},
      {18, 72, 60, DoorClass::k36_36, DoorClass::k32},
      {24, 48, 120, DoorClass::k36, DoorClass::k32},
  };
  const double face = 1584.0;
  // Runs of identical shops: the regularity that makes the street ambiguous.
  constexpr int kMinRun = 4, kMaxRun = 8;
  std::vector<Item> items;
  for (int side = 0; side < 4; ++side) {
    // Units along this face until it is full; the last wall takes what is left.
    std::vector<Item> face_items;
    double used = 0;
    double pending = 0;  // wall length carried to the next door
    int design = static_cast<int>(rng.Below(designs.size()));
    int run = rng.Int(kMinRun, kMaxRun);
    pending = 36.0 + 12.0 * rng.Below(4);  // corner pier
    while (true) {
      const Unit& u = designs[design];
      const double unit_len = u.pier + u.window_a + u.window_b + DoorClassWidthIn(u.shop) +
                              DoorClassWidthIn(u.upstairs);
      if (used + pending + unit_len + 48.0 > face) break;
      face_items.push_back({180.0, Edge::Wall(pending + u.pier + u.window_a), false});
      face_items.push_back({180.0, Edge::Door(u.shop), false});
      face_items.push_back({180.0, Edge::Wall(u.window_b), false});
      face_items.push_back({180.0, Edge::Door(u.upstairs), false});
      used += pending + u.pier + u.window_a + u.window_b + DoorClassWidthIn(u.shop) +
              DoorClassWidthIn(u.upstairs);
      pending = 0;
      if (--run == 0) {
        design = static_cast<int>(rng.Below(designs.size()));
        run = rng.Int(kMinRun, kMaxRun);
      }
    }
    face_items.push_back({180.0, Edge::Wall(face - used), false});
    face_items.front().angle_deg = 90.0;
    items.insert(items.end(), face_items.begin(), face_items.end());
  }
  MapInfo info;
  info.name = "storefront";
  info.description =
      "Synthetic storefront (Section 6.8): 1/10 mile of street frontage round a city block, "
      "shops built from three standard unit designs in runs.";
  Ring ring = BuildRing("block_frontage", true, items, 0.0, face, 0.0);
  return Map(info, {ring});
}

const std::vector<DomainInfo>& Domains() {
  static const std::vector<DomainInfo> kDomains = {
      {"engineering_building_3f", 1994, "MSU Engineering Building, 3rd floor (Tables 6.1-6.9)"},
      {"wells_hall_7f", 1994, "MSU Wells Hall, 7th floor"},
      {"wells_hall_7f_modified", 1994, "Wells Hall plus one artificial ribbon"},
      {"regular_polygon_46", 1994, "46-sided regular polygon, one unique feature"},
      {"storefront", 1994, "1/10 mile of storefronts round a city block"},
  };
  return kDomains;
}

Map GenerateDomain(const std::string& name, std::uint64_t seed) {
  Map map;
  if (name == "engineering_building_3f") {
    map = GenerateEngineeringBuilding(seed);
  } else if (name == "wells_hall_7f") {
    map = GenerateWellsHall(seed, false);
  } else if (name == "wells_hall_7f_modified") {
    map = GenerateWellsHall(seed, true);
  } else if (name == "regular_polygon_46") {
    map = GenerateRegularPolygon(seed);
  } else if (name == "storefront") {
    map = GenerateStorefront(seed);
  } else {
    std::string known;
    for (const auto& d : Domains()) known += (known.empty() ? "" : ", ") + d.name;
    throw std::invalid_argument("unknown domain '" + name + "' (known: " + known + ")");
  }
  MapInfo info = map.info();
  info.generator = "stickrep-map generate " + name;
  info.seed = seed;
  return Map(info, map.rings(), map.joins());
}

}  // namespace stickrep::map
