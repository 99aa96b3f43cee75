// Speed of the pose-recovery matchers on the Engineering Building map (641 edges):
// incorporating one sensed edge into the deterministic matcher — the first edge (every map
// position) and a later edge (the survivors) — and one Bayes filter update.
#include <benchmark/benchmark.h>

#include <string>

#include "recovery/bayes_localizer.h"
#include "recovery/pose_recovery.h"
#include "stickrep/map_io.h"

namespace {

using namespace stickrep;

struct Fixture {
  map::Map map =
      map::LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  map::MatchIndex index{map};
  // A typical start: the third door of the first ring, forwards, six edges.
  std::vector<map::SensedEdge> sequence = map::ExactSequence(index, 10, +1, 6);
};

Fixture& F() {
  static Fixture f;
  return f;
}

recovery::RecoveryConfig Config() {
  recovery::RecoveryConfig c;
  c.strategy = recovery::Strategy::kDeterministic;
  return c;
}

void BM_RecoveryFirstEdge(benchmark::State& state) {
  recovery::PoseRecovery r(F().index, Config());
  map::SensedEdge first = F().sequence[state.range(0)];
  first.angle_deg = std::numeric_limits<double>::quiet_NaN();
  for (auto _ : state) {
    r.Reset();
    benchmark::DoNotOptimize(r.Add(first));
  }
  state.counters["candidates"] = static_cast<double>(r.candidates().size());
}
// 0: a wall, 1: a door36 (the commonest edges).
BENCHMARK(BM_RecoveryFirstEdge)->Arg(0)->Arg(1);

void BM_RecoveryLaterEdge(benchmark::State& state) {
  recovery::PoseRecovery r(F().index, Config());
  const int k = static_cast<int>(state.range(0));
  std::size_t survivors = 0;
  for (auto _ : state) {
    state.PauseTiming();
    r.Reset();
    for (int i = 0; i < k; ++i) r.Add(F().sequence[i]);
    survivors = r.candidates().size();
    state.ResumeTiming();
    benchmark::DoNotOptimize(r.Add(F().sequence[k]));
  }
  state.counters["survivors"] = static_cast<double>(survivors);
}
BENCHMARK(BM_RecoveryLaterEdge)->Arg(1)->Arg(2)->Arg(3);

void BM_BayesUpdate(benchmark::State& state) {
  recovery::BayesModel m;
  m.confusion = recovery::Resolve(recovery::ErrorModel::Paper(), F().index);
  m.noise.class_region_in = recovery::DefaultClassRegions();
  recovery::BayesLocalizer b(F().index, m);
  const int k = static_cast<int>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    b.Reset();
    for (int i = 0; i < k; ++i) b.Add(F().sequence[i]);
    state.ResumeTiming();
    benchmark::DoNotOptimize(b.Add(F().sequence[k]));
  }
}
// 0: the first edge (prior over every state), 1-3: later updates.
BENCHMARK(BM_BayesUpdate)->Arg(0)->Arg(1)->Arg(3);

}  // namespace

BENCHMARK_MAIN();
