#pragma once
// A ready-made closed-loop simulation of a named plant: the true plant (nominal parameters
// with overrides, e.g. a faulty coil), a controller designed on the *nominal* model, an
// excitation, noise, and the experiment header the runner fills. `ambid sim` and the plant
// daemon's simulated source both run this.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/closed_loop.hpp"
#include "plant_sim/effects.hpp"
#include "plant_sim/plant.hpp"

namespace ambid::sim {

struct ScenarioOptions {
  std::string name = "simulation";
  std::string plant = "amb1dof_voltage";
  std::map<std::string, double> true_parameters;  // overrides of the truth; the sidecar keeps nominal
  std::vector<Effect> effects;                    // effects of the truth (effects.hpp); the sidecar stays nominal
  std::string controller = "lqr";                 // lqr (observer + integral action) | pid | leadlag
  std::string excitation = "prbs";                // prbs | multisine | chirp | stepped_sine | none
  double amplitude = 0.05;                        // excitation level at each plant input (V); rms for multisine
  double f_min = 1.0, f_max = 1000.0;             // band of multisine, chirp and stepped sine (Hz)
  double duration = 2.0;                          // s
  double sample_time = 1e-4;                      // s
  double position_noise = 0.0;                    // sensor noise std of x (m)
  double current_noise = 0.0;                     // sensor noise std of i1, i2 (A)
  double force_noise = 0.0;                       // process noise std of the force Fz (N)
  // lamstf: noise std as a fraction of the noise-free loop's rms, per channel (seed 002's
  // "% noise"; lamstf_scenario.hpp). Other families refuse a non-zero value.
  double noise_level = 0.0;
  double input_limit = 0.0;  // |u| limit of the amplifiers (V); 0: none
  // Families that run a rig's own loop (maglev1coil_voltage, maglev_loop.hpp): the board's
  // settings by name (maglev_rig.hpp; unset ones keep their defaults), the reference levels
  // (m, cycled; empty: the loop's default) and how long each is held (s).
  std::map<std::string, double> rig;
  std::vector<double> levels;
  double step_period = 2.0;
  std::uint64_t seed = 1;
};

struct Scenario {
  std::unique_ptr<Plant> truth;
  Experiment header;  // everything but the samples
  ClosedLoopOptions options;
};

// The scenario of a family that runs in the generic closed-loop runner (families.hpp; today
// amb1dof_voltage). Throws Error naming the bad option (unknown plant, controller, excitation
// or parameter name, non-positive duration or sample time, negative noise or amplitude), and
// for a family that runs its own loop instead.
Scenario build_scenario(const ScenarioOptions& options);

// The simulation of the family of options.plant (families.hpp): build_scenario +
// run_closed_loop for amb1dof_voltage, the rig loop for maglev1coil_voltage.
Experiment simulate_scenario(const ScenarioOptions& options, ClosedLoopStatistics* statistics = nullptr);

}  // namespace ambid::sim
