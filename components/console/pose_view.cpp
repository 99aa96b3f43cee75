#include "console/pose_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "plot/map_render.h"

namespace stickrep::console {

namespace {

constexpr double kDegPerRad = 180.0 / M_PI;
// tan(22.5 deg): a wall within 22.5 deg of a grid axis (in cells) is drawn along it.
constexpr double kTan22_5 = 0.41421356;

bool SamePlace(const PoseMark& a, const PoseMark& b) {
  return a.ring_id == b.ring_id && a.edge == b.edge && a.forward == b.forward;
}

// The character of an edge running (dx, dy) cells (dy up the map).
char EdgeChar(const map::Edge& e, double dx, double dy) {
  switch (e.type) {
    case map::EdgeType::kDoorway:
      return '+';
    case map::EdgeType::kElevator:
      return 'E';
    case map::EdgeType::kStairwell:
      return 'S';
    case map::EdgeType::kHallway:
      break;
    default:
      return '.';
  }
  if (std::abs(dy) <= kTan22_5 * std::abs(dx)) return '-';
  if (std::abs(dx) <= kTan22_5 * std::abs(dy)) return '|';
  return (dx > 0) == (dy > 0) ? '/' : '\\';
}

// Marks with `c` every cell the segment from a to b crosses (sampled at under half a cell).
void DrawSegment(CharGrid& grid, const map::Node& a, const map::Node& b, char c) {
  const double dx = (b.x_in - a.x_in) / grid.cell_in;
  const double dy = (b.y_in - a.y_in) / (2.0 * grid.cell_in);
  const int steps = static_cast<int>(std::ceil(2.0 * std::max(std::abs(dx), std::abs(dy)))) + 1;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const auto cell = grid.CellOf(a.x_in + t * (b.x_in - a.x_in), a.y_in + t * (b.y_in - a.y_in));
    if (grid.Contains(cell)) grid.rows[cell.first][cell.second] = c;
  }
}

// Walls first, then the other edges, then doors, so that a door is never hidden by the
// walls on either side of it.
void DrawMap(CharGrid& grid, const map::Map& map) {
  for (int pass = 0; pass < 3; ++pass) {
    for (const map::Ring& ring : map.rings()) {
      for (int i = 0; i < ring.EdgeCount(); ++i) {
        const map::Edge& e = ring.edges[i];
        if ((pass == 0) != e.IsWall() || (pass == 2) != e.IsDoor()) continue;
        const map::Node& a = ring.nodes[i];
        const map::Node& b = ring.nodes[(i + 1) % ring.NodeCount()];
        DrawSegment(grid, a, b,
                    EdgeChar(e, (b.x_in - a.x_in) / grid.cell_in,
                             (b.y_in - a.y_in) / (2.0 * grid.cell_in)));
      }
    }
  }
}

void Put(CharGrid& grid, double x_in, double y_in, char c) {
  const auto cell = grid.CellOf(x_in, y_in);
  if (grid.Contains(cell)) grid.rows[cell.first][cell.second] = c;
}

nlohmann::json MarkJson(const PoseMark& m) {
  return {{"ring", m.ring_id},
          {"edge", m.edge},
          {"forward", m.forward},
          {"offset_in", m.offset_in},
          {"x_in", m.x_in},
          {"y_in", m.y_in},
          {"heading_rad", m.heading_rad},
          {"probability", m.probability}};
}

}  // namespace

std::vector<PoseMark> OtherHypotheses(const PoseFrame& frame) {
  std::vector<PoseMark> others;
  for (const PoseMark& h : frame.hypotheses) {
    if (!frame.best || !SamePlace(h, *frame.best)) others.push_back(h);
  }
  return others;
}

char HeadingArrow(double heading_rad) {
  const double deg = std::fmod(std::fmod(heading_rad * kDegPerRad, 360.0) + 360.0, 360.0);
  static constexpr char kArrows[] = {'>', '^', '<', 'v'};
  return kArrows[static_cast<int>(std::floor((deg + 45.0) / 90.0)) % 4];
}

std::pair<int, int> CharGrid::CellOf(double x_in, double y_in) const {
  return {static_cast<int>(std::lround((max_y_in - y_in) / (2.0 * cell_in))),
          static_cast<int>(std::lround((x_in - min_x_in) / cell_in))};
}

bool CharGrid::Contains(std::pair<int, int> cell) const {
  return cell.first >= 0 && cell.first < static_cast<int>(rows.size()) && cell.second >= 0 &&
         cell.second < cols();
}

