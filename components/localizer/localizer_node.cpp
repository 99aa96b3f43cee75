#include "localizer/localizer_node.h"

#include <fmt/format.h>

#include "basePubSubTypes.h"
#include "localizationPubSubTypes.h"
#include "localizer/localizer_component.h"
#include "localizer/localizer_config.h"
#include "localizer/map_msg.h"
#include "perceptionPubSubTypes.h"
#include "runtime/component_node.h"
#include "runtime/latency.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"

namespace stickrep::localizer {

namespace {

// The localizer component on DDS. The node also publishes the map (map/stickrep, kept for
// late joiners such as the console) and measures, on the wall clock, the latency from the
// landmark process writing an observation to it arriving here, and from locomotion writing
// the odometry that completed an edge to the pose written.
class LocalizerNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const LocalizerSettings settings = LoadLocalizerSettings(ctx.config);
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    pose_ = &Publish<msgs::LocalizationPosePubSubType>("localization/pose");
    auto localizer = std::make_unique<LocalizerComponent>(
        cc, *map_, settings, robot,
        LocalizerComponent::Outputs{
            *pose_, Publish<msgs::PoseHypothesesPubSubType>("localization/hypotheses")});
    LocalizerComponent* c = localizer.get();
    component_ = c;
    map_writer_ = std::make_unique<runtime::Writer<msgs::StickRepMapPubSubType>>(
        ctx.participant, "map/stickrep");
    landmarks_ = &Feed<msgs::LandmarkObservationPubSubType>(
        "perception/landmark", [this, c](const message::LandmarkObservation& o) {
          c->OnLandmark(o);
          observation_latency_.Add((this->ctx().now_ns() - landmarks_->source_timestamp_ns()) * 1e-6);
        });
    Feed<msgs::SonarScanPubSubType>("robot/sonar",
                                    [c](const message::SonarScan& s) { c->OnSonar(s); });
    odometry_ = &Feed<msgs::OdometryPubSubType>("robot/odometry", [this, c](const message::Odometry& o) {
      const uint64_t poses_before = pose_->writer().counters().samples;
      c->OnOdometry(o);
      if (pose_->writer().counters().samples > poses_before) {
        pose_latency_.Add((this->ctx().now_ns() - odometry_->source_timestamp_ns()) * 1e-6);
      }
    });
    return localizer;
  }

  void Activate() override {
    msgs::StickRepMap m = localizer::ToMsg(component_->view().original());
    map_writer_->Publish(m, ctx().now_ns());
    ComponentNode::Activate();
  }

  std::string Summary() const override {
    return fmt::format("{}; landmark observation to localizer {}; odometry to pose update {}",
                       ComponentNode::Summary(), observation_latency_.Summary(),
                       pose_latency_.Summary());
  }

  std::unique_ptr<map::Map> map_;
  LocalizerComponent* component_ = nullptr;
  runtime::DdsPublisher<msgs::LocalizationPosePubSubType, message::LocalizationPose>* pose_ =
      nullptr;
  std::unique_ptr<runtime::Writer<msgs::StickRepMapPubSubType>> map_writer_;
  runtime::Reader<msgs::LandmarkObservationPubSubType>* landmarks_ = nullptr;
  runtime::Reader<msgs::OdometryPubSubType>* odometry_ = nullptr;
  runtime::LatencyLog observation_latency_, pose_latency_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLocalizerNode() {
  return std::make_unique<LocalizerNode>();
}

}  // namespace stickrep::localizer
