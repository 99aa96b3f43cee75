#pragma once

// The census of a map printed in the layout of Tables 6.1–6.9, side by side with the
// dissertation's numbers when asked (the Engineering Building), and as JSON.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stickrep/census.h"

namespace stickrep::map {

// How far one of our tables is from the paper's.
struct TableDeviation {
  std::string table;  // "Table 6.2"
  int cells = 0;
  int cells_differing = 0;
  int abs_sum = 0;  // sum over cells of |ours - paper|
  int ours_total = 0;
  int paper_total = 0;
};

std::vector<TableDeviation> CompareWithPaper(const Census& census);

// Text report. With `compare`, each cell reads "ours (paper)" and a deviation summary ends
// the report.
std::string FormatCensusText(const Map& map, const Census& census, bool compare);
nlohmann::json CensusJson(const Map& map, const Census& census, bool compare);

}  // namespace stickrep::map
