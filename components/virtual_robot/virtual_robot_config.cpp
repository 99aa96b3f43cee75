#include "virtual_robot/virtual_robot_config.h"

#include <fmt/format.h>

#include <cstdlib>
#include <random>

namespace stickrep::virtual_robot {

namespace {

// The `realism` section: one switch per clutter feature and the draws' main bounds.
world::RealismOptions LoadRealism(const StrictYaml& r) {
  world::RealismOptions o;
  o.baseboards = r.Get<bool>("baseboards");
  o.floor_reflections = r.Get<bool>("floor_reflections");
  o.floor_reflectance = r.Get<double>("floor_reflectance", 0.0, 0.8);
  o.ceiling_lights = r.Get<bool>("ceiling_lights");
  o.notice_boards = r.Get<bool>("notice_boards");
  o.pilasters = r.Get<bool>("pilasters");
  o.door_appearance = r.Get<bool>("door_appearance");
  o.dark_door_share = r.Get<double>("dark_door_share", 0.0, 1.0);
  o.white_door_share = r.Get<double>("white_door_share", 0.0, 1.0);
  if (o.dark_door_share + o.white_door_share > 1.0) {
    r.Fail("white_door_share", "dark_door_share + white_door_share must be at most 1");
  }
  o.doors_ajar = r.Get<bool>("doors_ajar");
  o.ajar_share = r.Get<double>("ajar_share", 0.0, 1.0);
  o.camera_misalignment = r.Get<bool>("camera_misalignment");
  o.max_roll_deg = r.Get<double>("max_roll_deg", 0.0, 10.0, "deg");
  o.max_pitch_deg = r.Get<double>("max_pitch_deg", 0.0, 10.0, "deg");
  o.min_k1 = r.Get<double>("min_k1", -0.3, 0.5);
  o.max_k1 = r.Get<double>("max_k1", -0.3, 0.5);
  if (o.min_k1 > o.max_k1) r.Fail("max_k1", "must be at least min_k1");
  o.illumination = r.Get<bool>("illumination");
  r.Finish();
  return o;
}

}  // namespace

VirtualRobotConfig LoadVirtualRobotConfig(const StrictYaml& c) {
  VirtualRobotConfig out;
  const std::string source = c.Get<std::string>("source");
  if (source != "replay" && source != "simulated") {
    c.Fail("source", "'" + source + "' is not one of: simulated, replay");
  }
  out.replay = source == "replay";
  if (c.Has("replay")) {
    const StrictYaml r = c.Child("replay");
    out.recording.file = r.Get<std::string>("file");
    out.recording.rate = r.Get<double>("rate", 0.5, 20.0);
    out.recording.start_s = r.Get<double>("start_s", 0.0, 1e7, "s");
    out.recording.duration_s = r.Get<double>("duration_s", 0.0, 1e7, "s");
    out.recording.loop = r.Get<bool>("loop");
    r.Finish();
    if (out.replay && out.recording.file.empty()) {
      r.Fail("file", "source is 'replay': name a recording (stickrep-record -o FILE)");
    }
  } else if (out.replay) {
    c.Fail("replay", "source is 'replay': a `replay` section must name the recording");
  }
  out.seed = c.Get<std::uint64_t>("seed");
  out.start_offset_in = c.Get<double>("start_offset_in", -1.0, 1e7, "in");
  WorldSimConfig& world = out.world;
  world.ring_id = c.Get<std::string>("ring_id");
  world.hallway_width_in = c.Get<double>("hallway_width_in", 36.0, 600.0, "in");
  world.open_door_fraction = c.Get<double>("open_door_fraction", 0.0, 1.0);
  world.image_noise_sigma = c.Get<double>("image_noise_sigma", 0.0, 50.0, "grey levels");
  world.sonar_surface_errors = c.Get<bool>("sonar_surface_errors");
  world.wheel_slip_stddev = c.Get<double>("wheel_slip_stddev", 0.0, 0.2);
  world.realism = LoadRealism(c.Child("realism"));
  out.start_lateral_offset_max_in = c.Get<double>("start_lateral_offset_max_in", 0.0, 120.0, "in");
  out.start_heading_error_max_deg = c.Get<double>("start_heading_error_max_deg", 0.0, 25.0, "deg");
  if (out.start_lateral_offset_max_in > world.hallway_width_in / 2.0 - 12.0) {
    c.Fail("start_lateral_offset_max_in",
           fmt::format("must leave a foot between the base centre and the wall: at most {:g} in "
                       "in a {:g} in hallway",
                       world.hallway_width_in / 2.0 - 12.0, world.hallway_width_in));
  }
  out.real_time_factor = c.Get<double>("real_time_factor", 0.1, 50.0);
  out.sim_rate_hz = c.Get<double>("sim_rate_hz", 1.0, 1000.0, "Hz");
  out.encoder_rate_hz = c.Get<double>("encoder_rate_hz", 1.0, 200.0, "Hz");
  out.sonar_rate_hz = c.Get<double>("sonar_rate_hz", 0.5, 50.0, "Hz");
  out.camera_rate_hz = c.Get<double>("camera_rate_hz", 0.5, 60.0, "Hz");
  out.wheel_command_timeout_s = c.Get<double>("wheel_command_timeout_s", 0.05, 5.0, "s");
  out.kidnap_after_localized_s = c.Get<double>("kidnap_after_localized_s", -1.0, 3600.0, "s");
  out.kidnap_jump_in = c.Get<double>("kidnap_jump_in", -1e6, 1e6, "in");
  out.summary_png = c.Get<std::string>("summary_png");
  c.Finish();
  return out;
}

StartPlacement DrawStart(const VirtualRobotConfig& config, const map::Ring& ring, int attempt) {
  // Attempt 0 draws from the seed itself, so a seed's start does not depend on redraws.
  const std::uint64_t seed =
      config.seed + static_cast<std::uint64_t>(attempt) * 0x9E3779B97F4A7C15ull;
  StartPlacement s;
  s.ring_position_in = config.start_offset_in;
  if (s.ring_position_in < 0.0) {
    std::mt19937_64 pick(seed);
    s.ring_position_in = std::uniform_real_distribution<double>(0.0, ring.LengthIn())(pick);
  }
  std::mt19937_64 pose_pick(seed ^ 0x5DEECE66Dull);
  const double max_offset = config.start_lateral_offset_max_in;
  const double max_heading = config.start_heading_error_max_deg;
  s.lateral_offset_in = std::uniform_real_distribution<double>(-max_offset, max_offset)(pose_pick);
  s.heading_error_deg = std::uniform_real_distribution<double>(-max_heading, max_heading)(pose_pick);
  return s;
}

PlacedRobot PlaceRobot(const map::Map& map, const sensing::RobotConfig& robot,
                       const VirtualRobotConfig& config, int ring) {
  PlacedRobot placed;
  for (int attempt = 0;; ++attempt) {
    placed.start = DrawStart(config, map.ring(ring), attempt);
    WorldSimConfig world = config.world;
    world.start_lateral_offset_in = placed.start.lateral_offset_in;
    world.start_heading_error_deg = placed.start.heading_error_deg;
    try {
      placed.sim = std::make_unique<WorldSim>(map, robot, world, placed.start.ring_position_in,
                                              config.seed);
      return placed;
    } catch (const ImpossibleStart& e) {
      if (attempt + 1 >= kMaxStartDraws) throw;
      placed.redraws.push_back(e.what() + std::string(" at ") +
                               std::to_string(placed.start.ring_position_in) +
                               " in along the ring: drawn again");
    }
  }
}

bool PoseMatchesTruth(const std::string& ring_id, int edge, bool forward, const SimTruth& truth) {
  return PoseMatchesTruth(ring_id, edge, forward, truth.seen_ring_id, truth.seen_edge_index,
                          truth.seen_forward_in_ring, truth.seen_ring_edge_count);
}

bool PoseMatchesTruth(const std::string& ring_id, int edge, bool forward,
                      const std::string& truth_ring_id, int truth_edge, bool truth_forward,
                      int ring_edge_count) {
  const int de = std::abs(edge - truth_edge);
  return ring_id == truth_ring_id && forward == truth_forward &&
         (de <= 1 || de == ring_edge_count - 1);
}

}  // namespace stickrep::virtual_robot
