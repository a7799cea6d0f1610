// The recursive prediction-error method (`rpem`) against the batch one (`pem`) on noisy
// closed-loop records of amb1dof_voltage (10 kHz, 1 V PRBS, 0.1 um on x, 1 mA on each current),
// and the identifier daemon's CPU per bearing at real time.
// - BM_RpemUpdate: one Amb1dofRecursivePem::update per sample over a 1e4-sample record;
//   counter samples_per_s, its inverse the cost per sample.
// - BM_Pem / BM_Rpem: whole records of 1e3..1e5 samples through identify_experiment (pem cold:
//   its starts and covariance; rpem: from the nominal model); counter samples_per_s.
// - BM_DaemonDefault: the identifier daemon's computation with its default method (rpem,
//   continuous: ContinuousEstimator with its default settings, carry 0.1) on 1 s of plant
//   samples published every 0.25 s (the daemon's default window); BM_DaemonPemWindows the same
//   samples in 0.25 s windows identified each by pem, cold (daemons::identify_window), as the
//   daemon did before rpem became its default. One iteration is 1 s of plant time, so the CPU
//   time per iteration (counter core_fraction) is the share of a core one bearing at 10 kHz
//   needs (target <= 0.10).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <ctime>
#include <map>
#include <string_view>
#include <vector>

#include "identifier/amb1dof_structure.hpp"
#include "identifier/families/amb1dof_prediction_error.hpp"
#include "identifier/families/amb1dof_recursive_pem.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/recursive_identification.hpp"
#include "identifier/time_domain/loop_signals.hpp"
#include "plant_sim/scenario.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "services/daemons/identify_window.hpp"

namespace {

using ambid::Experiment;

const Experiment& record(Eigen::Index samples) {
  static std::map<Eigen::Index, Experiment> cache;
  auto it = cache.find(samples);
  if (it == cache.end()) {
    ambid::sim::ScenarioOptions o;
    o.duration = double(samples) * o.sample_time;
    o.amplitude = 1.0;
    o.position_noise = 1e-7;
    o.current_noise = 1e-3;
    o.seed = 1;
    it = cache.emplace(samples, ambid::sim::simulate_scenario(o)).first;
  }
  return it->second;
}

double process_cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

void BM_RpemUpdate(benchmark::State& state) {
  const Experiment& e = record(10000);
  const ambid::ident::LoopSignals s = ambid::ident::loop_signals(e, {"x", "i1", "i2"}, {"u1", "u2"}, "bench");
  Eigen::Vector3d spread;
  for (Eigen::Index j = 0; j < 3; ++j) spread(j) = std::sqrt((s.y.col(j).array() - s.y.col(j).mean()).square().mean());
  const ambid::ident::PemWarmStart start =
      ambid::ident::amb1dof_cold_start(ambid::ident::amb1dof_nominal_structure(e, "bench"), spread, e.sample_time);
  ambid::ident::Amb1dofRecursivePem estimator(start, spread, e.sample_time,
                                              ambid::ident::amb1dof_coil_operating_point(e, "bench"));
  for (auto _ : state) {
    estimator.restart(s.y.row(0).transpose());  // the record again: not a jump of the state
    for (Eigen::Index k = 0; k < s.y.rows(); ++k) estimator.update(s.y.row(k).transpose(), s.u.row(k).transpose());
    benchmark::DoNotOptimize(estimator.v().data());
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(s.y.rows()) * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["projections"] = double(estimator.projections());
}

void identify(benchmark::State& state, const std::string& method) {
  const Experiment& e = record(state.range(0));
  ambid::ident::IdentifyOptions o;
  o.method = method;
  o.validation_fraction = 0.0;
  for (auto _ : state) {
    const ambid::Model m = ambid::ident::identify_experiment(e, o);
    benchmark::DoNotOptimize(m.discrete.A.data());
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(double(e.samples()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
void BM_Pem(benchmark::State& state) { identify(state, "pem"); }
void BM_Rpem(benchmark::State& state) { identify(state, "rpem"); }

// 1 s of plant samples (after the daemon's 0.25 s settle) in the daemon's 0.25 s windows.
std::vector<Experiment> plant_second() {
  const Experiment& e = record(12500);
  std::vector<Experiment> windows;
  for (Eigen::Index begin = 2500; begin < 12500; begin += 2500)
    windows.push_back(ambid::ident::experiment_segment(e, begin, begin + 2500));
  return windows;
}

template <typename Identify>
void plant_seconds(benchmark::State& state, Identify&& identify) {
  const std::vector<Experiment> windows = plant_second();
  double cpu = 0.0;
  std::uint64_t seq = 0;
  for (auto _ : state) {
    const double start = process_cpu_seconds();
    for (const Experiment& w : windows) {
      const ambid::bus::IdentifiedModel m = identify(w, seq++);
      benchmark::DoNotOptimize(m.seq);
    }
    cpu += process_cpu_seconds() - start;
  }
  state.counters["core_fraction"] = cpu / double(state.iterations());  // CPU s per plant s
}

void BM_DaemonDefault(benchmark::State& state) {
  static_assert(std::string_view(ambid::daemons::kDefaultDaemonMethod) == "rpem");
  ambid::daemons::ContinuousEstimator estimator;
  plant_seconds(state, [&](const Experiment& w, std::uint64_t seq) { return estimator.identify(w, "bench", seq); });
}

void BM_DaemonPemWindows(benchmark::State& state) {
  const ambid::ident::IdentifyOptions o = ambid::daemons::window_identify_options("pem");
  plant_seconds(state, [&](const Experiment& w, std::uint64_t seq) {
    return ambid::daemons::identify_window(w, "bench", seq, o);
  });
}

BENCHMARK(BM_RpemUpdate)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pem)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(30000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Rpem)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(30000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DaemonDefault)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DaemonPemWindows)->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_MAIN();
