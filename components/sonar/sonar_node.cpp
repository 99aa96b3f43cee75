#include "sonar/sonar_node.h"

#include <fmt/format.h>

#include "runtime/endpoint.h"
#include "sensing/robot_config.h"
#include "sensorsPubSubTypes.h"
#include "sonar/sonar_gate.h"

namespace stickrep::sonar {

namespace {

msgs::SonarReadingState ToMsg(ReadingState s) {
  switch (s) {
    case ReadingState::kValid: return msgs::SONAR_VALID;
    case ReadingState::kNoEcho: return msgs::SONAR_NO_ECHO;
    case ReadingState::kOutOfRange: return msgs::SONAR_OUT_OF_RANGE;
    case ReadingState::kOutsideFootprint: return msgs::SONAR_OUTSIDE_FOOTPRINT;
    case ReadingState::kMalformed: return msgs::SONAR_MALFORMED;
  }
  return msgs::SONAR_MALFORMED;
}

class SonarNode : public runtime::ProcessNode {
 public:
  void Configure(runtime::NodeContext& ctx) override {
    ctx_ = &ctx;
    const std::string device = ctx.config.Get<std::string>("device");
    if (device == "serial") {
      ctx.config.Fail("device", "the serial sonar driver is not built yet; use 'virtual'");
    } else if (device != "virtual") {
      ctx.config.Fail("device", "'" + device + "' is not one of: virtual, serial");
    }
    ctx.config.Finish();
    const sensing::RobotConfig robot = sensing::LoadRobotConfigFile(ctx.system.robot_file);
    gate_ = GateConfigFor(robot);
    if (robot.sonar_ring.count != kRingSize) {
      throw InputError(ctx.system.robot_file, 0, "robot.sonar_ring.count",
                       fmt::format("the sonar stream carries {} sensors", kRingSize));
    }
    writer_ = std::make_unique<runtime::Writer<msgs::SonarScanPubSubType>>(ctx.participant,
                                                                          "robot/sonar");
    echoes_ = std::make_unique<runtime::Reader<msgs::SonarEchoPubSubType>>(
        ctx.participant, ctx.executor, "device/sonar/echo",
        [this](const msgs::SonarEcho& e) { OnEcho(e); });
  }

  std::string Summary() const override {
    return fmt::format("{} scans gated, {} readings valid, {} outside the footprint", scans_,
                       valid_, outside_footprint_);
  }

 private:
  void OnEcho(const msgs::SonarEcho& echo) {
    ctx_->counters.CountIn();
    if (echo.header().stamp_ns() < last_stamp_ns_) {
      ctx_->counters.Drop("device/sonar/echo", "time went backwards");
      return;
    }
    last_stamp_ns_ = echo.header().stamp_ns();
    const GatedScan g = GateScan(echo.range_in(), gate_);
    msgs::SonarScan scan;
    for (int k = 0; k < kRingSize; ++k) {
      scan.range_in()[k] = g.range_in[k];
      scan.reading_state()[k] = ToMsg(g.state[k]);
      outside_footprint_ += g.state[k] == ReadingState::kOutsideFootprint;
    }
    scan.valid_count(static_cast<uint16_t>(g.valid_count));
    valid_ += g.valid_count;
    scans_++;
    // The scan keeps the device's time stamp: it describes that instant.
    if (writer_->Publish(scan, echo.header().stamp_ns())) ctx_->counters.CountOut();
  }

  runtime::NodeContext* ctx_ = nullptr;
  SonarGateConfig gate_;
  int64_t last_stamp_ns_ = 0;
  uint64_t scans_ = 0, valid_ = 0, outside_footprint_ = 0;
  std::unique_ptr<runtime::Writer<msgs::SonarScanPubSubType>> writer_;
  std::unique_ptr<runtime::Reader<msgs::SonarEchoPubSubType>> echoes_;
};

}  // namespace

std::unique_ptr<runtime::ProcessNode> MakeSonarNode() { return std::make_unique<SonarNode>(); }

}  // namespace stickrep::sonar
