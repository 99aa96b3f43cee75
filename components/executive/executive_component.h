#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "component/component.h"
#include "executive/executive.h"
#include "executive/executive_config.h"
#include "executive/link_monitor.h"
#include "messages/messages.h"
#include "stickrep/map.h"

namespace stickrep::executive {

// The mission executive's logic: the other processes' heartbeats, the pose, the base's state,
// odometry and goals in; motion commands (at the command rate), the mission's status and each
// goal's result out. A process that dies stops the robot until it is back (restarted); a
// host that falls silent stops the robot until it is heard again (LinkMonitor).
class ExecutiveComponent : public component::Component {
 public:
  struct Outputs {
    component::Publisher<message::MotionCommand>& commands;
    component::Publisher<message::MissionStatus>& status;
    component::Publisher<message::MissionGoalResult>& results;
  };
  // `host`: the host this process runs on. `why_not_heard`: what the transport can tell
  // about components not heard yet (e.g. no discovery server reached); may be empty.
  ExecutiveComponent(component::Context& ctx, const map::Map& map, const ExecutiveConfig& config,
                     const std::string& host, std::function<std::string()> why_not_heard,
                     Outputs out);

  void OnOdometry(const message::Odometry& o);
  void OnHeartbeat(const message::ComponentStatus& s);
  // Every writer of a process's heartbeat is gone (its liveliness lost).
  void OnHeartbeatGone(const std::string& component_name);
  void OnPose(const message::LocalizationPose& p);
  void OnMotionState(const message::MotionState& m);
  void OnGoal(const message::MissionGoal& g);
  // Sends the motion command the mission asks for now; also judges silent links.
  void Tick();

  std::vector<component::Timer> Timers() override;
  void Deactivate() override;
  std::string Summary() const override;

  const Mission& mission() const { return executive_.mission(); }

 private:
  void Handle(const std::vector<LinkMonitor::Event>& events);
  void Report();
  std::string WaitingMessage() const;
  void PublishStatus(const std::string& text, const std::string& goal_id = "");
  double NowS() const { return ctx_.NowNs() * 1e-9; }

  component::Context& ctx_;
  const map::Map& map_;
  Executive executive_;
  Mission& mission_;  // executive_'s
  LinkMonitor links_;
  double command_rate_hz_;
  bool exit_when_localized_;
  std::function<std::string()> why_not_heard_;
  Outputs out_;
  bool localized_ = false;  // the localizer's latest status
  // Each process's latest heartbeat sequence number: one that starts again is a new process.
  std::map<std::string, uint32_t> heartbeat_sequence_;
  int waiting_reports_ = 0;
};

}  // namespace stickrep::executive
