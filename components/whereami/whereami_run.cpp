#include "whereami/whereami_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/config_paths.h"
#include "common/strict_yaml.h"
#include "common/units.h"
#include "executive/executive.h"
#include "landmark/landmark_pipeline.h"
#include "localizer/sensed_doors.h"
#include "localizer/localizer.h"
#include "locomotion/drive.h"
#include "locomotion/hallway_behaviour.h"
#include "sonar/sonar_gate.h"
#include "stickrep/hallway_view.h"
#include "stickrep/map_io.h"
#include "stickrep/sequence_matcher.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::whereami {

namespace {

// The envelope is judged on straight runs (beyond 8 ft of a corner) once the robot has had
// 20 ft to align from its start, as the virtual robot process judges it.
constexpr double kEnvelopeCornerDistanceIn = 96.0;
constexpr double kEnvelopeSettleDistanceIn = 240.0;

StrictYaml Section(const std::string& file, const std::string& key) {
  return StrictYaml::LoadFile(file).Child(key);
}

// A periodic event on the simulated clock.
struct Every {
  double period_s;
  double next_s = 0.0;
  bool Due(double t) {
    if (t + 1e-9 < next_s) return false;
    next_s += period_s;
    return true;
  }
};

// One trace line per change of the localizer's estimate: the newest sensed edge, the best
// place with its probability, and where the robot truly is.
void TraceBelief(double t, const localizer::Localizer& localizer, const map::HallwayView& view,
                 const virtual_robot::WorldSim& sim, int ring, RunResult& result) {
  if (result.behaviour_log.size() >= 400) return;
  const localizer::PoseEstimate& e = localizer.estimate();
  const std::vector<map::SensedEdge>& seq = localizer.sensed_sequence();
  const std::string newest = seq.empty() ? "-" : map::Describe(seq.back());
  const virtual_robot::SimTruth truth = sim.Truth();
  std::string best = "no place";
  if (!e.hypotheses.empty()) {
    const localizer::Hypothesis& h = e.hypotheses.front();
    best = fmt::format("view edge {} {} p={:.3f}", h.edge, h.dir > 0 ? "fwd" : "back",
                       h.probability);
  }
  result.behaviour_log.push_back(fmt::format(
      "{:7.1f} s  localizer {}: newest {}, best {}, truth view edge {} {}: {}", t,
      localizer::ToString(e.status), newest, best,
      view.ViewEdge(ring, truth.edge_index), truth.forward_in_ring ? "fwd" : "back",
      e.message));
}

}  // namespace

RunSetup LoadRunSetup(const std::string& config_dir, const std::string& map_file,
                      const std::string& virtual_robot_file) {
  RunSetup s;
  const std::string dir = config_dir.empty() ? DefaultConfigDir() : config_dir;
  // Only the two paths are needed of system.yaml; the processes validate the rest.
  const std::string system_file = dir + "/system.yaml";
  const StrictYaml system = Section(system_file, "system");
  const std::string robot_file = ResolvePath(system.Get<std::string>("robot_file"), system_file);
  s.map_file =
      map_file.empty() ? ResolvePath(system.Get<std::string>("map_file"), system_file) : map_file;
  s.map = std::make_shared<const map::Map>(map::LoadMap(s.map_file));
  s.robot = sensing::LoadRobotConfigFile(robot_file);
  s.virtual_robot = virtual_robot::LoadVirtualRobotConfig(Section(
      virtual_robot_file.empty() ? dir + "/virtual_robot.yaml" : virtual_robot_file,
      "virtual_robot"));
  s.landmark = landmark::LoadLandmarkConfig(Section(dir + "/landmark.yaml", "landmark"));
  s.localizer = localizer::LoadLocalizerSettings(Section(dir + "/localizer.yaml", "localizer"));
  s.localizer.view.camera_fov_deg = s.robot.camera.fov_deg;  // doors too wide to see whole
  s.locomotion =
      locomotion::LoadLocomotionConfig(Section(dir + "/locomotion.yaml", "locomotion"), s.robot);
  s.executive = executive::LoadExecutiveConfig(Section(dir + "/executive.yaml", "executive"));
  return s;
}

