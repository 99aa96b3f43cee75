#include "whereami/whereami_run.h"

#include <fmt/format.h>
#include <spdlog/sinks/null_sink.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/config_paths.h"
#include "common/seeds.h"
#include "common/strict_yaml.h"
#include "common/units.h"
#include "localizer/edge_assembler.h"
#include "localizer/localizer_component.h"
#include "localizer/sensed_doors.h"
#include "stickrep/hallway_view.h"
#include "stickrep/map_io.h"
#include "stickrep/sequence_matcher.h"
#include "virtual_robot/world_sim.h"
#include "whereami/in_process_stack.h"

namespace stickrep::whereami {

namespace {

// The seed stream a random kidnap jump is drawn from (common/seeds.h).
constexpr std::uint64_t kKidnapJumpStream = 1;

StrictYaml Section(const std::string& file, const std::string& key) {
  return StrictYaml::LoadFile(file).Child(key);
}

// Components log to nowhere in a Where-am-I run: its report says what happened.
std::shared_ptr<spdlog::logger> QuietLogger() {
  static const auto log = std::make_shared<spdlog::logger>(
      "in-process", std::make_shared<spdlog::sinks::null_sink_mt>());
  return log;
}

}  // namespace

RunSetup LoadRunSetup(const std::string& config_dir, const std::string& map_file,
                      const std::string& virtual_robot_file) {
  RunSetup s;
  const std::string dir = config_dir.empty() ? DefaultConfigDir() : config_dir;
  // Only the two paths are needed of system.yaml; the processes validate the rest.
  const std::string system_file = dir + "/system.yaml";
  const StrictYaml system = Section(system_file, "system");
  const std::string robot_file = ResolvePath(system.Get<std::string>("robot_file"), system_file);
  s.map_file =
      map_file.empty() ? ResolvePath(system.Get<std::string>("map_file"), system_file) : map_file;
  s.map = std::make_shared<const map::Map>(map::LoadMap(s.map_file));
  s.robot = sensing::LoadRobotConfigFile(robot_file);
  s.virtual_robot = virtual_robot::LoadVirtualRobotConfig(Section(
      virtual_robot_file.empty() ? dir + "/virtual_robot.yaml" : virtual_robot_file,
      "virtual_robot"));
  s.landmark = landmark::LoadLandmarkConfig(Section(dir + "/landmark.yaml", "landmark"));
  s.localizer = localizer::LoadLocalizerSettings(Section(dir + "/localizer.yaml", "localizer"));
  s.localizer.view.camera_fov_deg = s.robot.camera.fov_deg;  // doors too wide to see whole
  s.locomotion = locomotion::ForMap(
      locomotion::LoadLocomotionConfig(Section(dir + "/locomotion.yaml", "locomotion"), s.robot),
      s.map->info().name);
  s.executive = executive::LoadExecutiveConfig(Section(dir + "/executive.yaml", "executive"));
  return s;
}

const char* ToString(Ending ending) {
  switch (ending) {
    case Ending::kCorrect: return "correct";
    case Ending::kWrong: return "wrong";
    case Ending::kNoneInTime: return "none in time";
    case Ending::kCollision: return "collision";
    case Ending::kFailed: return "failed";
  }
  return "?";
}

Ending RunResult::ending() const {
  if (failed) return Ending::kFailed;
  if (collisions > 0) return Ending::kCollision;
  if (!first) return Ending::kNoneInTime;
  return first->correct ? Ending::kCorrect : Ending::kWrong;
}

namespace {

// A run in progress: the stack, and what the run watches of it (the poses the virtual robot
// judged, the goal that keeps the robot travelling for a kidnap, the traces and the measured
// edges).
class Run {
 public:
  Run(const RunSetup& setup, const RunOptions& options, virtual_robot::PlacedRobot placed,
      int ring);
  RunResult Finish();

 private:
  void OnPose(const message::LocalizationPose& p);
  // Every published pose judged against the truth: confidence samples, wrong spells, LOSTs.
  void Watch(const message::LocalizationPose& p);
  bool RightInView(const message::LocalizationPose& p, const virtual_robot::SimTruth& t) const;
  void OpenSpell();
  void CloseSpell(const std::string& ended_by);
  void OnKidnap();
  void CountEdgesSensedBeforeKidnap();
  void WatchGivenUp(bool left_right_pose);
  int EdgesAlike(int held_edge, int held_dir, int true_edge, int true_dir) const;
  void OnRecovery(const Recovery& r);
  void SendGoalAhead(const Recovery& r);
  void AfterStep();
  void TraceBelief(const message::LocalizationPose& p);
  // Where the camera truly looks, for a trace line: the ring it is seen on (the robot may
  // have gone on from its start ring into another corridor), the view edge and the travel.
  std::string TruthInView(const virtual_robot::SimTruth& t) const;
  std::string BeliefInTruth(const virtual_robot::SimTruth& t) const;
  double NowS() const { return stack_.executor().ElapsedS(); }

