// Write throughput of a recording: camera frames (512 x 480 mono8, as the camera process
// publishes them) and small sensor samples, committed in batches as stickrep-record does.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <vector>

#include "bag/bag_storage.h"

namespace {

std::string FreshPath() {
  static int n = 0;
  const auto path = std::filesystem::temp_directory_path() /
                    ("stickrep_bag_bench_" + std::to_string(getpid()) + "_" +
                     std::to_string(n++) + ".db3");
  std::filesystem::remove(path);
  return path.string();
}

void WriteSamples(benchmark::State& state) {
  const std::size_t size = static_cast<std::size_t>(state.range(0));
  std::vector<std::uint8_t> payload(size, 0x5a);
  for (auto _ : state) {
    state.PauseTiming();
    const std::string path = FreshPath();
    state.ResumeTiming();
    {
      stickrep::bag::BagWriter w(path, 0.1);
      const auto id = w.AddTopic({0, "device/camera/frame", "stickrep::msgs::Image", "cdr", "[]"});
      for (int k = 0; k < 200; ++k) w.Write(id, k, k, payload.data(), payload.size());
      w.Flush();
    }
    state.PauseTiming();
    std::filesystem::remove(path);
    std::filesystem::remove(path + "-wal");
    std::filesystem::remove(path + "-shm");
    state.ResumeTiming();
  }
  state.SetBytesProcessed(state.iterations() * 200 * static_cast<int64_t>(size));
  state.SetItemsProcessed(state.iterations() * 200);
}

}  // namespace

// 245,792 bytes: a serialized camera frame; 236: a sonar echo.
BENCHMARK(WriteSamples)->Arg(245792)->Arg(236)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
