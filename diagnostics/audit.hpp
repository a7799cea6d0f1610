#pragma once
// The model audit (experiment-format.md, "Audit report"): where the nominal simulation of a
// measured machine is wrong, which effect of its family's catalogue (plant_sim/families.hpp:
// effects.hpp for amb1dof_voltage, maglev_effects.hpp for maglev1coil_voltage) explains it,
// that effect fitted, and the gain on data the fit did not see.
//
// Method: the nominal model of the sidecar (the family's extended simulator with no effect) is
// replayed in closed loop with the
// recorded controller and excitation, and compared with the measurement by the contract's
// NRMSE. The record is split in an estimation part (the first `estimation_fraction`) and a
// validation part (the rest). Every candidate (each effect; channel effects once per channel)
// is screened at +-1 and +-0.3 times its typical size, the best `fitted_candidates` are fitted on the
// estimation part (audit_fit.hpp) and scored on the validation part by the improvement z
// over the nominal model (audit_significance.hpp) less `complexity_penalty` per parameter
// beyond the first, which ranks them: z weighs the residual by the noise's own (coloured,
// loop-shaped) covariance where the mean NRMSE weighs every output's noise alike, and the
// penalty breaks near-ties toward the simpler effect (a broad three-parameter resonance
// matched saturation of another curve at z 3.60 against 3.58). On independent records at 0.1 um / 1 mA the NRMSE
// ranking named amplifier_gain for a coil resistance whose z was 1177 against 1055 (observer loop) and 189 against 34
// (lead-lag), sensor_delay for eddy currents at z 7.9 against 8.3, and an air gap (z 4) before a flexible mode (z 9).
// The best candidate becomes the cause only when its validation improvement is beyond what noise explains
// (audit_significance.hpp: z above the Bonferroni threshold for `false_acceptance` over the
// fitted candidates) and it lowers nrmse_total; otherwise cause = "none". On data where the
// nominal model is right a cause is named with probability at most `false_acceptance`.
// Besides: the plant FRF ratio measured / model (audit_frf.hpp), the nominal residual's
// correlation with each excitation, and its dependence on amplitude (audit_amplitude.hpp).
//
// audit.json has the contract's keys exactly, plus these additive ones: per finding
// "significance" {z, p_value, nrmse2_reduction}; "acceptance" {rule,
// false_acceptance_probability, z_threshold}; "frf_ratio" {estimator, segment, lines,
// nominal|extended: {"y/u": {frequency_hz, magnitude, phase_deg}}} (null when the validation
// segment is too short); "residual_excitation_correlation" {"y": {"r1": max |corr|}};
// "amplitude_dependence" {method, determinable, reason, spread, parts [{begin, end,
// excitation_rms, log_ratio, log_ratio_se}], z, dependent}; "clamped_samples" {count,
// left_out_of}: the samples where a controller clamp acted, which no NRMSE scores.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_amplitude.hpp"
#include "diagnostics/audit/audit_fit.hpp"
#include "diagnostics/audit/audit_frf.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "diagnostics/audit/audit_significance.hpp"
#include "diagnostics/audit/audit_spectrum.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

struct AuditOptions {
  // Called at the start of each screened or fitted candidate (stage, done, total); empty: none.
  std::function<void(const std::string& stage, std::size_t done, std::size_t total)> progress;
  double estimation_fraction = 0.5;
  int fitted_candidates = 5;
  double complexity_penalty = 0.5;      // ranking score = z - penalty * (parameters - 1)
  double false_acceptance = 0.01;       // P(a cause is named | the nominal model is right)
  Eigen::Index covariance_lags = 1000;  // M of the noise covariance in the improvement test
  FitOptions fit;
};

struct AuditFinding {
  sim::Effect effect;           // fitted; channel 0 means none (null in audit.json)
  Eigen::VectorXd nrmse_after;  // per output, validation segment
  double nrmse_total_before = 0.0, nrmse_total_after = 0.0;
  double score = 0.0;    // the ranking (AuditOptions::complexity_penalty), higher first
  ImprovementTest test;  // validation improvement against noise
  bool accepted = false;
  std::string evidence;
};

struct AuditResult {
  std::string plant_model;  // the family whose catalogue the findings come from
  std::vector<std::string> outputs, inputs;
  Eigen::VectorXd baseline_nrmse;      // nominal model, validation segment
  double baseline_total = 0.0;         // mean of the per-output NRMSE
  std::vector<AuditFinding> findings;  // fitted candidates, best score first
  std::string cause = "none";
  double false_acceptance = 0.0;     // AuditOptions::false_acceptance
  double z_threshold = 0.0;          // the z a finding needed to be accepted
  Segment estimation, validation;    // both leave out the samples where a controller clamp acted
  Eigen::Index clamped_samples = 0;  // of the record (controller.output_limits, state_limits)
  // For the report: deviations of the measurement and of the replayed models (the extended
  // one is the nominal one when the cause is none), residual spectra on the validation
  // segment, |correlation| of each nominal residual with each excitation (outputs x r).
  Eigen::VectorXd t;
  Eigen::MatrixXd measured, nominal, extended;
  Spectrum residual_nominal, residual_extended;
  Eigen::MatrixXd excitation_correlation;
  // Plant FRFs (indirect closed-loop Welch, validation segment) of the measurement and the
  // replayed models, their ratios, and the closed-loop y/r; empty when the segment is too short.
  AuditFrfs frfs;
  // Whether the nominal residual depends on the excitation amplitude (whole record).
  AmplitudeDependence amplitude;
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

}  // namespace ambid::diag
