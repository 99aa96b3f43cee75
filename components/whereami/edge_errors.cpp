#include "whereami/edge_errors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

namespace stickrep::whereami {

void EdgeErrorCounts::Add(const EdgeErrorCounts& o) {
  true_doors += o.true_doors;
  correct += o.correct;
  missized += o.missized;
  missed += o.missed;
  true_walls += o.true_walls;
  false_doors += o.false_doors;
  for (int t = 0; t < map::kDoorClassCount; ++t) {
    false_class[t] += o.false_class[t];
    for (int s = 0; s < map::kDoorClassCount; ++s) missized_to[t][s] += o.missized_to[t][s];
  }
  wall_error_in.insert(wall_error_in.end(), o.wall_error_in.begin(), o.wall_error_in.end());
  wall_residuals.insert(wall_residuals.end(), o.wall_residuals.begin(), o.wall_residuals.end());
  wall_ends += o.wall_ends;
  wall_ends_off_node += o.wall_ends_off_node;
  walls_at_corners += o.walls_at_corners;
  for (int w = 0; w < 2; ++w) {
    for (int b = 0; b < 2; ++b) {
      for (int a = 0; a < 2; ++a) walls_by_missed[w][b][a].Add(o.walls_by_missed[w][b][a]);
    }
  }
  leaf_reads += o.leaf_reads;
  leaf_wall_before += o.leaf_wall_before;
  leaf_wall_after += o.leaf_wall_after;
  leaf_split += o.leaf_split;
  leaf_sliver_in.insert(leaf_sliver_in.end(), o.leaf_sliver_in.begin(), o.leaf_sliver_in.end());
  const auto add = [](DoorTally& mine, const DoorTally& t) {
    mine.passed += t.passed;
    mine.correct += t.correct;
    mine.missized += t.missized;
    mine.missed += t.missed;
  };
  for (const auto& [width, t] : o.by_width) add(by_width[width], t);
  for (int k = 0; k < map::kDoorClassCount; ++k) add(by_class[k], o.by_class[k]);
  for (int r = 0; r < 2; ++r) {
    for (int k = 0; k < map::kDoorClassCount; ++k) add(by_row[r][k], o.by_row[r][k]);
    walls_by_row[r].Add(o.walls_by_row[r]);
    for (int k = 0; k < map::kDoorClassCount; ++k) add(row_by_before[r][k], o.row_by_before[r][k]);
  }
  for (std::size_t b = 0; b < walls_by_length.size(); ++b)
    walls_by_length[b].Add(o.walls_by_length[b]);
  for (std::size_t k = 0; k < walls_by_false_doors.size(); ++k)
    walls_by_false_doors[k] += o.walls_by_false_doors[k];
  for (int t = 0; t < map::kDoorMarkCount; ++t) {
    false_mark[t] += o.false_mark[t];
    for (int r = 0; r < map::kDoorMarkCount; ++r) {
      mark_read[t][r] += o.mark_read[t][r];
      mark_read_missized[t][r] += o.mark_read_missized[t][r];
    }
  }
}

namespace {

// Counts as shares of their sum; nullopt when there are none.
std::optional<recovery::ErrorModel::MarkRow> Shares(const EdgeErrorCounts::MarkCounts& n) {
  long sum = 0;
  for (long k : n) sum += k;
  if (sum == 0) return std::nullopt;
  recovery::ErrorModel::MarkRow row{};
  for (int k = 0; k < map::kDoorMarkCount; ++k) row[k] = static_cast<double>(n[k]) / sum;
  return row;
}

// A tally's rates, shrunk towards `prior` by EdgeErrorCounts::kClassPriorDoors doors' worth.
recovery::ErrorModel::DoorRates Shrunk(const EdgeErrorCounts::DoorTally& t,
                                       const recovery::ErrorModel::DoorRates& prior) {
  const double w = EdgeErrorCounts::kClassPriorDoors;
  const double n = static_cast<double>(t.passed) + w;
  return {(t.correct + w * prior.correct) / n, (t.missized + w * prior.missized) / n,
          (t.missed + w * prior.missed) / n};
}

// The missed rates of a row's doors after a missed and after a seen door before them, each
// class's shrunk towards its rate in a row by kClassPriorDoors doors' worth; none unless
// doors of a row were passed after both.
void SetRowMissedByBefore(const EdgeErrorCounts& c, recovery::ErrorModel::InRow* in_row) {
  long after[2] = {0, 0};
  for (int b = 0; b < 2; ++b) {
    for (const EdgeErrorCounts::DoorTally& t : c.row_by_before[b]) after[b] += t.passed;
  }
  if (after[0] == 0 || after[1] == 0) return;
  const double prior = EdgeErrorCounts::kClassPriorDoors;
  for (const auto& [cls, rates] : in_row->by_class) {
    const int k = static_cast<int>(cls);
    for (int b = 0; b < 2; ++b) {
      const EdgeErrorCounts::DoorTally& t = c.row_by_before[b][k];
      auto& out = b == 1 ? in_row->door_missed_after_missed : in_row->door_missed_after_seen;
      out[cls] = (t.missed + prior * rates.missed) / (t.passed + prior);
    }
  }
}

// The per-class door rates: each class's tally shrunk towards the overall rates, and split
// into doors alone and in a row (and the false doors of the short walls between doors apart
// from the other walls') where the runs passed any (ErrorModel::in_row).
void SetClassRates(const EdgeErrorCounts& c, recovery::ErrorModel* m) {
  const recovery::ErrorModel::DoorRates overall{m->door_correct, m->door_missized, m->door_missed};
  std::map<map::DoorClass, recovery::ErrorModel::DoorRates> classes;
  for (int k = 0; k < map::kDoorClassCount; ++k) {
    if (c.by_class[k].passed > 0)
      classes[static_cast<map::DoorClass>(k)] = Shrunk(c.by_class[k], overall);
  }
  m->by_class = classes;
  const EdgeErrorCounts::WallTally& row_walls = c.walls_by_row[1];
  bool rows = row_walls.walls > 0;
  for (const EdgeErrorCounts::DoorTally& t : c.by_row[1]) rows = rows || t.passed > 0;
  if (rows) {
    // Each context's rates, shrunk towards its class's (or, for the walls, all walls').
    recovery::ErrorModel::InRow in_row;
    m->by_class.clear();
    for (int k = 0; k < map::kDoorClassCount; ++k) {
      const auto cls = static_cast<map::DoorClass>(k);
      const auto it = classes.find(cls);
      if (it == classes.end()) continue;
      m->by_class[cls] = Shrunk(c.by_row[0][k], it->second);
      in_row.by_class[cls] = Shrunk(c.by_row[1][k], it->second);
    }
    const double prior = EdgeErrorCounts::kClassPriorDoors;
    const auto walls = [&](const EdgeErrorCounts::WallTally& w) {
      return std::min(1.0, (w.false_doors + prior * m->wall_false_door) / (w.walls + prior));
    };
    SetRowMissedByBefore(c, &in_row);
    in_row.wall_false_door = walls(row_walls);
    m->wall_false_door = walls(c.walls_by_row[0]);
    m->in_row = in_row;
  }
  const EdgeErrorCounts::WallTally& other_walls = c.walls_by_row[0];
  if (other_walls.wall_in > 0.0) {
    m->wall_false_door_per_in = other_walls.false_doors / other_walls.wall_in;
  }
}

// The marks' read shares (Table 6.8): of each true mark read with the class right, its
// mis-sized reads, and the false doors'.
void SetMarkReads(const EdgeErrorCounts& c, recovery::ErrorModel* m) {
  for (int t = 0; t < map::kDoorMarkCount; ++t) {
    const auto mark = static_cast<map::DoorMark>(t);
    const auto right = Shares(c.mark_read[t]);
    if (!right) continue;
    m->mark_read[mark] = *right;
    // The mis-sized reads of a mark, shrunk towards its reads with the class right by
    // kClassPriorDoors doors' worth: a few mis-sized doors, all read one way, do not make
    // that read certain.
    long n = 0;
    for (long k : c.mark_read_missized[t]) n += k;
    if (n == 0) continue;
    const double prior = EdgeErrorCounts::kClassPriorDoors;
    recovery::ErrorModel::MarkRow row{};
    for (int r = 0; r < map::kDoorMarkCount; ++r) {
      row[r] = (c.mark_read_missized[t][r] + prior * (*right)[r]) / (n + prior);
    }
    m->mark_read_missized[mark] = row;
  }
  if (!m->mark_read.empty()) {
    // No false door seen: its reads are taken to be the doors' reads, all marks together.
    EdgeErrorCounts::MarkCounts all = c.false_mark;
    if (!Shares(all)) {
      for (const EdgeErrorCounts::MarkCounts& n : c.mark_read) {
        for (int r = 0; r < map::kDoorMarkCount; ++r) all[r] += n[r];
      }
    }
    m->false_door_marks = Shares(all);
  }
}

// The false-door rates of the short walls between doors after a missed and after a seen
// door (ErrorModel::InRow), each shrunk towards the walls' in-row rate by
// kClassPriorDoors walls' worth; none where no such wall was passed after either.
void SetRowWallRatesByBefore(const EdgeErrorCounts& c, recovery::ErrorModel* m) {
  if (!m->in_row || !m->in_row->wall_false_door) return;
  EdgeErrorCounts::WallTally after[2];  // [before missed]
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) after[b].Add(c.walls_by_missed[1][b][a]);
  }
  if (after[0].walls == 0 || after[1].walls == 0) return;
  const double prior = EdgeErrorCounts::kClassPriorDoors;
  const double base = *m->in_row->wall_false_door;
  const auto rate = [&](const EdgeErrorCounts::WallTally& t) {
    return std::min(1.0, (t.false_doors + prior * base) / (t.walls + prior));
  };
  m->in_row->wall_false_door_after_seen = rate(after[0]);
  m->in_row->wall_false_door_after_missed = rate(after[1]);
}