  const map::Map& map_;
  const RunOptions& options_;
  const int ring_;
  const bool measuring_;
  InProcessStack stack_;
  const virtual_robot::VirtualRobotComponent& robot_;
  virtual_robot::WorldSim& sim_;
  const map::HallwayView& view_;
  // The localizer weighs the doors' marks: two doors are alike only when their surveyed
  // marks agree too.
  const bool marks_;
  // Measuring: the same assembly as the localizer's, never restarted but by reversals.
  localizer::EdgeAssembler assembler_;
  EdgeErrorMeter meter_;
  component::Publisher<message::MissionGoal>& goals_;
  RunResult result_;
  std::size_t judged_ = 0;  // the virtual robot's pose checks seen
  // The pose watch: the spell of a wrong LOCALIZED pose under way (and where it began), the
  // status and edge count of the last pose sample, the kidnap seen.
  std::optional<WrongSpell> spell_;
  bool spell_is_kidnap_ = false;
  std::uint64_t given_up_serial_ = 0;  // the last Localizer::GivenUp seen
  bool given_up_right_ = false;        // ... and it was a right pose
  long spell_edges_ = 0;
  double spell_in_ = 0.0;
  message::LocalizationStatus last_status_ = message::LocalizationStatus::kRecovering;
  bool last_localized_right_ = false;  // the last pose watched was LOCALIZED and right
  long last_sample_edges_ = -1;
  bool kidnap_seen_ = false;
  // The place held at the kidnap and the true one (view edges), until the robot has moved
  // kCompareAfterIn from the new place and its direction there is known.
  struct KidnapCompare {
    int held_edge, held_dir, true_edge;
    double at_in;
  };
  std::optional<KidnapCompare> kidnap_compare_;
  // Where the localizer's odometer stood at the kidnap (the frame of its sensed spans), and
  // how far into its sensed edges it had taken in: the edges it takes in after the kidnap
  // that ended before it were sensed at the old place. Reset once an edge sensed after the
  // kidnap comes (the rest are too) or the sequence restarts (the old place's are dropped).
  struct KidnapSensing {
    double odometer_in;
    int direction;
    std::size_t spans;
    std::uint64_t edges_total;
  };
  std::optional<KidnapSensing> kidnap_sensing_;
  static constexpr double kCompareAfterIn = 12.0;
  static constexpr const char* kGoalId = "far";
  double first_pose_in_ = -1.0;
  int last_view_edge_ = -1;
  int last_view_ring_ = -1;
  int traced_collisions_ = 0;  // contacts already written to the trace
  std::string last_belief_;
  message::LocomotionState last_state_ = message::LocomotionState::kStopped;
  // The place of the last goal sent: when the robot reaches it with travel still to watch,
  // the next goal is set as far on from there.
  std::optional<Recovery> goal_;
  message::MissionState last_mission_ = message::MissionState::kWaitingForComponents;
};

Run::Run(const RunSetup& setup, const RunOptions& options, virtual_robot::PlacedRobot placed,
         int ring)
    : map_(*setup.map),
      options_(options),
      ring_(ring),
      measuring_(options.measure_ft > 0.0),
      stack_(setup, std::move(placed.sim), QuietLogger(), !measuring_),
      robot_(stack_.virtual_robot()),
      sim_(stack_.sim()),
      view_(stack_.localizer().view()),
      marks_(stack_.localizer().localizer().config().bayes.confusion.marks),
      assembler_(localizer::MakeLocalizerConfig(setup.localizer, view_.view()).assembler),
      // From 20 ft on: the robot has aligned and the partial first edges are behind.
      meter_(view_.view().ring(ring), assembler_, 240.0),
      goals_(stack_.executor().Advertise<message::MissionGoal>("mission/goal")) {
  result_.start_redraws = placed.redraws;
  result_.start = robot_.start();
  component::SimExecutor& e = stack_.executor();
  e.Subscribe<message::LocalizationPose>(
      "localization/pose", [this](const message::LocalizationPose& p) { OnPose(p); });
  e.Subscribe<message::LandmarkObservation>(
      "perception/landmark", [this](const message::LandmarkObservation& o) {
        ++result_.doors_observed;
        if (measuring_) {
          assembler_.AddSighting(localizer::LocalizerComponent::Sighting(o));
        }
      });
  e.Subscribe<message::MotionState>("robot/motion/state", [this](const message::MotionState& m) {
    if (options_.trace && m.state != last_state_ && result_.behaviour_log.size() < 200) {
      result_.behaviour_log.push_back(fmt::format("{:7.1f} s  {}", NowS(), m.message));
    }
    last_state_ = m.state;
  });
  e.Subscribe<message::MissionStatus>("mission/status", [this](const message::MissionStatus& m) {
    const bool reached = m.state == message::MissionState::kGoalReached &&
                         last_mission_ != message::MissionState::kGoalReached;
    last_mission_ = m.state;
    if (reached && goal_ && result_.ended.empty()) SendGoalAhead(*goal_);
  });
  if (measuring_) {
    const int coaxial = setup.robot.camera.coaxial_sensor;
    const double head_in = setup.robot.sonar_ring.head_radius_in;
    e.Subscribe<message::SonarScan>("robot/sonar", [this, coaxial, head_in](const message::SonarScan& s) {
      if (s.state[coaxial] == sonar::ReadingState::kValid) {
        assembler_.SetWallRange(s.range_in[coaxial] + head_in);
      }
    });
    e.Subscribe<message::Odometry>("robot/odometry", [this](const message::Odometry& o) {
      const virtual_robot::SimTruth truth = sim_.Truth();
      meter_.Advance(o.distance_in, o.heading_rad,
                     truth.optical_axis_on_wall ? view_.ViewEdge(ring_, truth.edge_index) : -1);
      if (InchesToFeet(truth.distance_in) >= options_.measure_ft) {
        result_.ended = fmt::format("measured over {:.0f} ft", options_.measure_ft);
      }
    });
  }
  e.AddTimer(1.0 / setup.virtual_robot.sim_rate_hz, [this] { AfterStep(); });
}

// A pose is judged by the virtual robot when the localizer first declares it (and again
// after a kidnap); the run takes its verdict.
void Run::OnPose(const message::LocalizationPose& p) {
  if (measuring_) return;  // the robot travels its distance whatever the pose
  if (options_.trace) TraceBelief(p);
  Watch(p);
  const std::vector<virtual_robot::PoseCheck>& checks = robot_.checks();
  if (checks.size() > judged_) {
    judged_ = checks.size();
    OnRecovery(checks.back());
  }
  if (p.status == message::LocalizationStatus::kLost && robot_.kidnapped() &&
      !result_.lost_detected) {
    result_.lost_detected = true;
    result_.lost_after_ft = robot_.TravelledSinceEpochFt();
  }
}

void Run::Watch(const message::LocalizationPose& p) {
  const virtual_robot::SimTruth t = sim_.Truth();
  const bool placed = p.candidate_count > 0;
  const bool localized = placed && p.status == message::LocalizationStatus::kLocalized;
  const bool correct = placed && RightInView(p, t);
  const long edges = static_cast<long>(stack_.localizer().localizer().edges_total());
  if (placed && (edges != last_sample_edges_ || p.status != last_status_)) {
    result_.confidences.push_back({p.confidence, localized, correct});
  }
  last_sample_edges_ = edges;
  const bool turned_lost =
      p.status == message::LocalizationStatus::kLost && last_status_ != p.status;
  const bool left_right_pose = last_localized_right_ && !localized;
  last_localized_right_ = localized && correct;
  last_status_ = p.status;
  if (!result_.first) return;  // watched from the first pose on
  CountEdgesSensedBeforeKidnap();
  WatchGivenUp(left_right_pose);
  if (left_right_pose && (!robot_.kidnapped() || result_.second)) ++result_.right_poses_given_up;
  if (spell_) {
    if (!localized || correct) {
      CloseSpell(localized ? "corrected" : turned_lost ? "LOST" : "RECOVERING");
    }
  } else if (localized && !correct) {
    if (options_.trace && result_.behaviour_log.size() < 400) {
      const localizer::Hypothesis& h = stack_.localizer().localizer().estimate().hypotheses.front();
      result_.behaviour_log.push_back(fmt::format(
          "{:7.1f} s  wrong pose published as LOCALIZED: ring '{}' view edge {} {} + {:.0f} in, "
          "truth {}: {}",
          NowS(), view_.view().ring(h.ring).id, h.edge, h.dir > 0 ? "fwd" : "back", h.offset_in,
          TruthInView(t), p.message));
    }
    OpenSpell();
  }
  // LOST said for a right pose with no kidnap to notice (none yet, or the robot found itself
  // again since), as the pose was given up or edges after (lost_confirm_edges). LOST for a
  // wrong pose is the localizer doing its job.
  if (turned_lost && (left_right_pose || given_up_right_) &&
      (!robot_.kidnapped() || result_.second)) {
    ++result_.false_losts;
  }
}

// A pose the localizer gave up (a new Localizer::GivenUp): right or wrong, and how.
void Run::WatchGivenUp(bool left_right_pose) {
  const std::optional<localizer::Localizer::GivenUp>& g =
      stack_.localizer().localizer().given_up();
  if (!g) return;
  if (g->serial == given_up_serial_) {
    // LOST may be said for it edges after it was given up.
    if (!result_.given_up.empty()) {
      result_.given_up.back().lost = g->lost;
      result_.given_up.back().belief_on = g->belief_on;
    }
    return;
  }
  given_up_serial_ = g->serial;
  given_up_right_ = left_right_pose;
  RunResult::GivenUpPose p;
  p.pose = left_right_pose ? "right" : spell_ && spell_is_kidnap_ ? "kidnap" : "wrong";
  p.belief = g->belief;
  p.lost = g->lost;
  result_.given_up.push_back(p);
}

// Whether a published pose names where the robot is, judged in the hallway view the
// localizer matches in (the steps the follower passes straight merged into the walls either
// side, so the walls beside a pilaster are one edge): the view edge the camera looks at, or a
// neighbour, in the direction of travel. Off the start ring (the base went on into another
// corridor of the floor), as the virtual robot judges it.
bool Run::RightInView(const message::LocalizationPose& p, const virtual_robot::SimTruth& t) const {
  const std::vector<localizer::Hypothesis>& hs =
      stack_.localizer().localizer().estimate().hypotheses;
  if (t.seen_ring_id != sim_.ring_id() || hs.empty()) {
    return virtual_robot::PoseMatchesTruth(p.best.ring_id, p.best.edge_index, p.best.forward, t);
  }
  const localizer::Hypothesis& h = hs.front();
  if (h.ring != ring_ || (h.dir > 0) != t.seen_forward_in_ring) return false;
  const int n = view_.view().ring(ring_).EdgeCount();
  const int d = std::abs(h.edge - view_.ViewEdge(ring_, t.seen_edge_index));
  return d <= 1 || (view_.view().ring(ring_).closed && d == n - 1);
}

void Run::OpenSpell() {
  spell_ = WrongSpell{};
  spell_is_kidnap_ = false;
  spell_edges_ = static_cast<long>(stack_.localizer().localizer().edges_total());
  spell_in_ = sim_.Truth().distance_in;
}

void Run::CloseSpell(const std::string& ended_by) {
  CountEdgesSensedBeforeKidnap();
  spell_->edges = static_cast<long>(stack_.localizer().localizer().edges_total()) - spell_edges_;
  spell_->distance_ft = InchesToFeet(sim_.Truth().distance_in - spell_in_);
  spell_->ended_by = ended_by;
  if (spell_is_kidnap_) {
    result_.after_kidnap = *spell_;
  } else {
    result_.wrong_localized.push_back(*spell_);
  }
  spell_.reset();
}

// How many edges after the kidnap the map shows alike at the place the localizer holds and
// at the true one: the partial edge each is in, then whole edges of the same kind (doors of
// the same class, walls of lengths within the localizer's tolerance) from the first whole
// edge at the true place, lined up with the held place's next edges at the best of three
// alignments (the held pose may be inside a door the robot has not yet left), up to 100.
int Run::EdgesAlike(int held_edge, int held_dir, int true_edge, int true_dir) const {
  const map::MatchIndex index(view_.view());
  const int offset = index.RingOffset(ring_);
  int best = 0;
  for (int lead = 0; lead <= 2; ++lead) {
    int a = offset + held_edge;
    for (int i = 0; i < lead && a >= 0; ++i) a = index.Step(a, held_dir);
    int b = index.Step(offset + true_edge, true_dir);
    int alike = 0;
    for (; alike < 100 && a >= 0 && b >= 0; ++alike) {
      if (index.code(a) != index.code(b)) break;
      if (marks_ && index.mark(a) != index.mark(b) && index.mark(a) != map::DoorMark::kUnknown &&
          index.mark(b) != map::DoorMark::kUnknown) {
        break;
      }
      if (index.code(a) == map::kWallCode &&
          std::abs(index.metric(a) - index.metric(b)) > std::max(0.10 * index.metric(a), 6.0)) {
        break;
      }
      a = index.Step(a, held_dir);
      b = index.Step(b, true_dir);
    }
    best = std::max(best, alike);
  }
  return best + 1;  // the partial edge the robot was kidnapped in
}

// The kidnap: a pose published as LOCALIZED is wrong from this moment.
void Run::OnKidnap() {
  kidnap_seen_ = true;
  // The place held and the true one, compared once the robot has moved on (the direction it
  // travels in from the new place is known then).
  const std::vector<localizer::Hypothesis>& held =
      stack_.localizer().localizer().estimate().hypotheses;
  const virtual_robot::SimTruth t = sim_.Truth();
  if (!held.empty() && held.front().ring == ring_) {
    kidnap_compare_ = KidnapCompare{held.front().edge, held.front().dir,
                                    view_.ViewEdge(ring_, t.edge_index), t.distance_in};
  }
  if (spell_) CloseSpell("kidnapped");
  if (last_status_ != message::LocalizationStatus::kLocalized) {
    result_.after_kidnap = WrongSpell{0, 0.0, "not localized at the kidnap"};
    return;
  }
  OpenSpell();
  spell_is_kidnap_ = true;
  const localizer::Localizer& l = stack_.localizer().localizer();
  if (l.travel_direction() != 0) {
    kidnap_sensing_ = KidnapSensing{l.odometer_in(), l.travel_direction(), l.sensed_spans().size(),
                                    l.edges_total()};
  }
}

// The edges taken in since the last look that the robot sensed before the kidnap, counted in
// the kidnap's spell (WrongSpell::edges_sensed_before).
void Run::CountEdgesSensedBeforeKidnap() {
  if (!spell_ || !spell_is_kidnap_ || !kidnap_sensing_) return;
  KidnapSensing& k = *kidnap_sensing_;
  const localizer::Localizer& l = stack_.localizer().localizer();
  const std::vector<localizer::EdgeAssembler::Span>& spans = l.sensed_spans();
  if (spans.size() != k.spans + (l.edges_total() - k.edges_total)) {
    kidnap_sensing_.reset();  // the sequence restarted: what was pending was dropped
    return;
  }
  for (; k.spans < spans.size(); ++k.spans) {
    if (k.direction * (spans[k.spans].to_in - k.odometer_in) > 0.0) {
      kidnap_sensing_.reset();  // ends past the kidnap: this edge and the rest are the new place's
      return;
    }
    ++spell_->edges_sensed_before;
  }
  k.edges_total = l.edges_total();
}

void Run::OnRecovery(const Recovery& r) {
  if (!result_.first) {
    result_.first = r;
    first_pose_in_ = sim_.Truth().distance_in;
    if (options_.kidnap_after_s < 0.0 && options_.keep_going_ft <= 0.0) {
      result_.ended = "localized";
    } else {
      SendGoalAhead(r);
    }
  } else if (robot_.kidnapped() && !result_.second) {
    result_.second = r;
    result_.ended = "localized again after the kidnap";
  } else if (result_.ended.empty()) {
    // Localized again after the pose was given up: the executive dropped the goal then.
    SendGoalAhead(r);
  }
}

// Keeps the robot travelling until the kidnap: a goal a third of a closed ring ahead (the
// way on is then the shorter one, so the route does not reverse the robot), or the far end
// of an open one (a goal past an open ring's end would be a few edges behind the robot).
// Reached with travel still to watch, the next is set from there (the mission status).
void Run::SendGoalAhead(const Recovery& r) {
  const map::Ring& ring = map_.ring(ring_);
  const int n = ring.EdgeCount();
  const int ahead = ring.closed ? (r.forward ? r.edge + n / 3 : r.edge - n / 3 + n) % n
                                : (r.edge < n / 2 ? n - 1 : 0);
  message::MissionGoal goal;
  goal.header.stamp_ns = stack_.executor().NowNs();
  goal.goal_id = kGoalId;
  goal.target = fmt::format("{}/{}", r.ring_id, ahead);
  goals_.Publish(goal);
  goal_ = r;
  goal_->edge = ahead;
}

// After each step of the world: the kidnap, the distance kept going, and the true trace (the
// view edge the camera looks at).
void Run::AfterStep() {
  if (robot_.kidnapped() && !kidnap_seen_) OnKidnap();
  if (kidnap_compare_ && sim_.Truth().distance_in > kidnap_compare_->at_in + kCompareAfterIn) {
    const KidnapCompare& k = *kidnap_compare_;
    result_.kidnap_edges_alike =
        EdgesAlike(k.held_edge, k.held_dir, k.true_edge, sim_.Truth().forward_in_ring ? +1 : -1);
    kidnap_compare_.reset();
  }
  if (options_.keep_going_ft > 0.0 && first_pose_in_ >= 0.0 && result_.ended.empty() &&
      InchesToFeet(sim_.Truth().distance_in - first_pose_in_) >= options_.keep_going_ft) {
    result_.ended = fmt::format("kept going {:.0f} ft after the pose", options_.keep_going_ft);
  }
  if (!options_.trace) return;
  const virtual_robot::SimTruth truth = sim_.Truth();
  if (truth.collisions > traced_collisions_) {
    traced_collisions_ = truth.collisions;
    result_.behaviour_log.push_back(fmt::format(
        "{:7.1f} s  the base touches a wall: edge {} + {:.0f} in, {:+.1f} in off the axis, "
        "heading {:+.1f} deg, {:.0f} in from the nearest corner",
        NowS(), truth.edge_index, truth.offset_in, truth.lateral_offset_in,
        RadToDeg(truth.heading_error_rad), truth.corner_distance_in));
  }
  // The edges passed, on the ring the camera looks at (the robot may go on into another
  // corridor); a ring change is written before its first edge.
  const int ring = view_.original().FindRing(truth.seen_ring_id);
  if (ring < 0) return;
  const int e = view_.ViewEdge(ring, truth.seen_edge_index);
  if (e == last_view_edge_ && ring == last_view_ring_) return;
  if (ring != last_view_ring_ && last_view_ring_ >= 0) {
    result_.true_trace += fmt::format("<ring:{}> ", truth.seen_ring_id);
  }
  last_view_edge_ = e;
  last_view_ring_ = ring;
  const map::Edge& edge = view_.view().ring(ring).edges[e];
  map::SensedEdge as_sensed;
  as_sensed.code = map::CodeOf(edge);
  as_sensed.metric_in = edge.metric_in;
  result_.true_trace += fmt::format("{}[{}] ", map::Describe(as_sensed), e);
}

// One trace line per change of the localizer's estimate: the newest sensed edge, the best
// place with its probability, and where the robot truly is.
void Run::TraceBelief(const message::LocalizationPose& p) {
  const std::string belief = fmt::format("{} {} {}", static_cast<int>(p.status), p.edges_sensed,
                                         p.message);
  if (belief == last_belief_ || result_.behaviour_log.size() >= 400) return;
  last_belief_ = belief;
  const std::vector<map::SensedEdge>& seq = stack_.localizer().localizer().sensed_sequence();
  const std::string newest = seq.empty() ? "-" : map::Describe(seq.back());
  const virtual_robot::SimTruth truth = sim_.Truth();
  const std::string best =
      p.candidate_count == 0
          ? "no place"
          : fmt::format("ring '{}' edge {} {} p={:.3f}", p.best.ring_id, p.best.edge_index,
                        p.best.forward ? "fwd" : "back", p.best.probability);
  result_.behaviour_log.push_back(
      fmt::format("{:7.1f} s  localizer {}: newest {}, best {}, truth {}{}: {}", NowS(),
                  localizer::ToString(stack_.localizer().localizer().estimate().status), newest,
                  best, TruthInView(truth), BeliefInTruth(truth), p.message));
}

// For a trace line, the Bayes filter's belief at the true place (its view edge or a
// neighbour, its direction) and the places it holds most belief on (view edge, f/b for the
// direction): where the belief at the true place drops, those name the reads that pulled it
// down and where the belief went.
std::string Run::BeliefInTruth(const virtual_robot::SimTruth& t) const {
  const localizer::Localizer& loc = stack_.localizer().localizer();
  if (loc.config().method != localizer::MatchMethod::kBayes) return "";
  std::string out;
  if (t.seen_ring_id == sim_.ring_id()) {
    const int edge = view_.ViewEdge(ring_, t.seen_edge_index);
    out = fmt::format(" (belief there {:.4f})",
                      loc.BeliefNear(ring_, edge, t.seen_forward_in_ring ? +1 : -1));
  }
  const std::vector<localizer::Hypothesis>& hs = loc.estimate().hypotheses;
  for (std::size_t i = 0; i < hs.size() && i < 4; ++i) {
    out += fmt::format("{} {}{}{} {:.3f}", i == 0 ? ", the filter's places" : ",",
                       hs[i].ring == ring_ ? "" : view_.view().ring(hs[i].ring).id + " ",
                       hs[i].edge, hs[i].dir > 0 ? "f" : "b", hs[i].probability);
  }
  return out;
}

std::string Run::TruthInView(const virtual_robot::SimTruth& t) const {
  const int ring = view_.original().FindRing(t.seen_ring_id);
  if (ring < 0) return fmt::format("ring '{}' (not on the map)", t.seen_ring_id);
  return fmt::format("ring '{}' edge {} (view edge {}) {}", t.seen_ring_id, t.seen_edge_index,
                     view_.ViewEdge(ring, t.seen_edge_index),
                     t.seen_forward_in_ring ? "fwd" : "back");
}

RunResult Run::Finish() {
  stack_.executor().RunUntil([this] { return !result_.ended.empty(); }, options_.max_sim_s);
  if (result_.ended.empty() && first_pose_in_ >= 0.0) {
    result_.ended = fmt::format(
        "{:.0f} ft of travel after the pose by {:.0f} s simulated (the goal reached or given up)",
        InchesToFeet(sim_.Truth().distance_in - first_pose_in_), options_.max_sim_s);
  } else if (result_.ended.empty()) {
    result_.ended = fmt::format("no pose after {:.0f} s simulated", options_.max_sim_s);
  }
  if (spell_) CloseSpell("run ended");
  result_.sim_s = NowS();
  result_.frames = robot_.frames();
  result_.collisions = sim_.Truth().collisions;
  result_.kidnapped = robot_.kidnapped();
  result_.max_offset_in = robot_.max_offset_in();
  result_.max_heading_deg = robot_.max_heading_deg();
  result_.off_ring_ft = robot_.off_ring_ft();
  if (options_.record_path) result_.path = robot_.path();
  const std::vector<map::SensedEdge>& sensed =
      measuring_ ? assembler_.sequence() : stack_.localizer().localizer().sensed_sequence();
  result_.sensed_trace = map::Describe(sensed);
  if (measuring_) result_.errors = meter_.Finish();
  result_.drops = stack_.Drops();
  return std::move(result_);
}

}  // namespace

RunResult RunWhereAmI(const RunSetup& setup, const RunOptions& options) {
  const map::Map& map = *setup.map;
  RunSetup run_setup = setup;
  virtual_robot::VirtualRobotConfig& vr = run_setup.virtual_robot;
  vr.seed = options.seed;
  vr.summary_png.clear();
  if (!options.ring_id.empty()) vr.world.ring_id = options.ring_id;
  const int ring = vr.world.ring_id.empty() ? 0 : map.FindRing(vr.world.ring_id);
  if (ring < 0) throw std::invalid_argument("no ring '" + vr.world.ring_id + "' in the map");
  vr.kidnap_after_localized_s = options.kidnap_after_s;
  vr.kidnap_jump_in = options.kidnap_jump_in;
  if (options.kidnap_jump_random) {
    // Its own stream of the seed: the start's draw stays as it was.
    std::mt19937_64 rng(StreamSeed(options.seed, kKidnapJumpStream));
    const double length = map.ring(ring).LengthIn();
    vr.kidnap_jump_in = std::uniform_real_distribution<double>(0.1, 0.9)(rng) * length;
  }
  virtual_robot::PlacedRobot placed = virtual_robot::PlaceRobot(map, setup.robot, vr, ring);
  Run run(run_setup, options, std::move(placed), ring);
  RunResult result = run.Finish();
  result.seed = vr.seed;
  if (options.kidnap_after_s >= 0.0) result.kidnap_jump_in = vr.kidnap_jump_in;
  return result;
}

}  // namespace stickrep::whereami
