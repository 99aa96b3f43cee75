// `stickrep-console pose`: subscribes to the localizer's map, pose and hypotheses and shows
// them (console/pose_view.h) in the terminal, as JSON or as a PNG.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>

#include "common/input_error.h"
#include "console/console.h"
#include "console/pose_view.h"
#include "localizationPubSubTypes.h"
#include "msgs_json.h"
#include "localizer/map_msg.h"
#include "runtime/endpoint.h"
#include "runtime/process.h"

namespace stickrep::console {

namespace {

using Clock = runtime::Executor::Clock;

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// "LOCALIZED" for LOCALIZATION_LOCALIZED: the IDL's name without its enum prefix.
std::string StatusName(msgs::LocalizationStatus s) {
  const std::string name = msgs::EnumName(s);
  const std::string prefix = "LOCALIZATION_";
  return name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : name;
}

PoseMark MarkOf(const msgs::PoseHypothesis& h) {
  PoseMark m;
  m.ring_id = h.ring_id();
  m.edge = static_cast<int>(h.edge_index());
  m.forward = h.forward();
  m.offset_in = h.offset_in();
  m.x_in = h.pose().x_in();
  m.y_in = h.pose().y_in();
  m.heading_rad = h.pose().heading_rad();
  m.probability = h.probability();
  return m;
}

// The latest map, pose and hypotheses the localizer wrote, read with the catalogue's QoS
// (all three latched: a console that joins late gets them at once) for as long as it lives.
class PoseInputs {
 public:
  PoseInputs(runtime::Participant& participant, runtime::Executor& ex)
      : map_reader_(participant, ex, "map/stickrep",
                    [this](const msgs::StickRepMap& m) { OnMap(m); }),
        pose_reader_(participant, ex, "localization/pose",
                     [this](const msgs::LocalizationPose& p) {
                       pose_ = p;
                       pose_written_ns_ = pose_reader_.source_timestamp_ns();
                     }),
        hypotheses_reader_(participant, ex, "localization/hypotheses",
                           [this](const msgs::PoseHypotheses& h) { hypotheses_ = h; }) {}

  bool has_map() const { return map_.has_value() || !map_error_.empty(); }
  bool has_pose() const { return pose_.has_value(); }
  bool has_hypotheses() const { return hypotheses_.has_value(); }
  // Empty, or why the map received is not one (map::Map's checks).
  const std::string& map_error() const { return map_error_; }
  const map::Map& map() const { return *map_; }

  PoseFrame Frame() const {
    PoseFrame f;
    f.status = StatusName(pose_->status());
    f.confidence = pose_->confidence();
    f.candidates = static_cast<int>(pose_->candidate_count());
    f.edges_sensed = static_cast<int>(pose_->edges_sensed());
    f.message = pose_->message();
    if (!pose_->best().ring_id().empty()) f.best = MarkOf(pose_->best());
    if (hypotheses_) {
      for (const auto& h : hypotheses_->hypotheses()) f.hypotheses.push_back(MarkOf(h));
    }
    f.age_s = std::max<int64_t>(0, runtime::WallClockNowNs() - pose_written_ns_) * 1e-9;
    return f;
  }

 private:
  void OnMap(const msgs::StickRepMap& m) {
    try {
      map_ = localizer::FromMsg(m);
      map_error_.clear();
    } catch (const std::invalid_argument& e) {
      map_error_ = e.what();
    }
  }

