#pragma once

// Reading and writing StickRep map files (YAML under maps/, format in maps/README.md).
// Every problem in a file is reported as stickrep::InputError naming the file, the line,
// the key and the reason; programs turn it into exit code 2 (common/input_error.h).

#include <string>

#include "stickrep/map.h"

namespace stickrep::map {

// The newest format version (`stickrep_map: 2`). Version 1 files still load; the writer
// writes version 1 when a map uses nothing of version 2 (measured door widths, openings,
// corridor outlines, ring widths), so version 1 maps round-trip unchanged.
inline constexpr int kMapFormatVersion = 2;
// Whether a map needs format 2 to be written.
bool NeedsFormat2(const Map& map);

// How far an edge's metric may differ from the distance between its two nodes before the
// file is rejected: max(kGeometryToleranceIn, kGeometryToleranceRel * metric).
inline constexpr double kGeometryToleranceIn = 1.0;
inline constexpr double kGeometryToleranceRel = 0.01;

// Loads and validates a map file; throws InputError on any problem.
Map LoadMap(const std::string& path);
// Same for text already in memory; `name` stands for the file name in messages.
Map ParseMap(const std::string& text, const std::string& name);

// The map as a YAML document in the layout of maps/README.md. Deterministic: the same map
// gives the same bytes (the generators' reproducibility test relies on it).
std::string WriteMapYaml(const Map& map);
// Writes WriteMapYaml(map) to `path`; throws std::runtime_error if it cannot.
void SaveMap(const Map& map, const std::string& path);

// A number as the writer prints it: at most three decimals, no trailing zeros.
std::string FormatNumber(double value);

}  // namespace stickrep::map
