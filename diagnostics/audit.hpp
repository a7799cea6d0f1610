#pragma once
// The model audit (experiment-format.md, "Audit report"): where the nominal simulation of a
// measured machine is wrong, which effect of the catalogue (plant_sim/effects.hpp) explains
// it, that effect fitted, and the gain on data the fit did not see.
//
// Method: the nominal amb1dof_voltage of the sidecar is replayed in closed loop with the
// recorded controller and excitation, and compared with the measurement by the contract's
// NRMSE. The record is split in an estimation part (the first `estimation_fraction`) and a
// validation part (the rest). Every candidate (each effect; channel effects once per channel)
// is screened at +-1 and +-0.3 times its typical size, the best `fitted_candidates` are fitted on the
// estimation part (audit_fit.hpp) and scored on the validation part: score = validation
// nrmse_total * (1 + complexity_penalty * parameters). The best candidate becomes the cause
// only when its score is below (1 - min_gain) times the nominal nrmse_total: a gain that noise
// alone (fitted on one part, absent in the other) does not produce. Otherwise cause = "none".
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "core/experiment.hpp"
#include "diagnostics/audit_fit.hpp"
#include "diagnostics/audit_replay.hpp"
#include "diagnostics/audit_spectrum.hpp"
#include "identifier/frf_types.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diagnostics {

struct AuditOptions {
  double estimation_fraction = 0.5;
  int fitted_candidates = 5;
  double complexity_penalty = 0.02;  // relative score penalty per fitted parameter
  double min_gain = 0.2;             // relative reduction of nrmse_total needed for a cause
  FitOptions fit;
};

struct AuditFinding {
  sim::Effect effect;             // fitted; channel 0 means none (null in audit.json)
  Eigen::VectorXd nrmse_after;    // per output, validation segment
  double nrmse_total_before = 0.0, nrmse_total_after = 0.0;
  double score = 0.0;             // nrmse_total_after with the complexity penalty
  bool accepted = false;
  std::string evidence;
};

struct AuditResult {
  std::vector<std::string> outputs;
  Eigen::VectorXd baseline_nrmse;  // nominal model, validation segment
  double baseline_total = 0.0;     // mean of the per-output NRMSE
  std::vector<AuditFinding> findings;  // fitted candidates, best score first
  std::string cause = "none";
  Segment estimation, validation;
  // For the report: deviations of the measurement and of the replayed models (the extended
  // one is the nominal one when the cause is none), residual spectra on the validation
  // segment, |correlation| of each nominal residual with each excitation (outputs x r).
  Eigen::VectorXd t;
  Eigen::MatrixXd measured, nominal, extended;
  Spectrum residual_nominal, residual_extended;
  Eigen::MatrixXd excitation_correlation;
  // Closed-loop FRFs y/r (Welch, validation segment) of the measurement and of the replayed
  // nominal and extended models; empty when the segment is too short for them.
  ident::Frf loop_measured, loop_nominal, loop_extended;
  std::vector<sim::Effect> extended_effects;  // the accepted effect, or empty
};

// Error/InsufficientData when the experiment cannot be audited (no controller, no
// excitation, too short, a model without a catalogue, a nominal model that cannot be replayed).
AuditResult run_audit(const Experiment& measured, const AuditOptions& options = {});

// audit.json exactly as the contract has it.
nlohmann::json audit_json(const AuditResult& result, const std::string& experiment_file,
                          const std::string& extended_model_file);
// The extended model: nominal parameters plus the accepted effect(s) and their fit.
nlohmann::json extended_model_json(const Experiment& measured, const AuditResult& result);

}  // namespace ambid::diagnostics
