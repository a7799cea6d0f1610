// Speed of the whole model audit (diagnostics/audit.hpp: replay, screening of every candidate,
// Ceres fits, improvement tests, FRFs, amplitude dependence) on a 5-second record at 10 kHz,
// the size issue 7 names: wall seconds per audit (`--benchmark_filter=Audit`). Records as the
// hidden-effect tests draw them: PRBS 0.3 V, position noise 2 nm, current noise 20 uA.
#include <benchmark/benchmark.h>

#include <map>

#include "diagnostics/audit.hpp"
#include "plant_sim/scenario.hpp"

namespace {

const ambid::Experiment& record(const std::string& effect) {
  static std::map<std::string, ambid::Experiment> cache;
  auto it = cache.find(effect);
  if (it == cache.end()) {
    ambid::sim::ScenarioOptions o;
    o.duration = 5.0;
    o.amplitude = 0.3;
    o.position_noise = 2e-9;
    o.current_noise = 2e-5;
    o.seed = 3;
    if (effect == "eddy_current") o.effects = {ambid::sim::make_effect("eddy_current", {{"tau", 1e-4}})};
    if (effect == "coil_resistance")
      o.effects = {ambid::sim::make_effect("coil_resistance", {{"channel", 2}, {"dR", 3.0}})};
    it = cache.emplace(effect, ambid::sim::simulate_scenario(o)).first;
  }
  return it->second;
}

void audit(benchmark::State& state, const std::string& effect) {
  const ambid::Experiment& e = record(effect);
  for (auto _ : state) {
    const ambid::diag::AuditResult r = ambid::diag::run_audit(e);
    benchmark::DoNotOptimize(r.baseline_total);
    state.SetLabel("cause " + r.cause);
  }
}

void BM_AuditClean(benchmark::State& state) { audit(state, "none"); }
void BM_AuditEddyCurrent(benchmark::State& state) { audit(state, "eddy_current"); }
void BM_AuditCoilResistance(benchmark::State& state) { audit(state, "coil_resistance"); }

// One audit takes seconds: a single iteration each, timed by the wall clock.
BENCHMARK(BM_AuditClean)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_AuditEddyCurrent)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_AuditCoilResistance)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace
BENCHMARK_MAIN();
