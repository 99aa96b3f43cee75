#include "virtual_robot/virtual_robot_node.h"

#include <fmt/format.h>

#include <cmath>
#include <random>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "runtime/endpoint.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::virtual_robot {

namespace {

class VirtualRobotNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const StrictYaml& c = ctx.config;
    const std::string source = c.Get<std::string>("source");
    if (source == "replay") {
      c.Fail("source", "replaying a recording is not built yet; use 'simulated'");
    } else if (source != "simulated") {
      c.Fail("source", "'" + source + "' is not one of: simulated, replay");
    }
    const auto seed = c.Get<uint64_t>("seed");
    double start_in = c.Get<double>("start_offset_in", -1.0, 1e7, "in");
    WorldSimConfig world;
    world.ring_id = c.Get<std::string>("ring_id");
    world.hallway_width_in = c.Get<double>("hallway_width_in", 36.0, 600.0, "in");
    world.open_door_fraction = c.Get<double>("open_door_fraction", 0.0, 1.0);
    world.image_noise_sigma = c.Get<double>("image_noise_sigma", 0.0, 50.0, "grey levels");
    world.sonar_surface_errors = c.Get<bool>("sonar_surface_errors");
    world.wheel_slip_stddev = c.Get<double>("wheel_slip_stddev", 0.0, 0.2);
    rtf_ = c.Get<double>("real_time_factor", 0.1, 50.0);
    const double sim_rate_hz = c.Get<double>("sim_rate_hz", 1.0, 1000.0, "Hz");
    const double encoder_rate_hz = c.Get<double>("encoder_rate_hz", 1.0, 200.0, "Hz");
    const double sonar_rate_hz = c.Get<double>("sonar_rate_hz", 0.5, 50.0, "Hz");
    const double camera_rate_hz = c.Get<double>("camera_rate_hz", 0.5, 60.0, "Hz");
    wheel_timeout_s_ = c.Get<double>("wheel_command_timeout_s", 0.05, 5.0, "s");
    c.Finish();

    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    const map::Map map = map::LoadMap(ctx.system.map_file);
    const int ring = world.ring_id.empty() ? 0 : map.FindRing(world.ring_id);
    if (ring < 0) c.Fail("ring_id", "no ring '" + world.ring_id + "' in " + ctx.system.map_file);
    if (start_in < 0.0) {
      double length_in = 0.0;
      for (const map::Edge& e : map.ring(ring).edges) length_in += e.metric_in;
      std::mt19937_64 pick(seed);
      start_in = std::uniform_real_distribution<double>(0.0, length_in)(pick);
    }
    sim_ = std::make_unique<WorldSim>(map, robot, world, start_in, seed);
    const SimTruth t = sim_->Truth();
    ctx.log->info("simulating ring '{}' of {} ({:.0f} in), {:.0f} in wide hallway, real-time "
                  "factor {:g}; seed {}; start {:.1f} in = edge {} + {:.1f} in",
                  sim_->ring_id(), map.info().name, sim_->ring_length_in(),
                  world.hallway_width_in, rtf_, seed, start_in, t.edge_index, t.offset_in);

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
    ctx.executor.AddTimer(1.0 / (sim_rate_hz * rtf_), [this] { StepSim(); });
    ctx.executor.AddTimer(1.0 / (encoder_rate_hz * rtf_), [this] { PublishEncoders(); });
    ctx.executor.AddTimer(1.0 / (sonar_rate_hz * rtf_), [this] { PublishSonar(); });
    ctx.executor.AddTimer(1.0 / (camera_rate_hz * rtf_), [this] { PublishFrame(); });
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

  std::string Summary() const override {
    const SimTruth t = sim_->Truth();
    return fmt::format("{} frames, {} sonar scans served; travelled {:.1f} in, now on edge {} of "
                       "ring '{}'{}",
                       frames_, scans_, t.distance_in, t.edge_index, sim_->ring_id(),
                       pose_check_.empty() ? "; no pose recovered" : "; " + pose_check_);
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
    if (p.status() != msgs::LOCALIZATION_LOCALIZED || !pose_check_.empty()) return;
    const SimTruth t = sim_->Truth();
    const bool forward = t.forward_in_ring;
    const int n = sim_->edge_count();
    const int de = std::abs(static_cast<int>(p.best().edge_index()) - t.edge_index);
    // The localizer names the edge the robot is in once the last door has left the view;
    // allow the neighbouring edge for the moment of crossing a node.
    const bool correct = p.best().ring_id() == sim_->ring_id() && p.best().forward() == forward &&
                         (de <= 1 || de == n - 1);
    pose_check_ = fmt::format("pose recovered after {:.1f} in: ring '{}' edge {} {}; truth ring "
                              "'{}' edge {} {}: {}",
                              t.distance_in, p.best().ring_id(),
                              p.best().edge_index(), p.best().forward() ? "forward" : "backward",
                              sim_->ring_id(), t.edge_index, forward ? "forward" : "backward",
                              correct ? "CORRECT" : "INCORRECT");
    ctx_->log->info("{}", pose_check_);
  }

  void StepSim() {
    const int64_t now = ctx_->now_ns();
    // The base's watchdog: no set-point for a while means stop.
    if (now - last_wheels_ns_ > wheel_timeout_s_ * 1e9) left_ftps_ = right_ftps_ = 0.0;
    sim_->Step((now - last_step_ns_) * 1e-9 * rtf_, left_ftps_, right_ftps_);
    last_step_ns_ = now;
  }

  void PublishEncoders() {
    msgs::EncoderReading e;
    e.left_travel_in(sim_->left_travel_in());
    e.right_travel_in(sim_->right_travel_in());
    if (encoders_->Publish(e, SimNowNs())) ctx_->counters.CountOut();
    const SimTruth t = sim_->Truth();
    msgs::GroundTruth g;
    g.pose().x_in(t.X_WR.x_in);
    g.pose().y_in(t.X_WR.y_in);
    g.pose().heading_rad(t.X_WR.theta_rad);
    g.ring_id(sim_->ring_id());
    g.edge_index(static_cast<uint32_t>(t.edge_index));
    g.offset_in(t.offset_in);
    g.distance_in(t.distance_in);
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

  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<WorldSim> sim_;
  double rtf_ = 1.0;
  int64_t start_wall_ns_ = 0;
  double wheel_timeout_s_ = 0.5;
  double left_ftps_ = 0.0, right_ftps_ = 0.0;
  int64_t last_wheels_ns_ = 0, last_step_ns_ = 0;
  uint64_t frames_ = 0, scans_ = 0;
  std::string pose_check_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  std::unique_ptr<runtime::Writer<msgs::EncoderReadingPubSubType>> encoders_;
  std::unique_ptr<runtime::Writer<msgs::SonarEchoPubSubType>> sonar_;
  std::unique_ptr<runtime::Writer<msgs::ImagePubSubType>> camera_;
  std::unique_ptr<runtime::Writer<msgs::GroundTruthPubSubType>> truth_;
  std::unique_ptr<runtime::Reader<msgs::WheelCommandPubSubType>> wheels_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeVirtualRobotNode() {
  return std::make_unique<VirtualRobotNode>();
}

}  // namespace stickrep::virtual_robot
