#pragma once

// Floor plan sources: corridors written the way one reads them off an architect's plan, and
// the map (format 2) they make. A corridor is a centreline walked from one end — straight
// runs, corners at any angle, arcs written as chords — with a width, its two ends (wall or
// opening) and what lies along each side at which station (distance along the centreline
// from its start): doors at their measured width, openings, and alcoves (recesses of any
// depth, with doors in their back wall). Each corridor becomes one closed corridor outline
// (map::Outline::kCorridor) walked with the wall on the right; free-standing columns become
// obstacles. Format: maps/README.md, "Floor plan sources".

#include <string>

#include "stickrep/map.h"

namespace stickrep::map {

// Reads a floor plan source and builds its map; throws InputError (file, line, key, reason)
// for any problem: a feature that runs past a corner or off the corridor, features that
// overlap, a door width no class fits, a bad number.
Map LoadFloorPlan(const std::string& path);
// Same for text in memory; `name` stands for the file name in messages.
Map ParseFloorPlan(const std::string& text, const std::string& name);

}  // namespace stickrep::map
