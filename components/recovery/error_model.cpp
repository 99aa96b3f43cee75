#include "recovery/error_model.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "common/strict_yaml.h"

namespace stickrep::recovery {

namespace {

using map::DoorClass;

constexpr double kSumTolerance = 1e-3;
// The largest per-missed-door bias and spread of a wall read over a missed door (inches).
constexpr double kMaxMissedWallBiasIn = 24.0;
// The floor of a mark's read share: a read the measurement never saw is rare, not impossible.
constexpr double kMinMarkShare = 0.005;

std::string Num(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

void RequireProbability(double p, const std::string& what) {
  if (!(p >= 0.0 && p <= 1.0)) {
    throw std::invalid_argument(what + " = " + Num(p) + " is outside [0, 1]");
  }
}

DoorClass ClassKey(const StrictYaml& node, const std::string& key) {
  const auto c = map::ParseDoorClass(key);
  if (!c) {
    node.Fail(key, "unknown door class '" + key +
                       "' (legal: \"30\", \"32\", \"36\", \"40\", "
                       "\"30/30\", \"36/36\")");
  }
  return *c;
}

// Reads {class: probability, ...}; checks each value and that they sum to 1.
std::map<DoorClass, double> ReadDistribution(const StrictYaml& node) {
  std::map<DoorClass, double> out;
  if (!node.IsMap()) node.Fail("", "expected a mapping of door class to probability");
  double sum = 0;
  for (const std::string& key : node.Keys()) {
    const DoorClass c = ClassKey(node, key);
    const double p = node.Get<double>(key, 0.0, 1.0);
    out[c] = p;
    sum += p;
  }
  if (!out.empty() && std::abs(sum - 1.0) > kSumTolerance) {
    node.Fail("", "probabilities sum to " + Num(sum) + ", not 1");
  }
  node.Finish();
  return out;
}

// Reads {class: probability, ...} whose values need not sum to anything.
std::map<DoorClass, double> ReadClassProbabilities(const StrictYaml& node) {
  std::map<DoorClass, double> out;
  if (!node.IsMap()) node.Fail("", "expected a mapping of door class to probability");
  for (const std::string& key : node.Keys())
    out[ClassKey(node, key)] = node.Get<double>(key, 0.0, 1.0);
  node.Finish();
  return out;
}

}  // namespace

ErrorModel ErrorModel::None() {
  ErrorModel m;
  m.source = "no sensing error";
  m.door_correct = 1.0;
  m.door_missized = 0.0;
  m.door_missed = 0.0;
  m.wall_false_door = 0.0;
  return m;
}

// Each class's rates are probabilities that sum to 1; `prefix` names the key.
static void ValidateClassRates(const std::map<DoorClass, ErrorModel::DoorRates>& rates,
                               const std::string& prefix) {
  for (const auto& [c, r] : rates) {
    const std::string key = prefix + map::DoorClassName(c);
    RequireProbability(r.correct, key + ".correct");
    RequireProbability(r.missized, key + ".missized");
    RequireProbability(r.missed, key + ".missed");
    const double rs = r.correct + r.missized + r.missed;
    if (std::abs(rs - 1.0) > kSumTolerance) {
      throw std::invalid_argument(key + ": correct + missized + missed = " + Num(rs) +
                                  ", must be 1 within " + Num(kSumTolerance));
    }
  }
}

static void ValidateWallOverMissedDoor(const ErrorModel::WallOverMissedDoor& w) {
  if (!(std::abs(w.bias_in) <= kMaxMissedWallBiasIn)) {
    throw std::invalid_argument("wall_over_missed_door.bias_in is " + Num(w.bias_in) +
                                ", not in [-24, 24]");
  }
  if (!(w.sigma_in >= 0.0 && w.sigma_in <= kMaxMissedWallBiasIn)) {
    throw std::invalid_argument("wall_over_missed_door.sigma_in is " + Num(w.sigma_in) +
                                ", not in [0, 24]");
  }
}

// ErrorModel::Validate() of the `in_row:` rates.
static void ValidateInRow(const ErrorModel::InRow& row) {
  if (row.wall_false_door) RequireProbability(*row.wall_false_door, "in_row.wall_false_door");
  if (row.wall_false_door_after_missed.has_value() != row.wall_false_door_after_seen.has_value()) {
    throw std::invalid_argument(
        "in_row: wall_false_door_after_missed and wall_false_door_after_seen go together");
  }
  if (row.wall_false_door_after_missed) {
    RequireProbability(*row.wall_false_door_after_missed, "in_row.wall_false_door_after_missed");
    RequireProbability(*row.wall_false_door_after_seen, "in_row.wall_false_door_after_seen");
  }
  ValidateClassRates(row.by_class, "in_row.by_class.");
  if (row.door_missed_after_missed.empty() != row.door_missed_after_seen.empty()) {
    throw std::invalid_argument(
        "in_row: door_missed_after_missed and door_missed_after_seen go together");
  }
  for (const auto* rates : {&row.door_missed_after_missed, &row.door_missed_after_seen}) {
    for (const auto& [c, p] : *rates) {
      RequireProbability(p, std::string("in_row.door_missed_after_") +
                                (rates == &row.door_missed_after_seen ? "seen." : "missed.") +
                                std::string(map::DoorClassName(c)));
    }
  }
}

void ErrorModel::Validate() const {
  RequireProbability(door_correct, "door_correct");
  RequireProbability(door_missized, "door_missized");
  RequireProbability(door_missed, "door_missed");
  RequireProbability(wall_false_door, "wall_false_door");
  const double sum = door_correct + door_missized + door_missed;
  if (std::abs(sum - 1.0) > kSumTolerance) {
    throw std::invalid_argument("door_correct + door_missized + door_missed = " + Num(sum) +
                                ", must be 1 within " + Num(kSumTolerance));
  }
  for (const auto& [from, row] : missized_to) {
    double s = 0;
    for (const auto& [to, p] : row) {
      RequireProbability(p, std::string("missized_to.") + map::DoorClassName(from));
      if (to == from) {
        throw std::invalid_argument(std::string("missized_to.") + map::DoorClassName(from) +
                                    " sends a door to its own class");
      }
      s += p;
    }
    if (!row.empty() && std::abs(s - 1.0) > kSumTolerance) {
      throw std::invalid_argument(std::string("missized_to.") + map::DoorClassName(from) +
                                  " sums to " + Num(s) + ", not 1");
    }
  }
  double s = 0;
  for (const auto& [c, p] : false_door_classes) {
    RequireProbability(p, "false_door_classes");
    s += p;
  }
  if (!false_door_classes.empty() && std::abs(s - 1.0) > kSumTolerance) {
    throw std::invalid_argument("false_door_classes sums to " + Num(s) + ", not 1");
  }
  if (wall_false_door_per_in &&
      !(*wall_false_door_per_in >= 0.0 && *wall_false_door_per_in <= 0.1)) {
    throw std::invalid_argument("wall_false_door_per_in is " + Num(*wall_false_door_per_in) +
                                ", not in [0, 0.1]");
  }
  if (wall_false_doors_max && !wall_false_door_per_in) {
    throw std::invalid_argument("wall_false_doors_max needs wall_false_door_per_in");
  }
  if (wall_false_doors_max && !(*wall_false_doors_max >= 1 && *wall_false_doors_max <= 9)) {
    throw std::invalid_argument("wall_false_doors_max is " + std::to_string(*wall_false_doors_max) +
                                ", not in [1, 9]");
  }
  ValidateClassRates(by_class, "by_class.");
  if (in_row) ValidateInRow(*in_row);
  if (wall_over_missed_door) ValidateWallOverMissedDoor(*wall_over_missed_door);
  RequireProbability(leaf_split, "leaf_split");
  RequireProbability(leaf_sliver, "leaf_sliver");
  RequireProbability(leaf_wall_before, "leaf_wall_before");
  RequireProbability(leaf_wall_after, "leaf_wall_after");
  const double leaf = leaf_split + leaf_wall_before + leaf_wall_after;
  if (leaf > 1.0 + kSumTolerance) {
    throw std::invalid_argument("leaf_split + leaf_wall_before + leaf_wall_after = " + Num(leaf) +
                                ", more than 1");
  }
}

// The per-class rates under `key` of `node`: door class -> {correct, missized, missed},
// each summing to 1.
static std::map<DoorClass, ErrorModel::DoorRates> ReadClassRates(const StrictYaml& node,
                                                                 const std::string& key) {
  const StrictYaml bc = node.Child(key);
  if (!bc.IsMap()) node.Fail(key, "expected a mapping of door class to rates");
  std::map<DoorClass, ErrorModel::DoorRates> rates;
  for (const std::string& name : bc.Keys()) {
    const DoorClass c = ClassKey(bc, name);
    const StrictYaml row = bc.Child(name);
    ErrorModel::DoorRates r;
    r.correct = row.Get<double>("correct", 0.0, 1.0);
    r.missized = row.Get<double>("missized", 0.0, 1.0);
    r.missed = row.Get<double>("missed", 0.0, 1.0);
    const double rs = r.correct + r.missized + r.missed;
    if (std::abs(rs - 1.0) > kSumTolerance) {
      row.Fail("missed", "correct + missized + missed = " + Num(rs) + ", must be 1 within " +
                             Num(kSumTolerance));
    }
    row.Finish();
    rates[c] = r;
  }
  bc.Finish();
  return rates;
}

// The optional leaf_* shares (each 0 when absent): each a probability, the three places the
// rest of a leaf read goes to at most 1 together.
static void ReadLeafShares(const StrictYaml& node, ErrorModel* m) {
  const auto share = [&](const char* key) {
    return node.Has(key) ? node.Get<double>(key, 0.0, 1.0) : 0.0;
  };
  m->leaf_split = share("leaf_split");
  m->leaf_sliver = share("leaf_sliver");
  m->leaf_wall_before = share("leaf_wall_before");
  m->leaf_wall_after = share("leaf_wall_after");
  const double leaf = m->leaf_split + m->leaf_wall_before + m->leaf_wall_after;
  if (leaf > 1.0 + kSumTolerance) {
    node.Fail(node.Has("leaf_wall_after") ? "leaf_wall_after" : "leaf_wall_before",
              "leaf_split + leaf_wall_before + leaf_wall_after = " + Num(leaf) +
                  ", more than 1");
  }
}

// One row of `marks:`: {unknown: p, plain: p, window: p, poster: p}, missing keys 0, sum 1.
static ErrorModel::MarkRow ReadMarkRow(const StrictYaml& row) {
  if (!row.IsMap()) row.Fail("", "expected a mapping of read mark to probability");
  ErrorModel::MarkRow out{};
  double sum = 0.0;
  for (const std::string& key : row.Keys()) {
    const auto mark = map::ParseDoorMark(key);
    if (!mark) row.Fail(key, "unknown mark '" + key + "' (legal: unknown, plain, window, poster)");
    out[static_cast<int>(*mark)] = row.Get<double>(key, 0.0, 1.0);
    sum += out[static_cast<int>(*mark)];
  }
  if (std::abs(sum - 1.0) > kSumTolerance) {
    row.Fail("", "probabilities sum to " + Num(sum) + ", not 1");
  }
  row.Finish();
  return out;
}

// One optional block of mark rows (`marks:` or `marks_missized:`): a row per true mark
// (plain, window, poster) and, where `false_door` is given, the false doors' row.
static void ReadMarkBlock(const StrictYaml& node, const char* key,
                          std::map<map::DoorMark, ErrorModel::MarkRow>* rows,
                          std::optional<ErrorModel::MarkRow>* false_door) {
  if (!node.Has(key)) return;
  const StrictYaml block = node.Child(key);
  if (!block.IsMap()) node.Fail(key, "expected a mapping of true mark to read shares");
  const std::string legal = false_door ? "plain, window, poster, false_door" : "plain, window, poster";
  for (const std::string& name : block.Keys()) {
    if (false_door && name == "false_door") {
      *false_door = ReadMarkRow(block.Child(name));
      continue;
    }
    const auto mark = map::ParseDoorMark(name);
    if (!mark || *mark == map::DoorMark::kUnknown) {
      block.Fail(name, "unknown true mark '" + name + "' (legal: " + legal + ")");
    }
    (*rows)[*mark] = ReadMarkRow(block.Child(name));
  }
  if (false_door && !rows->empty() && !*false_door) {
    block.Fail("", "a `marks:` block needs a false_door row");
  }
  block.Finish();
}

static void ReadMarks(const StrictYaml& node, ErrorModel* m) {
  ReadMarkBlock(node, "marks", &m->mark_read, &m->false_door_marks);
  ReadMarkBlock(node, "marks_missized", &m->mark_read_missized, nullptr);
  if (!m->mark_read_missized.empty() && m->mark_read.empty()) {
    node.Fail("marks_missized", "marks_missized needs a `marks:` block");
  }
}

// The `in_row:` block under `node`.
static ErrorModel::InRow ReadInRow(const StrictYaml& node) {
  const StrictYaml row = node.Child("in_row");
  if (!row.IsMap()) node.Fail("in_row", "expected a mapping with wall_false_door and by_class");
  ErrorModel::InRow in_row;
  if (row.Has("wall_false_door"))
    in_row.wall_false_door = row.Get<double>("wall_false_door", 0.0, 1.0);
  if (row.Has("wall_false_door_after_missed") != row.Has("wall_false_door_after_seen")) {
    row.Fail(row.Has("wall_false_door_after_missed") ? "wall_false_door_after_missed"
                                                     : "wall_false_door_after_seen",
             "wall_false_door_after_missed and wall_false_door_after_seen go together");
  }
  if (row.Has("wall_false_door_after_missed")) {
    in_row.wall_false_door_after_missed = row.Get<double>("wall_false_door_after_missed", 0.0, 1.0);
    in_row.wall_false_door_after_seen = row.Get<double>("wall_false_door_after_seen", 0.0, 1.0);
  }
  if (row.Has("by_class")) in_row.by_class = ReadClassRates(row, "by_class");
  if (row.Has("door_missed_after_missed") != row.Has("door_missed_after_seen")) {
    row.Fail(
        row.Has("door_missed_after_missed") ? "door_missed_after_missed" : "door_missed_after_seen",
        "door_missed_after_missed and door_missed_after_seen go together");
  }
  if (row.Has("door_missed_after_missed")) {
    in_row.door_missed_after_missed = ReadClassProbabilities(row.Child("door_missed_after_missed"));
    in_row.door_missed_after_seen = ReadClassProbabilities(row.Child("door_missed_after_seen"));
  }
  row.Finish();
  return in_row;
}

static ErrorModel ErrorModelFromYaml(const StrictYaml& root) {
  const StrictYaml node = root.Child("error_model");
  ErrorModel m;
  m.source = node.Get<std::string>("source");
  m.door_correct = node.Get<double>("door_correct", 0.0, 1.0);
  m.door_missized = node.Get<double>("door_missized", 0.0, 1.0);
  m.door_missed = node.Get<double>("door_missed", 0.0, 1.0);
  m.wall_false_door = node.Get<double>("wall_false_door", 0.0, 1.0);
  if (node.Has("wall_false_door_per_in")) {
    m.wall_false_door_per_in = node.Get<double>("wall_false_door_per_in", 0.0, 0.1, "1/in");
  }
  if (node.Has("wall_false_doors_max")) {
    m.wall_false_doors_max = node.Get<int>("wall_false_doors_max", 1, 9);
    if (!m.wall_false_door_per_in) {
      node.Fail("wall_false_doors_max",
                "needs wall_false_door_per_in (without it a wall holds one false door at most)");
    }
  }
  const double sum = m.door_correct + m.door_missized + m.door_missed;
  if (std::abs(sum - 1.0) > kSumTolerance) {
    node.Fail("door_missed", "door_correct + door_missized + door_missed = " + Num(sum) +
                                 ", must be 1 within " + Num(kSumTolerance));
  }
  if (node.Has("missized_to")) {
    const StrictYaml mt = node.Child("missized_to");
    if (!mt.IsMap()) node.Fail("missized_to", "expected a mapping of door class to mapping");
    for (const std::string& key : mt.Keys()) {
      const DoorClass from = ClassKey(mt, key);
      const StrictYaml row = mt.Child(key);
      m.missized_to[from] = ReadDistribution(row);
      if (m.missized_to[from].count(from)) {
        mt.Fail(key, "a mis-sized door cannot be sensed with its own class");
      }
    }
    mt.Finish();
  }
  if (node.Has("false_door_classes")) {
    m.false_door_classes = ReadDistribution(node.Child("false_door_classes"));
  }
  if (node.Has("by_class")) m.by_class = ReadClassRates(node, "by_class");
  if (node.Has("in_row")) m.in_row = ReadInRow(node);
  if (node.Has("wall_over_missed_door")) {
    const StrictYaml w = node.Child("wall_over_missed_door");
    if (!w.IsMap()) node.Fail("wall_over_missed_door", "expected {bias_in: X, sigma_in: Y}");
    ErrorModel::WallOverMissedDoor over;
    over.bias_in = w.Get<double>("bias_in", -kMaxMissedWallBiasIn, kMaxMissedWallBiasIn, "in");
    over.sigma_in = w.Get<double>("sigma_in", 0.0, kMaxMissedWallBiasIn, "in");
    w.Finish();
    m.wall_over_missed_door = over;
  }
  ReadLeafShares(node, &m);
  ReadMarks(node, &m);
  node.Finish();
  root.Finish();
  return m;
}

ErrorModel LoadErrorModel(const std::string& path) {
  return ErrorModelFromYaml(StrictYaml::LoadFile(path));
}

ErrorModel ParseErrorModel(const std::string& text, const std::string& name) {
  return ErrorModelFromYaml(StrictYaml::LoadString(text, name));
}

std::vector<DoorClass> DefaultMissizedTargets(DoorClass c) {
  switch (c) {
    case DoorClass::k30:
      return {DoorClass::k32};
    case DoorClass::k32:
      return {DoorClass::k30, DoorClass::k36};
    case DoorClass::k36:
      return {DoorClass::k32, DoorClass::k40};
    case DoorClass::k40:
      return {DoorClass::k36};
    case DoorClass::k30_30:
      return {DoorClass::k36_36};
    case DoorClass::k36_36:
      return {DoorClass::k30_30};
  }
  return {};
}

// Confusion::mark_read[kUnknown]: the read rows mixed by the map's surveyed doors' marks,
// or equally over the rows the model gives when the map surveyed none.
static void MixUnsurveyed(const ErrorModel& model, const map::MatchIndex& index, Confusion* c) {
  std::array<double, map::kDoorMarkCount> weight{};
  double total = 0.0;
  for (int g = 0; g < index.EdgeCount(); ++g) {
    if (!map::IsDoorCode(index.code(g)) || index.mark(g) == map::DoorMark::kUnknown) continue;
    weight[static_cast<int>(index.mark(g))] += 1.0;
    total += 1.0;
  }
  if (total == 0.0) {
    for (const auto& [mark, row] : model.mark_read) weight[static_cast<int>(mark)] = 1.0;
    total = static_cast<double>(model.mark_read.size());
  }
  const int unknown = static_cast<int>(map::DoorMark::kUnknown);
  for (auto* rows : {&c->mark_read, &c->mark_read_missized}) {
    ErrorModel::MarkRow mixed{};
    for (int m = unknown + 1; m < map::kDoorMarkCount; ++m) {
      for (int r = 0; r < map::kDoorMarkCount; ++r) mixed[r] += weight[m] / total * (*rows)[m][r];
    }
    (*rows)[unknown] = mixed;
  }
}

double Confusion::RowMissed(int k, Before before) const {
  if (!row_missed_by_before || before == Before::kUnknown) return row_missed[k];
  return before == Before::kDoorMissed ? row_missed_after_missed[k] : row_missed_after_seen[k];
}

double Confusion::RowReadFactor(int k, Before before) const {
  const double left = 1.0 - row_missed[k];
  return left > 0.0 ? (1.0 - RowMissed(k, before)) / left : 1.0;
}

double Confusion::FalseDoorIn(double len_in, bool row, Before before) const {
  if (row && row_false_door_by_before && before != Before::kUnknown) {
    return before == Before::kDoorMissed ? row_false_door_after_missed : row_false_door_after_seen;
  }
  if (false_door_per_in <= 0.0) return row ? row_false_door : false_door;
  if (row && row_false_door_own) return row_false_door;
  return -std::expm1(-false_door_per_in * std::max(0.0, len_in));
}

// Confusion's per-class rates, alone and in a row: the model's own where it gives them, else
// the overall rates (in a row: the class's rates alone).
static void ResolveClassRates(const ErrorModel& model, Confusion* c) {
  for (int k = 0; k < kDoorClasses; ++k) {
    const auto it = model.by_class.find(static_cast<DoorClass>(k));
    const bool own = it != model.by_class.end();
    c->class_correct[k] = own ? it->second.correct : c->correct;
    c->class_missized[k] = own ? it->second.missized : c->missized;
    c->class_missed[k] = own ? it->second.missed : c->missed;
    c->row_correct[k] = c->class_correct[k];
    c->row_missized[k] = c->class_missized[k];
    c->row_missed[k] = c->class_missed[k];
    c->row_missed_after_missed[k] = c->row_missed_after_seen[k] = c->class_missed[k];
    if (!model.in_row) continue;
    const auto own_after = [k](const std::map<DoorClass, double>& rates, double* out) {
      const auto it = rates.find(static_cast<DoorClass>(k));
      if (it != rates.end()) *out = it->second;
    };
    const auto row = model.in_row->by_class.find(static_cast<DoorClass>(k));
    if (row == model.in_row->by_class.end()) continue;
    c->row_correct[k] = row->second.correct;
    c->row_missized[k] = row->second.missized;
    c->row_missed[k] = row->second.missed;
    c->row_missed_after_missed[k] = c->row_missed_after_seen[k] = row->second.missed;
    own_after(model.in_row->door_missed_after_missed, &c->row_missed_after_missed[k]);
    own_after(model.in_row->door_missed_after_seen, &c->row_missed_after_seen[k]);
  }
  c->row_missed_by_before = model.in_row && !model.in_row->door_missed_after_missed.empty();
}

Confusion Resolve(const ErrorModel& model, const map::MatchIndex& index) {
  Confusion c;
  c.correct = model.door_correct;
  c.missized = model.door_missized;
  c.missed = model.door_missed;
  c.false_door = model.wall_false_door;
  c.row_false_door = c.false_door;
  c.false_door_per_in = model.wall_false_door_per_in.value_or(0.0);
  c.false_doors_max = model.wall_false_doors_max.value_or(0);
  if (model.in_row && model.in_row->wall_false_door) {
    c.row_false_door = *model.in_row->wall_false_door;
    c.row_false_door_own = true;
  }
  if (model.in_row && model.in_row->wall_false_door_after_missed &&
      model.in_row->wall_false_door_after_seen) {
    c.row_false_door_after_missed = *model.in_row->wall_false_door_after_missed;
    c.row_false_door_after_seen = *model.in_row->wall_false_door_after_seen;
    c.row_false_door_by_before = true;
  }
  ResolveClassRates(model, &c);
  if (model.wall_over_missed_door) {
    c.missed_wall_bias_in = model.wall_over_missed_door->bias_in;
    c.missed_wall_var_in2 =
        model.wall_over_missed_door->sigma_in * model.wall_over_missed_door->sigma_in;
  }
  c.leaf_split = model.leaf_split;
  c.leaf_sliver = model.leaf_sliver;
  c.leaf_before = model.leaf_wall_before;
  c.leaf_after = model.leaf_wall_after;
  double doors = 0;
  for (int k = 0; k < kDoorClasses; ++k) {
    c.map_prior[k] =
        static_cast<double>(index.EdgesWithCode(map::DoorCode(static_cast<DoorClass>(k))).size());
    doors += c.map_prior[k];
  }
  for (double& p : c.map_prior) p = doors > 0 ? p / doors : 0.0;
  for (int k = 0; k < kDoorClasses; ++k) {
    const auto from = static_cast<DoorClass>(k);
    const auto it = model.missized_to.find(from);
    if (it != model.missized_to.end() && !it->second.empty()) {
      for (const auto& [to, p] : it->second) c.missized_to[k][static_cast<int>(to)] = p;
    } else {
      const auto targets = DefaultMissizedTargets(from);
      for (const DoorClass t : targets) {
        c.missized_to[k][static_cast<int>(t)] = 1.0 / static_cast<double>(targets.size());
      }
    }
  }
  if (model.HasMarks()) {
    c.marks = true;
    // A true mark the file does not list is read as the false doors are.
    for (int k = 0; k < map::kDoorMarkCount; ++k) c.mark_read[k] = *model.false_door_marks;
    for (const auto& [mark, row] : model.mark_read) c.mark_read[static_cast<int>(mark)] = row;
    c.mark_read_missized = c.mark_read;
    for (const auto& [mark, row] : model.mark_read_missized) {
      c.mark_read_missized[static_cast<int>(mark)] = row;
    }
    c.false_mark = *model.false_door_marks;
    MixUnsurveyed(model, index, &c);
  }
  if (!model.false_door_classes.empty()) {
    for (const auto& [k, p] : model.false_door_classes) c.false_class[static_cast<int>(k)] = p;
  } else if (doors > 0) {
    c.false_class = c.map_prior;
  } else {
    c.false_class[static_cast<int>(DoorClass::k36)] = 1.0;  // a map without doors
  }
  return c;
}

double Confusion::MarkLikelihood(map::DoorMark read, map::DoorMark truth, bool class_right) const {
  if (!marks) return 1.0;
  const ErrorModel::MarkRow& row =
      (class_right ? mark_read : mark_read_missized)[static_cast<int>(truth)];
  return std::max(row[static_cast<int>(read)], kMinMarkShare);
}

double Confusion::FalseDoorMarkLikelihood(map::DoorMark read) const {
  if (!marks) return 1.0;
  return std::max(false_mark[static_cast<int>(read)], kMinMarkShare);
}

// ---------------------------------------------------------------------------------------

SensingNoise SensingNoise::None() {
  SensingNoise n;
  n.width_sigma_rel = 0;
  n.jamb_sigma_in = 0;
  n.wheel_scale_sigma_rel = 0;
  n.wheel_walk_sigma_in_per_sqrt_in = 0;
  return n;
}

double SensingNoise::WallSigmaIn(double length_in) const {
  const double scale = wheel_scale_sigma_rel * length_in;
  const double walk2 =
      wheel_walk_sigma_in_per_sqrt_in * wheel_walk_sigma_in_per_sqrt_in * std::max(0.0, length_in);
  return std::sqrt(2.0 * jamb_sigma_in * jamb_sigma_in + scale * scale + walk2);
}

std::array<ClassRegion, kDoorClasses> DefaultClassRegions() {
  // docs/sensing.md, DefaultBoundaries(): Table 4.1 plus the Bayes-derived door30 region.
  return {{{28.5, 31.4}, {31.4, 33.5}, {33.5, 38.8}, {38.8, 42.7}, {56.4, 64.0}, {67.9, 76.3}}};
}

void StudyConfig::Validate() const {
  auto positive = [](double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string(what) + " must be > 0, got " + Num(v));
    }
  };
  auto non_negative = [](double v, const char* what) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string(what) + " must be >= 0, got " + Num(v));
    }
  };
  positive(speed_ftps, "speed_ftps");
  positive(frame_period_s, "frame_period_s");
  non_negative(noise.width_sigma_rel, "width_sigma_rel");
  non_negative(noise.jamb_sigma_in, "jamb_sigma_in");
  non_negative(noise.wheel_scale_sigma_rel, "wheel_scale_sigma_rel");
  non_negative(noise.wheel_walk_sigma_in_per_sqrt_in, "wheel_walk_sigma_in_per_sqrt_in");
  non_negative(base_tolerance.metric_rel, "tolerance_rel");
  non_negative(base_tolerance.metric_abs_in, "tolerance_in");
  for (int k = 0; k < kDoorClasses; ++k) {
    const ClassRegion& r = noise.class_region_in[k];
    const double w = map::DoorClassWidthIn(static_cast<map::DoorClass>(k));
    if (!(r.lo_in < w && w < r.hi_in)) {
      throw std::invalid_argument(std::string("class region of ") +
                                  map::DoorClassName(static_cast<map::DoorClass>(k)) +
                                  " must contain its nominal width");
    }
  }
  double last = 0;
  for (double s : relaxation_steps) {
    if (!(s > last) || s > 1.0) {
      throw std::invalid_argument("relaxation_steps must increase within (0, 1]");
    }
    last = s;
  }
  if (first_frame_edges < 1) throw std::invalid_argument("first_frame_edges must be >= 1");
  if (max_edges < 1) throw std::invalid_argument("max_edges must be >= 1");
  if (!(bayes.threshold > 0.5 && bayes.threshold < 1.0)) {
    throw std::invalid_argument("bayes.threshold must be in (0.5, 1)");
  }
  if (!(bayes.outlier > 0.0 && bayes.outlier < 0.5)) {
    throw std::invalid_argument("bayes.outlier must be in (0, 0.5)");
  }
}