  std::optional<map::Map> map_;
  std::string map_error_;
  std::optional<msgs::LocalizationPose> pose_;
  int64_t pose_written_ns_ = 0;
  std::optional<msgs::PoseHypotheses> hypotheses_;
  runtime::Reader<msgs::StickRepMapPubSubType> map_reader_;
  runtime::Reader<msgs::LocalizationPosePubSubType> pose_reader_;
  runtime::Reader<msgs::PoseHypothesesPubSubType> hypotheses_reader_;
};

// Refuses a --png path that cannot be written before joining the domain: a name that is not
// a .png, a directory that does not exist or is not writable.
void CheckPngPath(const std::string& path) {
  namespace fs = std::filesystem;
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (extension != ".png") {
    throw InputError(path, 0, "--png", "the picture's name must end in .png");
  }
  const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(path, 0, "--png", "cannot write: no directory " + dir.string());
  }
  if (access(dir.c_str(), W_OK) != 0 || (fs::exists(path, ec) && access(path.c_str(), W_OK) != 0)) {
    throw InputError(path, 0, "--png", "cannot write: permission denied");
  }
}

// Spins until the map (when `need_map`) and a pose are in, for at most `timeout_s`; false
// (said on stderr, naming what did not come) when they are not, or on Ctrl-C.
bool WaitForInputs(runtime::Executor& ex, const PoseInputs& in, bool need_map, double timeout_s) {
  const auto until = Clock::now() + Seconds(timeout_s);
  const auto ready = [&] { return in.has_pose() && (in.has_map() || !need_map); };
  while (!ready() && runtime::KeepRunning().load() && Clock::now() < until) {
    ex.SpinOnce(std::chrono::milliseconds(50));
  }
  if (ready() || !runtime::KeepRunning().load()) return ready();
  std::string missing;
  if (need_map && !in.has_map()) missing = "no map on map/stickrep";
  if (!in.has_pose()) {
    missing += std::string(missing.empty() ? "no" : " and no") + " pose on localization/pose";
  }
  fmt::print(stderr, "{} within {:g} s: is the localizer running?\n", missing, timeout_s);
  return false;
}

// One frame: JSON, or the drawing (after clearing a terminal's screen, else after a blank
// line between frames).
void PrintFrame(const ConsoleOptions& o, const PoseInputs& in, bool first, std::ostream& out) {
  if (o.json) {
    out << PoseJson(in.Frame()).dump() << '\n' << std::flush;
    return;
  }
  const bool tty = &out == &std::cout && isatty(STDOUT_FILENO);
  if (tty) {
    out << "\x1b[H\x1b[2J";
  } else if (!first) {
    out << '\n';
  }
  out << RenderPoseText(in.map(), in.Frame(), o.cols) << std::flush;
}

int WritePicture(const ConsoleOptions& o, const PoseInputs& in, std::ostream& out) {
  try {
    WritePosePng(in.map(), in.Frame(), o.png);
  } catch (const std::exception& e) {  // cv::imwrite's refusal, or cv::Exception
    throw InputError(o.png, 0, "--png", e.what());
  }
  out << "wrote " << o.png << '\n';
  return 0;
}

}  // namespace

int ShowPose(const ConsoleOptions& o, std::ostream& out) {
  if (!o.png.empty()) CheckPngPath(o.png);
  DomainSession s = JoinAsConsole(o);
  runtime::Executor ex;
  PoseInputs in(*s.participant, ex);
  const bool need_map = !o.json || !o.png.empty();
  const auto start = Clock::now();
  const auto until = o.duration_s > 0.0 ? start + Seconds(o.duration_s) : Clock::time_point::max();
  double timeout_s = o.timeout_s > 0.0 ? o.timeout_s : 10.0;
  if (o.duration_s > 0.0) timeout_s = std::min(timeout_s, o.duration_s);
  if (!WaitForInputs(ex, in, need_map, timeout_s)) return runtime::KeepRunning().load() ? 1 : 0;
  if (need_map && !in.map_error().empty()) {
    fmt::print(stderr, "the map on map/stickrep is not a valid map: {}\n", in.map_error());
    return 1;
  }
  if (!o.png.empty() || o.count == 1) {
    // The candidates come beside the pose; give them a moment (bounded) to arrive.
    const auto hypotheses_until = Clock::now() + Seconds(1.0);
    while (!in.has_hypotheses() && runtime::KeepRunning().load() &&
           Clock::now() < hypotheses_until) {
      ex.SpinOnce(std::chrono::milliseconds(20));
    }
    if (!o.png.empty()) return WritePicture(o, in, out);
    PrintFrame(o, in, /*first=*/true, out);
    return 0;
  }
  bool first = true;
  auto next = Clock::now();
  while (runtime::KeepRunning().load() && Clock::now() < until) {
    if (Clock::now() >= next) {
      PrintFrame(o, in, first, out);
      first = false;
      next += Seconds(1.0);
    }
    ex.Spin(runtime::KeepRunning(), std::min(next, until));
  }
  return 0;
}

}  // namespace stickrep::console
