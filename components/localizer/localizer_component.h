#pragma once

#include <memory>

#include "component/component.h"
#include "localizer/localizer.h"
#include "localizer/localizer_config.h"
#include "messages/messages.h"
#include "sensing/robot_config.h"
#include "stickrep/hallway_view.h"

namespace stickrep::localizer {

// The localizer process's logic: classified doors, the coaxial sonar range and odometry in;
// the pose (status and best place on the original map) and its hypotheses out, on every
// change and at the publish rate. Matching runs on the map as the hallway follower senses it
// (map::HallwayView); what is published names the original map's edges.
class LocalizerComponent : public component::Component {
 public:
  struct Outputs {
    component::Publisher<message::LocalizationPose>& pose;
    component::Publisher<message::PoseHypotheses>& hypotheses;
  };
  // `settings.view.camera_fov_deg` is taken from `robot`.
  LocalizerComponent(component::Context& ctx, const map::Map& map, LocalizerSettings settings,
                     const sensing::RobotConfig& robot, Outputs out);

  void OnLandmark(const message::LandmarkObservation& o);
  // A classified door as the edge assembler takes it: placed along the wall at the
  // odometer reading of its frame plus its centre's offset from the optical axis.
  static DoorSighting Sighting(const message::LandmarkObservation& o);
  // The coaxial sensor looks along the optical axis at the camera's wall: its range is how
  // far the wall is, which places the walls at a corner (EdgeAssembler::PlaceCorner).
  void OnSonar(const message::SonarScan& scan);
  void OnOdometry(const message::Odometry& odometry);
  // Publishes the current estimate (also done on every change).
  void PublishPose();

  std::vector<component::Timer> Timers() override;
  void Activate() override { PublishPose(); }
  std::string Summary() const override;

  const map::HallwayView& view() const { return *view_; }
  const Localizer& localizer() const { return *localizer_; }

 private:
  component::Context& ctx_;
  std::unique_ptr<map::HallwayView> view_;  // the map, and the map as sensed
  double publish_rate_hz_;
  int coaxial_sensor_;
  double head_radius_in_;
  std::unique_ptr<Localizer> localizer_;
  Outputs out_;
  uint64_t landmarks_used_ = 0;
  bool was_localized_ = false;
};

}  // namespace stickrep::localizer
