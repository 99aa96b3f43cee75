#include "map_tool/floor_plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <set>
#include <string>
#include <vector>

#include "common/strict_yaml.h"
#include "common/units.h"
#include "stickrep/map_io.h"

namespace stickrep::map {

namespace {

struct Vec {
  double x = 0.0, y = 0.0;
  Vec operator+(const Vec& o) const { return {x + o.x, y + o.y}; }
  Vec operator-(const Vec& o) const { return {x - o.x, y - o.y}; }
  Vec operator*(double k) const { return {x * k, y * k}; }
  double Dot(const Vec& o) const { return x * o.x + y * o.y; }
  double Cross(const Vec& o) const { return x * o.y - y * o.x; }
  double Norm() const { return std::hypot(x, y); }
};

Vec Heading(double rad) { return {std::cos(rad), std::sin(rad)}; }

// What the edge leaving a side point is.
enum class Kind { kWall, kDoor, kOpening };

struct SidePoint {
  Vec p;
  Kind next = Kind::kWall;
  double door_width_in = 0.0;
};

// One straight stretch of the centreline: stations [s0, s1], from `a` along `dir`.
struct Stretch {
  Vec a;
  Vec dir;
  double s0 = 0.0, s1 = 0.0;
};

// A door in an alcove's back wall, from the alcove's start.
struct AlcoveDoor {
  double at_in = 0.0;
  double width_in = 0.0;
};

struct Feature {
  double at_in = 0.0;
  double width_in = 0.0;
  Kind kind = Kind::kWall;  // kDoor, kOpening, or kWall for an alcove
  double depth_in = 0.0;    // alcoves (into the wall); piers are negative (out of it)
  std::vector<AlcoveDoor> doors;
  StrictYaml where;
};

Feature ReadFeature(const StrictYaml& y) {
  Feature f{0.0, 0.0, Kind::kWall, 0.0, {}, y};
  f.at_in = y.Get<double>("at_in", 0.0, 1e6, "in");
  int kinds = 0;
  if (y.Has("door_in")) {
    f.kind = Kind::kDoor;
    f.width_in = y.Get<double>("door_in", 1.0, 1000.0, "in");
    if (!NearestDoorClass(f.width_in)) {
      y.Fail("door_in", "no door class lies within " + FormatNumber(kDoorClassToleranceIn) +
                            " in of " + FormatNumber(f.width_in) +
                            " in; a wider gap is an opening (opening_in)");
    }
    ++kinds;
  }
  if (y.Has("opening_in")) {
    f.kind = Kind::kOpening;
    f.width_in = y.Get<double>("opening_in", 1.0, 1e5, "in");
    ++kinds;
  }
  if (y.Has("pier")) {
    // A pilaster or an engaged column standing out of the wall into the corridor: an alcove
    // of negative depth, with no doors.
    const StrictYaml a = y.Child("pier");
    f.kind = Kind::kWall;
    f.width_in = a.Get<double>("width_in", 1.0, 1e4, "in");
    f.depth_in = -a.Get<double>("depth_in", 1.0, 1e4, "in");
    a.Finish();
    ++kinds;
  }
  if (y.Has("alcove")) {
    const StrictYaml a = y.Child("alcove");
    f.kind = Kind::kWall;
    f.width_in = a.Get<double>("width_in", 1.0, 1e5, "in");
    f.depth_in = a.Get<double>("depth_in", 1.0, 1e5, "in");
    if (a.Has("doors")) {
      double end = 0.0;
      for (const StrictYaml& d : a.Sequence("doors")) {
        AlcoveDoor door{d.Get<double>("at_in", 0.0, 1e5, "in"),
                        d.Get<double>("door_in", 1.0, 1000.0, "in")};
        if (!NearestDoorClass(door.width_in)) {
          d.Fail("door_in", "no door class lies within " + FormatNumber(kDoorClassToleranceIn) +
                                " in of " + FormatNumber(door.width_in) + " in");
        }
        if (door.at_in < end - 1e-9) d.Fail("at_in", "overlaps the door before it");
        end = door.at_in + door.width_in;
        if (end > f.width_in + 1e-9) {
          d.Fail("at_in", "the door runs past the alcove's back wall (" +
                              FormatNumber(f.width_in) + " in wide)");
        }
        d.Finish();
        f.doors.push_back(door);
      }
    }
    a.Finish();
    ++kinds;
  }
  if (kinds != 1) {
    y.Fail("", "a feature is exactly one of door_in, opening_in, alcove, pier");
  }
  y.Finish();
  return f;
}

struct Corridor {
  std::string id;
  double width_in = 0.0;
  std::vector<Vec> vertices;  // the centreline
  std::vector<Stretch> stretches;
  Kind start_end = Kind::kWall, end_end = Kind::kWall;
  std::vector<Feature> right, left;
};

Kind ReadEnd(const StrictYaml& y, const std::string& key) {
  const std::string v = y.GetOr<std::string>(key, "wall");
  if (v == "wall") return Kind::kWall;
  if (v == "opening") return Kind::kOpening;
  y.Fail(key, "a corridor end is 'wall' or 'opening', not '" + v + "'");
}

// The centreline as a turtle walk: straight runs, corners, arcs as chords.
void ReadCentreline(const StrictYaml& y, Corridor& c) {
  const StrictYaml start = y.Child("start");
  const std::vector<StrictYaml> xy = start.Sequence("xy_in");
  if (xy.size() != 2) start.Fail("xy_in", "expected [x, y] in inches");
  Vec at{xy[0].As<double>(), xy[1].As<double>()};
  double heading = DegToRad(start.Get<double>("heading_deg", -360.0, 360.0, "deg"));
  start.Finish();
  c.vertices.push_back(at);
  double station = 0.0;
  auto run = [&](double length, double dir_rad) {
    const Vec d = Heading(dir_rad);
    c.stretches.push_back({at, d, station, station + length});
    at = at + d * length;
    station += length;
    c.vertices.push_back(at);
  };
  for (const StrictYaml& item : y.Sequence("path")) {
    if (!item.IsMap() || item.Keys().size() != 1) {
      throw InputError(item.file(), item.line(), item.path(),
                       "each path item is one of straight_in, turn_deg, arc");
    }
    const std::string key = item.Keys().front();
    if (key == "straight_in") {
      run(item.Get<double>("straight_in", 1.0, 1e6, "in"), heading);
    } else if (key == "turn_deg") {
      heading += DegToRad(item.Get<double>("turn_deg", -170.0, 170.0, "deg"));
    } else if (key == "arc") {
      const StrictYaml arc = item.Child("arc");
      const double turn = DegToRad(arc.Get<double>("turn_deg", -180.0, 180.0, "deg"));
      const double radius = arc.Get<double>("radius_in", 1.0, 1e6, "in");
      const int chords = arc.Get<int>("chords", 1, 360);
      arc.Finish();
      const double step = turn / chords;
      for (int k = 0; k < chords; ++k) {
        run(2.0 * radius * std::sin(std::abs(step) / 2.0), heading + step / 2.0);
        heading += step;
      }
    } else {
      throw InputError(item.file(), item.line(), item.path() + "." + key,
                       "unknown path item (straight_in, turn_deg, arc)");
    }
  }
  if (c.stretches.empty()) y.Fail("path", "a corridor needs at least one straight run or arc");
}

// The points of one feature set into a side wall running along `dir` (outward normal `o`)
// from `start` to `end`: a door or an opening spans them; an alcove goes in by its depth,
// along its back wall (doors set in it) and out again; a pier the same the other way.
template <typename Push>
void EmitFeature(const Feature& f, const Vec& start, const Vec& end, const Vec& dir,
                 const Vec& o, double corridor_width_in, Push& push) {
  if (f.kind == Kind::kDoor || f.kind == Kind::kOpening) {
    push(start, f.kind, f.width_in);
    push(end, Kind::kWall, 0.0);
    return;
  }
  if (-f.depth_in >= corridor_width_in / 2.0) {
    f.where.Fail("pier", "a pier " + FormatNumber(-f.depth_in) +
                             " in deep reaches the corridor's centreline");
  }
  const Vec in = start + o * f.depth_in;
  push(start, Kind::kWall, 0.0);
  push(in, Kind::kWall, 0.0);
  for (const AlcoveDoor& d : f.doors) {
    push(in + dir * d.at_in, Kind::kDoor, d.width_in);
    push(in + dir * (d.at_in + d.width_in), Kind::kWall, 0.0);
  }
  push(in + dir * f.width_in, Kind::kWall, 0.0);
  push(end, Kind::kWall, 0.0);
}

// One side of the corridor in centreline order: `sign` +1 for the right side, -1 for the
// left. Points lie half the width off the centreline, mitred at its vertices; features are
// set in at their stations.
std::vector<SidePoint> BuildSide(const Corridor& c, int sign, const std::vector<Feature>& feats,
                                 const std::string& side_name) {
  const double h = c.width_in / 2.0;
  const int n = static_cast<int>(c.stretches.size());
  // The outward normal of stretch j: from the centreline toward this side's wall.
  auto normal = [&](int j) {
    const Vec d = c.stretches[j].dir;
    return sign > 0 ? Vec{d.y, -d.x} : Vec{-d.y, d.x};
  };
  // Side vertex i: the start of stretch i's wall (i = n: the end of the last).
  std::vector<Vec> vertex(n + 1);
  vertex[0] = c.stretches[0].a + normal(0) * h;
  vertex[n] = c.vertices.back() + normal(n - 1) * h;
  for (int i = 1; i < n; ++i) {
    const Stretch& a = c.stretches[i - 1];
    const Stretch& b = c.stretches[i];
    const Vec pa = a.a + normal(i - 1) * h, pb = b.a + normal(i) * h;
    const double denom = a.dir.Cross(b.dir);
    vertex[i] = std::abs(denom) < 1e-9 ? pb : pa + a.dir * ((pb - pa).Cross(b.dir) / denom);
  }
  std::vector<SidePoint> out;
  auto push = [&](Vec p, Kind next, double door) {
    if (!out.empty() && (out.back().p - p).Norm() < 1e-6) {
      out.back().next = next;
      out.back().door_width_in = door;
      return;
    }
    out.push_back({p, next, door});
  };
  // Features sorted by station, each on one stretch, none overlapping.
  std::vector<const Feature*> sorted;
  for (const Feature& f : feats) sorted.push_back(&f);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Feature* a, const Feature* b) { return a->at_in < b->at_in; });
  size_t next_feature = 0;
  double last_end = -1.0;
  for (int j = 0; j < n; ++j) {
    const Stretch& s = c.stretches[j];
    const Vec o = normal(j);
    push(vertex[j], Kind::kWall, 0.0);
    // Where this stretch's wall starts and ends, as centreline stations abreast.
    const double wall_s0 = s.s0 + (vertex[j] - (s.a + o * h)).Dot(s.dir);
    const double wall_s1 = s.s0 + (vertex[j + 1] - (s.a + o * h)).Dot(s.dir);
    auto abreast = [&](double station) { return s.a + s.dir * (station - s.s0) + o * h; };
    while (next_feature < sorted.size() && sorted[next_feature]->at_in < s.s1 - 1e-9) {
      const Feature& f = *sorted[next_feature++];
      const double a = f.at_in, b = f.at_in + f.width_in;
      if (a < last_end - 1e-9) {
        f.where.Fail("at_in", "overlaps the feature before it on the " + side_name + " side");
      }
      if (a < wall_s0 - 1e-6 || b > wall_s1 + 1e-6) {
        f.where.Fail("at_in", "stations " + FormatNumber(a) + " to " + FormatNumber(b) +
                                  " do not lie on one straight stretch of the " + side_name +
                                  " wall (this stretch's wall runs from station " +
                                  FormatNumber(wall_s0) + " to " + FormatNumber(wall_s1) + ")");
      }
      last_end = b;
      EmitFeature(f, abreast(a), abreast(b), s.dir, o, c.width_in, push);
    }
  }
  if (next_feature < sorted.size()) {
    sorted[next_feature]->where.Fail("at_in", "lies beyond the corridor's end (station " +
                                                  FormatNumber(c.stretches.back().s1) + ")");
  }
  push(vertex[n], Kind::kWall, 0.0);
  return out;
}