// ErrorModel::wall_over_missed_door from the walls over missed doors: with m doors missed
// under a wall, its error is taken as m * bias plus a normal spread of the matcher's sigma
// and m * sigma^2 more; both fitted by moments over the walls.
void SetWallOverMissedDoor(const EdgeErrorCounts& c, const recovery::SensingNoise& noise,
                           recovery::ErrorModel* m) {
  double error_sum = 0.0, missed_sum = 0.0;
  int walls = 0;
  for (const EdgeErrorCounts::WallResidual& r : c.wall_residuals) {
    if (r.missed_doors == 0) continue;
    error_sum += r.error_in;
    missed_sum += r.missed_doors;
    ++walls;
  }
  if (walls < EdgeErrorCounts::kMinMissedWalls) return;
  recovery::ErrorModel::WallOverMissedDoor over;
  over.bias_in = error_sum / missed_sum;
  double excess = 0.0;
  for (const EdgeErrorCounts::WallResidual& r : c.wall_residuals) {
    if (r.missed_doors == 0) continue;
    const double d = r.error_in - r.missed_doors * over.bias_in;
    const double sigma = std::max(1.0, noise.WallSigmaIn(r.true_in));
    excess += d * d - sigma * sigma;
  }
  over.sigma_in = std::sqrt(std::max(0.0, excess / missed_sum));
  m->wall_over_missed_door = over;
}

}  // namespace

