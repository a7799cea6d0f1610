#pragma once
// Closed-loop records of an amb1dof_voltage bearing with hidden effects, generated without
// any of the audit's models: test data for the model audit (diagnostics/audit.hpp) that the
// audit's candidates did not produce.
//
// Independent of the audit's replay (Amb1dofExtended + run_closed_loop):
// - the plant and every effect are written here again from the equations of
//   plant_sim/EFFECTS.md (the nonlinear force K/4 (i/g)^2, flux linkage Ls i + K/2 phi(i/g));
// - integrated by RK4 with `substeps` (default 50) steps per sample, the sensor sampled from
//   the continuous trajectory (a sensor delay interpolates the fine-step history, not the
//   sampled values);
// - controllers "lqr" (ambid's design), "observer" (other weights: amb1dof_records.hpp),
//   "pid" (ambid's), "leadlag" (a lead-lag on x with a low-frequency lag, proportional
//   current loops; no integrator, so the rotor settles off-centre under a static effect);
// - sensor noise white plus first-order coloured, a small white process force.
// The sidecar is what ambid writes: nominal parameters, operating point, the controller, the
// excitation r (PRBS); the truth is recorded under extra "simulation".
//
// Effects (sim::Effect by name, channel, parameters): the catalogue's eleven with their
// parameters, plus
//   force_factor         {ratio} channel 1/2: K_j -> ratio K_j (force, air-gap inductance, back-EMF);
//   magnetic_saturation  {beta} as EFFECTS.md, or {i_sat} [A]: another saturation curve,
//                        phi(a) = a_s tanh(a / a_s) with a_s = i_sat / x0.
// Out-of-catalogue mismatches (OutOfCatalogue): one coil's Ls off, a sensor offset, further
// flexible modes, a slowly varying amplifier gain.
#include <cstdint>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::test_support {

// "lqr", "observer", "pid", "leadlag".
const std::vector<std::string>& effect_record_controllers();

struct FlexibleModeTruth {
  double coupling = 0.0, f = 0.0, zeta = 0.01;
};

struct OutOfCatalogue {
  int inductance_channel = 1;
  double inductance_error = 0.0;  // relative: Ls_j -> (1 + e) Ls_j
  double sensor_offset = 0.0;     // m, added to the measured x
  std::vector<FlexibleModeTruth> modes;
  int gain_drift_channel = 1;
  double gain_drift = 0.0;          // relative amplitude: kw_j (1 + a sin(2 pi t / period))
  double gain_drift_period = 10.0;  // s
};

struct EffectRecordOptions {
  std::string controller = "lqr";
  std::vector<sim::Effect> effects;  // catalogue effects, force_factor, saturation by i_sat
  OutOfCatalogue out_of_catalogue;
  double amplitude = 0.3;             // PRBS on each input (V)
  double duration = 0.6;              // s
  double sample_time = 1e-4;          // s
  double position_noise = 1e-7;       // m rms (white and coloured together)
  double current_noise = 1e-3;        // A rms on each current
  double coloured_fraction = 0.3;     // share of the noise variance that is first-order coloured
  double noise_time_constant = 5e-4;  // s, of the coloured part
  double force_noise = 0.02;          // N rms, white, held over a sample
  int substeps = 50;                  // RK4 steps per sample (more when a lag needs them)
  std::uint64_t seed = 1;
};

// Throws Error for an unknown controller or effect, a rotor that touches the bearing.
Experiment simulate_effect_record(const EffectRecordOptions& options);

}  // namespace ambid::test_support
