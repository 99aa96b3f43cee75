#include "whereami_tool/whereami_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/input_error.h"
#include "common/quantile.h"
#include "common/worker_pool.h"
#include "localizer/localizer_config.h"
#include "plot/map_render.h"
#include "stickrep/hallway_view.h"
#include "study_tool/study_report.h"
#include "whereami_tool/calibration_fit.h"
#include "whereami_tool/integrity_report.h"
#include "whereami_tool/wall_residuals.h"

namespace stickrep::whereami {

namespace {

std::string Describe(const std::optional<Recovery>& r) {
  if (!r) return "no pose";
  // The truth's ring is named where it is not the pose's (the base went on into another
  // corridor of the floor).
  const std::string truth_ring =
      r->truth_ring_id == r->ring_id ? std::string() : r->truth_ring_id + " ";
  return fmt::format("{} after {} edges, {:.1f} ft, {:.1f} s: {} edge {} {}, truth {}edge {} {}",
                     r->correct ? "CORRECT" : "INCORRECT", r->edges_sensed, r->distance_ft,
                     r->time_s, r->ring_id, r->edge, r->forward ? "fwd" : "back", truth_ring,
                     r->truth_edge, r->truth_forward ? "fwd" : "back");
}

nlohmann::json ToJson(const std::optional<Recovery>& r) {
  if (!r) return nullptr;
  return {{"ring", r->ring_id},        {"edge", r->edge},
          {"forward", r->forward},     {"truth_ring", r->truth_ring_id},
          {"truth_edge", r->truth_edge}, {"truth_forward", r->truth_forward},
          {"correct", r->correct},     {"edges_sensed", r->edges_sensed},
          {"distance_ft", r->distance_ft}, {"time_s", r->time_s}};
}

}  // namespace

Summary Summarize(const std::vector<RunResult>& results) {
  Summary s;
  s.runs = static_cast<int>(results.size());
  for (const RunResult& r : results) {
    s.collisions += r.collisions;
    s.endings[r.ending()]++;
    s.start_redraws += static_cast<int>(r.start_redraws.size());
    s.max_offset_in = std::max(s.max_offset_in, r.max_offset_in);
    s.max_heading_deg = std::max(s.max_heading_deg, r.max_heading_deg);
    s.left_ring += r.off_ring_ft > 0.0;
    if (r.kidnapped) {
      ++s.kidnapped;
      s.lost_detected += r.lost_detected;
      s.recovered_correct += r.second && r.second->correct;
    }
    if (!r.first) continue;
    ++s.localized;
    s.correct += r.first->correct;
    s.mean_edges += r.first->edges_sensed;
    s.mean_distance_ft += r.first->distance_ft;
    s.mean_time_s += r.first->time_s;
  }
  if (s.localized > 0) {
    s.mean_edges /= s.localized;
    s.mean_distance_ft /= s.localized;
    s.mean_time_s /= s.localized;
  }
  return s;
}

std::vector<RunResult> RunSeeds(const RunSetup& setup, const ToolOptions& options) {
  std::vector<RunResult> results(static_cast<size_t>(options.runs));
  ParallelFor(results.size(), options.threads, [&]() -> IndexTask {
    return [&](std::size_t i) {
      // One run that cannot be run is recorded as failed; the batch goes on.
      RunResult& result = results[i];
      result.seed = options.first_seed + static_cast<std::uint64_t>(i);
      try {
        RunOptions run;
        run.seed = result.seed;
        run.max_sim_s = options.max_sim_s;
        run.kidnap_after_s = options.kidnap_after_s;
        run.kidnap_jump_in = options.kidnap_jump_in;
        run.kidnap_jump_random = options.kidnap_jump_random;
        run.keep_going_ft = options.keep_going_ft;
        run.trace = options.trace;
        run.record_path = !options.path_png.empty();
        run.measure_ft = options.measure_ft;
        if (!options.rings.empty()) run.ring_id = options.rings[i % options.rings.size()];
        result = RunWhereAmI(setup, run);
      } catch (const std::exception& e) {
        result.failed = true;
        result.ended = std::string("failed: ") + e.what();
      }
    };
  });
  return results;
}

namespace {

// Measuring mode, one line per run; the assembled edges' counts added up over the runs that
// did not fail. Returns the number that failed.
int TallyMeasuredRuns(const RunSetup& setup, const ToolOptions& options, std::ostream& out,
                      EdgeErrorCounts& total) {
  int failed = 0;
  for (const RunResult& r : RunSeeds(setup, options)) {
    if (r.failed) {
      out << fmt::format("seed {:>4}  failed: {}\n", r.seed, r.ended);
      ++failed;
      continue;
    }
    const EdgeErrorCounts& c = r.errors;
    out << fmt::format("seed {:>4}  {} true doors: {} correct, {} mis-sized, {} missed; {} true "
                       "walls, {} false doors\n",
                       r.seed, c.true_doors, c.correct, c.missized, c.missed, c.true_walls,
                       c.false_doors);
    if (options.trace) {
      out << "            sensed: " << r.sensed_trace << "\n            passed: " << r.true_trace
          << "\n";
    }
    total.Add(c);
  }
  return failed;
}

// Doors alone and in a row, by class, a row's doors by the door before them, and the false
// doors on the short walls between doors against the other walls (EdgeErrorCounts::by_row,
// row_by_before, walls_by_row).
void PrintRowTallies(const EdgeErrorCounts& total, std::ostream& out) {
  const auto rates = [](const EdgeErrorCounts::DoorTally& t) {
    return fmt::format("{:>4} {:>4} {:>4} {:>4} ({:>3.0f} % missed)", t.passed, t.correct,
                       t.missized, t.missed, 100.0 * t.missed / std::max<long>(1, t.passed));
  };
  out << fmt::format(
      "  by class, doors alone and in a row (another door beside it or under {:g} "
      "in of wall away): passed, with their class, mis-sized, missed\n",
      map::kRowWallIn);
  for (int k = 0; k < map::kDoorClassCount; ++k) {
    const EdgeErrorCounts::DoorTally& alone = total.by_row[0][k];
    const EdgeErrorCounts::DoorTally& row = total.by_row[1][k];
    if (alone.passed + row.passed == 0) continue;
    out << fmt::format("    {:>5}  alone {}   in a row {}\n",
                       map::DoorClassName(static_cast<map::DoorClass>(k)), rates(alone),
                       rates(row));
  }
  out << fmt::format(
      "  doors of a row past a wall under {:g} in from the door before it, by that door: "
      "passed, with their class, mis-sized, missed\n",
      map::kRowWallIn);
  for (int k = 0; k < map::kDoorClassCount; ++k) {
    const EdgeErrorCounts::DoorTally& seen = total.row_by_before[0][k];
    const EdgeErrorCounts::DoorTally& missed = total.row_by_before[1][k];
    if (seen.passed + missed.passed == 0) continue;
    out << fmt::format("    {:>5}  after a seen door {}   after a missed door {}\n",
                       map::DoorClassName(static_cast<map::DoorClass>(k)), rates(seen),
                       rates(missed));
  }
  const auto per_wall = [](const EdgeErrorCounts::WallTally& w) {
    return fmt::format("{:.1f} % ({} on {} walls)",
                       100.0 * w.false_doors / std::max<long>(1, w.walls), w.false_doors, w.walls);
  };
  out << fmt::format(
      "  false doors per true wall: on walls under {:g} in between two doors {}; "
      "on the other walls {}\n",
      map::kRowWallIn, per_wall(total.walls_by_row[1]), per_wall(total.walls_by_row[0]));
  const EdgeErrorCounts::WallTally& other = total.walls_by_row[0];
  out << fmt::format("  false doors per 100 in of the other walls: {:.3f} ({} on {:.0f} in)\n",
                     100.0 * other.false_doors / std::max(1.0, other.wall_in), other.false_doors,
                     other.wall_in);
  out << "  false doors per true wall by the wall's length (in):";
  const auto& bins = EdgeErrorCounts::kWallLengthBinsIn;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const std::string range = b + 1 < bins.size() ? fmt::format("{:g}-{:g}", bins[b], bins[b + 1])
                                                  : fmt::format("{:g}+", bins[b]);
    out << fmt::format("{} {}", b == 0 ? "" : ";", range) << " "
        << per_wall(total.walls_by_length[b]);
  }
  out << "\n  the other walls by the false doors each held:";
  const auto& held = total.walls_by_false_doors;
  for (std::size_t k = 0; k < held.size(); ++k) {
    out << fmt::format("{} {}{} {} ({:.1f} %)", k == 0 ? "" : ";", k,
                       k + 1 == held.size() ? "+" : "", held[k],
                       100.0 * held[k] / std::max<long>(1, other.walls));
  }
  out << "\n";
}

// How the leaves' marks (Table 6.8) were read: counts, true mark by row, false doors last.
void PrintMarkReads(const EdgeErrorCounts& total, std::ostream& out) {
  out << "  door marks read (Table 6.8), sensed doors:  unknown    plain   window   poster\n";
  for (const bool right : {true, false}) {
    for (int t = 1; t < map::kDoorMarkCount; ++t) {
      const auto mark = static_cast<map::DoorMark>(t);
      const EdgeErrorCounts::MarkCounts& n = (right ? total.mark_read : total.mark_read_missized)[t];
      long sum = 0;
      for (long k : n) sum += k;
      if (sum == 0) continue;
      out << fmt::format("    {:<40} {:>8} {:>8} {:>8} {:>8}  ({:.1f} % read as {})\n",
                         fmt::format("true {}, {}", map::DoorMarkName(mark),
                                     right ? "class right" : "mis-sized"),
                         n[0], n[1], n[2], n[3], 100.0 * n[t] / sum, map::DoorMarkName(mark));
    }
  }
  const EdgeErrorCounts::MarkCounts& f = total.false_mark;
  out << fmt::format("    {:<40} {:>8} {:>8} {:>8} {:>8}\n", "false doors", f[0], f[1], f[2], f[3]);
}

// The measured rates beside Table 6.10, the walls' length error and the doors by width.
void PrintMeasuredRates(const recovery::ErrorModel& model, const EdgeErrorCounts& total,
                        const recovery::SensingNoise& noise, std::ostream& out) {
  out << fmt::format("\nper assembled edge (%)             paper Table 6.10   ours\n");
  out << fmt::format("  true doors sensed with their class   {:>8.2f} {:>8.2f}\n", 83.67,
                     100.0 * model.door_correct);
  out << fmt::format("  true doors mis-sized                 {:>8.2f} {:>8.2f}\n", 10.20,
                     100.0 * model.door_missized);
  out << fmt::format("  true doors missed                    {:>8.2f} {:>8.2f}\n", 6.12,
                     100.0 * model.door_missed);
  // Over every wall: the model's wall_false_door is the other walls' alone once the short
  // walls between doors have their own (ErrorModel::in_row).
  out << fmt::format("  false doors per true wall            {:>8.2f} {:>8.2f}\n", 15.91,
                     100.0 * total.false_doors / std::max<long>(1, total.true_walls));
  if (!total.wall_error_in.empty()) {
    double mean = 0.0, sq = 0.0;
    for (double e : total.wall_error_in) mean += e;
    mean /= total.wall_error_in.size();
    for (double e : total.wall_error_in) sq += (e - mean) * (e - mean);
    out << fmt::format("  walls between two doors sensed right: {} measured, sensed - true {:+.2f} "
                       "in mean, {:.2f} in standard deviation\n",
                       total.wall_error_in.size(), mean,
                       std::sqrt(sq / std::max<std::size_t>(1, total.wall_error_in.size() - 1)));
  }
  PrintWallResiduals(total, noise, out);
  if (model.wall_over_missed_door) {
    out << fmt::format(
        "  walls over missed doors, per missed door (wall_over_missed_door): "
        "{:+.2f} in longer, {:.2f} in sd beyond the matcher's own\n",
        model.wall_over_missed_door->bias_in, model.wall_over_missed_door->sigma_in);
  }
  out << "  by door width (in): passed, with their class, mis-sized, missed\n";
  for (const auto& [width, t] : total.by_width) {
    out << fmt::format("    {:>3}  {:>5} {:>5} {:>5} {:>5}  ({:.0f} % missed)\n", width, t.passed,
                       t.correct, t.missized, t.missed,
                       100.0 * t.missed / std::max<long>(1, t.passed));
  }
  PrintRowTallies(total, out);
  const long one_leaf = total.leaf_reads - total.leaf_split;
  out << fmt::format("  doors read narrower by >= {:g} in (a double door's leaf): {}; the other "
                     "leaf as a second door {} ({} after a sliver of wall, median {:.1f} in); "
                     "one leaf {}: the rest in the wall before {}, after {}, neither {}\n",
                     recovery::kLeafDeficitIn, total.leaf_reads, total.leaf_split,
                     total.leaf_sliver_in.size(), Median(total.leaf_sliver_in), one_leaf,
                     total.leaf_wall_before, total.leaf_wall_after,
                     one_leaf - total.leaf_wall_before - total.leaf_wall_after);
  PrintMarkReads(total, out);
  out << "(Table 6.10 counts frames; ours counts the edges the localizer is given, after the "
         "frames of a door are voted into one edge)\n";
}

// Measuring mode: the assembled edges' error rates beside Table 6.10, and the error model.
int Measure(const RunSetup& setup, const ToolOptions& options, std::ostream& out) {
  out << fmt::format("Assembled edges against the truth: map '{}', rings {}, seeds {}..{}, {:g} "
                     "ft each (from 20 ft on)\n",
                     setup.map->info().name,
                     options.rings.empty() ? std::string("(the virtual robot's)")
                                           : fmt::format("{}", fmt::join(options.rings, ", ")),
                     options.first_seed,
                     options.first_seed + static_cast<std::uint64_t>(options.runs) - 1,
                     options.measure_ft);
  EdgeErrorCounts total;
  const int failed = TallyMeasuredRuns(setup, options, out, total);
  const std::string source = fmt::format(
      "measured by stickrep-whereami on {} ({}), seeds {}..{}, {} true doors, {} true "
      "walls",
      setup.map->info().name,
      options.rings.empty() ? std::string("the virtual robot's ring")
                            : fmt::format("{}", fmt::join(options.rings, " ")),
      options.first_seed, options.first_seed + static_cast<std::uint64_t>(options.runs) - 1,
      total.true_doors, total.true_walls);
  const recovery::SensingNoise noise =
      localizer::MakeLocalizerConfig(localizer::ForMap(setup.localizer, *setup.map), *setup.map)
          .bayes.noise;
  const recovery::ErrorModel model = total.ToModel(source, &noise);
  PrintMeasuredRates(model, total, noise, out);
  if (!options.error_model_out.empty()) {
    if (failed > 0 || total.true_doors == 0) {
      out << fmt::format("no error model written: {} runs failed, {} true doors passed\n", failed,
                         total.true_doors);
      return 1;
    }
    model.Validate();
    std::ofstream f(options.error_model_out);
    if (!f) {
      throw InputError(options.error_model_out, 0, "--write-error-model", "cannot be written");
    }
    f << recovery::FormatErrorModelYaml(
        model, "The landmark pipeline's errors per assembled edge, measured on the live logic\n"
               "(stickrep-whereami --measure-ft); schema of configs/error_model_paper.yaml.");
    out << "error model written to " << options.error_model_out << "\n";
  }
  return 0;
}

// The tool's input, checked before any run.
RunSetup LoadCheckedSetup(const ToolOptions& options) {
  if (options.runs < 1) throw InputError("--runs", 0, "runs", "must be at least 1");
  RunSetup setup = LoadRunSetup(options.config_dir, options.map_file, options.virtual_robot_file);
  for (const std::string& ring : options.rings) {
    if (setup.map->FindRing(ring) < 0) {
      throw InputError(setup.map_file, 0, "--ring", "no ring '" + ring + "' in the map");
    }
  }
  // Each run reads the files of the observation model the map gets; a bad one is this tool's
  // input error, not a failed run.
  localizer::MakeLocalizerConfig(localizer::ForMap(setup.localizer, *setup.map),
                                 map::HallwayView(*setup.map, setup.localizer.view).view());
  return setup;
}

// The observation model `chosen` (ForMap's) names, as the header prints it.
std::string ObservationModelText(const localizer::LocalizerSettings& chosen) {
  return fmt::format(" ({}: {}, declared at confidence {:g}, the posterior {:.7g})",
                     localizer::ObservationForName(chosen.observation_for),
                     std::filesystem::path(chosen.observation.error_model_file).filename().string(),
                     chosen.observation.localized_confidence, chosen.observation.bayes_threshold);
}

void PrintRunsHeader(const RunSetup& setup, const ToolOptions& options, std::ostream& out) {
  out << fmt::format(
      "Where-am-I runs of the components in one process: map '{}' ({}), seeds {}..{}, {:.0f} in "
      "hallway, "
      "start up to {:g} in off the axis and {:g} deg turned; matcher {}{}{}\n",
      setup.map->info().name, setup.map_file, options.first_seed,
      options.first_seed + static_cast<std::uint64_t>(options.runs) - 1,
      setup.virtual_robot.world.hallway_width_in, setup.virtual_robot.start_lateral_offset_max_in,
      setup.virtual_robot.start_heading_error_max_deg,
      setup.localizer.localizer.method == localizer::MatchMethod::kBayes ? "bayes"
                                                                         : "deterministic",
      setup.localizer.localizer.method == localizer::MatchMethod::kBayes
          ? ObservationModelText(localizer::ForMap(setup.localizer, *setup.map))
          : std::string(),
      options.kidnap_after_s < 0.0 ? std::string()
      : options.kidnap_jump_random
          ? fmt::format(", kidnapped {:g} s after the pose by a jump drawn from each seed over "
                        "the middle 80 % of the ring",
                        options.kidnap_after_s)
          : fmt::format(", kidnapped {:g} s after the pose by {:g} in", options.kidnap_after_s,
                        options.kidnap_jump_in));
}

// One run's lines, and its path drawn over the map when asked for.
void PrintRun(const RunResult& r, const RunSetup& setup, const ToolOptions& options,
              std::ostream& out) {
  out << fmt::format("seed {:>4}  start {}\n", r.seed, r.failed ? "-" : r.start);
  for (const std::string& redraw : r.start_redraws) {
    out << "            start " << redraw << "\n";
  }
  out << fmt::format("            {}: {}", ToString(r.ending()), Describe(r.first));
  if (r.kidnapped) {
    out << fmt::format(
        "\n            kidnapped {:.0f} in along the ring: {}{}; then {}", r.kidnap_jump_in,
        r.lost_detected ? fmt::format("LOST after {:.1f} ft", r.lost_after_ft)
                        : std::string("never LOST"),
        r.after_kidnap
            ? fmt::format(" (wrong pose LOCALIZED for {} edges sensed "
                          "after the kidnap and {} before it, {:.1f} "
                          "ft, ended by {}; the map alike for {} edges)",
                          r.after_kidnap->edges - r.after_kidnap->edges_sensed_before,
                          r.after_kidnap->edges_sensed_before, r.after_kidnap->distance_ft,
                          r.after_kidnap->ended_by, r.kidnap_edges_alike)
            : std::string(),
        Describe(r.second));
  }
  if (r.false_losts > 0 || r.right_poses_given_up > 0 || !r.wrong_localized.empty()) {
    out << fmt::format(
        "\n            {} LOST while right, {} right poses given up, {} spells of a wrong "
        "LOCALIZED pose",
        r.false_losts, r.right_poses_given_up, r.wrong_localized.size());
  }
  out << fmt::format(
      "\n            {} frames, {} doors seen, {} collisions, envelope max "
      "{:.1f} in / {:.1f} deg{}; {:.1f} s simulated, {}\n",
      r.frames, r.doors_observed, r.collisions, r.max_offset_in, r.max_heading_deg,
      r.off_ring_ft > 0.0
          ? fmt::format(" ({:.1f} ft outside the start ring's hallway, not judged)", r.off_ring_ft)
          : std::string(),
      r.sim_s, r.ended);
  if (options.trace) {
    out << "            sensed: " << r.sensed_trace << "\n            passed: " << r.true_trace
        << "\n";
  }
  if (options.trace) {
    for (const std::string& line : r.behaviour_log) out << "            " << line << "\n";
  }
  if (!options.path_png.empty() && !r.path.empty()) {
    map::RenderOptions picture;
    picture.paths.push_back({r.path});
    picture.markers.push_back({r.path.front().first, r.path.front().second, "start"});
    picture.markers.push_back({r.path.back().first, r.path.back().second, ToString(r.ending())});
    const std::string file = fmt::format("{}_seed{}.png", options.path_png, r.seed);
    map::RenderMapPng(*setup.map, file, picture);
    out << "            path drawn in " << file << "\n";
  }
}

nlohmann::json RunJson(const RunResult& r) {
  nlohmann::json given_up = nlohmann::json::array();
  for (const RunResult::GivenUpPose& g : r.given_up) {
    nlohmann::json j = {{"pose", g.pose}, {"belief", g.belief}, {"lost", g.lost}};
    if (g.belief_on) j["belief_on"] = *g.belief_on;
    given_up.push_back(std::move(j));
  }
  nlohmann::json confidences = nlohmann::json::array();
  for (const ConfidenceSample& c : r.confidences) {
    confidences.push_back(
        {{"confidence", c.confidence}, {"correct", c.correct}, {"localized", c.localized}});
  }
  return {
      {"seed", r.seed},
      {"start", r.start},
      {"first", ToJson(r.first)},
      {"kidnapped", r.kidnapped},
      {"lost_detected", r.lost_detected},
      {"lost_after_ft", r.lost_after_ft},
      {"second", ToJson(r.second)},
      {"kidnap_jump_in", r.kidnap_jump_in},
      {"kidnap_edges_alike", r.kidnap_edges_alike},
      {"after_kidnap",
       r.after_kidnap ? nlohmann::json{{"edges", r.after_kidnap->edges},
                                       {"edges_sensed_before", r.after_kidnap->edges_sensed_before},
                                       {"distance_ft", r.after_kidnap->distance_ft},
                                       {"ended_by", r.after_kidnap->ended_by}}
                      : nlohmann::json(nullptr)},
      {"false_losts", r.false_losts},
      {"right_poses_given_up", r.right_poses_given_up},
      {"given_up", given_up},
      {"wrong_localized_spells", r.wrong_localized.size()},
      {"frames", r.frames},
      {"doors_observed", r.doors_observed},
      {"collisions", r.collisions},
      {"max_offset_in", r.max_offset_in},
      {"max_heading_deg", r.max_heading_deg},
      {"off_ring_ft", r.off_ring_ft},
      {"sim_s", r.sim_s},
      {"ended", r.ended},
      {"ending", ToString(r.ending())},
      {"sensed", r.sensed_trace},
      {"drops", r.drops},
      {"start_redraws", r.start_redraws},
      {"confidences", confidences}};
}

// The runs added up, beside the paper's Table 6.22 where it has the map.
void PrintSummary(const Summary& s, const RunSetup& setup, std::ostream& out) {
  out << fmt::format(
      "\n{} runs: {} localized, {} correct ({:.1f} %); {} collisions; envelope beyond 8 ft of "
      "corners after 20 ft, in the start ring's hallway: max |offset| {:.1f} in, max |heading "
      "error| {:.1f} deg; {} runs went on outside it (another corridor, a hall), not judged "
      "there\n",
      s.runs, s.localized, s.correct, 100.0 * s.correct / s.runs, s.collisions, s.max_offset_in,
      s.max_heading_deg, s.left_ring);
  std::vector<std::string> endings;
  for (const Ending e : {Ending::kCorrect, Ending::kWrong, Ending::kNoneInTime, Ending::kCollision,
                         Ending::kFailed}) {
    const auto it = s.endings.find(e);
    endings.push_back(fmt::format("{} {}", it == s.endings.end() ? 0 : it->second, ToString(e)));
  }
  out << fmt::format("endings: {}; {} starts against a wall drawn again\n",
                     fmt::join(endings, ", "), s.start_redraws);
  if (s.kidnapped > 0) {
    out << fmt::format("kidnapped {}: LOST detected {}, recovered correctly {}\n", s.kidnapped,
                       s.lost_detected, s.recovered_correct);
  }
  out << fmt::format("\n{:<34} {:>7} {:>12} {:>8} {:>11}\n", "", "edges", "distance ft", "time s",
                     "accuracy %");
  out << fmt::format("{:<34} {:>7.2f} {:>12.2f} {:>8.2f} {:>11.1f}\n",
                     "ours: rendered frames, live logic", s.mean_edges, s.mean_distance_ft,
                     s.mean_time_s, 100.0 * s.correct / s.runs);
  if (const auto paper =
          recovery::report::PaperSummaryFor(setup.map->info().name, /*with_error=*/true)) {
    out << fmt::format("{:<34} {:>7.2f} {:>12.2f} {:>8.2f} {:>11.1f}\n",
                       "paper Table 6.22, modeled error", paper->edges, paper->distance_ft,
                       paper->time_s, paper->accuracy_pct);
  }
  out << "(edges: the localizer's sequence when it declared the pose; distance and time: "
         "travelled from the start, aligning and turns included; accuracy over all runs)\n";
}

void WriteRunsJson(const std::string& path, const RunSetup& setup, const ToolOptions& options,
                   const nlohmann::json& runs, const Summary& s, const nlohmann::json& more) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "--json", "cannot be written");
  const localizer::ObservationSettings& model =
      localizer::ForMap(setup.localizer, *setup.map).observation;
  nlohmann::json j{{"map", setup.map->info().name},
                   {"calibration",
                    {{"slope", model.calibration.slope},
                     {"offset", model.calibration.offset},
                     {"localized_confidence", model.localized_confidence}}},
                   {"first_seed", options.first_seed},
                   {"runs", runs},
                   {"correct", s.correct},
                   {"localized", s.localized},
                   {"mean_edges", s.mean_edges},
                   {"mean_distance_ft", s.mean_distance_ft},
                   {"mean_time_s", s.mean_time_s}};
  j.update(more);
  f << j.dump(2) << "\n";
}

}  // namespace

