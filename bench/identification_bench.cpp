// Identification speed on closed-loop data of amb1dof_voltage (10 kHz, PRBS, nominal plant):
// samples identified per wall second (counter `samples_per_s`) against the record length
// (1e4 to 1e6 samples) and, for the ARX-based methods, the ARX order. closed-loop and
// projection include their jackknife uncertainty (8 leave-one-segment-out fits); pem its
// closed-loop start and covariance. Whole methods run through
// identify_experiment (no validation segment), the ARX fit alone through fit_arx.
#include <benchmark/benchmark.h>

#include <map>

#include "identifier/identify_experiment.hpp"
#include "identifier/time_domain/arx.hpp"
#include "identifier/time_domain/loop_signals.hpp"
#include "plant_sim/scenario.hpp"

namespace {

// One simulated record per length, shared by all benchmarks.
const ambid::Experiment& record(Eigen::Index samples) {
  static std::map<Eigen::Index, ambid::Experiment> cache;
  auto it = cache.find(samples);
  if (it == cache.end()) {
    ambid::sim::ScenarioOptions o;
    o.duration = double(samples) * o.sample_time;
    o.amplitude = 0.5;
    it = cache.emplace(samples, ambid::sim::simulate_scenario(o)).first;
  }
  return it->second;
}

void identify(benchmark::State& state, const std::string& method) {
  const ambid::Experiment& e = record(state.range(0));
  ambid::ident::IdentifyOptions o;
  o.method = method;
  o.validation_fraction = 0.0;
  o.jackknife_segments = 0;  // one fit per iteration: the rate of the method, not of its 8-fold jackknife
  if (state.range(1) > 0) o.arx_order = state.range(1);
  for (auto _ : state) {
    const ambid::Model m = ambid::ident::identify_experiment(e, o);
    benchmark::DoNotOptimize(m.discrete.A.data());
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(e.samples()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Deadbeat(benchmark::State& state) { identify(state, "deadbeat"); }
void BM_DeadbeatIv(benchmark::State& state) { identify(state, "deadbeat-iv"); }
void BM_ClosedLoop(benchmark::State& state) { identify(state, "closed-loop"); }
void BM_Projection(benchmark::State& state) { identify(state, "projection"); }
void BM_Pem(benchmark::State& state) { identify(state, "pem"); }

void BM_FitArx(benchmark::State& state) {
  const ambid::Experiment& e = record(state.range(0));
  const ambid::ident::LoopSignals s = ambid::ident::loop_signals(e, "bench");
  ambid::ident::ArxOptions o;
  o.order = state.range(1);
  for (auto _ : state) {
    const ambid::ident::ArxModel m = ambid::ident::fit_arx(s.y, s.u, o);
    benchmark::DoNotOptimize(m.a.data());
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(e.samples()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

// Arguments: {samples, ARX order (0: the method's default / not used)}.
BENCHMARK(BM_Deadbeat)->Args({10000, 0})->Args({100000, 0})->Args({1000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeadbeatIv)->Args({10000, 0})->Args({100000, 0})->Args({1000000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ClosedLoop)->ArgsProduct({{10000, 100000, 1000000}, {4, 8, 16}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Projection)->ArgsProduct({{10000, 100000}, {4, 8, 16}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pem)->Args({10000, 0})->Args({30000, 0})->Args({100000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitArx)->ArgsProduct({{10000, 100000, 1000000}, {4, 8, 16, 32}})->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