static StudyConfig StudyConfigFromYaml(const StrictYaml& root) {
  const StrictYaml node = root.Child("study");
  StudyConfig c;
  c.source = node.Get<std::string>("source");
  c.speed_ftps = node.Get<double>("speed_ftps", 0.01, 100.0, "ft/s");
  c.frame_period_s = node.Get<double>("frame_period_s", 0.001, 10.0, "s");

  const StrictYaml us = node.Child("ultrasonic");
  c.noise.width_sigma_rel = us.Get<double>("width_sigma_rel", 0.0, 0.5);
  c.noise.jamb_sigma_in = us.Get<double>("jamb_sigma_in", 0.0, 24.0, "in");
  const StrictYaml regions = us.Child("class_regions_in");
  if (!regions.IsMap()) us.Fail("class_regions_in", "expected a mapping of door class to [lo, hi]");
  std::array<bool, kDoorClasses> seen{};
  for (const std::string& key : regions.Keys()) {
    const map::DoorClass k = ClassKey(regions, key);
    const auto lohi = regions.Sequence(key);
    if (lohi.size() != 2) regions.Fail(key, "expected [lo, hi] in inches");
    ClassRegion r{lohi[0].As<double>(), lohi[1].As<double>()};
    const double w = map::DoorClassWidthIn(k);
    if (!(r.lo_in < w && w < r.hi_in)) {
      regions.Fail(key, "the region must contain the class width " + Num(w) + " in");
    }
    c.noise.class_region_in[static_cast<int>(k)] = r;
    seen[static_cast<int>(k)] = true;
  }
  for (int k = 0; k < kDoorClasses; ++k) {
    if (!seen[k]) {
      regions.Fail("", std::string("no region for class ") +
                           map::DoorClassName(static_cast<map::DoorClass>(k)));
    }
  }
  regions.Finish();
  us.Finish();

  const StrictYaml wheel = node.Child("wheel");
  c.noise.wheel_scale_sigma_rel = wheel.Get<double>("scale_sigma_rel", 0.0, 0.5);
  c.noise.wheel_walk_sigma_in_per_sqrt_in =
      wheel.Get<double>("walk_sigma_in_per_sqrt_in", 0.0, 10.0, "in/sqrt(in)");
  wheel.Finish();

  const StrictYaml match = node.Child("matching");
  c.base_tolerance.metric_rel = match.Get<double>("tolerance_rel", 0.0, 1.0);
  c.base_tolerance.metric_abs_in = match.Get<double>("tolerance_in", 0.0, 120.0, "in");
  c.base_tolerance.angle_deg = match.Get<double>("angle_tolerance_deg", -1.0, 180.0, "deg");
  c.relaxation_steps.clear();
  for (const StrictYaml& s : match.Sequence("relaxation_steps")) {
    c.relaxation_steps.push_back(s.As<double>());
  }
  double last = 0;
  for (double s : c.relaxation_steps) {
    if (!(s > last) || s > 1.0) {
      match.Fail("relaxation_steps", "steps must increase within (0, 1]");
    }
    last = s;
  }
  c.first_frame_edges = match.Get<int>("first_frame_edges", 1, 100);
  match.Finish();

  c.max_edges = node.Get<int>("max_edges", 1, 100000);

  const StrictYaml bayes = node.Child("bayes");
  c.bayes.threshold = bayes.Get<double>("threshold", 0.5, 0.999999);
  c.bayes.outlier = bayes.Get<double>("outlier", 1e-12, 0.5);
  c.bayes.max_missed_doors = bayes.Get<int>("max_missed_doors", 0, 4);
  c.bayes.angle_tolerance_deg = bayes.Get<double>("angle_tolerance_deg", 0.0, 180.0, "deg");
  c.bayes.w2_over_missed_doors = bayes.GetOr<bool>("w2_over_missed_doors", false);
  c.bayes.false_door_fit = bayes.GetOr<bool>("false_door_fit", false);
  c.bayes.first_part_in_noise = bayes.GetOr<bool>("first_part_in_noise", false);
  bayes.Finish();
  node.Finish();
  root.Finish();
  try {
    c.Validate();
  } catch (const std::invalid_argument& e) {
    node.Fail("", e.what());
  }
  return c;
}