int RunTool(const ToolOptions& options, std::ostream& out, std::ostream& err) {
  try {
    if (!options.fit_calibration.empty()) {
      PrintPooledCalibrationFit(FitCalibrationFromBatches(options.fit_calibration), out);
      return 0;
    }
    const RunSetup setup = LoadCheckedSetup(options);
    if (options.measure_ft > 0.0) return Measure(setup, options, out);
    PrintRunsHeader(setup, options, out);
    const std::vector<RunResult> results = RunSeeds(setup, options);
    nlohmann::json runs = nlohmann::json::array();
    for (const RunResult& r : results) {
      PrintRun(r, setup, options, out);
      runs.push_back(RunJson(r));
    }
    const Summary s = Summarize(results);
    PrintSummary(s, setup, out);
    const IntegritySummary integrity = SummarizeIntegrity(results);
    if (options.kidnap_after_s >= 0.0 || options.keep_going_ft > 0.0) {
      PrintIntegrity(integrity, out);
    }
    const Reliability reliability = ReliabilityOf(results);
    if (options.reliability) PrintReliability(reliability, out);
    if (!options.json_path.empty()) {
      WriteRunsJson(options.json_path, setup, options, runs, s,
                    {{"integrity", ToJson(integrity)}, {"reliability", ToJson(reliability)}});
    }
    return 0;
  } catch (const InputError& e) {
    err << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    err << "stickrep-whereami: " << e.what() << "\n";
    return kExitBadInput;
  }
}

}  // namespace stickrep::whereami
