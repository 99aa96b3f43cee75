#pragma once

// The map message family: a map::Map as the localizer publishes it on map/stickrep
// (msgs::StickRepMap, transient-local, for readers that join late), and back.
//
// The message carries the map's name and, per ring, its id, whether it is closed, and its
// edges in ring order: kind, metric, door class, pattern, and the node at the start of the
// edge (adjacency angle, x, y). It carries no joins, obstacles, node heights or orientations,
// corridor outlines, hallway widths, edge prototypes or description. FromMsg therefore gives
// a map with the same rings, edges and node positions: what a console needs to draw the
// floor and place a pose on it, not a copy of the map file.

#include "localization.h"
#include "stickrep/map.h"

namespace stickrep::localizer {

// The map as the localizer publishes it. An opening (map format 2) has no EdgeKind of its
// own in the IDL: it travels as the value after EDGE_STAIRWELL (6), which FromMsg reads back.
msgs::StickRepMap ToMsg(const map::Map& map);

// The map a StickRepMap message describes. Edge prototypes are the default for their type.
// An open ring's end node, which the message does not carry, is placed one metric along the
// last edge, in the direction that edge leaves its start node: the previous edge's
// direction turned by the start node's adjacency angle (180 straight on, 90 a right turn,
// 270 a left turn, walking with the wall on the right); +x for a ring of one edge.
// Throws std::invalid_argument naming the ring and edge when the message is not a valid
// map (an unknown edge kind or door class, a ring without edges, a non-positive metric).
map::Map FromMsg(const msgs::StickRepMap& msg);

}  // namespace stickrep::localizer