StudyConfig LoadStudyConfig(const std::string& path) {
  return StudyConfigFromYaml(StrictYaml::LoadFile(path));
}

StudyConfig ParseStudyConfig(const std::string& text, const std::string& name) {
  return StudyConfigFromYaml(StrictYaml::LoadString(text, name));
}

// The shortest text that reads back as the same double: a model that loaded loads again
// (rounding could push a sum that was just within kSumTolerance past it).
static std::string RoundTripNumber(double v) {
  char buf[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return std::string(buf);
}

// A `by_class:` block of per-class rates at `indent`; nothing when there are none.
static std::string FormatClassRates(const std::map<DoorClass, ErrorModel::DoorRates>& rates,
                                    const std::string& indent) {
  if (rates.empty()) return "";
  std::string out = indent + "by_class:\n";
  for (const auto& [c, r] : rates) {
    out += indent + "  \"" + std::string(map::DoorClassName(c)) +
           "\": {correct: " + RoundTripNumber(r.correct) +
           ", missized: " + RoundTripNumber(r.missized) + ", missed: " + RoundTripNumber(r.missed) +
           "}\n";
  }
  return out;
}

// The `in_row:` block of an error model file.
static std::string FormatInRow(const ErrorModel::InRow& row) {
  const auto number = RoundTripNumber;
  std::string out = "  in_row:\n";
  if (row.wall_false_door) out += "    wall_false_door: " + number(*row.wall_false_door) + "\n";
  if (row.wall_false_door_after_missed && row.wall_false_door_after_seen) {
    out += "    wall_false_door_after_missed: " + number(*row.wall_false_door_after_missed) +
           "\n    wall_false_door_after_seen: " + number(*row.wall_false_door_after_seen) + "\n";
  }
  out += FormatClassRates(row.by_class, "    ");
  for (const auto* rates : {&row.door_missed_after_missed, &row.door_missed_after_seen}) {
    if (rates->empty()) continue;
    out += rates == &row.door_missed_after_missed ? "    door_missed_after_missed: {"
                                                  : "    door_missed_after_seen: {";
    const char* sep = "";
    for (const auto& [c, p] : *rates) {
      out += std::string(sep) + "\"" + std::string(map::DoorClassName(c)) + "\": " + number(p);
      sep = ", ";
    }
    out += "}\n";
  }
  return out;
}

std::string FormatErrorModelYaml(const ErrorModel& m, const std::string& comment) {
  const auto number = RoundTripNumber;
  const auto distribution = [&](const std::map<map::DoorClass, double>& d) {
    std::string s = "{";
    for (const auto& [c, p] : d) {
      s += (s.size() > 1 ? ", \"" : "\"") + std::string(map::DoorClassName(c)) + "\": " + number(p);
    }
    return s + "}";
  };
  std::string out;
  std::string line;
  for (char ch : comment + "\n") {
    if (ch != '\n') {
      line += ch;
      continue;
    }
    if (!line.empty()) out += "# " + line + "\n";
    line.clear();
  }
  out += "error_model:\n";
  out += "  source: " + YamlQuoted(m.source) + "\n";
  out += "  door_correct: " + number(m.door_correct) + "\n";
  out += "  door_missized: " + number(m.door_missized) + "\n";
  out += "  door_missed: " + number(m.door_missed) + "\n";
  out += "  wall_false_door: " + number(m.wall_false_door) + "\n";
  if (m.wall_false_door_per_in) {
    out += "  wall_false_door_per_in: " + number(*m.wall_false_door_per_in) + "\n";
  }
  if (m.wall_false_doors_max) {
    out += "  wall_false_doors_max: " + std::to_string(*m.wall_false_doors_max) + "\n";
  }
  std::string missized = "{";
  for (const auto& [c, row] : m.missized_to) {
    missized += (missized.size() > 1 ? ", \"" : "\"") + std::string(map::DoorClassName(c)) +
                "\": " + distribution(row);
  }
  out += "  missized_to: " + missized + "}\n";
  out += "  false_door_classes: " + distribution(m.false_door_classes) + "\n";
  out += FormatClassRates(m.by_class, "  ");
  if (m.in_row) out += FormatInRow(*m.in_row);
  if (m.wall_over_missed_door) {
    out += "  wall_over_missed_door: {bias_in: " + number(m.wall_over_missed_door->bias_in) +
           ", sigma_in: " + number(m.wall_over_missed_door->sigma_in) + "}\n";
  }
  if (m.leaf_split > 0.0 || m.leaf_sliver > 0.0 || m.leaf_wall_before > 0.0 ||
      m.leaf_wall_after > 0.0) {
    out += "  leaf_split: " + number(m.leaf_split) + "\n";
    out += "  leaf_sliver: " + number(m.leaf_sliver) + "\n";
    out += "  leaf_wall_before: " + number(m.leaf_wall_before) + "\n";
    out += "  leaf_wall_after: " + number(m.leaf_wall_after) + "\n";
  }
  if (m.HasMarks()) {
    const auto row = [&](const ErrorModel::MarkRow& r) {
      std::string s = "{";
      for (int k = 0; k < map::kDoorMarkCount; ++k) {
        s += (k ? ", " : "") + std::string(map::DoorMarkName(static_cast<map::DoorMark>(k))) +
             ": " + number(r[k]);
      }
      return s + "}";
    };
    out += "  marks:\n";
    for (const auto& [mark, r] : m.mark_read) {
      out += "    " + std::string(map::DoorMarkName(mark)) + ": " + row(r) + "\n";
    }
    out += "    false_door: " + row(*m.false_door_marks) + "\n";
    if (!m.mark_read_missized.empty()) out += "  marks_missized:\n";
    for (const auto& [mark, r] : m.mark_read_missized) {
      out += "    " + std::string(map::DoorMarkName(mark)) + ": " + row(r) + "\n";
    }
  }
  return out;
}

}  // namespace stickrep::recovery
