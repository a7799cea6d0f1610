// Bearings one core serves at real time (issue 14: target >= 10 per core), with the identifier
// daemon's default estimator (rpem, continuous: daemons::ContinuousEstimator with its default
// settings) published every 0.5 s (deploy/config/identifier.json) on the stack's bearing with
// realistic noise (deploy/config/nominal-bearing.json: 0.1 um, 1 mA; one seed per bearing, 5 s
// records), each bearing its own windows (DescribedWindows) and estimator, as the daemon keeps
// per plant. One iteration is 0.5 s of plant time (10 kHz) of every bearing.
//   BM_FleetWindows/N: N bearings' batches straight into their windows, every window
//     identified; no bus.
//   BM_FleetOverBus/<vendor>/N: the same batches written by one participant (the plant side)
//     and taken by another in this process (the identifier side) over the loopback profile,
//     then identified; 0 = fastdds, 1 = cyclone. The difference to BM_FleetWindows is the bus.
//   BM_FleetBusOnly/<vendor>/N: the bus part alone (write, take, into the windows, nothing
//     identified): its cost per bearing at 10 kHz. Compare BM_BusSamples
//     (bus_throughput_bench) for the raw vendor rate of the same payload.
// Counters: bearings_per_core = plant seconds handled per second of the PROCESS's CPU time
// (both sides of the bus included), i.e. bearings one core keeps at real time;
// unidentified = windows the estimator refused (reported, not hidden); items_per_second =
// samples per second of process CPU time, to compare with BM_BusSamples' raw vendor rate.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "plant_sim/scenario.hpp"
#include "services/bus/make_bus.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/plant_samples.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "services/daemons/described_windows.hpp"
#include "services/daemons/scenario_json.hpp"

namespace {

using namespace std::chrono_literals;
using ambid::daemons::DescribedWindows;

constexpr Eigen::Index kBatch = 500;
constexpr double kWindow = 0.5;                 // s, deploy/config/identifier.json
constexpr Eigen::Index kBatchesPerWindow = 10;  // 0.5 s at 10 kHz
constexpr int kMaxBearings = 16;

const char* vendor(std::int64_t i) { return i == 0 ? "fastdds" : "cyclone"; }

// Bearing k's 5 s record (10 windows), seed 1 + k.
const std::vector<ambid::Experiment>& records() {
  static const std::vector<ambid::Experiment> r = [] {
    ambid::sim::ScenarioOptions o =
        ambid::daemons::read_scenario_file(std::string(AMBID_SOURCE_DIR) + "/deploy/config/nominal-bearing.json");
    o.duration = 5.0;
    std::vector<ambid::Experiment> out;
    for (int k = 0; k < kMaxBearings; ++k) {
      ambid::sim::ScenarioOptions ok = o;
      ok.seed = o.seed + std::uint64_t(k);
      out.push_back(ambid::sim::simulate_scenario(ok));
    }
    return out;
  }();
  return r;
}

std::string plant(int k) { return "bearing-" + std::to_string(k); }

// The plant side: bearing k's batches, its record looping (a new record every 5 s, seq 0).
struct Source {
  ambid::bus::PlantDescription description;
  std::uint64_t seq = 0;

  ambid::bus::PlantSamples next(int k) {
    const ambid::Experiment& e = records()[std::size_t(k)];
    const std::uint64_t per_record = std::uint64_t(e.samples() / kBatch);
    ambid::bus::PlantSamples b = ambid::convert::sample_batch(e, Eigen::Index(seq % per_record) * kBatch, kBatch,
                                                              plant(k), seq % per_record, 0.0);
    b.description_id = description.description_id;
    ++seq;
    return b;
  }
};

// The identifier side: one DescribedWindows and one estimator per bearing, as the daemon keeps them.
struct Fleet {
  std::vector<Source> sources;
  std::vector<DescribedWindows> windows;
  std::vector<ambid::daemons::ContinuousEstimator> estimators;
  std::int64_t unidentified = 0;
  std::uint64_t seq = 0;