recovery::ErrorModel EdgeErrorCounts::ToModel(const std::string& source,
                                              const recovery::SensingNoise* noise) const {
  recovery::ErrorModel m;
  m.source = source;
  const double doors = std::max<long>(1, true_doors);
  m.door_correct = correct / doors;
  m.door_missized = missized / doors;
  m.door_missed = missed / doors;  // the three add up: every true door is one of them
  // False doors per wall; a wall may hold more than one (a long wall read with two), but
  // the rate per wall is a probability, at most 1 (the rate per inch counts them all).
  m.wall_false_door =
      std::min(1.0, static_cast<double>(false_doors) / std::max<long>(1, true_walls));
  for (int t = 0; t < map::kDoorClassCount; ++t) {
    long row = 0;
    for (long n : missized_to[t]) row += n;
    if (row == 0) continue;
    for (int s = 0; s < map::kDoorClassCount; ++s) {
      if (missized_to[t][s] > 0) {
        m.missized_to[static_cast<map::DoorClass>(t)][static_cast<map::DoorClass>(s)] =
            static_cast<double>(missized_to[t][s]) / row;
      }
    }
  }
  long fp = 0;
  for (long n : false_class) fp += n;
  for (int c = 0; c < map::kDoorClassCount && fp > 0; ++c) {
    if (false_class[c] > 0) {
      m.false_door_classes[static_cast<map::DoorClass>(c)] = static_cast<double>(false_class[c]) / fp;
    }
  }
  SetClassRates(*this, &m);
  SetRowWallRatesByBefore(*this, &m);
  if (leaf_reads > 0) {
    m.leaf_split = static_cast<double>(leaf_split) / leaf_reads;
    m.leaf_sliver = leaf_split > 0 ? static_cast<double>(leaf_sliver_in.size()) / leaf_split : 0.0;
    m.leaf_wall_before = static_cast<double>(leaf_wall_before) / leaf_reads;
    m.leaf_wall_after = static_cast<double>(leaf_wall_after) / leaf_reads;
  }
  SetMarkReads(*this, &m);
  if (noise != nullptr) SetWallOverMissedDoor(*this, *noise, &m);
  return m;
}

