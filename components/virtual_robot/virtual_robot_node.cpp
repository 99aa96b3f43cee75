#include "virtual_robot/virtual_robot_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/units.h"
#include <random>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "runtime/endpoint.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"
#include "plot/map_render.h"
#include "systemPubSubTypes.h"
#include "virtual_robot/replay_robot_node.h"
#include "virtual_robot/virtual_robot_config.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::virtual_robot {

namespace {

// The navigation envelope (§6.4.2) is judged away from corners, where the robot turns
// instead of following (8 ft), and once the robot has had room to align from its start
// (20 ft travelled).
constexpr double kEnvelopeCornerDistanceIn = 96.0;
constexpr double kEnvelopeSettleDistanceIn = 240.0;

class VirtualRobotNode : public runtime::ProcessNode {
 public:
  explicit VirtualRobotNode(VirtualRobotConfig config) : config_(std::move(config)) {}

  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const VirtualRobotConfig& config = config_;
    const std::uint64_t seed = config.seed;
    const WorldSimConfig& world = config.world;
    rtf_ = config.real_time_factor;
    wheel_timeout_s_ = config.wheel_command_timeout_s;
    kidnap_after_s_ = config.kidnap_after_localized_s;
    kidnap_jump_in_ = config.kidnap_jump_in;
    summary_png_ = config.summary_png;

    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    const map::Map& map = *map_;
    const int ring = world.ring_id.empty() ? 0 : map.FindRing(world.ring_id);
    if (ring < 0) {
      ctx.config.Fail("ring_id", "no ring '" + world.ring_id + "' in " + ctx.system.map_file);
    }
    // Off the axis and turned from it, so aligning and centring (A3, A4) has work to do.
    PlacedRobot placed = PlaceRobot(map, robot, config, ring);
    for (const std::string& r : placed.redraws) ctx.log->warn("{}", r);
    const StartPlacement start = placed.start;
    const double start_in = start.ring_position_in;
    const double max_offset_in = config.start_lateral_offset_max_in;
    const double max_heading_deg = config.start_heading_error_max_deg;
    sim_ = std::move(placed.sim);
    const SimTruth t = sim_->Truth();
    start_check_ = fmt::format(
        "start ring '{}' edge {} + {:.1f} in, {:+.1f} in off the axis, heading {:+.1f} deg "
        "(seed {})",
        sim_->ring_id(), t.edge_index, t.offset_in, t.lateral_offset_in,
        RadToDeg(t.heading_error_rad), seed);
    path_.push_back({t.X_WR.x_in, t.X_WR.y_in});
    markers_.push_back({t.X_WR.x_in, t.X_WR.y_in, "start"});
    ctx.log->info("simulating ring '{}' of {} ({:.0f} in), {:.0f} in wide hallway, real-time "
                  "factor {:g}; seed {}; start {:.1f} in = edge {} + {:.1f} in, {:+.1f} in off the "
                  "hallway axis (drawn within +-{:g}), heading error {:+.1f} deg (within +-{:g})",
                  sim_->ring_id(), map.info().name, sim_->ring_length_in(),
                  world.hallway_width_in, rtf_, seed, start_in, t.edge_index, t.offset_in,
                  t.lateral_offset_in, max_offset_in, RadToDeg(t.heading_error_rad),
                  max_heading_deg);

    encoders_ = std::make_unique<runtime::Writer<msgs::EncoderReadingPubSubType>>(
        ctx.participant, "device/base/encoders");
    sonar_ = std::make_unique<runtime::Writer<msgs::SonarEchoPubSubType>>(ctx.participant,
                                                                         "device/sonar/echo");
    camera_ = std::make_unique<runtime::Writer<msgs::ImagePubSubType>>(ctx.participant,
                                                                      "device/camera/frame");
    truth_ = std::make_unique<runtime::Writer<msgs::GroundTruthPubSubType>>(ctx.participant,
                                                                           "sim/ground_truth");
    wheels_ = std::make_unique<runtime::Reader<msgs::WheelCommandPubSubType>>(
        ctx.participant, ctx.executor, "device/base/wheel_command",
        [this](const msgs::WheelCommand& w) { OnWheels(w); });
    // The simulation knows the truth, so it is where a recovered pose is judged.
    poses_ = std::make_unique<runtime::Reader<msgs::LocalizationPosePubSubType>>(
        ctx.participant, ctx.executor, "localization/pose",
        [this](const msgs::LocalizationPose& p) { OnPose(p); });
    // Rates are in simulated time: faster than real time, every timer runs rtf times as often.
    sim_period_s_ = 1.0 / config.sim_rate_hz;
    camera_rate_hz_ = config.camera_rate_hz;
    ctx.executor.AddTimer(1.0 / (config.sim_rate_hz * rtf_), [this] { StepSim(); });
    ctx.executor.AddTimer(1.0 / (config.encoder_rate_hz * rtf_), [this] { PublishEncoders(); });
    ctx.executor.AddTimer(1.0 / (config.sonar_rate_hz * rtf_), [this] { PublishSonar(); });
    ctx.executor.AddTimer(1.0 / (config.camera_rate_hz * rtf_), [this] { PublishFrame(); });
  }