Edge MakeEdge(Kind kind, double length_in, double door_width_in) {
  switch (kind) {
    case Kind::kDoor: {
      Edge e = Edge::Door(*NearestDoorClass(door_width_in));
      e.metric_in = length_in;
      return e;
    }
    case Kind::kOpening: {
      Edge e = Edge::Wall(length_in);
      e.type = EdgeType::kOpening;
      return e;
    }
    case Kind::kWall:
      break;
  }
  return Edge::Wall(length_in);
}

// The closed outline: the right side from the start, across the far end, the left side
// back, across the near end. Free space lies on the left of this order.
Ring BuildRing(const Corridor& c) {
  std::vector<SidePoint> right = BuildSide(c, +1, c.right, "right");
  std::vector<SidePoint> left = BuildSide(c, -1, c.left, "left");
  std::vector<SidePoint> loop = right;
  loop.back().next = c.end_end;
  // The left side reversed: the edge from point i+1 back to point i keeps point i's kind.
  for (int i = static_cast<int>(left.size()) - 1; i >= 0; --i) {
    SidePoint p = left[i];
    if (i > 0) {
      p.next = left[i - 1].next;
      p.door_width_in = left[i - 1].door_width_in;
    } else {
      p.next = c.start_end;
    }
    loop.push_back(p);
  }
  Ring ring;
  ring.id = c.id;
  ring.closed = true;
  ring.outline = Outline::kCorridor;
  ring.width_in = c.width_in;
  const int n = static_cast<int>(loop.size());
  for (int i = 0; i < n; ++i) {
    const Vec a = loop[i].p, b = loop[(i + 1) % n].p;
    const Vec before = a - loop[(i + n - 1) % n].p;
    const double turn = std::atan2(before.Cross(b - a), before.Dot(b - a));
    Node node;
    node.angle_deg = 180.0 + RadToDeg(turn);
    node.x_in = a.x;
    node.y_in = a.y;
    node.gamma_deg = RadToDeg(std::atan2(b.y - a.y, b.x - a.x));
    ring.nodes.push_back(node);
    ring.edges.push_back(MakeEdge(loop[i].next, (b - a).Norm(), loop[i].door_width_in));
  }
  return ring;
}

