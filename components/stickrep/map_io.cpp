#include "stickrep/map_io.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/strict_yaml.h"

namespace stickrep::map {

namespace {

// Ring ids, names and patterns are single words so that they read well in messages and
// reports and never need quoting.
bool IsIdentifier(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

std::string DoorClassList() { return "30, 32, 36, 40, 30/30, 36/36"; }

// Three numbers under `key` (a YAML sequence), e.g. xyz_in: [x, y, z].
void ReadTriple(const StrictYaml& y, const std::string& key, double out[3]) {
  const std::vector<StrictYaml> items = y.Sequence(key);
  if (items.size() != 3) {
    y.Fail(key, "expected a list of 3 numbers, got " + std::to_string(items.size()));
  }
  for (int i = 0; i < 3; ++i) {
    out[i] = items[i].As<double>();
    if (std::abs(out[i]) > 1e7) y.Fail(key, "coordinate out of range (|value| > 1e7)");
  }
}

struct LoadedEdge {
  Edge edge;
  int line = 0;
};

Node ReadNode(const StrictYaml& y) {
  Node n;
  n.angle_deg = y.Get<double>("angle_deg", 0.0, 360.0, "deg");
  double xyz[3];
  ReadTriple(y, "xyz_in", xyz);
  n.x_in = xyz[0];
  n.y_in = xyz[1];
  n.z_in = xyz[2];
  if (y.Has("abg_deg")) {
    double abg[3];
    ReadTriple(y, "abg_deg", abg);
    for (int i = 0; i < 3; ++i) {
      if (abg[i] < -360.0 || abg[i] > 360.0) y.Fail("abg_deg", "angles must lie in [-360, 360]");
    }
    n.alpha_deg = abg[0];
    n.beta_deg = abg[1];
    n.gamma_deg = abg[2];
  } else {
    y.GetOr<std::string>("abg_deg", "");
  }
  n.artificial = y.GetOr<bool>("artificial", false);
  y.Finish();
  return n;
}

// A version 2 doorway: its measured opening `width_in`, the class derived from it (or
// given, and then within the tolerance of the width).
void ReadMeasuredDoor(const StrictYaml& y, Edge& e) {
  const double width = y.Get<double>("width_in", 1.0, 1000.0, "in");
  if (y.Has("metric_in")) y.Fail("metric_in", "a doorway with width_in takes no metric_in");
  std::optional<DoorClass> door_class;
  if (y.Has("class")) {
    const std::string cls = y.Get<std::string>("class");
    door_class = ParseDoorClass(cls);
    if (!door_class) {
      y.Fail("class",
             "door class '" + cls + "' is not a legal door width (" + DoorClassList() + " in)");
    }
    if (std::abs(DoorClassWidthIn(*door_class) - width) > kDoorClassToleranceIn) {
      y.Fail("width_in", "a door of class " + cls + " cannot be " + FormatNumber(width) +
                             " in wide (tolerance " + FormatNumber(kDoorClassToleranceIn) +
                             " in)");
    }
  } else {
    door_class = NearestDoorClass(width);
    if (!door_class) {
      y.Fail("width_in", "no door class lies within " + FormatNumber(kDoorClassToleranceIn) +
                             " in of " + FormatNumber(width) + " in (" + DoorClassList() +
                             "); a wider gap is an 'opening' edge");
    }
  }
  e.door_class = door_class;
  e.metric_in = width;
}

Edge ReadEdge(const StrictYaml& y, int version) {
  Edge e;
  const std::string type_name = y.Get<std::string>("type");
  const auto type = ParseEdgeType(type_name);
  if (!type) {
    y.Fail("type", "unknown edge type '" + type_name +
                       "' (corner, doorway, elevator, hallway, opening, pattern, stairwell)");
  }
  e.type = *type;
  if (e.IsOpening() && version < 2) {
    y.Fail("type", "'opening' edges need map format 2 (stickrep_map: 2)");
  }
  if (e.IsDoor() && y.Has("width_in")) {
    if (version < 2) y.Fail("width_in", "measured door widths need map format 2");
    ReadMeasuredDoor(y, e);
  } else if (e.IsDoor()) {
    const std::string cls = y.Get<std::string>("class");
    const auto door_class = ParseDoorClass(cls);
    if (!door_class) {
      y.Fail("class",
             "door class '" + cls + "' is not a legal door width (" + DoorClassList() + " in)");
    }
    e.door_class = *door_class;
    e.metric_in = DoorClassWidthIn(*door_class);
    if (y.Has("metric_in")) {
      const double m = y.Get<double>("metric_in");
      if (std::abs(m - e.metric_in) > 0.5) {
        y.Fail("metric_in", "a door of class " + cls + " is " + FormatNumber(e.metric_in) +
                                " in wide, not " + FormatNumber(m));
      }
    }
  } else {
    if (y.Has("class")) y.Fail("class", "only doorway edges have a door class");
    e.metric_in = y.Get<double>("metric_in");
    if (!(e.metric_in > 0.0)) {
      y.Fail("metric_in", "metric must be > 0 in, got " + FormatNumber(e.metric_in));
    }
    if (e.metric_in > 1e6) y.Fail("metric_in", "metric above 1e6 in: not a building edge");
  }
  e.prototype = DefaultPrototype(e.type);
  if (y.Has("prototype")) {
    const std::string p = y.Get<std::string>("prototype");
    const auto prototype = ParsePrototype(p);
    if (!prototype) {
      y.Fail("prototype", "unknown prototype '" + p + "' (doorjam, wallsegment, pattern)");
    }
    if ((e.type == EdgeType::kDoorway && *prototype != Prototype::kDoorjam) ||
        (e.type == EdgeType::kHallway && *prototype != Prototype::kWallsegment)) {
      y.Fail("prototype",
             std::string("a ") + EdgeTypeName(e.type) + " edge cannot have prototype " + p);
    }
    e.prototype = *prototype;
  }
  if (y.Has("pattern")) {
    e.pattern = y.Get<std::string>("pattern");
    if (!IsIdentifier(e.pattern)) {
      y.Fail("pattern", "a pattern is one word of letters, digits, '_', '-' or '.'");
    }
  }
  y.Finish();
  return e;
}

double Distance(const Node& a, const Node& b) {
  return std::sqrt((a.x_in - b.x_in) * (a.x_in - b.x_in) + (a.y_in - b.y_in) * (a.y_in - b.y_in) +
                   (a.z_in - b.z_in) * (a.z_in - b.z_in));
}

Ring ReadRing(const StrictYaml& y, int version, std::vector<int>* node_lines) {
  Ring ring;
  ring.id = y.Get<std::string>("id");
  if (!IsIdentifier(ring.id)) {
    y.Fail("id", "a ring id is one word of letters, digits, '_', '-' or '.' (at most 64)");
  }
  ring.closed = y.Get<bool>("closed");
  for (const char* key : {"outline", "width_in"}) {
    if (version < 2 && y.Has(key)) y.Fail(key, "needs map format 2 (stickrep_map: 2)");
  }
  if (y.Has("outline")) {
    const std::string outline = y.Get<std::string>("outline");
    if (outline == "corridor") {
      ring.outline = Outline::kCorridor;
      if (!ring.closed) y.Fail("outline", "a corridor outline is a closed ring");
    } else if (outline != "side") {
      y.Fail("outline", "unknown outline '" + outline + "' (side, corridor)");
    }
  }
  if (y.Has("width_in")) ring.width_in = y.Get<double>("width_in", 24.0, 2400.0, "in");
  const StrictYaml path = y.Child("path");
  const std::vector<StrictYaml> items = path.Elements();
  std::vector<int> edge_lines;
  bool expect_node = true;
  for (const StrictYaml& item : items) {
    if (!item.IsMap() || item.Keys().size() != 1) {
      throw InputError(item.file(), item.line(), item.path(),
                       "each path item is a mapping with one key, 'node' or 'edge'");
    }
    const std::string kind = item.Keys().front();
    if (kind != "node" && kind != "edge") {
      throw InputError(item.file(), item.line(), item.path() + "." + kind,
                       "unknown key (a path item is 'node' or 'edge')");
    }
    if ((kind == "node") != expect_node) {
      throw InputError(item.file(), item.line(), item.path(),
                       std::string("expected a ") + (expect_node ? "node" : "edge") +
                           ": nodes and edges alternate, starting with a node");
    }
    const StrictYaml body = item.Child(kind);
    if (kind == "node") {
      ring.nodes.push_back(ReadNode(body));
      node_lines->push_back(body.line());
    } else {
      ring.edges.push_back(ReadEdge(body, version));
      edge_lines.push_back(body.line());
    }
    expect_node = !expect_node;
  }
  if (ring.edges.empty()) path.Fail("", "a ring needs at least one edge");
  if (ring.closed && expect_node == false) {
    path.Fail("",
              "a closed ring ends with an edge (node 0 closes it); this one ends with a node."
              " Set closed: false for an open ring");
  }
  if (!ring.closed && expect_node == true) {
    path.Fail("", "an open ring ends with a node (its far end); this one ends with an edge");
  }
  // The coordinates must agree with the metrics; for a closed ring this also checks that the
  // last edge really returns to node 0.
  for (int i = 0; i < ring.EdgeCount(); ++i) {
    const Node& a = ring.nodes[i];
    const Node& b = ring.nodes[(i + 1) % ring.NodeCount()];
    const double d = Distance(a, b);
    const double m = ring.edges[i].metric_in;
    if (std::abs(d - m) > std::max(kGeometryToleranceIn, kGeometryToleranceRel * m)) {
      std::string reason = "edge " + std::to_string(i) + " is " + FormatNumber(m) +
                           " in but its nodes are " + FormatNumber(d) + " in apart";
      if (ring.closed && i + 1 == ring.EdgeCount()) {
        reason += " (the ring does not close; set closed: false if it is open)";
      }
      throw InputError(y.file(), edge_lines[i], y.path() + ".path", reason);
    }
  }
  y.Finish();
  return ring;
}

// The version 2 `obstacles:` list, if any.
std::vector<Obstacle> ReadObstacles(const StrictYaml& root, int version) {
  std::vector<Obstacle> obstacles;
  if (!root.Has("obstacles")) return obstacles;
  if (version < 2) root.Fail("obstacles", "needs map format 2 (stickrep_map: 2)");
  std::set<std::string> ids;
  for (const StrictYaml& oy : root.Sequence("obstacles")) {
    Obstacle o;
    o.id = oy.Get<std::string>("id");
    if (!IsIdentifier(o.id)) oy.Fail("id", "an obstacle id is one word (letters, digits, _-.)");
    if (!ids.insert(o.id).second) oy.Fail("id", "obstacle id '" + o.id + "' is used twice");
    const std::vector<StrictYaml> corners = oy.Sequence("polygon_in");
    if (corners.size() < 3) oy.Fail("polygon_in", "a polygon needs at least 3 corners");
    for (const StrictYaml& c : corners) {
      const std::vector<StrictYaml> xy = c.Elements();
      if (xy.size() != 2) {
        throw InputError(c.file(), c.line(), c.path(), "a corner is [x, y] in inches");
      }
      const double x = xy[0].As<double>(), y = xy[1].As<double>();
      if (std::abs(x) > 1e7 || std::abs(y) > 1e7) {
        throw InputError(c.file(), c.line(), c.path(), "coordinate out of range (|value| > 1e7)");
      }
      o.polygon_in.push_back({x, y});
    }
    oy.Finish();
    obstacles.push_back(std::move(o));
  }
  return obstacles;
}

}  // namespace

Map ParseMap(const std::string& text, const std::string& name) {
  const StrictYaml root = StrictYaml::LoadString(text, name);
  const int version = root.Get<int>("stickrep_map");
  if (version < 1 || version > kMapFormatVersion) {
    root.Fail("stickrep_map", "unsupported map format version " + std::to_string(version) +
                                  " (this build reads 1 to " +
                                  std::to_string(kMapFormatVersion) + ")");
  }
  MapInfo info;
  info.name = root.Get<std::string>("name");
  if (!IsIdentifier(info.name)) root.Fail("name", "a map name is one word (letters, digits, _-.)");
  info.description = root.GetOr<std::string>("description", "");
  if (root.Has("generator")) {
    const StrictYaml g = root.Child("generator");
    info.generator = g.Get<std::string>("program");
    if (g.Has("seed")) info.seed = g.Get<std::uint64_t>("seed");  // generators that draw
    g.Finish();
  } else {
    root.GetOr<std::string>("generator", "");
  }

  std::vector<Ring> rings;
  std::map<std::string, int> ring_index;
  std::vector<std::vector<int>> node_lines;
  for (const StrictYaml& ry : root.Sequence("rings")) {
    node_lines.emplace_back();
    Ring ring = ReadRing(ry, version, &node_lines.back());
    if (!ring_index.emplace(ring.id, static_cast<int>(rings.size())).second) {
      ry.Fail("id", "ring id '" + ring.id + "' is used by an earlier ring");
    }
    rings.push_back(std::move(ring));
  }
  if (rings.empty()) root.Fail("rings", "a map needs at least one ring");

  std::vector<Join> joins;
  if (root.Has("joins")) {
    for (const StrictYaml& jy : root.Sequence("joins")) {
      Join j;
      j.ring = jy.Get<std::string>("ring");
      j.to_ring = jy.Get<std::string>("to_ring");
      const auto a = ring_index.find(j.ring);
      if (a == ring_index.end()) jy.Fail("ring", "no ring with id '" + j.ring + "'");
      const auto b = ring_index.find(j.to_ring);
      if (b == ring_index.end()) jy.Fail("to_ring", "no ring with id '" + j.to_ring + "'");
      if (a->second == b->second) jy.Fail("to_ring", "a ring cannot be joined to itself");
      const Ring& ra = rings[a->second];
      const Ring& rb = rings[b->second];
      j.node = jy.Get<int>("node", 0, ra.NodeCount() - 1, "(node index)");
      j.to_node = jy.Get<int>("to_node", 0, rb.NodeCount() - 1, "(node index)");
      if (!ra.nodes[j.node].artificial) {
        jy.Fail("node", "node " + std::to_string(j.node) + " of ring '" + j.ring +
                            "' is not artificial; rings are joined at artificial nodes (line " +
                            std::to_string(node_lines[a->second][j.node]) + ")");
      }
      jy.Finish();
      joins.push_back(j);
    }
  } else {
    root.GetOr<std::string>("joins", "");
  }
  std::vector<Obstacle> obstacles = ReadObstacles(root, version);
  root.Finish();
  try {
    return Map(std::move(info), std::move(rings), std::move(joins), std::move(obstacles));
  } catch (const std::invalid_argument& e) {
    // The checks above should have caught everything with a line number already.
    throw InputError(name, 0, "", e.what());
  }
}

Map LoadMap(const std::string& path) {
  // Size and type are checked before reading so that a huge file of garbage is refused
  // without loading it; NUL bytes and YAML syntax are checked by StrictYaml::LoadString.
  return ParseMap(ReadYamlText(path), path);
}

std::string FormatNumber(double value) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.3f", value);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

bool NeedsFormat2(const Map& map) {
  if (!map.obstacles().empty()) return true;
  for (const Ring& ring : map.rings()) {
    if (ring.outline != Outline::kSide || ring.width_in) return true;
    for (const Edge& e : ring.edges) {
      if (e.IsOpening()) return true;
      if (e.IsDoor() && std::abs(e.metric_in - DoorClassWidthIn(*e.door_class)) > 1e-9) {
        return true;
      }
    }
  }
  return false;
}

std::string WriteMapYaml(const Map& map) {
  const MapInfo& info = map.info();
  std::ostringstream out;
  out << "# StickRep map (format: maps/README.md). Lengths in inches, angles in degrees.\n";
  if (!info.generator.empty()) {
    out << (info.seed ? "# Generated; edit the generator, not this file, and regenerate with the seed below.\n"
                      : "# Generated from a source; edit the source, not this file, and regenerate.\n");
  }
  out << "stickrep_map: " << (NeedsFormat2(map) ? 2 : 1) << "\n";
  out << "name: " << info.name << "\n";
  if (!info.description.empty()) out << "description: " << YamlQuoted(info.description) << "\n";
  if (!info.generator.empty()) {
    out << "generator:\n  program: " << YamlQuoted(info.generator) << "\n";
    if (info.seed) out << "  seed: " << *info.seed << "\n";
  }
  out << "rings:\n";
  for (const Ring& ring : map.rings()) {
    out << "  - id: " << ring.id << "\n";
    out << "    closed: " << (ring.closed ? "true" : "false") << "\n";
    if (ring.outline != Outline::kSide) out << "    outline: " << OutlineName(ring.outline) << "\n";
    if (ring.width_in) out << "    width_in: " << FormatNumber(*ring.width_in) << "\n";
    out << "    path:\n";
    for (int i = 0; i < ring.NodeCount(); ++i) {
      const Node& n = ring.nodes[i];
      out << "      - node: {angle_deg: " << FormatNumber(n.angle_deg) << ", xyz_in: ["
          << FormatNumber(n.x_in) << ", " << FormatNumber(n.y_in) << ", " << FormatNumber(n.z_in)
          << "]";
      if (n.alpha_deg != 0.0 || n.beta_deg != 0.0 || n.gamma_deg != 0.0) {
        out << ", abg_deg: [" << FormatNumber(n.alpha_deg) << ", " << FormatNumber(n.beta_deg)
            << ", " << FormatNumber(n.gamma_deg) << "]";
      }
      if (n.artificial) out << ", artificial: true";
      out << "}\n";
      if (i >= ring.EdgeCount()) break;
      const Edge& e = ring.edges[i];
      out << "      - edge: {type: " << EdgeTypeName(e.type);
      if (e.IsDoor()) {
        out << ", class: " << YamlQuoted(DoorClassName(*e.door_class));
        if (std::abs(e.metric_in - DoorClassWidthIn(*e.door_class)) > 1e-9) {
          out << ", width_in: " << FormatNumber(e.metric_in);
        }
      } else {
        out << ", metric_in: " << FormatNumber(e.metric_in);
      }
      if (e.prototype != DefaultPrototype(e.type))
        out << ", prototype: " << PrototypeName(e.prototype);
      if (!e.pattern.empty()) out << ", pattern: " << e.pattern;
      out << "}\n";
    }
  }
  if (!map.obstacles().empty()) {
    out << "obstacles:\n";
    for (const Obstacle& o : map.obstacles()) {
      out << "  - id: " << o.id << "\n    polygon_in: [";
      for (size_t i = 0; i < o.polygon_in.size(); ++i) {
        out << (i ? ", " : "") << "[" << FormatNumber(o.polygon_in[i][0]) << ", "
            << FormatNumber(o.polygon_in[i][1]) << "]";
      }
      out << "]\n";
    }
  }
  if (!map.joins().empty()) {
    out << "joins:\n";
    for (const Join& j : map.joins()) {
      out << "  - {ring: " << j.ring << ", node: " << j.node << ", to_ring: " << j.to_ring
          << ", to_node: " << j.to_node << "}\n";
    }
  }
  return out.str();
}

void SaveMap(const Map& map, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << WriteMapYaml(map);
  if (!out) throw std::runtime_error("error writing " + path);
}

}  // namespace stickrep::map
