#pragma once

// The whole Where-am-I run without middleware: the virtual robot's world and the sonar,
// camera, locomotion, landmark, localizer and executive components, the very classes the
// processes run, read from the same configuration files and wired by topic on the in-process
// executor's simulated clock (in_process_stack.h). Deterministic for a seed, and as fast as
// the renderer allows: it measures what the live stack does without the scheduling of seven
// processes on one machine.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "executive/executive_config.h"
#include "landmark/landmark_config.h"
#include "localizer/localizer_config.h"
#include "locomotion/locomotion_config.h"
#include "sensing/robot_config.h"
#include "stickrep/map.h"
#include "virtual_robot/virtual_robot_component.h"
#include "virtual_robot/virtual_robot_config.h"
#include "whereami/edge_errors.h"

namespace stickrep::whereami {

// Everything a run is built from, as the processes read it.
struct RunSetup {
  std::string map_file;
  std::shared_ptr<const map::Map> map;
  sensing::RobotConfig robot;
  virtual_robot::VirtualRobotConfig virtual_robot;
  landmark::LandmarkConfig landmark;
  localizer::LocalizerSettings localizer;
  locomotion::LocomotionConfig locomotion;
  executive::ExecutiveConfig executive;
};

// Reads system.yaml, robot.yaml and the sections of the virtual robot, landmark,
// localizer, locomotion and executive processes from `config_dir` (configs/ by default).
// `map_file` and `virtual_robot_file`, when not empty, replace system.yaml's map and
// virtual_robot.yaml. Throws InputError naming the file, line and key of a bad value.
RunSetup LoadRunSetup(const std::string& config_dir, const std::string& map_file = "",
                      const std::string& virtual_robot_file = "");

struct RunOptions {
  std::uint64_t seed = 1;        // replaces the virtual robot's seed
  double max_sim_s = 600.0;      // give up after this much simulated time
  // Pose maintenance: once localized, send a goal half the ring ahead (so the robot keeps
  // travelling) and kidnap the robot kidnap_after_s later by kidnap_jump_in along the
  // ring; the run then goes on until the pose is recovered again. -1: no kidnap, the run
  // ends at the first localized pose.
  double kidnap_after_s = -1.0;
  double kidnap_jump_in = 0.0;
  // Instead of kidnap_jump_in: a jump drawn uniformly over the middle 80 % of the ring's
  // length from the run's seed (the start's stream is not touched).
  bool kidnap_jump_random = false;
  // Without a kidnap: once localized, keep travelling (a goal half the ring ahead) this far
  // and watch the pose all the way (RunResult::false_losts, wrong_localized); 0: the run ends
  // at the first localized pose.
  double keep_going_ft = 0.0;
  // Record the sensed sequence and the map edges the camera passed (RunResult::trace).
  bool trace = false;
  // Record the base's true path (RunResult::path).
  bool record_path = false;
  // Replaces the virtual robot's ring (empty: keep it).
  std::string ring_id;
  // Measuring the assembled edges' errors (RunResult::errors) instead of localizing: the
  // robot travels this far, whatever the localizer says. 0: a Where-am-I run.
  double measure_ft = 0.0;
};

// One localized pose and how it compares with the truth.
using Recovery = virtual_robot::PoseCheck;

// A spell of a wrong pose published as LOCALIZED: how many edges the localizer sensed and
// how far the robot travelled before it said LOST or named the right place (from the kidnap,
// or from the first wrong sample), and how it ended.
struct WrongSpell {
  long edges = 0;  // sensed edges the localizer took in while the wrong pose was held
  double distance_ft = 0.0;
  std::string ended_by;  // "LOST", "RECOVERING", "corrected", or "run ended"
  // Of those, after a kidnap: edges the robot had sensed before it (a door is taken in once
  // the camera is past it, the wall before it with it), of the old place: no evidence of the
  // kidnap.
  long edges_sensed_before = 0;
};

// A pose the localizer published with its confidence, and whether it named where the robot
// truly was (sampled when the evidence changed: each sensed edge and each change of status).
struct ConfidenceSample {
  double confidence = 0.0;
  bool localized = false;
  bool correct = false;
};

// How a run ended. A run that touched a wall counts as a collision whatever else happened;
// a run that could not be run (e.g. no possible start) as failed.
enum class Ending { kCorrect, kWrong, kNoneInTime, kCollision, kFailed };
const char* ToString(Ending ending);

struct RunResult {
  std::uint64_t seed = 0;
  std::string start;  // where the run started, in words
  std::vector<std::string> start_redraws;  // starts refused (against a wall) and drawn again
  std::optional<Recovery> first;
  bool kidnapped = false;
  bool lost_detected = false;       // the localizer turned LOST after the kidnap
  double lost_after_ft = 0.0;       // travelled from the kidnap to LOST
  std::optional<Recovery> second;   // recovered after the kidnap
  double kidnap_jump_in = 0.0;      // how far the kidnap moved the robot along the ring
  // After the kidnap: how long the old (now wrong) pose stayed LOCALIZED, and how many edges
  // from the kidnap on the map shows alike at the old place and the new one (the first
  // partial wall included): no localizer can tell them apart sooner than the edge after.
  std::optional<WrongSpell> after_kidnap;
  int kidnap_edges_alike = 0;
  // Outside a kidnap's spell, once first localized: LOST said while the pose was right, and
  // the spells of a wrong pose published as LOCALIZED.
  int false_losts = 0;
  // Outside a kidnap's spell: a right LOCALIZED pose given up (to RECOVERING or LOST).
  int right_poses_given_up = 0;
  std::vector<WrongSpell> wrong_localized;
  // Every LOCALIZED pose the filter gave up, once first localized (Localizer::GivenUp):
  // whether it was right, the wrong pose a kidnap left or another wrong pose; the filter's
  // belief in it when given up, and whether LOST was said (rather than RECOVERING); where
  // LOST was weighed again edges on, the belief in it then (Localizer::GivenUp::belief_on).
  struct GivenUpPose {
    std::string pose;  // "right", "kidnap" or "wrong"
    double belief = 0.0;
    bool lost = false;
    std::optional<double> belief_on;
  };
  std::vector<GivenUpPose> given_up;
  std::vector<ConfidenceSample> confidences;
  int frames = 0;
  int doors_observed = 0;
  int collisions = 0;
  double max_offset_in = 0.0;       // beyond 8 ft of corners, after 20 ft
  double max_heading_deg = 0.0;
  double off_ring_ft = 0.0;  // travelled outside the start ring's hallway, not judged
  double sim_s = 0.0;
  std::string ended;                // why the run ended
  // With RunOptions::trace: the localizer's sensed sequence when the run ended, and the
  // edges of the map (as the hallway follower senses it) that the camera's axis passed.
  std::string sensed_trace;
  std::string true_trace;
  // With RunOptions::record_path: the base's true position (x, y in inches, building frame)
  // every few inches of travel.
  std::vector<std::pair<double, double>> path;
  // With RunOptions::trace: the hallway behaviour's changes of state, with the simulated
  // time and its reason (the first 200).
  std::vector<std::string> behaviour_log;
  // With RunOptions::measure_ft: the assembled edges against the truth, from 20 ft on.
  EdgeErrorCounts errors;
  bool failed = false;              // the run could not be run; `ended` says why
  // Samples a component dropped, "component: topic: reason x count" (none on a sound run).
  std::vector<std::string> drops;

  Ending ending() const;
};

RunResult RunWhereAmI(const RunSetup& setup, const RunOptions& options);

}  // namespace stickrep::whereami