  void Activate() override {
    start_wall_ns_ = last_step_ns_ = ctx_->now_ns();
  }

  // Simulated time: starts at the wall clock and runs rtf times as fast. Every sample the
  // virtual robot serves is stamped with it, so the processes that pair samples by time
  // stay consistent at any real-time factor.
  int64_t SimNowNs() const {
    return start_wall_ns_ + static_cast<int64_t>((ctx_->now_ns() - start_wall_ns_) * rtf_);
  }

  void Deactivate() override {
    if (summary_png_.empty()) return;
    map::RenderOptions options;
    options.paths.push_back(map::PathOverlay{path_});
    options.markers = markers_;
    try {
      map::RenderMapPng(*map_, summary_png_, options);
      ctx_->log->info("wrote the map with the path to {}", summary_png_);
    } catch (const std::exception& e) {
      ctx_->log->warn("could not write {}: {}", summary_png_, e.what());
    }
  }

  std::string Summary() const override {
    const SimTruth t = sim_->Truth();
    std::string checks;
    for (const std::string& c : pose_checks_) checks += "; " + c;
    // Keeping up: the frames due in the simulated time run, and the longest simulation step
    // (the timer fires late when the machine cannot keep up, and the step grows).
    const double sim_s = start_wall_ns_ > 0 ? (SimNowNs() - start_wall_ns_) * 1e-9 : 0.0;
    return fmt::format(
        "{}; {} frames ({:.0f} due), {} sonar scans served; {:.1f} s simulated at {:g}x real "
        "time, longest step {:.0f} ms (nominal {:.0f}); travelled {:.1f} in, now on edge {} of "
        "ring '{}'; {} collisions; after 20 ft, beyond 8 ft of corners: max |offset| {:.1f} in, "
        "max |heading error| {:.1f} deg{}",
        start_check_, frames_, sim_s * camera_rate_hz_, scans_, sim_s, rtf_, max_step_s_ * 1e3,
        sim_period_s_ * 1e3, t.distance_in, t.edge_index, sim_->ring_id(), t.collisions,
        max_offset_in_, max_heading_deg_, checks.empty() ? "; no pose recovered" : checks);
  }

 private:
  void OnWheels(const msgs::WheelCommand& w) {
    ctx_->counters.CountIn();
    if (!std::isfinite(w.left_speed_ftps()) || !std::isfinite(w.right_speed_ftps())) {
      ctx_->counters.Drop("device/base/wheel_command", "non-finite wheel speed");
      return;
    }
    left_ftps_ = w.left_speed_ftps();
    right_ftps_ = w.right_speed_ftps();
    last_wheels_ns_ = ctx_->now_ns();
  }