Corridor ReadCorridor(const StrictYaml& y) {
  Corridor c;
  c.id = y.Get<std::string>("id");
  c.width_in = y.Get<double>("width_in", 24.0, 2400.0, "in");
  ReadCentreline(y, c);
  if (y.Has("ends")) {
    const StrictYaml ends = y.Child("ends");
    c.start_end = ReadEnd(ends, "start");
    c.end_end = ReadEnd(ends, "end");
    ends.Finish();
  }
  for (const char* side : {"right", "left"}) {
    if (!y.Has(side)) continue;
    for (const StrictYaml& f : y.Sequence(side)) {
      (std::string(side) == "right" ? c.right : c.left).push_back(ReadFeature(f));
    }
  }
  y.Finish();
  return c;
}

Obstacle ReadObstacle(const StrictYaml& y) {
  Obstacle o;
  o.id = y.Get<std::string>("id");
  if (y.Has("circle")) {
    const StrictYaml c = y.Child("circle");
    const std::vector<StrictYaml> xy = c.Sequence("centre_in");
    if (xy.size() != 2) c.Fail("centre_in", "expected [x, y] in inches");
    const double cx = xy[0].As<double>(), cy = xy[1].As<double>();
    const double r = c.Get<double>("diameter_in", 1.0, 1e4, "in") / 2.0;
    const int sides = c.Get<int>("sides", 3, 360);
    c.Finish();
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * kPi * k / sides;
      o.polygon_in.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
  } else {
    for (const StrictYaml& p : y.Sequence("polygon_in")) {
      const std::vector<StrictYaml> xy = p.Elements();
      if (xy.size() != 2) throw InputError(p.file(), p.line(), p.path(), "expected [x, y]");
      o.polygon_in.push_back({xy[0].As<double>(), xy[1].As<double>()});
    }
    if (o.polygon_in.size() < 3) y.Fail("polygon_in", "a polygon needs at least 3 corners");
  }
  y.Finish();
  return o;
}

}  // namespace

