#include "virtual_robot/virtual_robot_node.h"

#include <fmt/format.h>

#include "basePubSubTypes.h"
#include "common/units.h"
#include "localizationPubSubTypes.h"
#include "plot/map_render.h"
#include "runtime/component_node.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"
#include "virtual_robot/replay_robot_node.h"
#include "virtual_robot/virtual_robot_component.h"
#include "virtual_robot/virtual_robot_config.h"

namespace stickrep::virtual_robot {

namespace {

// The virtual robot's component on DDS: wheel commands and poses in; echoes, frames,
// encoders and the ground truth out, on a clock that runs real_time_factor times as fast as
// the wall clock. At exit it draws the map with the true path (summary_png).
class VirtualRobotNode : public runtime::ComponentNode {
 public:
  explicit VirtualRobotNode(VirtualRobotConfig config) : config_(std::move(config)) {}

  void Deactivate() override {
    runtime::ComponentNode::Deactivate();
    if (!config_.summary_png.empty()) WriteSummaryPng();
  }

 protected:
  std::unique_ptr<component::Component> Build(runtime::NodeContext& ctx,
                                              component::Context& component_ctx) override {
    SetRealTimeFactor(config_.real_time_factor);
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    const WorldSimConfig& world = config_.world;
    const int ring = world.ring_id.empty() ? 0 : map_->FindRing(world.ring_id);
    if (ring < 0) {
      ctx.config.Fail("ring_id", "no ring '" + world.ring_id + "' in " + ctx.system.map_file);
    }
    // Off the axis and turned from it, so aligning and centring (A3, A4) has work to do.
    PlacedRobot placed = PlaceRobot(*map_, robot, config_, ring);
    for (const std::string& r : placed.redraws) ctx.log->warn("{}", r);
    const StartPlacement start = placed.start;
    const SimTruth t = placed.sim->Truth();
    ctx.log->info("simulating ring '{}' of {} ({:.0f} in), {:.0f} in wide hallway, real-time "
                  "factor {:g}; seed {}; start {:.1f} in = edge {} + {:.1f} in, {:+.1f} in off the "
                  "hallway axis (drawn within +-{:g}), heading error {:+.1f} deg (within +-{:g})",
                  placed.sim->ring_id(), map_->info().name, placed.sim->ring_length_in(),
                  world.hallway_width_in, config_.real_time_factor, config_.seed,
                  start.ring_position_in, t.edge_index, t.offset_in, t.lateral_offset_in,
                  config_.start_lateral_offset_max_in, RadToDeg(t.heading_error_rad),
                  config_.start_heading_error_max_deg);
    auto component = std::make_unique<VirtualRobotComponent>(
        component_ctx, config_, std::move(placed.sim),
        VirtualRobotComponent::Outputs{
            Publish<msgs::SonarEchoPubSubType>("device/sonar/echo"),
            Publish<msgs::ImagePubSubType>("device/camera/frame"),
            Publish<msgs::EncoderReadingPubSubType>("device/base/encoders"),
            Publish<msgs::GroundTruthPubSubType>("sim/ground_truth")});
    VirtualRobotComponent* c = component.get();
    component_ = c;
    Feed<msgs::WheelCommandPubSubType>("device/base/wheel_command",
                                       [c](const message::WheelCommand& w) { c->OnWheels(w); });
    // The simulation knows the truth, so it is where a recovered pose is judged.
    Feed<msgs::LocalizationPosePubSubType>(
        "localization/pose", [c](const message::LocalizationPose& p) { c->OnPose(p); });
    return component;
  }

 private:
  void WriteSummaryPng() {
    map::RenderOptions options;
    options.paths.push_back(map::PathOverlay{component_->path()});
    for (const VirtualRobotComponent::Marker& m : component_->markers()) {
      options.markers.push_back({m.x_in, m.y_in, m.label});
    }
    try {
      map::RenderMapPng(*map_, config_.summary_png, options);
      ctx().log->info("wrote the map with the path to {}", config_.summary_png);
    } catch (const std::exception& e) {
      ctx().log->warn("could not write {}: {}", config_.summary_png, e.what());
    }
  }

  VirtualRobotConfig config_;
  std::unique_ptr<map::Map> map_;
  VirtualRobotComponent* component_ = nullptr;  // owned by the ComponentNode
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