  void OnPose(const msgs::LocalizationPose& p) {
    if (p.status() != msgs::LOCALIZATION_LOCALIZED) {
      judged_ = false;  // the next LOCALIZED is a new recovery (after LOST)
      return;
    }
    if (judged_) return;
    judged_ = true;
    const SimTruth t = sim_->Truth();
    const bool forward = t.seen_forward_in_ring;
    const bool correct =
        PoseMatchesTruth(p.best().ring_id(), static_cast<int>(p.best().edge_index()),
                         p.best().forward(), t);
    const double sim_s = (SimNowNs() - start_wall_ns_) * 1e-9;
    const double wall_s = (ctx_->now_ns() - start_wall_ns_) * 1e-9;
    const double travelled_in = t.distance_in - recovery_start_in_;
    std::string check = fmt::format(
        "pose recovered after {} edges, {:.1f} ft, {:.1f} s simulated ({:.1f} s wall): ring '{}' "
        "edge {} {}; truth ring '{}' edge {} {}: {}",
        p.edges_sensed(), InchesToFeet(travelled_in), sim_s - recovery_start_s_,
        wall_s - recovery_start_wall_s_, p.best().ring_id(), p.best().edge_index(),
        p.best().forward() ? "forward" : "backward", t.seen_ring_id, t.seen_edge_index,
        forward ? "forward" : "backward", correct ? "CORRECT" : "INCORRECT");
    ctx_->log->info("{}", check);
    pose_checks_.push_back(check);
    markers_.push_back({t.X_WR.x_in, t.X_WR.y_in, fmt::format("recovered {}", pose_checks_.size())});
    if (kidnap_after_s_ >= 0.0 && !kidnapped_) {
      kidnap_at_sim_s_ = sim_s + kidnap_after_s_;
    }
  }

  // Teleports the robot (a kidnapping) once the configured time after recovery has passed.
  void MaybeKidnap() {
    if (kidnapped_ || kidnap_at_sim_s_ < 0.0) return;
    const double sim_s = (SimNowNs() - start_wall_ns_) * 1e-9;
    if (sim_s < kidnap_at_sim_s_) return;
    kidnapped_ = true;
    const SimTruth before = sim_->Truth();
    const double ring_position = sim_->RingPosition() + kidnap_jump_in_;
    sim_->Teleport(ring_position);
    const SimTruth after = sim_->Truth();
    ctx_->log->info("kidnapped: teleported from edge {} to edge {} ({:+.0f} in along the ring)",
                    before.edge_index, after.edge_index, kidnap_jump_in_);
    markers_.push_back({after.X_WR.x_in, after.X_WR.y_in, "kidnapped to"});
    path_.push_back({after.X_WR.x_in, after.X_WR.y_in});
    recovery_start_in_ = after.distance_in;
    recovery_start_s_ = sim_s;
    recovery_start_wall_s_ = (ctx_->now_ns() - start_wall_ns_) * 1e-9;
  }

  void StepSim() {
    const int64_t now = ctx_->now_ns();
    // The base's watchdog: no set-point for a while means stop.
    if (now - last_wheels_ns_ > wheel_timeout_s_ * 1e9) left_ftps_ = right_ftps_ = 0.0;
    const double step_s = (now - last_step_ns_) * 1e-9 * rtf_;
    sim_->Step(step_s, left_ftps_, right_ftps_);
    LogMotionChange(now);
    max_step_s_ = std::max(max_step_s_, step_s);
    last_step_ns_ = now;
    const SimTruth t = sim_->Truth();
    if (t.collisions > collisions_) {
      collisions_ = t.collisions;
      ctx_->log->warn("collision: the base touched a wall at ({:.0f}, {:.0f}) in, {:+.1f} in off "
                      "the hallway axis; it stalls there (collision {})",
                      t.X_WR.x_in, t.X_WR.y_in, t.lateral_offset_in, t.collisions);
    }
    // The navigation envelope of §6.4.2 is judged on straight runs, away from corners.
    if (t.corner_distance_in > kEnvelopeCornerDistanceIn &&
        t.distance_in > kEnvelopeSettleDistanceIn) {
      max_offset_in_ = std::max(max_offset_in_, std::abs(t.lateral_offset_in));
      max_heading_deg_ = std::max(max_heading_deg_, std::abs(RadToDeg(t.heading_error_rad)));
    }
  }

  // The base starting and coming to rest, on the wall clock (seconds since the Unix epoch),
  // so a run's log shows when the robot really stopped (e.g. after its link was cut).
  void LogMotionChange(int64_t now_ns) {
    const bool moving = std::max(std::abs(left_ftps_), std::abs(right_ftps_)) > kAtRestFtps;
    if (moving == moving_) return;
    moving_ = moving;
    ctx_->log->info("truth: base {} at wall clock {:.3f} s", moving ? "moving" : "at rest",
                    now_ns * 1e-9);
  }

