#pragma once
// The monitored parameters and fault signatures of the single-coil maglev (maglev1coil_voltage,
// experiment-format.md "Plant families"), as `ambid diagnose` reads them window by window with
// the grey-box fit (identifier/families/maglev_greybox.hpp: m and kw taken as known, the
// operating point the record's measured one).
//
// Monitored, with the fault each stands for when it moves alone:
//   R    coil_resistance       (the coil's winding heats or corrodes)
//   L    magnetic_saturation   (coil inductance: the iron's permeability)
//   Km   force_factor          (force constant; with m taken as known the fit reads Km/m, so
//                               a heavier body reads as a weaker force constant)
//   n_i  force_law             (current exponent of F = Km i^n_i / x^n_x)
//   n_x  force_law             (gap exponent)
// Not watched: Ke (scatters 5-15 % per 3 s window at the rig's noise), rho (1 by construction
// at a measured operating point), the unstable pole (a function of n_x and x0).
//
// The signatures come from the model, like amb1dof_voltage's (fault_signatures.hpp): the rig
// loop of plant_sim/maglev_loop.hpp with the header's nominal parameters, sample time and PID
// (the sidecar's rig.settings where it has them, else the board's defaults), noise-free, full
// logging precision, levels x0 and x0 +- 0.5 mm held 1.5 s for 12 s, uniform w of +-0.5 V
// (seed 1), is run with each fault at +- relative_step and identified by the grey-box fit as
// a window is; a signature is the central difference of the relative change of each monitored
// parameter. Faults: coil_resistance (R), amplifier_gain (kw: the fit takes kw as known, so
// R, L and Ke read kw_nominal / kw), magnetic_saturation (L), force_factor (Km), sensor_gain
// (the Hall sensor's scale) and sensor_offset (its offset, per relative offset offset / x0). Measured at the rig
// defaults (3.25 ms, 14 mm; maglev_diagnosis_test.cpp prints them), d log p per relative change:
//                      R      L      Km      n_i    n_x
//   coil_resistance    1.000  0.000  -0.005  0.000  0.000
//   amplifier_gain    -1.003 -1.003   0.005  0.000  0.000
//   magnetic_sat.      0.000  1.000  -0.001  0.000  0.000
//   force_factor       0.000  0.000   1.002  0.000  0.000
//   sensor_gain        0.000  0.002  -0.403  0.369  0.336
//   sensor_offset      0.000  0.000 -13.48   0.003  1.001
// A sensor gain scales the acceleration the fit sees, which pushes both exponents up, while
// the equilibrium currents across the levels pin n_x / n_i: its signature is small and
// depends on the levels (at 13-16 mm a +2 % gain read Km +5.6 %, n_i +0.3 %, n_x +0.2 %).
// maglev_diagnosis_test.cpp checks them against the structure and diagnoses simulated faulty
// records with them.
#include <span>
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/fault_signatures.hpp"
#include "diagnostics/monitored_parameter.hpp"

namespace ambid::diag {

// R L Km n_i n_x with their roles, in the order an estimate window carries them.
std::span<const MonitoredParameter> maglev_monitored_parameters();

// The hypotheses of the loop of `header` (plant maglev1coil_voltage, its nominal parameters,
// sample time, operating point x). Only options.relative_step is used. Throws Error for another
// plant, a header without an operating point x, or a loop that touches a stop or whose records
// the grey-box fit cannot identify (naming the run).
std::vector<FaultHypothesis> maglev_fault_hypotheses(const Experiment& header, const SignatureOptions& options = {});

// The same for the loop `ambid sim --plant maglev1coil_voltage` runs by default (the published
// parameters, 3.25 ms, 14 mm), computed once on first use (13 runs: ~1 s).
const std::vector<FaultHypothesis>& default_maglev_fault_hypotheses();

}  // namespace ambid::diag
