#include "localizer/localizer_node.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "localizer/localizer.h"
#include "localizer/localizer_config.h"
#include "localizer/map_msg.h"
#include "perceptionPubSubTypes.h"
#include "runtime/endpoint.h"
#include "runtime/latency.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"

namespace stickrep::localizer {

namespace {

std::optional<map::DoorClass> FromMsg(msgs::DoorClass c) {
  switch (c) {
    case msgs::DOOR_30: return map::DoorClass::k30;
    case msgs::DOOR_32: return map::DoorClass::k32;
    case msgs::DOOR_36: return map::DoorClass::k36;
    case msgs::DOOR_40: return map::DoorClass::k40;
    case msgs::DOOR_30_30: return map::DoorClass::k30_30;
    case msgs::DOOR_36_36: return map::DoorClass::k36_36;
    default: return std::nullopt;
  }
}

msgs::LocalizationStatus ToMsg(Status s) {
  switch (s) {
    case Status::kRecovering: return msgs::LOCALIZATION_RECOVERING;
    case Status::kLocalized: return msgs::LOCALIZATION_LOCALIZED;
    case Status::kLost: return msgs::LOCALIZATION_LOST;
  }
  return msgs::LOCALIZATION_RECOVERING;
}

class LocalizerNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    LocalizerSettings settings = LoadLocalizerSettings(ctx.config);
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    settings.view.camera_fov_deg = robot.camera.fov_deg;  // doors too wide to see whole
    view_ = std::make_unique<map::HallwayView>(map::LoadMap(ctx.system.map_file), settings.view);
    const map::Map& matched = view_->view();
    coaxial_sensor_ = robot.camera.coaxial_sensor;
    head_radius_in_ = robot.sonar_ring.head_radius_in;
    const LocalizerConfig config = MakeLocalizerConfig(settings, matched);
    if (config.method == MatchMethod::kBayes) {
      ctx.log->info("Bayes matcher: error model {}, threshold {}", settings.error_model_file,
                    config.bayes.settings.threshold);
    }
    localizer_ = std::make_unique<Localizer>(matched, config);
    ctx.log->info("map '{}': {} rings, {} edges; matched as the hallway follower senses it: "
                  "{} edges ({} wall steps under {} in passed straight)",
                  matched.info().name, matched.RingCount(), view_->original().EdgeCount(),
                  matched.EdgeCount(), view_->steps_removed(), settings.view.max_step_in);

    pose_ = std::make_unique<runtime::Writer<msgs::LocalizationPosePubSubType>>(
        ctx.participant, "localization/pose");
    hypotheses_ = std::make_unique<runtime::Writer<msgs::PoseHypothesesPubSubType>>(
        ctx.participant, "localization/hypotheses");
    map_writer_ = std::make_unique<runtime::Writer<msgs::StickRepMapPubSubType>>(
        ctx.participant, "map/stickrep");
    landmarks_ = std::make_unique<runtime::Reader<msgs::LandmarkObservationPubSubType>>(
        ctx.participant, ctx.executor, "perception/landmark",
        [this](const msgs::LandmarkObservation& o) { OnLandmark(o); });
    sonar_ = std::make_unique<runtime::Reader<msgs::SonarScanPubSubType>>(
        ctx.participant, ctx.executor, "robot/sonar",
        [this](const msgs::SonarScan& s) { OnSonar(s); });
    odometry_ = std::make_unique<runtime::Reader<msgs::OdometryPubSubType>>(
        ctx.participant, ctx.executor, "robot/odometry",
        [this](const msgs::Odometry& o) { OnOdometry(o); });
    ctx.executor.AddTimer(1.0 / settings.publish_rate_hz, [this] { PublishPose(); });
  }

  void Activate() override {
    msgs::StickRepMap m = localizer::ToMsg(view_->original());
    map_writer_->Publish(m, ctx_->now_ns());
    PublishPose();
  }

  std::string Summary() const override {
    const PoseEstimate& e = localizer_->estimate();
    return fmt::format("{} landmarks used, {} edges sensed, {} restarts, {} losses; status {} "
                       "with {} candidates; landmark observation to localizer {}; odometry to "
                       "pose update {}",
                       landmarks_used_, localizer_->edges_total(), localizer_->restarts(),
                       localizer_->losses(), ToString(e.status), e.candidates,
                       observation_latency_.Summary(), pose_latency_.Summary());
  }

