#include "study_tool/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <thread>

#include "common/worker_pool.h"
#include "recovery/bayes_localizer.h"
#include "recovery/sensed_stream.h"

namespace stickrep::recovery {

std::string MethodSpec::Id() const {
  const std::string base = kind == Kind::kBayes ? "bayes" : StrategyName(strategy);
  if (!error_free) return base;
  return kind == Kind::kBayes ? "bayes-no-error" : "no-error";
}

const ExperimentResult* DomainResult::Find(const std::string& id) const {
  for (const auto& e : experiments) {
    if (e.method.Id() == id) return &e;
  }
  return nullptr;
}

TrialSummary Summarise(const RunResult* runs, int count, double speed_ftps) {
  TrialSummary t;
  t.runs = count;
  int with_error = 0, recovered = 0, nc = 0, correct = 0, incorrect = 0, posed = 0;
  double edges = 0, travel = 0, restarts = 0;
  for (int i = 0; i < count; ++i) {
    const RunResult& r = runs[i];
    with_error += r.had_error;
    switch (r.outcome) {
      case Outcome::kCorrect:
        ++correct;
        recovered += r.had_error;
        break;
      case Outcome::kIncorrect:
        ++incorrect;
        break;
      case Outcome::kNotConverged:
        ++nc;
        break;
    }
    if (r.outcome != Outcome::kNotConverged) {
      ++posed;
      edges += r.edges;
      travel += r.travel_in;
      restarts += r.restarts;
    }
  }
  const double n = count > 0 ? count : 1;
  t.pct_with_error = 100.0 * with_error / n;
  t.pct_recovered = with_error > 0 ? 100.0 * recovered / with_error : 0.0;
  t.pct_not_converged = 100.0 * nc / n;
  t.pct_correct = 100.0 * correct / n;
  t.pct_incorrect = 100.0 * incorrect / n;
  if (posed > 0) {
    t.mean_edges = edges / posed;
    t.mean_distance_ft = travel / posed / 12.0;
    t.mean_time_s = t.mean_distance_ft / speed_ftps;
    t.mean_restarts = restarts / posed;
  }
  return t;
}

namespace {

// What one worker thread needs for one method.
struct MethodRunner {
  MethodSpec spec;
  std::unique_ptr<PoseRecovery> recovery;
  std::unique_ptr<BayesLocalizer> bayes;
};

RunResult RunOne(MethodRunner& m, SensedStream& stream, int max_edges, double frame_in) {
  RunResult r;
  std::uint64_t restarts_before = 0;
  if (m.recovery) {
    m.recovery->Reset();
    restarts_before = m.recovery->restarts();
  } else {
    m.bayes->Reset();
  }
  double end_in = 0;
  std::vector<map::SensedEdge> batch;
  int i = 0;
  while (i < max_edges) {
    // The edges that complete in the same frames: a wall and the door that ends it.
    batch.clear();
    const StreamEdge* last = nullptr;
    while (i < max_edges) {
      const StreamEdge* e = stream.At(i);
      if (e == nullptr) break;  // an open ring ended
      ++i;
      batch.push_back(e->sensed);
      r.had_error = r.had_error || !e->faithful;
      last = e;
      if (!e->with_next) break;
    }
    if (last == nullptr) break;
    r.edges = static_cast<std::uint16_t>(std::min(i, 65535));
    end_in = last->end_in;
    RecoveryStatus st = RecoveryStatus::kEmpty;
    std::optional<map::Candidate> pose;
    if (m.recovery) {
      st = m.recovery->AddEdges(batch.data(), batch.size());
      if (st == RecoveryStatus::kLocalized) pose = m.recovery->pose();
    } else {
      for (const map::SensedEdge& e : batch) st = m.bayes->Add(e);
      if (st == RecoveryStatus::kLocalized) {
        pose =
            map::Candidate{0, m.bayes->best().edge, static_cast<std::int8_t>(m.bayes->best().dir)};
      }
    }
    if (pose) {
      r.outcome = pose->last == last->truth && pose->dir == stream.dir() ? Outcome::kCorrect
                                                                         : Outcome::kIncorrect;
      break;
    }
    if (st == RecoveryStatus::kFailed) break;
  }
  if (m.recovery) {
    r.restarts = static_cast<std::uint16_t>(
        std::min<std::uint64_t>(m.recovery->restarts() - restarts_before, 65535));
  }
  const double frames = std::max(1.0, std::ceil(end_in / frame_in - 1e-9));
  r.travel_in = static_cast<float>(frames * frame_in);
  return r;
}

void CheckStudyOptions(const map::Map& map, const StudyOptions& options) {
  if (map.EdgeCount() == 0) throw std::invalid_argument("the map has no edges");
  if (options.trials < 1) throw std::invalid_argument("trials must be at least 1");
  if (options.runs < 1) throw std::invalid_argument("runs must be at least 1");
  if (options.methods.empty()) throw std::invalid_argument("no method to study");
  options.error_model.Validate();
  options.config.Validate();
}

// The map's indices of the rings named in `ids` (every ring: none).
std::vector<int> StartRingIndices(const map::Map& map, const std::vector<std::string>& ids) {
  std::vector<int> rings;
  for (const std::string& id : ids) {
    int found = -1;
    std::string known;
    for (int r = 0; r < map.RingCount(); ++r) {
      if (map.ring(r).id == id) found = r;
      known += (r > 0 ? ", " : "") + map.ring(r).id;
    }
    if (found < 0) {
      throw std::invalid_argument("start ring '" + id + "' is not a ring of map '" +
                                  map.info().name + "' (its rings: " + known + ")");
    }
    rings.push_back(found);
  }
  return rings;
}

// What every worker reads: the map's index and the two ways of sensing it, through the
// error model or error-free with exact matching (§6.4.1), and which of them are needed.
struct StudySensing {
  const map::MatchIndex* index = nullptr;
  const StudyConfig* cfg = nullptr;
  Confusion modeled;
  Confusion clean;
  SensingNoise quiet;
  map::MatchTolerance exact;
  double frame_in = 0;
  bool need_modeled = false, need_clean = false;
  std::vector<int> start_rings;  // empty: every ring
};

StudySensing PrepareSensing(const map::Map& map, const map::MatchIndex& index,
                            const StudyOptions& options) {
  const StudyConfig& cfg = options.config;
  StudySensing s;
  s.index = &index;
  s.start_rings = StartRingIndices(map, options.start_rings);
  s.cfg = &cfg;
  s.modeled = Resolve(options.error_model, index);
  s.clean = Resolve(ErrorModel::None(), index);
  s.quiet = SensingNoise::None();
  s.quiet.class_region_in = cfg.noise.class_region_in;
  s.exact = {0.0, 0.0, cfg.base_tolerance.angle_deg};
  s.frame_in = cfg.FrameTravelIn();
  for (const MethodSpec& m : options.methods) (m.error_free ? s.need_clean : s.need_modeled) = true;
  return s;
}

// The result before any run: the map's figures, and room for every run of every method.
DomainResult EmptyResult(const map::Map& map, const map::MatchIndex& index,
                         const StudyOptions& options, std::uint64_t total) {
  DomainResult out;
  out.map_name = map.info().name;
  out.map_edges = index.EdgeCount();
  double sum = 0;
  for (int g = 0; g < index.EdgeCount(); ++g) sum += index.metric(g);
  out.mean_edge_metric_in = sum / index.EdgeCount();
  out.experiments.resize(options.methods.size());
  for (std::size_t m = 0; m < options.methods.size(); ++m) {
    out.experiments[m].method = options.methods[m];
    out.experiments[m].runs.resize(total);
  }
  return out;
}

// One worker thread's runners, one per method.
std::vector<MethodRunner> MakeRunners(const StudySensing& s,
                                      const std::vector<MethodSpec>& methods) {
  const StudyConfig& cfg = *s.cfg;
  std::vector<MethodRunner> runners;
  for (const MethodSpec& spec : methods) {
    MethodRunner r;
    r.spec = spec;
    if (spec.kind == MethodSpec::Kind::kStrategy) {
      RecoveryConfig rc = RecoveryConfig::For(spec.strategy, cfg);
      if (spec.error_free) rc.base_tolerance = s.exact;
      r.recovery = std::make_unique<PoseRecovery>(*s.index, rc);
    } else {
      BayesModel bm{spec.error_free ? s.clean : s.modeled, spec.error_free ? s.quiet : cfg.noise,
                    cfg.bayes};
      r.bayes = std::make_unique<BayesLocalizer>(*s.index, bm);
    }
    runners.push_back(std::move(r));
  }
  return runners;
}

// Run `idx` (trial-major) of every method, all reading the same sensed edges.
void RunIndex(std::size_t idx, const StudySensing& s, const StudyOptions& options,
              std::vector<MethodRunner>& runners, DomainResult& out) {
  const StudyConfig& cfg = *s.cfg;
  const std::uint64_t trial = idx / options.runs, run = idx % options.runs;
  const std::uint64_t seed = RunSeed(options.seed, trial, run);
  std::optional<SensedStream> noisy, exact_stream;
  if (s.need_modeled) {
    noisy.emplace(*s.index, s.modeled, cfg.noise, cfg.base_tolerance, seed, s.start_rings);
  }
  if (s.need_clean) exact_stream.emplace(*s.index, s.clean, s.quiet, s.exact, seed, s.start_rings);
  for (std::size_t m = 0; m < runners.size(); ++m) {
    MethodRunner& runner = runners[m];
    SensedStream& stream = runner.spec.error_free ? *exact_stream : *noisy;
    out.experiments[m].runs[idx] = RunOne(runner, stream, cfg.max_edges, s.frame_in);
  }
}

// Each trial's summary, and the trial reported.
void SummariseTrials(ExperimentResult& e, const StudyOptions& options) {
  for (int t = 0; t < options.trials; ++t) {
    e.trials.push_back(Summarise(&e.runs[static_cast<std::size_t>(t) * options.runs], options.runs,
                                 options.config.speed_ftps));
  }
  // The paper reports "the median error rate trial" (§6.6.1); without error, the trial
  // with the median mean edge count.
  std::vector<int> order(options.trials);
  std::iota(order.begin(), order.end(), 0);
  const bool by_edges = e.method.error_free;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const double ka = by_edges ? e.trials[a].mean_edges : e.trials[a].pct_with_error;
    const double kb = by_edges ? e.trials[b].mean_edges : e.trials[b].pct_with_error;
    return ka < kb;
  });
  e.median_trial = order[(options.trials - 1) / 2];
  e.all = Summarise(e.runs.data(), static_cast<int>(e.runs.size()), options.config.speed_ftps);
}

}  // namespace

DomainResult RunStudy(const map::Map& map, const StudyOptions& options) {
  CheckStudyOptions(map, options);
  const auto t0 = std::chrono::steady_clock::now();

  const map::MatchIndex index(map);
  const StudySensing sensing = PrepareSensing(map, index, options);
  const std::uint64_t total =
      static_cast<std::uint64_t>(options.trials) * static_cast<std::uint64_t>(options.runs);
  DomainResult out = EmptyResult(map, index, options, total);

  // One runner per method and worker thread; each run has its own seeded streams.
  const auto make_worker = [&]() -> IndexTask {
    auto runners =
        std::make_shared<std::vector<MethodRunner>>(MakeRunners(sensing, options.methods));
    return [&, runners](std::size_t idx) { RunIndex(idx, sensing, options, *runners, out); };
  };
  const int threads =
      options.threads > 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  std::function<void(std::size_t, std::size_t)> progress;
  if (options.progress) {
    progress = [&](std::size_t done, std::size_t all) { options.progress(done, all); };
  }
  ParallelFor(total, threads, make_worker, progress);

  for (ExperimentResult& e : out.experiments) SummariseTrials(e, options);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace stickrep::recovery