  void PublishEncoders() {
    MaybeKidnap();
    msgs::EncoderReading e;
    e.left_travel_in(sim_->left_travel_in());
    e.right_travel_in(sim_->right_travel_in());
    if (encoders_->Publish(e, SimNowNs())) ctx_->counters.CountOut();
    const SimTruth t = sim_->Truth();
    msgs::GroundTruth g;
    g.pose().x_in(t.X_WR.x_in);
    g.pose().y_in(t.X_WR.y_in);
    g.pose().heading_rad(t.X_WR.theta_rad);
    // Where the camera looks over the whole floor: the place a pose is judged on, live and
    // in a replay alike.
    g.ring_id(t.seen_ring_id);
    g.edge_index(static_cast<uint32_t>(t.seen_edge_index));
    g.offset_in(t.seen_offset_in);
    g.distance_in(t.distance_in);
    g.lateral_offset_in(t.lateral_offset_in);
    g.heading_error_deg(RadToDeg(t.heading_error_rad));
    g.collisions(static_cast<uint32_t>(t.collisions));
    g.forward_in_ring(t.seen_forward_in_ring);
    if (std::hypot(t.X_WR.x_in - path_.back().first, t.X_WR.y_in - path_.back().second) > 6.0) {
      path_.push_back({t.X_WR.x_in, t.X_WR.y_in});
    }
    truth_->Publish(g, SimNowNs());
  }

  void PublishSonar() {
    msgs::SonarEcho s;
    s.range_in(sim_->Sonar());
    if (sonar_->Publish(s, SimNowNs())) {
      ctx_->counters.CountOut();
      scans_++;
    }
  }

  void PublishFrame() {
    msgs::Image img;
    img.width_px(static_cast<uint32_t>(sim_->image_width_px()));
    img.height_px(static_cast<uint32_t>(sim_->image_height_px()));
    img.step_bytes(img.width_px());
    img.encoding("mono8");
    img.data(sim_->RenderFrame());
    if (camera_->Publish(img, SimNowNs())) {
      ctx_->counters.CountOut();
      frames_++;
    }
  }

  VirtualRobotConfig config_;
  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<WorldSim> sim_;
  double rtf_ = 1.0;
  int64_t start_wall_ns_ = 0;
  double wheel_timeout_s_ = 0.5;
  double left_ftps_ = 0.0, right_ftps_ = 0.0;
  int64_t last_wheels_ns_ = 0, last_step_ns_ = 0;
  uint64_t frames_ = 0, scans_ = 0;
  double max_step_s_ = 0.0, sim_period_s_ = 0.02, camera_rate_hz_ = 5.0;
  int collisions_ = 0;
  static constexpr double kAtRestFtps = 0.01;
  bool moving_ = false;
  double max_offset_in_ = 0.0, max_heading_deg_ = 0.0;
  std::unique_ptr<map::Map> map_;
  std::string start_check_;
  std::vector<std::string> pose_checks_;
  bool judged_ = false;
  double kidnap_after_s_ = -1.0, kidnap_jump_in_ = 0.0, kidnap_at_sim_s_ = -1.0;
  bool kidnapped_ = false;
  double recovery_start_in_ = 0.0, recovery_start_s_ = 0.0, recovery_start_wall_s_ = 0.0;
  std::string summary_png_;
  std::vector<std::pair<double, double>> path_;
  std::vector<map::MarkerOverlay> markers_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  std::unique_ptr<runtime::Writer<msgs::EncoderReadingPubSubType>> encoders_;
  std::unique_ptr<runtime::Writer<msgs::SonarEchoPubSubType>> sonar_;
  std::unique_ptr<runtime::Writer<msgs::ImagePubSubType>> camera_;
  std::unique_ptr<runtime::Writer<msgs::GroundTruthPubSubType>> truth_;
  std::unique_ptr<runtime::Reader<msgs::WheelCommandPubSubType>> wheels_;
};

}  // namespace

// The node the config's `source` asks for, made once the config is read.
class SourceNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    VirtualRobotConfig config = LoadVirtualRobotConfig(ctx.config);
    node_ = config.replay ? MakeReplayRobotNode(config)
                          : std::make_unique<VirtualRobotNode>(std::move(config));
    node_->Configure(ctx);
  }
  void Activate() override { node_->Activate(); }
  void Deactivate() override { node_->Deactivate(); }
  std::string Summary() const override { return node_ ? node_->Summary() : ""; }

 private:
  std::unique_ptr<runtime::ProcessNode> node_;
};

std::unique_ptr<runtime::ProcessNode> MakeVirtualRobotNode() {
  return std::make_unique<SourceNode>();
}

}  // namespace stickrep::virtual_robot