namespace {

// Where a true edge was seen: the odometer range of its run of samples.
struct Passage {
  int edge;
  double first_in, last_in;
};

// A door at passage p read as `sensed[i]`, narrower than it is by at least
// recovery::kLeafDeficitIn: where the rest of its width went. `on_door` are the sensed
// doors whose centre lay on this true door, `sensed[i]` first. Returns the index of the
// second leaf when the door was read as both leaves (not a false door then), else 0.
std::size_t CountLeafRead(const map::Ring& view_ring, const std::vector<map::SensedEdge>& sensed,
                          const std::vector<std::size_t>& on_door,
                          const std::vector<int>& passed_edges, std::size_t p,
                          EdgeErrorCounts* c) {
  const std::size_t i = on_door.front();
  const map::Edge& door = view_ring.edges[passed_edges[p]];
  const double deficit =
      door.metric_in - map::DoorClassWidthIn(static_cast<map::DoorClass>(sensed[i].code - 1));
  if (deficit < recovery::kLeafDeficitIn) return 0;
  ++c->leaf_reads;
  // Both leaves, right after each other or with a sliver of wall (the meeting stiles)
  // between them.
  if (on_door.size() >= 2) {
    const std::size_t second = on_door[1];
    if (second == i + 1) {
      ++c->leaf_split;
      return second;
    }
    if (second == i + 2 && sensed[i + 1].code == map::kWallCode &&
        sensed[i + 1].metric_in < deficit) {
      ++c->leaf_split;
      c->leaf_sliver_in.push_back(sensed[i + 1].metric_in);
      return second;
    }
  }
  // One leaf: sensed minus true length of the wall on one side, when both are walls.
  const auto excess = [&](std::size_t si, std::size_t pi) {
    const map::Edge& wall = view_ring.edges[passed_edges[pi]];
    if (sensed[si].code != map::kWallCode || !wall.IsWall()) return 0.0;
    return sensed[si].metric_in - wall.metric_in;
  };
  const double before = i > 0 ? excess(i - 1, p - 1) : 0.0;
  const double after =
      i + 1 < sensed.size() && p + 1 < passed_edges.size() ? excess(i + 1, p + 1) : 0.0;
  if (before > 0.5 * deficit && before >= after) {
    ++c->leaf_wall_before;
  } else if (after > 0.5 * deficit) {
    ++c->leaf_wall_after;
  }
  return 0;
}

// The true edges passed, in order; an edge passed twice (a lap) is taken once per pass.
std::vector<Passage> Passages(const std::vector<TruthSample>& truth) {
  std::vector<Passage> passed;
  for (const TruthSample& s : truth) {
    if (s.view_edge < 0) continue;
    if (passed.empty() || passed.back().edge != s.view_edge) {
      passed.push_back({s.view_edge, s.odometer_in, s.odometer_in});
    } else {
      passed.back().last_in = s.odometer_in;
    }
  }
  return passed;
}

}  // namespace