  explicit Fleet(int n) {
    for (int k = 0; k < n; ++k) {
      sources.push_back({ambid::convert::describe(records()[std::size_t(k)], plant(k))});
      windows.emplace_back(ambid::daemons::WindowSettings{.window = kWindow, .settle = 0.0});
      windows.back().describe(sources.back().description);
      estimators.emplace_back();
    }
  }
  // Index of bearing `plant_id` ("bearing-K").
  static std::size_t index(const std::string& plant_id) { return std::stoul(plant_id.substr(8)); }

  void take(const ambid::bus::PlantSamples& b, bool identify) {
    const std::size_t k = index(b.plant_id);
    DescribedWindows& w = windows[k];
    w.add(b);
    while (w.full()) {
      const ambid::Experiment window = w.take();
      if (!identify) continue;
      try {
        benchmark::DoNotOptimize(estimators[k].identify(window, b.plant_id, seq++));
      } catch (const ambid::Error&) {
        ++unidentified;
      }
    }
  }
};

void set_counters(benchmark::State& state, int n, const Fleet& fleet) {
  state.counters["bearings_per_core"] = benchmark::Counter(n * kWindow, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["unidentified"] = double(fleet.unidentified);
  state.SetItemsProcessed(state.iterations() * n * kBatchesPerWindow * kBatch);
}

void BM_FleetWindows(benchmark::State& state) {
  const int n = int(state.range(0));
  Fleet fleet(n);
  for (auto _ : state)
    for (int k = 0; k < n; ++k)
      for (Eigen::Index b = 0; b < kBatchesPerWindow; ++b) fleet.take(fleet.sources[std::size_t(k)].next(k), true);
  set_counters(state, n, fleet);
}
BENCHMARK(BM_FleetWindows)->Arg(1)->Arg(10)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->MinTime(5.0);

void over_bus(benchmark::State& state, bool identify) {
  static int next_domain = 210;
  const int domain = next_domain++;
  const int n = int(state.range(1));
  auto plant_side = ambid::bus::make_bus(vendor(state.range(0)), domain);
  auto identifier_side = ambid::bus::make_bus(vendor(state.range(0)), domain);
  auto writer = plant_side->writer<ambid::bus::PlantSamples>();
  auto reader = identifier_side->reader<ambid::bus::PlantSamples>();
  for (int i = 0; i < 100 && writer->matched() == 0; ++i) identifier_side->wait(50ms);
  std::this_thread::sleep_for(1s);  // discovery both ways
  Fleet fleet(n);
  const std::int64_t per_iteration = n * kBatchesPerWindow;
  std::int64_t received = 0, lost = 0;
  for (auto _ : state) {
    // 0.5 s of every bearing, interleaved as n plant daemons would send it.
    for (Eigen::Index b = 0; b < kBatchesPerWindow; ++b)
      for (int k = 0; k < n; ++k) writer->write(fleet.sources[std::size_t(k)].next(k));
    std::int64_t got = 0;
    const auto give_up = std::chrono::steady_clock::now() + 2s;
    while (got < per_iteration && std::chrono::steady_clock::now() < give_up) {
      identifier_side->wait(1ms);
      for (const auto& batch : reader->take()) {
        fleet.take(batch, identify);
        ++got;
      }
    }
    received += got;
    lost += per_iteration - got;
  }
  set_counters(state, n, fleet);
  state.counters["lost_batches"] = double(lost);
}

void BM_FleetOverBus(benchmark::State& state) { over_bus(state, true); }
BENCHMARK(BM_FleetOverBus)
    ->ArgsProduct({{0, 1}, {10}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(5.0);

void BM_FleetBusOnly(benchmark::State& state) { over_bus(state, false); }
BENCHMARK(BM_FleetBusOnly)
    ->ArgsProduct({{0, 1}, {10}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
