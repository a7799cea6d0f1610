#pragma once
// The single-coil maglev rig in closed loop as its identification runs go: reference steps
// between levels, the board's PID with its clamps, uniform white noise w added to the command
// (not logged), the Hall sensor and the DAC of MaglevRig, logged at the logger's resolution.
// The true plant is integrated by RK4 with `substeps` steps per sample (u held by the DAC).
//
// The record it returns is an experiment of plant model maglev1coil_voltage with signals
// y = [x, i] and u = [u] (the command as logged), the board's PID in the contract's form and
// r reconstructed from the logged u as a rig's users would (attach_rig_controller,
// maglev_controller.hpp: w is not logged; r carries it and the reference's part of the
// command); the PID settings, the reference schedule and the truth are kept under the sidecar's
// `rig` and `simulation` keys. Its
// operating point is *measured* as the rig's users take it: the means of x, i and u over the
// second half of the first level (`operating_point_source: "measured"`).
#include <cstdint>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/maglev_parameters.hpp"
#include "plant_sim/maglev_rig.hpp"

namespace ambid::sim {

struct MaglevRunOptions {
  std::string name = "maglev simulation";
  double sample_time = 3.25e-3;  // s (the rig runs at 1.3, 1.5, 3.25 or 4 ms)
  Eigen::Index samples = 3000;
  std::vector<double> levels = {0.014, 0.013, 0.015, 0.0145, 0.016, 0.0135};  // reference, m, cycled
  double step_period = 2.0;                                                   // s each level is held
  double noise_amplitude = 0.5;                                               // w uniform in [-a, a] V
  double position_noise = 0.0;  // std of white sensor noise on y (m), seen by the controller and logged
  double current_noise = 0.0;   // std of white noise on the logged current (A)
  double force_noise = 0.0;     // std of the process force Fz (N), held over a sample
  // A periodic force on the body, Fz += harmonic_force sin(2 pi harmonic_frequency t) (N, Hz),
  // held over each RK4 step at its midpoint (a mains-frequency field, a vibrating stand).
  double harmonic_force = 0.0, harmonic_frequency = 0.0;
  int substeps = 20;  // RK4 steps per sample
  std::uint64_t seed = 1;
};

struct MaglevRun {
  Experiment experiment;
  // Empty when the record ran to its end; else why it ended early (the body touched a stop).
  std::string ended;
  Eigen::Index clamped_samples = 0;  // samples at which a PID or output clamp acted
};

// The body starts at rest at the first level, at the true plant's equilibrium, with the PID's
// integral at the command that holds it. A touch of a stop (x <= x_min or x >= x_max, checked
// every RK4 step) ends the record at the sample before it with a message naming the stop, the
// time and the gap. Error for bad options (naming them) or levels outside the stops.
MaglevRun run_maglev_rig(const MaglevParameters& truth, const MaglevParameters& nominal, const MaglevRig& rig,
                         const MaglevRunOptions& options);

}  // namespace ambid::sim
