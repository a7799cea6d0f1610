// The rig protocol codec: encoding and decoding one full SAMPLES frame (22 samples of the AMB's
// 3 + 2 + 2 channels, 1469 bytes). items/s is samples/s: the gateway's headroom over the
// board's 10 kHz times the emulator's speed.
#include <benchmark/benchmark.h>

#include "services/rig/rig_frame.hpp"

namespace {

ambid::rig::Frame full_batch() {
  ambid::rig::SampleBatch b;
  b.sample_time = 1e-4;
  b.model = "amb1dof_voltage";
  b.ny = 3;
  b.nu = 2;
  b.nr = 2;
  const std::size_t n = ambid::rig::max_batch_samples(3, 2, 2, b.model.size());
  for (std::size_t k = 0; k < n; ++k) {
    b.t.push_back(double(k) * 1e-4);
    b.y.insert(b.y.end(), {1e-6 * double(k), 1.0, 1.0});
    b.u.insert(b.u.end(), {5.0, 5.0});
    b.r.insert(b.r.end(), {0.05, -0.05});
  }
  return {1, b};
}

void BM_EncodeBatch(benchmark::State& state) {
  const ambid::rig::Frame f = full_batch();
  for (auto _ : state) benchmark::DoNotOptimize(ambid::rig::encode(f));
  state.SetItemsProcessed(state.iterations() * 22);
}

void BM_DecodeBatch(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes = ambid::rig::encode(full_batch());
  for (auto _ : state) benchmark::DoNotOptimize(ambid::rig::decode(bytes));
  state.SetItemsProcessed(state.iterations() * 22);
}

}  // namespace

BENCHMARK(BM_EncodeBatch);
BENCHMARK(BM_DecodeBatch);
BENCHMARK_MAIN();
