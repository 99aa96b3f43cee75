#pragma once

// The dissertation's published numbers used by the reports, in one place: the census of the
// Engineering Building's third floor (Tables 6.1–6.9, §6.2) and the no-error edges of
// Table 6.22 (§6.8). Row and column order: door30, door32, door36, door40, wall.

#include <array>
#include <string_view>

namespace stickrep::map::paper {

// Tables 6.1–6.3: ordered pairs of adjacent edges (row first, column second) at 90°, 180°
// and 270°.
inline constexpr std::array<std::array<std::array<int, 5>, 5>, 3> kPairs = {{
    // Table 6.1, 90°
    {{{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 115}}},
    // Table 6.2, 180°
    {{{11, 0, 0, 0, 11},
      {0, 0, 0, 0, 4},
      {0, 0, 28, 0, 183},
      {0, 0, 0, 0, 11},
      {10, 4, 181, 11, 0}}},
    // Table 6.3, 270°
    {{{0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 1}, {0, 0, 0, 0, 0}, {0, 0, 2, 0, 98}}},
}};

// Table 6.4: <door><wall><door>, both nodes 180°; row first door, column last door.
inline constexpr std::array<std::array<int, 4>, 4> kDoorWallDoor = {
    {{4, 0, 4, 2}, {0, 0, 1, 0}, {5, 2, 118, 3}, {0, 0, 4, 4}}};
// Table 6.5: <wall><door><wall>, both nodes 180°, by door class.
inline constexpr std::array<int, 4> kWallDoorWall = {0, 4, 152, 11};
// Table 6.6: <door><wall><door><wall>, all 180°.
inline constexpr std::array<std::array<int, 4>, 4> kDoorWallDoorWall = {
    {{0, 0, 1, 2}, {0, 0, 0, 0}, {0, 2, 114, 3}, {0, 0, 2, 4}}};
// Table 6.7: <wall><door><wall><door>. Its caption says 90°, but no door meets a wall at
// 90° in Table 6.1, so the counts can only be of 180° sequences; the census uses 180°.
inline constexpr std::array<std::array<int, 4>, 4> kWallDoorWallDoor = {
    {{0, 0, 0, 0}, {0, 0, 1, 0}, {5, 1, 109, 2}, {0, 0, 4, 4}}};

// Table 6.8: door census. Columns: blank, old window, no window, new window, 2 new windows,
// poster. The blank column equals the number of doors of each class implied by Tables
// 6.1–6.3 (22, 4, 212, 11), so we read it as "all doors of the class" and the other columns
// as marks carried by some of those doors.
inline constexpr std::array<std::string_view, 6> kPatternColumns = {
    "blank", "old window", "no window", "new window", "2 new windows", "poster"};
// The map's pattern word for each column after the first.
inline constexpr std::array<std::string_view, 5> kPatternWords = {
    "old_window", "no_window", "new_window", "two_new_windows", "poster"};
inline constexpr std::array<std::array<int, 6>, 4> kDoorCensus = {
    {{22, 0, 0, 0, 0, 0}, {4, 0, 0, 0, 0, 0}, {212, 54, 10, 3, 104, 29}, {11, 11, 0, 0, 0, 0}}};

// Table 6.9: walls longer than 0 and at least each threshold (inches).
inline constexpr std::array<double, 11> kWallThresholdsIn = {0,  12, 16,  32,  48, 64,
                                                             80, 96, 112, 128, 160};
inline constexpr std::array<int, 11> kWallCensus = {431, 415, 370, 328, 223, 202,
                                                    160, 121, 102, 88,  62};

// §6.4.1: mean edge metric of the Engineering Building.
inline constexpr double kEngineeringMeanEdgeMetricIn = 67.64;

// Table 6.22, no sensing error.
struct NoErrorFigure {
  std::string_view map_name;
  std::string_view label;
  double edges;
  double distance_ft;
  double time_s;
};
inline constexpr std::array<NoErrorFigure, 5> kNoErrorEdges = {{
    {"engineering_building_3f", "Engr Bldg", 5.28, 29.76, 11.45},
    {"wells_hall_7f", "Wells Hall", 13.72, 69.97, 26.91},
    {"wells_hall_7f_modified", "Modified Wells", 12.61, 64.31, 24.74},
    {"regular_polygon_46", "Regular Polygon", 46.00, 383.33, 147.44},
    {"storefront", "Storefront", 14.28, 73.76, 28.54},
}};

// The base's top speed used for Table 6.22's times (§6.3).
inline constexpr double kBaseSpeedFtPerS = 2.6;

// The entry of kNoErrorEdges for a map name, or nullptr.
inline const NoErrorFigure* NoErrorFor(std::string_view map_name) {
  for (const auto& f : kNoErrorEdges) {
    if (f.map_name == map_name) return &f;
  }
  return nullptr;
}

}  // namespace stickrep::map::paper
