// Samples per second through the bus and through the identifier's computation, for the
// plant_samples payload the plant daemon sends (batches of 500 samples of 3 outputs, 2 inputs,
// 2 references at 10 kHz):
//   BM_BusSamples/<writer vendor>/<reader vendor>: raw vendor throughput, two participants in
//     one process over the loopback profile (0 = fastdds, 1 = cyclone), samples received per s
//     with at most 16 batches in flight;
//   BM_IdentifierWindows: what the identifier daemon does with them (windows of 2500 samples
//     collected, each published by its default method: rpem, continuous), samples per s.
// The plant -> identifier path sustains the smaller of the two.
#include <benchmark/benchmark.h>

#include <atomic>

#include "plant_sim/scenario.hpp"
#include "services/bus/make_bus.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/daemons/continuous_estimator.hpp"

namespace {

using namespace std::chrono_literals;
using ambid::convert::sample_batch;

const ambid::Experiment& record() {
  static const ambid::Experiment e = [] {
    ambid::sim::ScenarioOptions o;
    o.duration = 1.0;
    return ambid::sim::simulate_scenario(o);
  }();
  return e;
}

const char* vendor(std::int64_t i) { return i == 0 ? "fastdds" : "cyclone"; }

void BM_BusSamples(benchmark::State& state) {
  static int domain = 200;
  const int d = domain++;
  auto a = ambid::bus::make_bus(vendor(state.range(0)), d);
  auto b = ambid::bus::make_bus(vendor(state.range(1)), d);
  auto writer = a->writer<ambid::bus::PlantSamples>();
  auto reader = b->reader<ambid::bus::PlantSamples>();
  for (int i = 0; i < 100 && writer->matched() == 0; ++i) b->wait(50ms);
  std::this_thread::sleep_for(1s);
  const ambid::Experiment& e = record();
  // At most `window` batches in flight: the sustained rate without overrunning the reader's
  // KEEP_LAST history (a flood loses batches: Fast DDS -> Cyclone kept 3 % of them here).
  constexpr std::uint64_t window = 16;
  std::uint64_t seq = 0, received = 0;
  auto drain = [&] {
    for (const auto& batch : reader->take()) received += batch.count / 500;
  };
  for (auto _ : state) {
    writer->write(sample_batch(e, Eigen::Index(seq % 20) * 500, 500, "bench", seq, 0.0));
    ++seq;
    const auto give_up = std::chrono::steady_clock::now() + 2s;
    for (drain(); seq - received > window; drain()) {
      if (std::chrono::steady_clock::now() > give_up) {
        state.SkipWithError("no progress for 2 s (batches lost)");
        break;
      }
      b->wait(10ms);
    }
  }
  state.SetItemsProcessed(std::int64_t(received) * 500);
  state.counters["received_fraction"] = double(received) / double(seq);
}
BENCHMARK(BM_BusSamples)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();

void BM_IdentifierWindows(benchmark::State& state) {
  const ambid::Experiment& e = record();
  ambid::sim::ScenarioOptions o;
  ambid::convert::SampleWindow window(ambid::sim::build_scenario(o).header, 2500);
  ambid::daemons::ContinuousEstimator estimator;
  std::uint64_t seq = 0;
  for (auto _ : state) {
    for (int k = 0; k < 5; ++k, ++seq)
      window.add(sample_batch(e, Eigen::Index(seq % 20) * 500, 500, "bench", seq % 20, 0.0));
    while (window.full()) benchmark::DoNotOptimize(estimator.identify(window.take(), "bench", seq));
  }
  state.SetItemsProcessed(std::int64_t(seq) * 500);
}
BENCHMARK(BM_IdentifierWindows)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
