// Hallway following in closed loop, without DDS: the simulated world (WorldSim, free planar
// motion with wheel slip, sonar with the surface errors of §4.3), the sonar process's gate,
// the hallway behaviour and dead reckoning from the encoders, at the rates of the live stack
// (20 Hz control, 10 Hz sonar, 100 Hz simulation), round whole rings of the shipped maps.
// The robot must complete a lap with no collision, inside the navigation envelope of §6.4.2
// (1 ft of the axis, 7.5° of its direction) wherever it is more than 8 ft from a corner,
// without oscillating and never above the base's rated 2.6 ft/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "common/units.h"
#include "locomotion/drive.h"
#include "locomotion/hallway_behaviour.h"
#include "locomotion/locomotion_config.h"
#include "sensing/robot_config.h"
#include "sonar/sonar_gate.h"
#include "stickrep/map_io.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::locomotion {
namespace {

constexpr double kSimDt = 0.01;       // 100 Hz world
constexpr int kControlEvery = 5;      // 20 Hz control
constexpr int kSonarEvery = 10;       // 10 Hz sonar
constexpr double kCornerZoneIn = 96.0;  // the envelope is judged beyond 8 ft of a corner
// An offset sign change counts once the offset has passed this far to the other side:
// smaller wiggles are sonar noise, not oscillation.
constexpr double kSwingBandIn = 2.0;

struct LapFigures {
  bool completed = false;
  double lap_time_s = 0.0;
  double travelled_in = 0.0;
  int collisions = 0;
  double max_offset_in = 0.0;       // beyond the corner zone
  double max_heading_deg = 0.0;     // beyond the corner zone
  double max_speed_ftps = 0.0;      // commanded body speed
  double max_wheel_ftps = 0.0;      // commanded wheel speed
  int max_swings_per_run = 0;       // offset sign changes on one straight run
  int turns = 0, reversals = 0, obstacle_stops = 0;
  std::string worst_place;          // where the largest offset was seen
  double envelope_entered_after_in = -1.0;  // path length before the first in-envelope report
};

std::string MapPath(const std::string& name) {
  return std::string(STICKREP_SOURCE_DIR) + "/maps/" + name;
}

// Drives round the ring against ring order (the camera on the mapped wall) until the
// robot's foot on the hallway axis has gone once round, or the time runs out.
LapFigures DriveLap(const std::string& map_file, const std::string& ring_id, double start_offset_in,
                    double speed_ftps, std::uint64_t seed, double start_lateral_in = 0.0,
                    double start_heading_deg = 0.0, double settle_in = 0.0,
                    double view_offset_in = 0.0) {
  const map::Map map = map::LoadMap(MapPath(map_file));
  const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(sensing::DefaultRobotConfigPath());
  virtual_robot::WorldSimConfig wc;
  wc.ring_id = ring_id;
  wc.hallway_width_in = 120.0;  // configs/virtual_robot.yaml
  wc.sonar_surface_errors = true;
  wc.wheel_slip_stddev = 0.01;
  wc.start_lateral_offset_in = start_lateral_in;
  wc.start_heading_error_deg = start_heading_deg;
  virtual_robot::WorldSim sim(map, robot, wc, start_offset_in, seed);
  const sonar::SonarGateConfig gate = sonar::GateConfigFor(robot);
  HallwayBehaviourConfig behaviour_config;
  ApplyRobot(robot, behaviour_config);
  if (view_offset_in > 0.0) {
    // Paced for the camera and riding off the axis in narrow hallways (configs/locomotion.yaml).
    behaviour_config.frames_per_door = 3;
    behaviour_config.max_view_offset_in = view_offset_in;
  }
  HallwayBehaviour behaviour(behaviour_config);
  Odometer odometer(robot.base.wheel_base_in);
  DriveLimits limits;
  limits.max_speed_ftps = robot.base.max_speed_ftps;
  limits.wheel_base_in = robot.base.wheel_base_in;

  LapFigures f;
  const double axis_length = sim.axis_length_in();
  const double timeout_s = 2.0 * axis_length / FeetToInches(speed_ftps) + 120.0;
  double progress_in = 0.0;
  double last_axis = sim.Truth().axis_position_in;
  WheelSpeeds wheels;
  int swings = 0, side = 0;
  bool on_straight = false;
  for (long step = 0; step * kSimDt < timeout_s; ++step) {
    const double t = step * kSimDt;
    if (step % kSonarEvery == 0) {
      const sonar::GatedScan g = sonar::GateScan(sim.Sonar(), gate);
      std::vector<SonarRange> scan(sonar::kRingSize);
      for (int k = 0; k < sonar::kRingSize; ++k) {
        scan[k] = {g.range_in[k], g.state[k] == sonar::ReadingState::kValid,
                   g.state[k] == sonar::ReadingState::kOutsideFootprint};
      }
      behaviour.OnScan(scan, t);
    }
    if (step % kControlEvery == 0) {
      odometer.Update(sim.left_travel_in(), sim.right_travel_in());
      const BehaviourOutput out = behaviour.Step(speed_ftps, odometer.pose().heading_rad,
                                                 odometer.distance_in(), t, kControlEvery * kSimDt);
      wheels = ToWheelSpeeds(out.linear_ftps, out.angular_radps, limits);
      f.max_speed_ftps = std::max(f.max_speed_ftps, std::abs(out.linear_ftps));
      f.max_wheel_ftps =
          std::max({f.max_wheel_ftps, std::abs(wheels.left_ftps), std::abs(wheels.right_ftps)});
      f.turns += out.turn_started;
      f.reversals += out.reversed;
      f.obstacle_stops += out.obstacle_stop_started;
      if (f.envelope_entered_after_in < 0.0 && out.in_envelope) {
        f.envelope_entered_after_in = sim.Truth().distance_in;
      }
    }
    sim.Step(kSimDt, wheels.left_ftps, wheels.right_ftps);
    if (step % kControlEvery != 0) continue;

    const virtual_robot::SimTruth truth = sim.Truth();
    double delta = std::remainder(truth.axis_position_in - last_axis, axis_length);
    last_axis = truth.axis_position_in;
    progress_in -= delta;  // forward travel is against ring order
    // The envelope is judged on straight runs, once the robot has had `settle_in` of travel
    // to align from its start.
    const bool straight =
        truth.corner_distance_in > kCornerZoneIn && truth.distance_in > settle_in;
    if (straight) {
      const double offset = std::abs(truth.lateral_offset_in);
      if (offset > f.max_offset_in) {
        f.max_offset_in = offset;
        f.worst_place = fmt::format("edge {} + {:.0f} in, ({:.0f}, {:.0f}) in, t = {:.1f} s",
                                    truth.edge_index, truth.offset_in, truth.X_WR.x_in,
                                    truth.X_WR.y_in, t);
      }
      f.max_heading_deg = std::max(f.max_heading_deg, std::abs(RadToDeg(truth.heading_error_rad)));
      if (!on_straight) swings = 0, side = 0;
      const int now_side = truth.lateral_offset_in > kSwingBandIn    ? +1
                           : truth.lateral_offset_in < -kSwingBandIn ? -1
                                                                     : 0;
      if (now_side != 0 && side != 0 && now_side != side) ++swings;
      if (now_side != 0) side = now_side;
      f.max_swings_per_run = std::max(f.max_swings_per_run, swings);
    }
    on_straight = straight;
    if (progress_in >= axis_length) {
      f.completed = true;
      f.lap_time_s = t;
      break;
    }
  }
  const virtual_robot::SimTruth end = sim.Truth();
  f.collisions = end.collisions;
  f.travelled_in = end.distance_in;
  if (!f.completed) {
    f.worst_place += fmt::format("; lap not completed: {:.0f} of {:.0f} in round the axis, "
                                 "stuck at edge {} + {:.0f} in, ({:.0f}, {:.0f}) in",
                                 progress_in, axis_length, end.edge_index, end.offset_in,
                                 end.X_WR.x_in, end.X_WR.y_in);
  }
  return f;
}

void Print(const std::string& what, const LapFigures& f) {
  std::cout << fmt::format(
      "[closed loop] {}: lap {} in {:.1f} s ({:.0f} ft travelled); collisions {}; beyond 8 ft "
      "of corners max |offset| {:.1f} in, max |heading error| {:.1f} deg, max offset swings "
      "per straight {}; max speed {:.2f} ft/s (wheels {:.2f}); turns {}, reversals {}, "
      "obstacle stops {}; largest offset at {}\n",
      what, f.completed ? "completed" : "NOT completed", f.lap_time_s,
      InchesToFeet(f.travelled_in), f.collisions, f.max_offset_in, f.max_heading_deg,
      f.max_swings_per_run, f.max_speed_ftps, f.max_wheel_ftps, f.turns, f.reversals,
      f.obstacle_stops, f.worst_place);
}

void ExpectAGoodLap(const LapFigures& f, int corners) {
  EXPECT_TRUE(f.completed) << f.worst_place;
  EXPECT_EQ(f.collisions, 0);
  EXPECT_LE(f.max_offset_in, 12.0) << f.worst_place;
  EXPECT_LE(f.max_heading_deg, 7.5);
  EXPECT_LE(f.max_swings_per_run, 2);
  EXPECT_LE(f.max_speed_ftps, 2.6 + 1e-9);
  EXPECT_LE(f.max_wheel_ftps, 2.6 + 1e-9);
  EXPECT_EQ(f.turns, corners);
  EXPECT_EQ(f.reversals, 0);
  EXPECT_EQ(f.obstacle_stops, 0);
}

TEST(HallwayClosedLoopTest, StorefrontBlockFrontageLap) {
  const LapFigures f = DriveLap("storefront.yaml", "block_frontage", 100.0, 2.6, 1994);
  Print("storefront block_frontage", f);
  ExpectAGoodLap(f, 4);
}

TEST(HallwayClosedLoopTest, OffTheAxisAndTurnedAtTheStartAlignsWithin20Ft) {
  // 18 in off the axis toward the opposite wall, turned 10° toward the mapped one: outside
  // the envelope of §6.4.2 (1 ft, 7.5°) until the behaviour has aligned and centred (A3, A4).
  const LapFigures f = DriveLap("engineering_building_3f.yaml", "wing1_corridor", 1500.0, 2.6,
                                7, -18.0, 10.0, 240.0);
  Print("engineering_building_3f wing1_corridor from 18 in, 10 deg off", f);
  ExpectAGoodLap(f, 4);
  EXPECT_GT(f.envelope_entered_after_in, 0.0);
  EXPECT_LE(f.envelope_entered_after_in, 240.0);
}

TEST(HallwayClosedLoopTest, EngineeringBuildingWing1CorridorLap) {
  const LapFigures f = DriveLap("engineering_building_3f.yaml", "wing1_corridor", 100.0, 2.6, 20261121);
  Print("engineering_building_3f wing1_corridor", f);
  ExpectAGoodLap(f, 4);
}

TEST(HallwayClosedLoopTest, ScienceHallOnTheCameraLineTouchesNoWallAlongTheStudyHall) {
  // The science hall's labs corridor is 88 in wide: paced for the camera, the base rides
  // 10 in off the axis at about 2.4 ft/s. Where the corridor bends along the side that
  // opens into the study hall, only the wall it heads into shows the bend; with this
  // seed's slip and sonar errors that wall stops the base, which must square up to it and
  // go on, not wait before it, reverse with a track gone wrong and touch it (as it did
  // before squaring up). The ring has hallway ends, so the base travels it back and forth
  // for the time a lap would take.
  const LapFigures f =
      DriveLap("science_hall_2f.yaml", "labs_corridor", 12100.0, 2.6, 40, 0.0, 0.0, 0.0, 10.0);
  Print("science_hall_2f labs_corridor on the 10 in line, seed 40", f);
  EXPECT_EQ(f.collisions, 0);
  EXPECT_GT(InchesToFeet(f.travelled_in), 1000.0);
  EXPECT_LE(f.max_speed_ftps, 2.6 + 1e-9);
}

}  // namespace
}  // namespace stickrep::locomotion