Map ParseFloorPlan(const std::string& text, const std::string& name) {
  const StrictYaml root = StrictYaml::LoadString(text, name);
  const int version = root.Get<int>("stickrep_floor");
  if (version != 1) root.Fail("stickrep_floor", "unsupported floor plan version (this build reads 1)");
  MapInfo info;
  info.name = root.Get<std::string>("name");
  info.description = root.GetOr<std::string>("description", "");
  info.generator = "stickrep-map floor " + std::filesystem::path(name).filename().string();
  std::vector<Ring> rings;
  for (const StrictYaml& cy : root.Sequence("corridors")) rings.push_back(BuildRing(ReadCorridor(cy)));
  std::vector<Obstacle> obstacles;
  if (root.Has("obstacles")) {
    for (const StrictYaml& oy : root.Sequence("obstacles")) obstacles.push_back(ReadObstacle(oy));
  }
  root.Finish();
  // The map's own checks (ids, names, geometry against metrics) with the source's name.
  try {
    const Map map(info, std::move(rings), {}, std::move(obstacles));
    return ParseMap(WriteMapYaml(map), name + " (as a map)");
  } catch (const std::invalid_argument& e) {
    throw InputError(name, 0, "", e.what());
  }
}

Map LoadFloorPlan(const std::string& path) { return ParseFloorPlan(ReadYamlText(path), path); }

}  // namespace stickrep::map
