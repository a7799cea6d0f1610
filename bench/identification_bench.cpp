// Identification speed on closed-loop data of amb1dof_voltage (10 kHz, PRBS, nominal plant):
// samples identified per wall second (counter `samples_per_s`) against the record length
// (1e4 to 1e6 samples) and, for the ARX-based methods, the ARX order. closed-loop and
// projection include their jackknife uncertainty (8 leave-one-segment-out fits); pem its
// closed-loop, deadbeat-iv and deadbeat starts and covariance (BM_Pem: cold; BM_PemWarm: from
// a previous fit, counter pem_iterations: its Levenberg-Marquardt steps). Whole methods run through
// identify_experiment (no validation segment), the ARX fit alone through fit_arx.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "identifier/identify_experiment.hpp"
#include "identifier/time_domain/arx.hpp"
#include "identifier/time_domain/loop_signals.hpp"
#include "plant_sim/scenario.hpp"

namespace {

// One simulated record per length, seed and noise, shared by all benchmarks. Noisy: a real
// bearing's sensors (0.1 um on x, 1 mA on each current) and a 1 V PRBS.
const ambid::Experiment& record(Eigen::Index samples, std::uint64_t seed = 1, bool noisy = false) {
  static std::map<std::tuple<Eigen::Index, std::uint64_t, bool>, ambid::Experiment> cache;
  auto it = cache.find({samples, seed, noisy});
  if (it == cache.end()) {
    ambid::sim::ScenarioOptions o;
    o.duration = double(samples) * o.sample_time;
    o.amplitude = noisy ? 1.0 : 0.5;
    o.position_noise = noisy ? 1e-7 : 0.0;
    o.current_noise = noisy ? 1e-3 : 0.0;
    o.seed = seed;
    it = cache.emplace(std::tuple{samples, seed, noisy}, ambid::sim::simulate_scenario(o)).first;
  }
  return it->second;
}

ambid::ident::IdentifyOptions options(const std::string& method) {
  ambid::ident::IdentifyOptions o;
  o.method = method;
  o.validation_fraction = 0.0;
  o.jackknife_segments = 0;  // one fit per iteration: the rate of the method, not of its 8-fold jackknife
  return o;
}

void run(benchmark::State& state, const ambid::Experiment& e, const ambid::ident::IdentifyOptions& o) {
  int iterations = 0;
  for (auto _ : state) {
    const ambid::Model m = ambid::ident::identify_experiment(e, o);
    benchmark::DoNotOptimize(m.discrete.A.data());
    if (m.extra.json().contains("pem")) iterations = m.extra.json()["pem"]["iterations"].get<int>();
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(e.samples()) * double(state.iterations()), benchmark::Counter::kIsRate);
  if (o.method == "pem") state.counters["pem_iterations"] = iterations;
}

void identify(benchmark::State& state, const std::string& method) {
  ambid::ident::IdentifyOptions o = options(method);
  if (state.range(1) > 0) o.arx_order = state.range(1);
  run(state, record(state.range(0)), o);
}

void BM_Deadbeat(benchmark::State& state) { identify(state, "deadbeat"); }
void BM_DeadbeatIv(benchmark::State& state) { identify(state, "deadbeat-iv"); }
void BM_ClosedLoop(benchmark::State& state) { identify(state, "closed-loop"); }
void BM_Projection(benchmark::State& state) { identify(state, "projection"); }
// pem on noisy records (its starts and Levenberg-Marquardt converge differently on noise-free
// data, where the free predictor gain tends to a deadbeat one): cold, and warm-started from the
// fit of another record of the same bearing (the service's previous window), as the identifier
// daemon would run it window after window.
void BM_Pem(benchmark::State& state) { run(state, record(state.range(0), 1, true), options("pem")); }
void BM_PemWarm(benchmark::State& state) {
  ambid::ident::IdentifyOptions o = options("pem");
  o.pem_warm_start =
      ambid::ident::pem_warm_start(ambid::ident::identify_experiment(record(state.range(0), 2, true), o));
  run(state, record(state.range(0), 1, true), o);
}

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
BENCHMARK(BM_PemWarm)->Args({10000, 0})->Args({100000, 0})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FitArx)->ArgsProduct({{10000, 100000, 1000000}, {4, 8, 16, 32}})->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
