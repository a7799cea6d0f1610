// Closed-loop simulation speed of amb1dof_voltage at 10 kHz: simulated seconds per second of
// CPU time on one core (counter `realtime_factor`; `realtime_factor_wall` per wall-clock
// second, lower when other processes share the core), against the RK4 sub-steps per sample,
// for the default scenario (LQR observer controller, PRBS excitation) with and without
// noise. Target: >= 1000 at the runner's default sub-steps (kDefaultSubsteps).
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <chrono>

#include "plant_sim/integrator.hpp"
#include "plant_sim/scenario.hpp"

namespace {

void run(benchmark::State& state, bool noisy) {
  const int substeps = int(state.range(0));
  ambid::sim::ScenarioOptions o;
  o.duration = 1.0;
  o.sample_time = 1e-4;
  o.excitation = "prbs";
  if (noisy) {
    o.position_noise = 1e-7;
    o.current_noise = 1e-4;
    o.force_noise = 0.1;
  }
  ambid::sim::Scenario s = ambid::sim::build_scenario(o);
  s.options.substeps = substeps;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    auto e = ambid::sim::run_closed_loop(*s.truth, s.header, s.options);
    benchmark::DoNotOptimize(e.y.data());
  }
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  state.counters["realtime_factor"] =
      benchmark::Counter(o.duration * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["realtime_factor_wall"] = o.duration * double(state.iterations()) / wall.count();
  state.counters["samples_per_s"] =
      benchmark::Counter(double(s.options.samples) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Amb1dofClosedLoop(benchmark::State& state) { run(state, false); }
void BM_Amb1dofClosedLoopNoisy(benchmark::State& state) { run(state, true); }

// Argument: RK4 sub-steps per sample (the runner's default is kDefaultSubsteps = 1).
BENCHMARK(BM_Amb1dofClosedLoop)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Amb1dofClosedLoopNoisy)->Arg(ambid::sim::kDefaultSubsteps)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  // Each run returns a fresh ~0.6 MB record. By default glibc hands the freed record back to
  // the kernel and page-faults it in again on the next repetition (~13 % of the CPU time,
  // mostly in the kernel): a cost of repeating the run in one process, not of simulating.
  // Keep it in the heap instead.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
