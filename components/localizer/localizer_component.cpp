#include "localizer/localizer_component.h"

#include <fmt/format.h>

#include <utility>

#include "localizer/sensed_doors.h"
#include "stickrep/map_io.h"

namespace stickrep::localizer {

namespace {

message::LocalizationStatus ToMessage(Status s) {
  switch (s) {
    case Status::kRecovering: return message::LocalizationStatus::kRecovering;
    case Status::kLocalized: return message::LocalizationStatus::kLocalized;
    case Status::kLost: return message::LocalizationStatus::kLost;
  }
  return message::LocalizationStatus::kRecovering;
}

}  // namespace

LocalizerComponent::LocalizerComponent(component::Context& ctx, const map::Map& map,
                                       LocalizerSettings settings,
                                       const sensing::RobotConfig& robot, Outputs out)
    : ctx_(ctx),
      publish_rate_hz_(settings.publish_rate_hz),
      coaxial_sensor_(robot.camera.coaxial_sensor),
      head_radius_in_(robot.sonar_ring.head_radius_in),
      out_(out) {
  settings.view.camera_fov_deg = robot.camera.fov_deg;  // doors too wide to see whole
  settings = ForMap(std::move(settings), map);
  view_ = std::make_unique<map::HallwayView>(map, settings.view);
  const map::Map& matched = view_->view();
  const LocalizerConfig config = MakeLocalizerConfig(settings, matched);
  if (config.method == MatchMethod::kBayes) {
    ctx.log->info("Bayes matcher ({}): error model {}, declared at confidence {} (posterior {})",
                  ObservationForName(settings.observation_for),
                  settings.observation.error_model_file, settings.observation.localized_confidence,
                  config.bayes.settings.threshold);
  }
  localizer_ = std::make_unique<Localizer>(matched, config);
  ctx.log->info("map '{}': {} rings, {} edges; matched as the hallway follower senses it: "
                "{} edges ({} wall steps under {} in passed straight)",
                matched.info().name, matched.RingCount(), view_->original().EdgeCount(),
                matched.EdgeCount(), view_->steps_removed(), settings.view.max_step_in);
}

std::vector<component::Timer> LocalizerComponent::Timers() {
  return {{1.0 / publish_rate_hz_, [this] { PublishPose(); }}};
}

DoorSighting LocalizerComponent::Sighting(const message::LandmarkObservation& o) {
  return {o.door_class, o.width_in, o.confidence, o.odometry_distance_in + o.center_offset_in,
          o.mark};
}

void LocalizerComponent::OnLandmark(const message::LandmarkObservation& o) {
  localizer_->AddSighting(Sighting(o));
  landmarks_used_++;
}

void LocalizerComponent::OnSonar(const message::SonarScan& scan) {
  if (scan.state[coaxial_sensor_] != sonar::ReadingState::kValid) return;  // no wall there
  localizer_->SetWallRange(scan.range_in[coaxial_sensor_] + head_radius_in_);
}

void LocalizerComponent::OnOdometry(const message::Odometry& odometry) {
  if (!localizer_->Advance(odometry.distance_in, odometry.heading_rad)) return;
  const PoseEstimate& e = localizer_->estimate();
  PublishPose();
  ctx_.log->info("{}: {} ({} edges sensed)", ToString(e.status), e.message, e.edges_sensed);
  if (e.status == Status::kLocalized && !was_localized_) {
    ctx_.log->info("sensed: {}", map::Describe(localizer_->sensed_sequence()));
  }
  was_localized_ = e.status == Status::kLocalized;
}

void LocalizerComponent::PublishPose() {
  const PoseEstimate& e = localizer_->estimate();
  const int64_t now = ctx_.NowNs();
  message::LocalizationPose p;
  p.header.stamp_ns = now;
  p.status = ToMessage(e.status);
  p.candidate_count = e.candidates;
  p.confidence = e.confidence;
  p.edges_sensed = e.edges_sensed;
  p.message = e.message;
  message::PoseHypotheses hs;
  hs.header.stamp_ns = now;
  for (const Hypothesis& matched : e.hypotheses) {
    const Hypothesis h = OnOriginalMap(*view_, matched);
    hs.hypotheses.push_back({view_->original().ring(h.ring).id, h.edge, h.dir > 0, h.offset_in,
                             h.x_in, h.y_in, h.heading_rad, h.probability});
  }
  if (!hs.hypotheses.empty()) p.best = hs.hypotheses.front();
  out_.pose.Publish(p);
  out_.hypotheses.Publish(hs);
}

std::string LocalizerComponent::Summary() const {
  const PoseEstimate& e = localizer_->estimate();
  return fmt::format("{} landmarks used, {} edges sensed, {} restarts, {} losses; status {} "
                     "with {} candidates",
                     landmarks_used_, localizer_->edges_total(), localizer_->restarts(),
                     localizer_->losses(), ToString(e.status), e.candidates);
}

}  // namespace stickrep::localizer