CharGrid DrawPoseGrid(const map::Map& map, const PoseFrame& frame, int cols) {
  cols = std::max(cols, 2);
  double min_x = std::numeric_limits<double>::max(), min_y = min_x;
  double max_x = std::numeric_limits<double>::lowest(), max_y = max_x;
  for (const map::Ring& ring : map.rings()) {
    for (const map::Node& n : ring.nodes) {
      min_x = std::min(min_x, n.x_in);
      max_x = std::max(max_x, n.x_in);
      min_y = std::min(min_y, n.y_in);
      max_y = std::max(max_y, n.y_in);
    }
  }
  CharGrid grid;
  grid.min_x_in = min_x;
  grid.max_y_in = max_y;
  grid.cell_in = std::max(1.0, max_x - min_x) / (cols - 1);
  const int rows = static_cast<int>(std::lround((max_y - min_y) / (2.0 * grid.cell_in))) + 1;
  grid.rows.assign(rows, std::string(cols, ' '));
  DrawMap(grid, map);
  const std::vector<PoseMark> others = OtherHypotheses(frame);
  // The lowest rank drawn last, on top of the ranks below it.
  for (int k = std::min<int>(others.size(), kMaxDrawnHypotheses); k >= 1; --k) {
    Put(grid, others[k - 1].x_in, others[k - 1].y_in, static_cast<char>('0' + k));
  }
  if (frame.best) {
    Put(grid, frame.best->x_in, frame.best->y_in, HeadingArrow(frame.best->heading_rad));
  }
  return grid;
}

std::string PoseHeader(const PoseFrame& f) {
  std::string best = "best -";
  if (f.best) {
    const PoseMark& b = *f.best;
    best = fmt::format("best {}/{} {} {:+.1f} in (x {:.1f}, y {:.1f} in, heading {:.0f} deg)",
                       b.ring_id, b.edge, b.forward ? "forward" : "reverse", b.offset_in, b.x_in,
                       b.y_in, b.heading_rad * kDegPerRad);
  }
  return fmt::format("{}  confidence {:.2f}  candidates {}  edges sensed {}  {}  pose age {:.1f} s",
                     f.status, f.confidence, f.candidates, f.edges_sensed, best, f.age_s);
}

std::string RenderPoseText(const map::Map& map, const PoseFrame& frame, int cols) {
  const CharGrid grid = DrawPoseGrid(map, frame, cols);
  std::string text = PoseHeader(frame) + "\n";
  for (const std::string& row : grid.rows) {
    const auto end = row.find_last_not_of(' ');
    text += (end == std::string::npos ? std::string() : row.substr(0, end + 1)) + "\n";
  }
  text += fmt::format(
      "{} best pose  1-{} other hypotheses by rank  + door  - | / \\ wall  "
      ". other edge  1 column = {:.0f} in, 1 row = {:.0f} in\n",
      frame.best ? HeadingArrow(frame.best->heading_rad) : '>', kMaxDrawnHypotheses, grid.cell_in,
      2.0 * grid.cell_in);
  return text;
}

nlohmann::json PoseJson(const PoseFrame& f) {
  nlohmann::json hypotheses = nlohmann::json::array();
  for (const PoseMark& h : f.hypotheses) hypotheses.push_back(MarkJson(h));
  return {{"status", f.status},
          {"confidence", f.confidence},
          {"candidates", f.candidates},
          {"edges_sensed", f.edges_sensed},
          {"age_s", f.age_s},
          {"message", f.message},
          {"best", f.best ? MarkJson(*f.best) : nlohmann::json(nullptr)},
          {"hypotheses", hypotheses}};
}

void WritePosePng(const map::Map& map, const PoseFrame& frame, const std::string& path) {
  map::RenderOptions options;
  const std::vector<PoseMark> others = OtherHypotheses(frame);
  // The lowest rank drawn last, on top; the best over all of them.
  for (int k = std::min<int>(others.size(), kMaxDrawnHypotheses); k >= 1; --k) {
    const PoseMark& h = others[k - 1];
    options.poses.push_back(
        {h.x_in, h.y_in, h.heading_rad, fmt::format("{} p {:.2f}", k, h.probability)});
  }
  if (frame.best) {
    const PoseMark& b = *frame.best;
    options.poses.push_back(
        {b.x_in, b.y_in, b.heading_rad, fmt::format("{} p {:.2f}", frame.status, b.probability)});
  }
  map::RenderMapPng(map, path, options);
}

}  // namespace stickrep::console
