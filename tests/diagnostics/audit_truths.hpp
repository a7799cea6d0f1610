#pragma once
// Records for the audit's acceptance tests that the audit's replay did not generate: the
// closed loop integrated by RK4 with 20 sub-steps per sample (the replay takes one; the
// plant's own stepper for catalogue effects alone, a generic one beyond them),
// under a PID or another LQR than the replay's default scenario, sensor noise 0.1 um on x and
// 1 mA on the currents (white, or coloured on x: a first-order lag of 0.3 ms), a small process
// force noise (5 mN), a multisine of 1 V rms from 2 to 800 Hz. Besides the catalogue's effects (Amb1dofExtended
// inside), the truth can hold mismatches the catalogue has no name for: a second flexible mode, a slowly varying
// amplifier gain. Clean records come from tests/support/amb1dof_records (another generator).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/experiment.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag::testing {

struct TruthOptions {
  std::vector<sim::Effect> effects;          // of the catalogue
  std::map<std::string, double> parameters;  // true parameter overrides (sidecar stays nominal)
  std::string controller = "pid";            // lqr | pid (designed on the nominal model)
  double second_mode_f = 0.0;                // Hz; 0: none
  double second_mode_coupling = 0.0;         // as flexible_mode's coupling
  double second_mode_zeta = 0.01;
  double gain_variation = 0.0;  // kw1(t) = kw1 (1 + a sin(2 pi f t))
  double gain_variation_hz = 1.0;
  bool coloured_noise = false;  // x noise through a 0.3 ms lag instead of white
  double duration = 0.8;        // s
  std::uint64_t seed = 1;
};

// Throws Error for sensor_delay together with an out-of-catalogue mismatch or coloured noise
// (its delay line is advanced by the plant's own stepper, which those replace), and what the
// simulator throws.
Experiment simulate_truth(const TruthOptions& options);

// A clean record of tests/support/amb1dof_records ("lqr", "pid", "observer") at 0.1 um / 1 mA,
// 1 V PRBS, `duration` s after a 0.1 s settling.
Experiment independent_clean(const std::string& controller, std::uint64_t seed, double duration = 0.8);

}  // namespace ambid::diag::testing
