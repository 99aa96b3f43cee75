#include "virtual_robot/replay_robot_node.h"

#include <fmt/format.h>

#include <cstring>
#include <mutex>
#include <optional>

#include "localizationPubSubTypes.h"
#include "recording/replay_session.h"
#include "runtime/endpoint.h"
#include "stickrep/map_io.h"
#include "systemPubSubTypes.h"

namespace stickrep::virtual_robot {

namespace {

constexpr const char* kTruthTopic = "sim/ground_truth";

class ReplayRobotNode : public runtime::ProcessNode {
 public:
  explicit ReplayRobotNode(const VirtualRobotConfig& config) : config_(config) {}

  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    map_ = std::make_unique<map::Map>(map::LoadMap(ctx.system.map_file));
    recording::ReplayOptions o;
    o.file = config_.recording.file;
    o.rate = config_.recording.rate;
    o.start_s = config_.recording.start_s;
    o.duration_s = config_.recording.duration_s;
    o.loop = config_.recording.loop;
    session_ = std::make_unique<recording::ReplaySession>(ctx.participant, ctx.executor, o);
    poses_ = std::make_unique<runtime::Reader<msgs::LocalizationPosePubSubType>>(
        ctx.participant, ctx.executor, "localization/pose",
        [this](const msgs::LocalizationPose& p) { OnPose(p); });
    ctx.executor.AddTimer(0.5, [this] { ReportEnd(); });
    ctx.log->info("replaying {} ({:.1f} s of recording, {} topics) at rate {:g}{}", o.file,
                  session_->replayer().span_s(), session_->replayer().topics().size(), o.rate,
                  o.loop ? ", looping" : "");
  }

  void Activate() override {
    session_->replayer().Start([this](const std::string& topic, const bag::Message& m) {
      if (topic == kTruthTopic) KeepTruth(m);
    });
  }

  void Deactivate() override { session_->replayer().Stop(); }

  std::string Summary() const override {
    std::string checks;
    for (const std::string& c : pose_checks_) checks += "; " + c;
    return fmt::format("replay of {}: {}{}", config_.recording.file, session_->Summary(),
                       checks.empty() ? "; no pose recovered" : checks);
  }

 private:
  // Runs on the replay thread: the latest recorded truth, for judging poses.
  void KeepTruth(const bag::Message& m) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(m.data.size()));
    std::memcpy(payload.data, m.data.data(), m.data.size());
    payload.length = static_cast<uint32_t>(m.data.size());
    msgs::GroundTruthPubSubType support;
    msgs::GroundTruth truth;
    try {
      if (!support.deserialize(&payload, &truth)) return;
    } catch (const std::exception&) {
      return;  // `stickrep-bag check` names such samples; a judge without truth says so
    }
    std::lock_guard<std::mutex> lock(truth_mutex_);
    truth_ = truth;
  }

  void OnPose(const msgs::LocalizationPose& p) {
    if (p.status() != msgs::LOCALIZATION_LOCALIZED) {
      judged_ = false;
      return;
    }
    if (judged_) return;
    judged_ = true;
    std::optional<msgs::GroundTruth> truth;
    {
      std::lock_guard<std::mutex> lock(truth_mutex_);
      truth = truth_;
    }
    const std::string pose = fmt::format("ring '{}' edge {} {}", p.best().ring_id(),
                                         p.best().edge_index(),
                                         p.best().forward() ? "forward" : "backward");
    std::string check;
    if (!truth) {
      check = fmt::format("pose recovered after {} edges: {}; the recording has no {} to judge it",
                          p.edges_sensed(), pose, kTruthTopic);
    } else {
      const int ring = map_->FindRing(truth->ring_id());
      const int edges = ring < 0 ? 0 : static_cast<int>(map_->rings()[ring].edges.size());
      const bool correct = PoseMatchesTruth(
          p.best().ring_id(), static_cast<int>(p.best().edge_index()), p.best().forward(),
          truth->ring_id(), static_cast<int>(truth->edge_index()), truth->forward_in_ring(), edges);
      check = fmt::format("pose recovered after {} edges: {}; recorded truth ring '{}' edge {} "
                          "{}: {}",
                          p.edges_sensed(), pose, truth->ring_id(), truth->edge_index(),
                          truth->forward_in_ring() ? "forward" : "backward",
                          correct ? "CORRECT" : "INCORRECT");
    }
    ctx_->log->info("{}", check);
    pose_checks_.push_back(check);
  }

  void ReportEnd() {
    if (end_reported_ || !session_->replayer().done()) return;
    end_reported_ = true;
    ctx_->log->info("the recording has been replayed to its end; {} wheel commands ignored "
                    "(open loop); waiting to be stopped",
                    session_->wheel_commands_ignored());
  }

  VirtualRobotConfig config_;
  runtime::NodeContext* ctx_ = nullptr;
  std::unique_ptr<map::Map> map_;
  std::unique_ptr<recording::ReplaySession> session_;
  std::unique_ptr<runtime::Reader<msgs::LocalizationPosePubSubType>> poses_;
  std::mutex truth_mutex_;
  std::optional<msgs::GroundTruth> truth_;
  bool judged_ = false;
  bool end_reported_ = false;
  std::vector<std::string> pose_checks_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeReplayRobotNode(const VirtualRobotConfig& config) {
  return std::make_unique<ReplayRobotNode>(config);
}

}  // namespace stickrep::virtual_robot
