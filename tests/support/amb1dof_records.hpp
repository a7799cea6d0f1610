#pragma once
// Closed-loop records of the amb1dof_voltage bearing that ambid's estimators did not generate,
// with their true linear models: for tests of every folder (identifier, diagnostics) that
// need an independent truth.
//
// Independent of the estimators' model: the NONLINEAR plant (force ~ (i / gap)^2, inductance
// ~ 1 / gap) integrated by RK4 with `substeps` steps per sample (the estimators use the exact
// zero-order hold of a linear model), under one of three controllers designed on the nominal
// model:
//   "lqr"       ambid's LQR + observer with integral action (plant_sim scenario "lqr");
//   "pid"       a decentralised PID on x with proportional current loops (scenario "pid");
//   "leadlag"   a decentralised lead-lag with integral action on x, the same current loops
//               (scenario "leadlag");
//   "observer"  an LQR + observer designed with other weights (a softer regulator, observer
//               poles within radius 0.9), see the definition.
// Truth: the true plant linearised where its closed loop settles. Every controller integrates
// x, so the loop comes to rest at x = 0 with both bias currents at i_eq (which a coil or
// amplifier fault moves, and ks, kr with it); v1..v9 are seed 000 eq. (4) of the true
// parameters with i0 = i_eq, i_eq read from an unexcited, noise-free run of the same loop.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/amb1dof_parameters.hpp"
#include "plant_sim/observer_controller.hpp"

namespace ambid::test_support {

// "lqr", "pid", "leadlag", "observer".
const std::vector<std::string>& amb1dof_record_controllers();

// The PRBS clock divider noisy records use under `controller` (each register clock held that
// many samples): 30 under the decentralised loops ("pid", "leadlag"), 1 under the others. Their stiff current
// loops (1000 V/A) follow the current command up to ~380 Hz, so the coil's own R and L show
// only in what the excitation puts below that; a PRBS clocked every sample spreads its power
// to 5 kHz, one clocked every 3 ms puts 90 % of it below 330 Hz (1 s windows at 0.1 um / 1 mA:
// R1, R2 scatter ~0.6 % instead of ~2.3 %). Noise-free records keep 1: there pem's noise-free
// convergence test (step below 0.05 sigma) was not met with 30 under pid and leadlag.
int prbs_clock_divider(const std::string& controller);

struct Amb1dofRecordOptions {
  std::string controller = "lqr";
  std::map<std::string, double> true_parameters;  // overrides of the nominal parameters (e.g. R1)
  double amplitude = 1.0;                         // PRBS on each input (V); rms for multisine
  std::string excitation = "prbs";                // or multisine (band f_min..f_max, plant_sim/scenario.hpp)
  int clock_divider = 1;                          // of the PRBS (prbs_clock_divider)
  double f_min = 1.0, f_max = 1000.0;             // Hz
  double duration = 2.0;                          // s, after the settling
  double settle = 0.5;                            // s of settling at the start of the record
  double position_noise = 0.0;                    // m rms on x
  double current_noise = 0.0;                     // A rms on i1 and i2
  int substeps = 16;                              // RK4 steps per sample
  double sample_time = 1e-4;
  std::uint64_t seed = 1;
  // A fault in the middle of the record: from `step_time` s after the settling on, the true
  // plant has these overrides too (e.g. R1 +20 %); the state goes on, the loop re-settles by
  // itself as on a real bearing. Empty: no step.
  std::map<std::string, double> step_parameters;
  double step_time = 0.0;
};

struct Amb1dofRecord {
  Experiment experiment;                   // settle + duration (the PRBS runs throughout)
  Eigen::Index settled = 0;                // the first sample after the settling
  sim::Amb1dofParameters true_parameters;  // with i0 = i_eq
  std::map<std::string, double> truth;     // v1..v9 of true_parameters
  // With step_parameters: the first sample after the step and the truth from there on (the
  // plant with the step's overrides linearised where its loop settles); else stepped = 0.
  Eigen::Index stepped = 0;
  sim::Amb1dofParameters true_parameters_after_step;
  std::map<std::string, double> truth_after_step;
};

// The "observer" controller's design weights, other than amb1dof_observer_controller_options:
// deviations of 20 um, 20 mm/s and 50 mA accepted (a softer regulator), the integral three
// times looser, more process noise assumed in the velocity and current rows and observer
// poles within radius 0.9.
sim::ObserverControllerOptions other_observer_options();

// Throws Error for an unknown controller (naming the known ones), a step outside the record
// after the settling, and what the simulator throws.
Amb1dofRecord simulate_amb1dof_record(const Amb1dofRecordOptions& options);

}  // namespace ambid::test_support
