#include "landmark/landmark_node.h"

#include <fmt/format.h>

#include <map>

#include "basePubSubTypes.h"
#include "landmark/landmark_component.h"
#include "landmark/landmark_config.h"
#include "perceptionPubSubTypes.h"
#include "runtime/component_node.h"
#include "runtime/latency.h"
#include "sensorsPubSubTypes.h"

namespace stickrep::landmark {

namespace {

// Observations written on DDS, with the latency from the camera process writing the frame
// to this process writing the observation made from it (wall clock).
class TimedObservations : public component::Publisher<message::LandmarkObservation> {
 public:
  TimedObservations(runtime::NodeContext& ctx,
                    component::Publisher<message::LandmarkObservation>& out)
      : ctx_(ctx), out_(out) {}
  // The camera process wrote the frame stamped `stamp_ns` at wall time `written_ns`.
  void FrameArrived(int64_t stamp_ns, int64_t written_ns) {
    written_at_ns_[stamp_ns] = written_ns;
    while (written_at_ns_.size() > 64) written_at_ns_.erase(written_at_ns_.begin());
  }
  bool Publish(const message::LandmarkObservation& o) override {
    if (!out_.Publish(o)) return false;
    const auto it = written_at_ns_.find(o.image_stamp_ns);
    if (it != written_at_ns_.end()) latency_.Add((ctx_.now_ns() - it->second) * 1e-6);
    return true;
  }
  std::string Summary() const { return latency_.Summary(); }

 private:
  runtime::NodeContext& ctx_;
  component::Publisher<message::LandmarkObservation>& out_;
  std::map<int64_t, int64_t> written_at_ns_;  // frame stamp -> when the camera wrote it
  runtime::LatencyLog latency_;
};

class LandmarkNode : public runtime::ComponentNode {
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& cc) override {
    const LandmarkConfig config = LoadLandmarkConfig(ctx.config);
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    observations_ = std::make_unique<TimedObservations>(
        ctx, Publish<msgs::LandmarkObservationPubSubType>("perception/landmark"));
    auto landmark = std::make_unique<LandmarkComponent>(cc, robot, config, *observations_);
    LandmarkComponent* c = landmark.get();
    Feed<msgs::SonarScanPubSubType>("robot/sonar",
                                    [c](const message::SonarScan& s) { c->OnScan(s); });
    Feed<msgs::OdometryPubSubType>("robot/odometry",
                                   [c](const message::Odometry& o) { c->OnOdometry(o); });
    images_ = &Feed<msgs::ImagePubSubType>("robot/camera/image", [this, c](const message::Image& m) {
      observations_->FrameArrived(m.header.stamp_ns, images_->source_timestamp_ns());
      c->OnImage(m);
    });
    return landmark;
  }

  std::string Summary() const override {
    return fmt::format("{}; camera frame to observation {}", ComponentNode::Summary(),
                       observations_->Summary());
  }

  std::unique_ptr<TimedObservations> observations_;
  runtime::Reader<msgs::ImagePubSubType>* images_ = nullptr;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeLandmarkNode() { return std::make_unique<LandmarkNode>(); }

}  // namespace stickrep::landmark