namespace {

// Sensed doors by the passage their centre lay on (passage index -> sensed indices), for the
// doors centred within [lo, hi].
std::map<int, std::vector<std::size_t>> DoorsByPassage(
    const std::vector<map::SensedEdge>& sensed,
    const std::vector<localizer::EdgeAssembler::Span>& spans, const std::vector<Passage>& passed,
    double lo, double hi) {
  std::map<int, std::vector<std::size_t>> doors_on;
  for (std::size_t i = 0; i < sensed.size() && i < spans.size(); ++i) {
    if (!map::IsDoorCode(sensed[i].code)) continue;
    const double centre = 0.5 * (spans[i].from_in + spans[i].to_in);
    if (centre < lo || centre > hi) continue;
    for (std::size_t p = 0; p < passed.size(); ++p) {
      const double a = std::min(passed[p].first_in, passed[p].last_in);
      const double b = std::max(passed[p].first_in, passed[p].last_in);
      if (centre >= a - 3.0 && centre <= b + 3.0) {
        doors_on[static_cast<int>(p)].push_back(i);
        break;
      }
    }
  }
  return doors_on;
}

// Walls between two correctly sensed doors: the sensed wall right after the first, against
// the map's length.
void CountWallErrors(const map::Ring& view_ring, const std::vector<map::SensedEdge>& sensed,
                     const std::vector<Passage>& passed,
                     const std::vector<std::optional<std::size_t>>& matched, EdgeErrorCounts* c) {
  for (std::size_t p = 0; p + 2 < passed.size(); ++p) {
    if (!matched[p] || !matched[p + 2]) continue;
    const map::Edge& wall = view_ring.edges[passed[p + 1].edge];
    const std::size_t next = *matched[p] + 1;
    if (!wall.IsWall() || next >= sensed.size() || next + 1 != *matched[p + 2] ||
        sensed[next].code != map::kWallCode) {
      continue;
    }
    c->wall_error_in.push_back(sensed[next].metric_in - wall.metric_in);
  }
}

// One false door: its class and the mark read on it.
void AddFalseDoor(const map::SensedEdge& e, EdgeErrorCounts* c) {
  ++c->false_doors;
  c->false_class[e.code - 1]++;
  c->false_mark[static_cast<int>(e.mark)]++;
}

// The bin of EdgeErrorCounts::walls_by_length a wall of `length_in` counts in.
std::size_t WallLengthBin(double length_in) {
  const auto& bins = EdgeErrorCounts::kWallLengthBinsIn;
  std::size_t b = 0;
  while (b + 1 < bins.size() && length_in >= bins[b + 1]) ++b;
  return b;
}

// A true wall (edge `edge` of the view ring) passed whole, and the sensed doors on it
// (`on_it`, indices into `sensed`), all false: counted by row and by length.
void CountWall(const map::Ring& view_ring, int edge, const std::vector<map::SensedEdge>& sensed,
               const std::vector<std::size_t>& on_it, EdgeErrorCounts* c) {
  const double length_in = view_ring.edges[edge].metric_in;
  const bool row = map::InDoorRow(view_ring, edge);
  ++c->true_walls;
  if (!row) {
    ++c->walls_by_false_doors[std::min<std::size_t>(on_it.size(), EdgeErrorCounts::kMostCounted)];
  }
  for (EdgeErrorCounts::WallTally* t :
       {&c->walls_by_row[row], &c->walls_by_length[WallLengthBin(length_in)]}) {
    ++t->walls;
    t->wall_in += length_in;
    t->false_doors += static_cast<long>(on_it.size());
  }
  for (std::size_t k : on_it) AddFalseDoor(sensed[k], c);
}

// The true node nearest odometer reading `x` (node k lies between passages k and k + 1), and
// how far it is; -1 when there is none.
std::pair<int, double> NearestNode(const std::vector<Passage>& passed, double x) {
  int best = -1;
  double dist = 0.0;
  for (std::size_t k = 0; k + 1 < passed.size(); ++k) {
    const double at = 0.5 * (passed[k].last_in + passed[k + 1].first_in);
    if (best < 0 || std::abs(at - x) < dist) {
      best = static_cast<int>(k);
      dist = std::abs(at - x);
    }
  }
  return {best, dist};
}

// Sensed walls whose ends lie near true nodes, against the true edges between the nodes
// (EdgeErrorCounts::wall_residuals). Only walls inside [lo, hi], the first edge left out.
void CountWallResiduals(const map::Ring& view_ring, const std::vector<map::SensedEdge>& sensed,
                        const std::vector<localizer::EdgeAssembler::Span>& spans,
                        const std::vector<Passage>& passed,
                        const std::map<int, std::vector<std::size_t>>& doors_on, double lo,
                        double hi, EdgeErrorCounts* c) {
  using End = EdgeErrorCounts::WallEnd;
  // What bounds the wall at node k on the side of passage `outside`.
  const auto end_kind = [&](int outside) {
    const map::Edge& e = view_ring.edges[passed[outside].edge];
    if (!e.door_class) return End::kOther;
    const auto it = doors_on.find(outside);
    if (it == doors_on.end()) return End::kOther;
    return sensed[it->second.front()].code == map::DoorCode(*e.door_class) ? End::kDoorRight
                                                                           : End::kDoorMissized;
  };
  for (std::size_t i = 1; i < sensed.size() && i < spans.size(); ++i) {
    if (sensed[i].code != map::kWallCode || sensed[i].metric_is_lower_bound) continue;
    // At a corner the next wall is seen before the turn, so its span is not placed along
    // the odometer beside the one before: walls that begin or end at a sensed node are
    // counted apart, not matched.
    const bool corner = !std::isnan(sensed[i].angle_deg) ||
                        (i + 1 < sensed.size() && !std::isnan(sensed[i + 1].angle_deg));
    if (corner || i + 1 >= sensed.size()) {
      c->walls_at_corners += corner;
      continue;
    }
    const double a = std::min(spans[i].from_in, spans[i].to_in);
    const double b = std::max(spans[i].from_in, spans[i].to_in);
    if (a < lo || b > hi) continue;
    const auto [na, da] = NearestNode(passed, a);
    const auto [nb, db] = NearestNode(passed, b);
    c->wall_ends += 2;
    c->wall_ends_off_node +=
        (da > EdgeErrorCounts::kNodeNearIn) + (db > EdgeErrorCounts::kNodeNearIn);
    if (na < 0 || nb < 0 || na == nb || da > EdgeErrorCounts::kNodeNearIn ||
        db > EdgeErrorCounts::kNodeNearIn) {
      continue;
    }
    // Passages first..last lie between the two nodes; outside them, one on each side.
    const int first = std::min(na, nb) + 1, last = std::max(na, nb);
    EdgeErrorCounts::WallResidual r;
    for (int q = first; q <= last; ++q) {
      const map::Edge& e = view_ring.edges[passed[q].edge];
      r.true_in += e.metric_in;
      r.over_missed = r.over_missed || e.door_class.has_value();
      r.missed_doors += e.door_class.has_value();
    }
    r.error_in = sensed[i].metric_in - r.true_in;
    r.start = end_kind(first - 1);
    r.end = end_kind(last + 1);
    c->wall_residuals.push_back(r);
  }
}

// A true wall between two true doors (passages p - 1 and p + 1): whether a false door was
// read on it, by which of the two doors went unseen (EdgeErrorCounts::walls_by_missed).
void CountWallByNeighbours(const map::Ring& view_ring, const std::vector<int>& passed_edges,
                           const std::map<int, std::vector<std::size_t>>& doors_on, std::size_t p,
                           bool false_door, EdgeErrorCounts* c) {
  if (p == 0 || p + 1 >= passed_edges.size()) return;
  const map::Edge& before = view_ring.edges[passed_edges[p - 1]];
  const map::Edge& after = view_ring.edges[passed_edges[p + 1]];
  if (!before.door_class || !after.door_class) return;
  const bool before_missed = doors_on.count(static_cast<int>(p - 1)) == 0;
  const bool after_missed = doors_on.count(static_cast<int>(p + 1)) == 0;
  const bool short_wall = view_ring.edges[passed_edges[p]].metric_in < map::kRowWallIn;
  EdgeErrorCounts::WallTally& t = c->walls_by_missed[short_wall][before_missed][after_missed];
  ++t.walls;
  t.wall_in += view_ring.edges[passed_edges[p]].metric_in;
  t.false_doors += false_door;
}

// The tally of EdgeErrorCounts::row_by_before the door at passage p counts in: a door of a
// row after the short wall past the door before it, by whether that door was missed; null
// for any other door.
EdgeErrorCounts::DoorTally* RowTallyByBefore(
    const map::Ring& view_ring, const std::vector<Passage>& passed,
    const std::map<int, std::vector<std::size_t>>& doors_on, std::size_t p, double lo,
    EdgeErrorCounts* c) {
  if (p < 3 || !map::InDoorRow(view_ring, passed[p].edge)) return nullptr;
  const map::Edge& wall = view_ring.edges[passed[p - 1].edge];
  const map::Edge& door = view_ring.edges[passed[p - 2].edge];
  if (!wall.IsWall() || !map::InDoorRow(view_ring, passed[p - 1].edge) || !door.door_class ||
      std::min(passed[p - 2].first_in, passed[p - 2].last_in) < lo) {
    return nullptr;
  }
  const bool before_missed = doors_on.count(static_cast<int>(p - 2)) == 0;
  const int cls = static_cast<int>(*view_ring.edges[passed[p].edge].door_class);
  return &c->row_by_before[before_missed ? 1 : 0][cls];
}

}  // namespace

