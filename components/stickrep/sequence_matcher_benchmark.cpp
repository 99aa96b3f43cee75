// Hot path of the matching core on the Engineering Building: matching a whole no-error
// sequence from scratch (what one simulated run does per edge in the worst case), and the
// whole Figure 6.1 analysis.
#include <benchmark/benchmark.h>

#include "stickrep/ambiguity.h"
#include "stickrep/map_io.h"
#include "stickrep/sequence_matcher.h"

namespace stickrep::map {
namespace {

const Map& Engineering() {
  static const Map map =
      LoadMap(std::string(STICKREP_SOURCE_DIR) + "/maps/engineering_building_3f.yaml");
  return map;
}

void BM_MatchSequenceFromEveryStart(benchmark::State& state) {
  const MatchIndex index(Engineering());
  SequenceMatcher matcher(index);
  const int length = static_cast<int>(state.range(0));
  std::vector<std::vector<SensedEdge>> sequences;
  for (int g = 0; g < index.EdgeCount(); ++g)
    sequences.push_back(ExactSequence(index, g, +1, length));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(matcher.MatchAll(sequences[i]));
    i = (i + 1) % sequences.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MatchSequenceFromEveryStart)->Arg(1)->Arg(3)->Arg(6)->Arg(12);

void BM_AmbiguityAnalysis(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(AnalyseAmbiguity(Engineering()).mean_edges);
}
BENCHMARK(BM_AmbiguityAnalysis)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stickrep::map

BENCHMARK_MAIN();
