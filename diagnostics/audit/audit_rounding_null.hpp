#pragma once
// What the logger's rounding alone does to the audit's residual check (audit_residual_check.hpp,
// "noise that r itself carries"). On a record logged at a coarse resolution (audit_rounding.hpp)
// the controller read y at full precision while the record keeps y_logged = y + q, q within half
// a step; the excitation reconstructed from it, r = u - C y_logged, thus carries -C q, and the
// residual of even the right model carries q: residual and r are correlated by noise that is
// known (the step, the controller), not by a wrong model.
//
// A replica is a record of that noise made from the model itself: the model in closed loop
// with the recorded controller, driven by the record's r (full precision, as the rig's
// controller reads), its outputs logged at the record's resolutions on a grid shifted by a
// seeded random fraction of a step (so each replica rounds differently) and its inputs on the
// record's own grid (where a DAC's levels lie relative to it matters), r
// reconstructed from the rounded replica as from the record, and the replica replayed exactly
// as the audit replays the record (audit_replay.hpp, followed). Its residual and r hold the
// model's answer to the rounding and nothing else.
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_residual_check.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

// `count` replicas (seeds 1..count) of `measured` for the family's model with `effects`: whole
// record, deviations. Empty when the record is not rounded (logging_resolution all 0) or the
// model cannot be run over the whole record (it leaves its valid region); a replica whose replay
// fails is left out.
std::vector<NullReplica> rounding_replicas(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                           int count);

}  // namespace ambid::diag