EdgeErrorCounts CompareWithTruth(const map::Ring& view_ring,
                                 const std::vector<map::SensedEdge>& sensed,
                                 const std::vector<localizer::EdgeAssembler::Span>& spans,
                                 const std::vector<TruthSample>& truth, double from_in,
                                 double to_in) {
  EdgeErrorCounts c;
  const double lo = std::min(from_in, to_in), hi = std::max(from_in, to_in);
  const std::vector<Passage> passed = Passages(truth);
  const std::map<int, std::vector<std::size_t>> doors_on =
      DoorsByPassage(sensed, spans, passed, lo, hi);
  // The sensed door each passage's door was matched with (for wall length checks).
  std::vector<std::optional<std::size_t>> matched(passed.size());
  std::vector<int> passed_edges;
  for (const Passage& q : passed) passed_edges.push_back(q.edge);
  for (std::size_t p = 0; p < passed.size(); ++p) {
    const double a = std::min(passed[p].first_in, passed[p].last_in);
    const double b = std::max(passed[p].first_in, passed[p].last_in);
    if (a < lo || b > hi || p == 0 || p + 1 == passed.size()) continue;  // not passed whole
    const map::Edge& edge = view_ring.edges[passed[p].edge];
    const auto it = doors_on.find(static_cast<int>(p));
    if (edge.door_class) {
      ++c.true_doors;
      using Tally = EdgeErrorCounts::DoorTally;
      const int cls = static_cast<int>(*edge.door_class);
      Tally* const tallies[] = {&c.by_width[static_cast<int>(std::lround(edge.metric_in))],
                                &c.by_class[cls],
                                &c.by_row[map::InDoorRow(view_ring, passed[p].edge)][cls]};
      Tally* const row_tally = RowTallyByBefore(view_ring, passed, doors_on, p, lo, &c);
      const auto count = [&tallies, row_tally](long Tally::*field) {
        for (Tally* t : tallies) ++(t->*field);
        if (row_tally) ++(row_tally->*field);
      };
      count(&Tally::passed);
      if (it == doors_on.end()) {
        ++c.missed;
        count(&Tally::missed);
        continue;
      }
      const std::size_t first = it->second.front();
      std::size_t leaf = 0;
      const map::SymbolCode want = map::DoorCode(*edge.door_class);
      if (sensed[first].code == want) {
        ++c.correct;
        count(&Tally::correct);
        matched[p] = first;
      } else {
        ++c.missized;
        count(&Tally::missized);
        c.missized_to[cls][sensed[first].code - 1]++;
        leaf = CountLeafRead(view_ring, sensed, it->second, passed_edges, p, &c);
      }
      // A door the map gives no mark for is left out of the mark counts: what the renderer
      // drew there is no measure of what an unsurveyed door shows.
      const int truth = static_cast<int>(map::DoorMarkOfPattern(edge.pattern));
      auto& mark_row = sensed[first].code == want ? c.mark_read[truth] : c.mark_read_missized[truth];
      if (truth != static_cast<int>(map::DoorMark::kUnknown)) {
        mark_row[static_cast<int>(sensed[first].mark)]++;
      }
      // More sensed doors on the same true door are false doors as well (but for a double
      // door's second leaf).
      for (std::size_t k = 1; k < it->second.size(); ++k) {
        const map::SensedEdge& other = sensed[it->second[k]];
        if (it->second[k] == leaf && leaf > 0) {
          if (truth != static_cast<int>(map::DoorMark::kUnknown)) {
            c.mark_read_missized[truth][static_cast<int>(other.mark)]++;
          }
          continue;
        }
        AddFalseDoor(other, &c);
      }
    } else if (edge.IsWall()) {
      static const std::vector<std::size_t> kNone;
      CountWall(view_ring, passed[p].edge, sensed, it == doors_on.end() ? kNone : it->second, &c);
      CountWallByNeighbours(view_ring, passed_edges, doors_on, p, it != doors_on.end(), &c);
    }
  }
  CountWallErrors(view_ring, sensed, passed, matched, &c);
  CountWallResiduals(view_ring, sensed, spans, passed, doors_on, lo, hi, &c);
  return c;
}

