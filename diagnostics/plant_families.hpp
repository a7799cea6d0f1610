#pragma once
// What diagnostics has per plant family (the families themselves: plant_sim/families.hpp), in
// one registry (plant_families.cpp): the monitored physical parameters with the fault each
// stands for, the fault signatures of a loop (fault isolation), how `ambid diagnose` cuts and
// identifies a record of the family, and the effect catalogue the audit fits (plant_sim's,
// where the family has one). Callers ask here and get a clear error naming the family and the
// piece it lacks; an unknown plant model is refused with the list of known ones.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "diagnostics/fault_signatures.hpp"
#include "diagnostics/monitored_parameter.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

enum class DiagnosticsPiece {
  fault_signatures,  // closed-loop fault signatures and monitored parameters (monitor/)
  effect_catalogue,  // the audit's candidate extensions (audit/)
};

// Throws Error "WHO: unknown plant 'NAME' (known: ...)" or "WHO: plant model 'NAME' has no
// PIECE yet" unless the family has the piece.
void require_diagnostics_piece(const std::string& model, DiagnosticsPiece piece, const std::string& who);

// How a record of the family is watched: its monitored parameters, the signatures of its
// faults, and the identification of its windows.
struct MonitoredFamily {
  std::string_view name;
  std::span<const MonitoredParameter> (*monitored)();
  std::vector<FaultHypothesis> (*hypotheses)(const Experiment& header, const SignatureOptions& options);
  const std::vector<FaultHypothesis>& (*default_hypotheses)();
  std::string_view window_method;  // the identification of a window (methods.hpp)
  double window = 0.0;             // s: the window `ambid diagnose` cuts a record into by default
  // Samples dropped from the first window of a record (amb1dof_voltage: it starts at the
  // nominal operating point and settles to the plant's own; later windows carry the controller
  // state). deadbeat drops none (its offset term absorbs the shift).
  Eigen::Index settling_samples = 0;
};

// The family with monitored parameters called `model`; the errors of require_diagnostics_piece.
const MonitoredFamily& monitored_family(const std::string& model, const std::string& who);

// The family's monitored parameters, in the order an estimate window carries them.
std::vector<std::string> monitored_parameters(const std::string& family);
// Throws Error naming the parameter, the family and its monitored ones when it is not monitored.
ParameterRole parameter_role(const std::string& family, std::string_view parameter);
// The fault hypotheses of the loop of `header` (its plant model's family).
std::vector<FaultHypothesis> fault_hypotheses(const Experiment& header, const SignatureOptions& options = {});
// Those of the family's default loop (the one `ambid sim` runs), computed once per process.
const std::vector<FaultHypothesis>& default_fault_hypotheses(const std::string& family);

// The family's effect catalogue, with the errors of require_diagnostics_piece.
const std::vector<sim::EffectSpec>& effect_catalogue_of(const std::string& model, const std::string& who);

// Starting values of the audit's candidates that the family reads from the record itself
// (maglev1coil_voltage: its grey-box fit, audit/maglev_starts.hpp); empty for a family without.
std::vector<sim::Effect> audit_starts_from_data(const Experiment& measured);

// The audit's replay of `effects` over the first `samples` samples: the effects the family's
// extended plant takes, and what the record's logged signals add to the controller's output
// (maglev1coil_voltage: the DAC's error on the logged command, audit/maglev_dac_replay.hpp);
// `effects` and zero for a family without.
ReplayInputs audit_replay_inputs(const Experiment& measured, const std::vector<sim::Effect>& effects,
                                 Eigen::Index samples);

// The one-step prediction of the family's model with `effects` (maglev1coil_voltage: the
// coil's current, audit/maglev_coil_equation.hpp); empty for a family without.
OneStepPrediction audit_one_step_prediction(const Experiment& measured, const std::vector<sim::Effect>& effects);

}  // namespace ambid::diag