const char* ToString(Ending ending) {
  switch (ending) {
    case Ending::kCorrect: return "correct";
    case Ending::kWrong: return "wrong";
    case Ending::kNoneInTime: return "none in time";
    case Ending::kCollision: return "collision";
    case Ending::kFailed: return "failed";
  }
  return "?";
}

Ending RunResult::ending() const {
  if (failed) return Ending::kFailed;
  if (collisions > 0) return Ending::kCollision;
  if (!first) return Ending::kNoneInTime;
  return first->correct ? Ending::kCorrect : Ending::kWrong;
}

RunResult RunWhereAmI(const RunSetup& setup, const RunOptions& options) {
  const map::Map& map = *setup.map;
  const sensing::RobotConfig& robot = setup.robot;
  virtual_robot::VirtualRobotConfig vr = setup.virtual_robot;
  vr.seed = options.seed;
  if (!options.ring_id.empty()) vr.world.ring_id = options.ring_id;
  const bool measuring = options.measure_ft > 0.0;
  const int ring = vr.world.ring_id.empty() ? 0 : map.FindRing(vr.world.ring_id);
  if (ring < 0) throw std::invalid_argument("no ring '" + vr.world.ring_id + "' in the map");
  virtual_robot::PlacedRobot placed = virtual_robot::PlaceRobot(map, robot, vr, ring);
  virtual_robot::WorldSim& sim = *placed.sim;

  const sonar::SonarGateConfig gate = sonar::GateConfigFor(robot);
  locomotion::HallwayBehaviour behaviour(setup.locomotion.behaviour);
  locomotion::BehaviourState last_state = locomotion::BehaviourState::kNoScan;
  locomotion::Odometer odometer(robot.base.wheel_base_in);
  const landmark::LandmarkPipeline pipeline(robot, setup.landmark.detector,
                                            setup.landmark.estimator);
  const map::HallwayView view(map, setup.localizer.view);
  const localizer::LocalizerConfig localizer_config =
      localizer::MakeLocalizerConfig(setup.localizer, view.view());
  localizer::Localizer localizer(view.view(), localizer_config);
  // Measuring: the same assembly as the localizer's, never restarted but by reversals.
  localizer::EdgeAssembler assembler(localizer_config.assembler);
  // From 20 ft on: the robot has aligned and the partial first edges are behind.
  EdgeErrorMeter meter(view.view().ring(ring), assembler, 240.0);
  executive::Executive executive(map, setup.executive.mission);
  for (const std::string& name : setup.executive.mission.required_components) {
    executive.mission().OnComponentActive(name);
  }

  RunResult result;
  result.seed = vr.seed;
  result.start_redraws = placed.redraws;
  {
    const virtual_robot::SimTruth t = sim.Truth();
    result.start = fmt::format("ring '{}' edge {} + {:.1f} in, {:+.1f} in off the axis, heading "
                               "{:+.1f} deg",
                               sim.ring_id(), t.edge_index, t.offset_in, t.lateral_offset_in,
                               RadToDeg(t.heading_error_rad));
  }

  Every sim_step{1.0 / vr.sim_rate_hz};
  Every encoders{1.0 / vr.encoder_rate_hz};
  Every sonar{1.0 / vr.sonar_rate_hz};
  Every camera{1.0 / vr.camera_rate_hz};
  const int coaxial = robot.camera.coaxial_sensor;
  sensing::SonarScan last_scan;
  locomotion::WheelSpeeds wheels;
  bool moving = false;
  double epoch_in = 0.0, epoch_s = 0.0;  // where the current recovery began
  double kidnap_at_s = -1.0;
  bool was_localized = false;

  const auto judge = [&](double t) {
    const localizer::PoseEstimate& e = localizer.estimate();
    const localizer::Hypothesis h = localizer::OnOriginalMap(view, e.hypotheses.front());
    const virtual_robot::SimTruth truth = sim.Truth();
    Recovery r;
    r.ring_id = map.ring(h.ring).id;
    r.edge = h.edge;
    r.forward = h.dir > 0;
    r.truth_ring_id = truth.seen_ring_id;
    r.truth_edge = truth.seen_edge_index;
    r.truth_forward = truth.seen_forward_in_ring;
    r.correct = virtual_robot::PoseMatchesTruth(r.ring_id, r.edge, r.forward, truth);
    r.edges_sensed = e.edges_sensed;
    r.distance_ft = InchesToFeet(truth.distance_in - epoch_in);
    r.time_s = t - epoch_s;
    executive.OnLocalized(executive::MapPose{h.ring, h.edge, h.dir, h.offset_in},
                          fmt::format("ring '{}' edge {}", r.ring_id, r.edge));
    return r;
  };

  int last_view_edge = -1;
  const map::Ring& view_ring = view.view().ring(ring);
  double t = 0.0;
  for (; t < options.max_sim_s; t = sim_step.next_s) {
    if (options.trace) {
      const int e = view.ViewEdge(ring, sim.Truth().edge_index);
      if (e != last_view_edge) {
        last_view_edge = e;
        const map::Edge& edge = view_ring.edges[e];
        map::SensedEdge as_sensed;
        as_sensed.code = map::CodeOf(edge);
        as_sensed.metric_in = edge.metric_in;
        result.true_trace += fmt::format("{}[{}] ", map::Describe(as_sensed), e);
      }
    }
    sim_step.Due(t);
    if (sonar.Due(t)) {
      const sonar::GatedScan g = sonar::GateScan(sim.Sonar(), gate);
      std::vector<locomotion::SonarRange> ranges(sonar::kRingSize);
      last_scan = {};
      for (int k = 0; k < sonar::kRingSize; ++k) {
        const bool valid = g.state[k] == sonar::ReadingState::kValid;
        ranges[k] = {g.range_in[k], valid, g.state[k] == sonar::ReadingState::kOutsideFootprint};
        last_scan.ranges_in.push_back(g.range_in[k]);
        last_scan.valid.push_back(valid);
      }
      behaviour.OnScan(ranges, t);
      if (last_scan.valid[coaxial]) {
        localizer.SetWallRange(last_scan.ranges_in[coaxial] + robot.sonar_ring.head_radius_in);
        assembler.SetWallRange(last_scan.ranges_in[coaxial] + robot.sonar_ring.head_radius_in);
      }
    }
    if (camera.Due(t)) {
      const std::vector<std::uint8_t> frame = sim.RenderFrame();
      ++result.frames;
      const vision::ImageView image{sim.image_width_px(), sim.image_height_px(),
                                    sim.image_width_px(), "mono8", frame.data(), frame.size()};
      const landmark::FrameOutcome out = pipeline.Process(image, last_scan);
      if (out.kind == landmark::FrameOutcome::Kind::kObservation) {
        ++result.doors_observed;
        const sensing::LandmarkObservation& o = out.observation;
        const localizer::DoorSighting sighting{localizer::ToMapDoorClass(o.door_class), o.width_in, o.confidence,
                                               odometer.distance_in() + out.center_offset_in};
        localizer.AddSighting(sighting);
        assembler.AddSighting(sighting);
      }
    }
    if (encoders.Due(t)) {
      odometer.Update(sim.left_travel_in(), sim.right_travel_in());
      executive.OnOdometer(odometer.distance_in());
      if (measuring) {
        const virtual_robot::SimTruth truth = sim.Truth();
        meter.Advance(odometer.distance_in(), odometer.pose().heading_rad,
                      truth.optical_axis_on_wall ? view.ViewEdge(ring, truth.edge_index) : -1);
        if (InchesToFeet(truth.distance_in) >= options.measure_ft) {
          result.ended = fmt::format("measured over {:.0f} ft", options.measure_ft);
          break;
        }
      } else if (localizer.Advance(odometer.distance_in(), odometer.pose().heading_rad)) {
        const localizer::PoseEstimate& e = localizer.estimate();
        if (options.trace) TraceBelief(t, localizer, view, sim, ring, result);
        if (e.status == localizer::Status::kLocalized && !e.hypotheses.empty()) {
          if (!was_localized) {
            const Recovery r = judge(t);
            if (!result.first) {
              result.first = r;
              if (options.kidnap_after_s < 0.0) {
                result.ended = "localized";
                break;
              }
              // Keep travelling: a goal half the ring ahead.
              const int n = map.ring(ring).EdgeCount();
              const int ahead = r.forward ? r.edge + n / 2 : r.edge - n / 2 + n;
              executive.OnGoal("far", fmt::format("{}/{}", r.ring_id, ahead % n));
              kidnap_at_s = t + options.kidnap_after_s;
            } else if (result.kidnapped) {
              result.second = r;
              result.ended = "localized again after the kidnap";
              break;
            }
          }
          was_localized = true;
        } else if (e.status == localizer::Status::kLost) {
          if (result.kidnapped && !result.lost_detected) {
            result.lost_detected = true;
            result.lost_after_ft = InchesToFeet(sim.Truth().distance_in - epoch_in);
          }
          executive.OnLost();
          was_localized = false;
        } else {
          was_localized = false;
        }
      }
      const executive::MotionRequest request = executive.mission().Motion();
      if (request.move) {
        if (!moving) behaviour.Reset();
        moving = true;
        const locomotion::BehaviourOutput out =
            behaviour.Step(request.linear_speed_ftps, odometer.pose().heading_rad,
                           odometer.distance_in(), t, encoders.period_s);
        wheels = locomotion::ToWheelSpeeds(out.linear_ftps, out.angular_radps,
                                           setup.locomotion.limits);
        if (options.trace && out.state != last_state && result.behaviour_log.size() < 200) {
          result.behaviour_log.push_back(fmt::format("{:7.1f} s  {}", t, out.reason));
        }
        last_state = out.state;
        executive.mission().OnMotionState(out.in_envelope, t);
      } else {
        moving = false;
        wheels = {};
      }
    }
    if (kidnap_at_s >= 0.0 && t >= kidnap_at_s && !result.kidnapped) {
      result.kidnapped = true;
      sim.Teleport(sim.RingPosition() + options.kidnap_jump_in);
      epoch_in = sim.Truth().distance_in;
      epoch_s = t;
    }
    sim.Step(sim_step.period_s, wheels.left_ftps, wheels.right_ftps);
    const virtual_robot::SimTruth truth = sim.Truth();
    if (options.record_path) {
      const std::pair<double, double> at{truth.X_WR.x_in, truth.X_WR.y_in};
      if (result.path.empty() || std::hypot(at.first - result.path.back().first,
                                            at.second - result.path.back().second) > 3.0) {
        result.path.push_back(at);
      }
    }
    if (truth.corner_distance_in > kEnvelopeCornerDistanceIn &&
        truth.distance_in > kEnvelopeSettleDistanceIn) {
      result.max_offset_in = std::max(result.max_offset_in, std::abs(truth.lateral_offset_in));
      result.max_heading_deg =
          std::max(result.max_heading_deg, std::abs(RadToDeg(truth.heading_error_rad)));
    }
  }
  if (result.ended.empty()) {
    result.ended = fmt::format("no pose after {:.0f} s simulated", options.max_sim_s);
  }
  result.sim_s = t;
  result.collisions = sim.Truth().collisions;
  const std::vector<map::SensedEdge>& sensed =
      measuring ? assembler.sequence() : localizer.sensed_sequence();
  result.sensed_trace = map::Describe(sensed);
  if (measuring) result.errors = meter.Finish();
  return result;
}

}  // namespace stickrep::whereami
