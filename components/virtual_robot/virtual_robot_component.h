#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "component/component.h"
#include "messages/messages.h"
#include "virtual_robot/virtual_robot_config.h"
#include "virtual_robot/world_sim.h"

namespace stickrep::virtual_robot {

// A localized pose set beside where the robot truly was when it was declared.
struct PoseCheck {
  std::string ring_id;
  int edge = 0;
  bool forward = true;
  std::string truth_ring_id;
  int truth_edge = 0;
  bool truth_forward = true;
  bool correct = false;
  int edges_sensed = 0;
  double distance_ft = 0.0;  // travelled since the start (or since the kidnap)
  double time_s = 0.0;       // simulated, likewise
};

// "pose recovered after 5 edges, 22.5 ft, 15.4 s simulated: ring 'r' edge 59 backward; truth
// ring 'r' edge 59 backward: CORRECT".
std::string Describe(const PoseCheck& c);

// The virtual robot's logic: the hardware and the world. It moves the simulated base by the
// wheel commands it is given (stopping it when they stop coming), serves encoder readings,
// sonar echoes and camera frames at their configured rates, and, as the one that knows the
// truth, publishes sim/ground_truth and judges every pose the localizer declares. It can
// kidnap the robot a while after the first pose (pose maintenance runs). Rates and times are
// simulated: the clock it is given is the simulation's.
class VirtualRobotComponent : public component::Component {
 public:
  struct Outputs {
    component::Publisher<message::SonarEcho>& echoes;
    component::Publisher<message::Image>& frames;
    component::Publisher<message::EncoderReading>& encoders;
    component::Publisher<message::GroundTruth>& truth;
  };
  // `sim` is the world with the robot at its start (PlaceRobot).
  VirtualRobotComponent(component::Context& ctx, const VirtualRobotConfig& config,
                        std::unique_ptr<WorldSim> sim, Outputs out);

  void OnWheels(const message::WheelCommand& w);
  void OnPose(const message::LocalizationPose& p);

  std::vector<component::Timer> Timers() override;
  void Activate() override;
  std::string Summary() const override;

  WorldSim& sim() { return *sim_; }
  const WorldSim& sim() const { return *sim_; }
  // "ring 'r' edge e + o in, x in off the axis, heading h deg (seed s)".
  const std::string& start() const { return start_; }
  const std::vector<PoseCheck>& checks() const { return checks_; }
  bool kidnapped() const { return kidnapped_; }
  // How far the base has travelled since the start, or since the kidnap.
  double TravelledSinceEpochFt() const;
  // The base's true path (a point every 3 in) and the places worth marking on it.
  const std::vector<std::pair<double, double>>& path() const { return path_; }
  struct Marker {
    double x_in, y_in;
    std::string label;
  };
  const std::vector<Marker>& markers() const { return markers_; }
  int frames() const { return frames_; }
  // On straight runs of the start ring's hallway (beyond 8 ft of a corner, after 20 ft), the
  // largest offset from the hallway axis and heading error (§6.4.2's envelope); and how far
  // the base travelled outside that hallway after 20 ft (another corridor of the floor, a
  // hall), where the envelope is not judged.
  double max_offset_in() const { return max_offset_in_; }
  double max_heading_deg() const { return max_heading_deg_; }
  double off_ring_ft() const { return off_ring_in_ / 12.0; }
  // Simulated seconds since activation.
  double ElapsedS() const;

 private:
  void Step();
  void PublishEncodersAndTruth();
  void PublishEcho();
  void PublishFrame();
  void MaybeKidnap();
  void Record(const SimTruth& t);
  void LogMotionChange();
  PoseCheck Judge(const message::LocalizationPose& p) const;
  message::Header Stamp() const;

  component::Context& ctx_;
  VirtualRobotConfig config_;
  std::unique_ptr<WorldSim> sim_;
  Outputs out_;
  std::string start_;
  int64_t start_ns_ = 0, last_step_ns_ = 0, last_wheels_ns_ = 0;
  double left_ftps_ = 0.0, right_ftps_ = 0.0;
  double max_step_s_ = 0.0;
  bool moving_ = false;
  int frames_ = 0, scans_ = 0, collisions_ = 0;
  double max_offset_in_ = 0.0, max_heading_deg_ = 0.0;
  double off_ring_in_ = 0.0, recorded_distance_in_ = 0.0;
  std::vector<PoseCheck> checks_;
  bool judged_ = false;
  double kidnap_at_s_ = -1.0;
  bool kidnapped_ = false;
  double epoch_in_ = 0.0, epoch_s_ = 0.0;  // where the current recovery began
  std::vector<std::pair<double, double>> path_;
  std::vector<Marker> markers_;
};

}  // namespace stickrep::virtual_robot
