#include "map_tool/census_report.h"

#include <fmt/format.h>

#include <cstdlib>

#include "stickrep/paper_reference.h"

namespace stickrep::map {

namespace {

constexpr const char* kRowNames[5] = {"door30", "door32", "door36", "door40", "wall"};

std::string Cell(int ours, int paper, bool compare) {
  return compare ? fmt::format("{} ({})", ours, paper) : fmt::format("{}", ours);
}

// Accumulates one table's deviation cell by cell.
struct Tally {
  TableDeviation d;
  void Add(int ours, int paper) {
    ++d.cells;
    d.cells_differing += ours != paper ? 1 : 0;
    d.abs_sum += std::abs(ours - paper);
    d.ours_total += ours;
    d.paper_total += paper;
  }
};

template <std::size_t R, std::size_t C>
TableDeviation Compare(const std::string& name, const std::array<std::array<int, C>, R>& ours,
                       const std::array<std::array<int, C>, R>& paper) {
  Tally t;
  t.d.table = name;
  for (std::size_t i = 0; i < R; ++i) {
    for (std::size_t j = 0; j < C; ++j) t.Add(ours[i][j], paper[i][j]);
  }
  return t.d;
}

template <std::size_t N>
TableDeviation Compare(const std::string& name, const std::array<int, N>& ours,
                       const std::array<int, N>& paper) {
  Tally t;
  t.d.table = name;
  for (std::size_t i = 0; i < N; ++i) t.Add(ours[i], paper[i]);
  return t.d;
}

template <std::size_t R, std::size_t C>
void Matrix(std::string& out, const std::string& title, const std::string& corner,
            const std::array<std::array<int, C>, R>& ours,
            const std::array<std::array<int, C>, R>& paper, bool compare) {
  const int w = compare ? 11 : 7;
  out += title + "\n";
  out += fmt::format("  {:<8}", corner);
  for (std::size_t j = 0; j < C; ++j) out += fmt::format("{:>{}}", kRowNames[j], w);
  out += "\n";
  for (std::size_t i = 0; i < R; ++i) {
    out += fmt::format("  {:<8}", kRowNames[i]);
    for (std::size_t j = 0; j < C; ++j) {
      out += fmt::format("{:>{}}", Cell(ours[i][j], paper[i][j], compare), w);
    }
    out += "\n";
  }
  out += "\n";
}

}  // namespace

std::vector<TableDeviation> CompareWithPaper(const Census& c) {
  std::vector<TableDeviation> out;
  out.push_back(Compare("Table 6.1", c.pairs[0], paper::kPairs[0]));
  out.push_back(Compare("Table 6.2", c.pairs[1], paper::kPairs[1]));
  out.push_back(Compare("Table 6.3", c.pairs[2], paper::kPairs[2]));
  out.push_back(Compare("Table 6.4", c.door_wall_door, paper::kDoorWallDoor));
  out.push_back(Compare("Table 6.5", c.wall_door_wall, paper::kWallDoorWall));
  out.push_back(Compare("Table 6.6", c.door_wall_door_wall, paper::kDoorWallDoorWall));
  out.push_back(Compare("Table 6.7", c.wall_door_wall_door, paper::kWallDoorWallDoor));
  out.push_back(Compare("Table 6.8", c.door_census, paper::kDoorCensus));
  out.push_back(Compare("Table 6.9", c.wall_census, paper::kWallCensus));
  return out;
}

std::string FormatCensusText(const Map& map, const Census& c, bool compare) {
  std::string out;
  out += fmt::format("Census of {} ({})\n", map.info().name,
                     compare ? "ours (paper), paper = the Engineering Building, Tables 6.1-6.9"
                             : "Tables 6.1-6.9 layout");
  out += fmt::format(
      "  rings {} ({} closed), joins {}, artificial nodes {}\n"
      "  edges {} (leaf edges {}: a double door counts as two leaves), walls {}, other edges {}\n"
      "  doors by class: 30 {}, 32 {}, 36 {}, 40 {}, 30/30 {}, 36/36 {}; door leaves {}\n"
      "  pairs counted {}, across artificial nodes (not counted) {}, other types/angles {}\n"
      "  total metric {:.0f} in ({:.0f} ft); mean edge metric {:.2f} in per leaf edge{}, "
      "{:.2f} in per map edge\n\n",
      c.rings, c.closed_rings, c.joins, c.artificial_nodes, c.edges, c.leaf_edges, c.walls,
      c.other_edges, c.doors_by_class[0], c.doors_by_class[1], c.doors_by_class[2],
      c.doors_by_class[3], c.doors_by_class[4], c.doors_by_class[5], c.door_leaves, c.pairs_counted,
      c.pairs_artificial, c.pairs_other, c.total_metric_in, c.total_metric_in / 12.0,
      c.mean_leaf_metric_in,
      compare ? fmt::format(" ({:.2f})", paper::kEngineeringMeanEdgeMetricIn) : std::string(),
      c.mean_edge_metric_in);
  const char* titles[3] = {"Table 6.1  adjacent pairs, angle 90 deg (row first, column second)",
                           "Table 6.2  adjacent pairs, angle 180 deg",
                           "Table 6.3  adjacent pairs, angle 270 deg"};
  for (int a = 0; a < 3; ++a) Matrix(out, titles[a], "", c.pairs[a], paper::kPairs[a], compare);
  Matrix(out, "Table 6.4  <door><wall><door>, 180 deg (row first door, column last door)", "",
         c.door_wall_door, paper::kDoorWallDoor, compare);
  out += "Table 6.5  <wall><door><wall>, 180 deg\n";
  for (int i = 0; i < 4; ++i) {
    out += fmt::format("  {:<8}{:>11}\n", kRowNames[i],
                       Cell(c.wall_door_wall[i], paper::kWallDoorWall[i], compare));
  }
  out += "\n";
  Matrix(out, "Table 6.6  <door><wall><door><wall>, 180 deg", "", c.door_wall_door_wall,
         paper::kDoorWallDoorWall, compare);
  Matrix(out, "Table 6.7  <wall><door><wall><door>, 180 deg (caption of the text says 90)", "",
         c.wall_door_wall_door, paper::kWallDoorWallDoor, compare);
  out += "Table 6.8  door census (blank = all doors of the class; other columns = marks)\n";
  out += fmt::format("  {:<8}", "");
  for (const auto& col : paper::kPatternColumns) out += fmt::format("{:>15}", col);
  out += "\n";
  for (int i = 0; i < 4; ++i) {
    out += fmt::format("  {:<8}", kRowNames[i]);
    for (int j = 0; j < 6; ++j) {
      out += fmt::format("{:>15}", Cell(c.door_census[i][j], paper::kDoorCensus[i][j], compare));
    }
    out += "\n";
  }
  out += "\nTable 6.9  wall census (walls longer than / at least)\n  ";
  for (std::size_t t = 0; t < paper::kWallThresholdsIn.size(); ++t) {
    out += fmt::format("{:>11}",
                       (t == 0 ? ">" : ">=") + fmt::format("{:.0f}", paper::kWallThresholdsIn[t]));
  }
  out += "\n  ";
  for (std::size_t t = 0; t < paper::kWallThresholdsIn.size(); ++t) {
    out += fmt::format("{:>11}", Cell(c.wall_census[t], paper::kWallCensus[t], compare));
  }
  out += "\n";
  if (compare) {
    out += "\nDeviation from the paper (sum over cells of |ours - paper|)\n";
    out += fmt::format("  {:<10}{:>7}{:>11}{:>9}{:>8}{:>8}\n", "table", "cells", "differing",
                       "|diff|", "ours", "paper");
    for (const TableDeviation& d : CompareWithPaper(c)) {
      out += fmt::format("  {:<10}{:>7}{:>11}{:>9}{:>8}{:>8}\n", d.table, d.cells,
                         d.cells_differing, d.abs_sum, d.ours_total, d.paper_total);
    }
    out += fmt::format("  {:<10}{:>27.2f}{:>8.2f}  (mean edge metric, in per leaf edge)\n",
                       "§6.4.1", c.mean_leaf_metric_in, paper::kEngineeringMeanEdgeMetricIn);
  }
  return out;
}

nlohmann::json CensusJson(const Map& map, const Census& c, bool compare) {
  nlohmann::json j;
  j["map"] = map.info().name;
  j["rings"] = c.rings;
  j["closed_rings"] = c.closed_rings;
  j["joins"] = c.joins;
  j["artificial_nodes"] = c.artificial_nodes;
  j["edges"] = c.edges;
  j["leaf_edges"] = c.leaf_edges;
  j["walls"] = c.walls;
  j["other_edges"] = c.other_edges;
  j["door_leaves"] = c.door_leaves;
  nlohmann::json by_class;
  for (int k = 0; k < kDoorClassCount; ++k) {
    by_class[DoorClassName(static_cast<DoorClass>(k))] = c.doors_by_class[k];
  }
  j["doors_by_class"] = by_class;
  j["pairs_counted"] = c.pairs_counted;
  j["pairs_artificial"] = c.pairs_artificial;
  j["pairs_other"] = c.pairs_other;
  j["total_metric_in"] = c.total_metric_in;
  j["mean_leaf_metric_in"] = c.mean_leaf_metric_in;
  j["mean_edge_metric_in"] = c.mean_edge_metric_in;
  j["row_order"] = {"door30", "door32", "door36", "door40", "wall"};
  j["table_6_1"] = c.pairs[0];
  j["table_6_2"] = c.pairs[1];
  j["table_6_3"] = c.pairs[2];
  j["table_6_4"] = c.door_wall_door;
  j["table_6_5"] = c.wall_door_wall;
  j["table_6_6"] = c.door_wall_door_wall;
  j["table_6_7"] = c.wall_door_wall_door;
  j["table_6_8"] = c.door_census;
  nlohmann::json columns = nlohmann::json::array();
  for (const auto& col : paper::kPatternColumns) columns.push_back(std::string(col));
  j["table_6_8_columns"] = columns;
  j["table_6_9"] = c.wall_census;
  j["table_6_9_thresholds_in"] = paper::kWallThresholdsIn;
  if (compare) {
    nlohmann::json dev = nlohmann::json::array();
    for (const TableDeviation& d : CompareWithPaper(c)) {
      dev.push_back({{"table", d.table},
                     {"cells", d.cells},
                     {"cells_differing", d.cells_differing},
                     {"abs_sum", d.abs_sum},
                     {"ours_total", d.ours_total},
                     {"paper_total", d.paper_total}});
    }
    j["deviation_from_paper"] = dev;
    j["paper_mean_edge_metric_in"] = paper::kEngineeringMeanEdgeMetricIn;
  }
  return j;
}

}  // namespace stickrep::map
