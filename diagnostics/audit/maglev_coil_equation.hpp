#pragma once
// The coil's equation of a maglev1coil_voltage model checked sample by sample on the record:
// the logged current one sample ahead, predicted from the logged current and command
// (plant_sim/maglev_extended.hpp: L di/dt = kw u - R i - e, the command held over the sample,
// through the model's DAC), for the audit's head to head (audit_rivals.hpp).
//
// Why: the closed-loop replay tells a coil resistance from an amplifier gain only by the coil's
// pole R / L (both fit the steady current's u0 / i0 = R / kw), and at 4 ms the pole lies within
// a sample while the replay's command leaves the logged one; a wrong resistance or gain changes
// every sample's current response to the logged command: i[k+1] = a i[k] + (1 - a) kw u[k] / R
// with a = exp(-R Ts / L) (at 4 ms 0.061 for the nominal R 210 ohm, L 0.3 H; 0.044 for 235 ohm). The logged current
// and command carry that response within the logger's 0.01 mA; a model whose coil equation is
// right leaves the current's own noise. Effects that leave the coil alone (sensor effects,
// force law, delay) predict alike and tie.
#include <Eigen/Core>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// Per sample k (rows, deviations of the current from the operating point, one column): the
// logged i[k+1] and the model's prediction of it from the logged i[k] and u[k] (through the
// model's DAC); the last row repeats the logged current in both. The back-EMF is left out (the
// body at rest at the operating gap): it is millivolts at the steps' speeds, and the gap's rate
// from the logger's 0.01 mm is noise (at 1.3 ms 3 mm/s rms per sample difference), which a
// model with a larger back-EMF constant would take into its prediction and lose by, whatever
// its coil. So the test weighs R, L, kw and the DAC alone, and the other effects tie. Error
// when the record has no i or u, or the model cannot be built.
OneStepPrediction maglev_coil_prediction(const Experiment& measured, const std::vector<sim::Effect>& effects);

}  // namespace ambid::diag
