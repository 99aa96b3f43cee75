#pragma once

// The world of the virtual robot's tests: a small square ring, and a world without noise.

#include "stickrep/map.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::virtual_robot::testing {

// A square closed ring, 400 in a side, with one 36 in door in the middle of the first side.
inline map::Map SquareRing() {
  map::Ring ring;
  ring.id = "square";
  ring.edges = {map::Edge::Wall(182), map::Edge::Door(map::DoorClass::k36),
                map::Edge::Wall(182), map::Edge::Wall(400),
                map::Edge::Wall(400), map::Edge::Wall(400)};
  const double xs[] = {0, 182, 218, 400, 400, 0};
  const double ys[] = {0, 0, 0, 0, 400, 400};
  // Ring order walks with the wall on the right, so the square is walked clockwise:
  // along +x at y = 0 the hallway (left of travel) lies at y > 0... inside the square.
  ring.nodes.resize(6);
  for (int i = 0; i < 6; ++i) {
    ring.nodes[i].x_in = xs[i];
    ring.nodes[i].y_in = ys[i];
    ring.nodes[i].angle_deg = (i == 0 || i >= 3) ? 90.0 : 180.0;
  }
  return map::Map(map::MapInfo{"square", "", "", std::nullopt}, {ring});
}

inline WorldSimConfig Exact() {
  WorldSimConfig c;
  c.hallway_width_in = 120.0;
  c.sonar_surface_errors = false;
  c.wheel_slip_stddev = 0.0;
  c.image_noise_sigma = 0.0;
  return c;
}

}  // namespace stickrep::virtual_robot::testing
