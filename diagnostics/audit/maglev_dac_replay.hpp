#pragma once
// How the audit replays the maglev1coil_voltage candidate actuator_quantisation (a DAC that
// rounds the command to multiples of `step`, plant_sim/maglev_extended.hpp). Replayed as a
// rounding of the replay's own command, the DAC turns every micrometre by which the replay
// leaves the logged x into a command across a step edge: at 1.5 ms the derivative gain makes
// 1 um 0.07 V, and a 0.35 V DAC replayed that way fitted the data worse than no DAC (z 1.8,
// NRMSE 0.143 against the nominal's 0.140). The rig's controller commanded the logged u to
// within its 0.01 V, so the DAC's error at each sample is known from the record:
// round(u_logged) - u_logged. The replay adds it to the replay's command (through the
// excitation) and leaves the DAC out of the plant: a replay that follows the record gets
// exactly the voltage the DAC put out, one that leaves it gets that voltage plus its own
// controller's answer, with no rounding of its own.
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// ReplayInputs for the first `samples` samples of `measured` (absolute u as logged, u_names
// "u", the controller's output "u"): the plant's effects less the DAC, and its error. Error when the record has no u
// the controller drives while a DAC is among the effects.
ReplayInputs maglev_replay_inputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                  Eigen::Index samples);

}  // namespace ambid::diag