EdgeErrorMeter::EdgeErrorMeter(const map::Ring& view_ring, localizer::EdgeAssembler& assembler,
                               double skip_in)
    : view_ring_(view_ring), assembler_(assembler), skip_in_(skip_in) {}

void EdgeErrorMeter::Advance(double odometer_in, double heading_rad, int view_edge) {
  // Edges are placed between readings too (sightings, corner ranges): what the assembler
  // holds before this reading is what a reversal in it would forget.
  if (assembler_.sequence().size() != sequence_.size()) {
    sequence_ = assembler_.sequence();
    spans_ = assembler_.spans();
  }
  assembler_.Advance(odometer_in, heading_rad);
  if (assembler_.TakeReversal()) {
    CompareDirection(sequence_, spans_);
    truth_.clear();
    sequence_.clear();
    spans_.clear();
    ++directions_;
  }
  truth_.push_back({odometer_in, view_edge});
}

void EdgeErrorMeter::CompareDirection(const std::vector<map::SensedEdge>& sensed,
                                      const std::vector<localizer::EdgeAssembler::Span>& spans) {
  if (truth_.empty()) return;
  const double start = truth_.front().odometer_in;
  const double end = truth_.back().odometer_in;
  const double sign = end >= start ? 1.0 : -1.0;
  // Only the first direction begins with aligning; later ones begin at a reversal, whose
  // first and last edges CompareWithTruth leaves out as not passed whole.
  const double skip = directions_ == 1 ? skip_in_ : 0.0;
  counts_.Add(CompareWithTruth(view_ring_, sensed, spans, truth_, start + sign * skip, end));
}

EdgeErrorCounts EdgeErrorMeter::Finish() {
  CompareDirection(assembler_.sequence(), assembler_.spans());
  truth_.clear();
  return counts_;
}

}  // namespace stickrep::whereami