 private:
  void OnLandmark(const msgs::LandmarkObservation& o) {
    ctx_->counters.CountIn();
    const auto door = FromMsg(o.door_class());
    if (!door) {
      ctx_->counters.Drop("perception/landmark", "not a door class");
      return;
    }
    if (!std::isfinite(o.width_in()) || o.width_in() <= 0.0 ||
        !std::isfinite(o.odometry_distance_in()) || !std::isfinite(o.center_offset_in())) {
      ctx_->counters.Drop("perception/landmark", "non-finite or non-positive width or position");
      return;
    }
    localizer_->AddSighting(
        {*door, o.width_in(), o.confidence(), o.odometry_distance_in() + o.center_offset_in()});
    landmarks_used_++;
    // Wall clock from the landmark process writing the observation to here (the header
    // carries the frame's time, simulated on the virtual robot).
    observation_latency_.Add((ctx_->now_ns() - landmarks_->source_timestamp_ns()) * 1e-6);
  }

  // The coaxial sensor looks along the optical axis at the camera's wall: its range is how
  // far the wall is, which places the walls at a corner (EdgeAssembler::PlaceCorner).
  void OnSonar(const msgs::SonarScan& s) {
    ctx_->counters.CountIn();
    if (s.reading_state()[coaxial_sensor_] != msgs::SONAR_VALID) return;  // no wall there
    const double range = s.range_in()[coaxial_sensor_];
    if (!std::isfinite(range) || range <= 0.0) {
      ctx_->counters.Drop("robot/sonar", "a reading marked valid is not a positive range");
      return;
    }
    localizer_->SetWallRange(range + head_radius_in_);
  }

  void OnOdometry(const msgs::Odometry& o) {
    ctx_->counters.CountIn();
    if (!std::isfinite(o.distance_in())) {
      ctx_->counters.Drop("robot/odometry", "non-finite distance");
      return;
    }
    if (!std::isfinite(o.pose().heading_rad())) {
      ctx_->counters.Drop("robot/odometry", "non-finite heading");
      return;
    }
    if (localizer_->Advance(o.distance_in(), o.pose().heading_rad())) {
      const PoseEstimate& e = localizer_->estimate();
      PublishPose();
      // Wall clock from locomotion writing the odometry that completed an edge to the pose
      // written: transport, matching, publication.
      pose_latency_.Add((ctx_->now_ns() - odometry_->source_timestamp_ns()) * 1e-6);
      ctx_->log->info("{}: {} ({} edges sensed)", ToString(e.status), e.message, e.edges_sensed);
      if (e.status == Status::kLocalized && !was_localized_) {
        ctx_->log->info("sensed: {}", map::Describe(localizer_->sensed_sequence()));
      }
      was_localized_ = e.status == Status::kLocalized;
    }
  }

  void PublishPose() {
    const PoseEstimate& e = localizer_->estimate();
    msgs::LocalizationPose p;
    p.status(ToMsg(e.status));
    p.candidate_count(static_cast<uint32_t>(e.candidates));
    p.confidence(e.confidence);
    p.edges_sensed(static_cast<uint32_t>(e.edges_sensed));
    p.message(e.message);
    msgs::PoseHypotheses hs;
    for (const Hypothesis& matched : e.hypotheses) {
      const Hypothesis h = OnOriginalMap(*view_, matched);
      msgs::PoseHypothesis m;
      m.ring_id(view_->original().ring(h.ring).id);
      m.edge_index(static_cast<uint32_t>(h.edge));
      m.forward(h.dir > 0);
      m.offset_in(h.offset_in);
      m.pose().x_in(h.x_in);
      m.pose().y_in(h.y_in);
      m.pose().heading_rad(h.heading_rad);
      m.probability(h.probability);
      hs.hypotheses().push_back(m);
    }
    if (!hs.hypotheses().empty()) p.best(hs.hypotheses().front());
    if (pose_->Publish(p, ctx_->now_ns())) ctx_->counters.CountOut();
    hypotheses_->Publish(hs, ctx_->now_ns());
  }

  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<map::HallwayView> view_;  // the map, and the map as sensed
  int coaxial_sensor_ = 0;
  double head_radius_in_ = 0.0;
  std::unique_ptr<Localizer> localizer_;
  uint64_t landmarks_used_ = 0;
  bool was_localized_ = false;
  runtime::LatencyLog observation_latency_, pose_latency_;
  std::unique_ptr<runtime::Writer<msgs::LocalizationPosePubSubType>> pose_;
  std::unique_ptr<runtime::Writer<msgs::PoseHypothesesPubSubType>> hypotheses_;
  std::unique_ptr<runtime::Writer<msgs::StickRepMapPubSubType>> map_writer_;
  std::unique_ptr<runtime::Reader<msgs::LandmarkObservationPubSubType>> landmarks_;
  std::unique_ptr<runtime::Reader<msgs::OdometryPubSubType>> odometry_;
  std::unique_ptr<runtime::Reader<msgs::SonarScanPubSubType>> sonar_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLocalizerNode() {
  return std::make_unique<LocalizerNode>();
}

}  // namespace stickrep::localizer
