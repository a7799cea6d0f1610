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
// A candidate is significant when its validation improvement is beyond what noise explains (audit_significance.hpp: z
// above the Bonferroni threshold for `false_acceptance` over the fitted candidates) and it
// lowers nrmse_total. (Tried: that z on signals whitened by the noise's joint autoregression,
// audit_whitening.hpp, fitted to each candidate's estimation residual: amplifier bandwidth under
// the lead-lag loop z 2.80 -> 28.8, but 3 of 120 clean records got a catalogue cause at z 3.2-3.8,
// with or without the unwhitened z > 1.645 as well; not kept.)
//
// Residual check (audit_residual_check.hpp): the validation residual of a model is consistent
// with noise when, per output, the sum over the excited bins of its multiple coherence with r
// (non-overlapping Hann windows, K of them, p excitations) is within the upper tail of its
// null law (Beta(p, K - p) per bin, a scaled chi-square for the sum). Coherence is the r-driven
// part of the residual spectrum against the residual's own incoherent floor, bin by bin, so it
// is invariant to the level and colour of the closed-loop noise: nothing is assumed of the
// generator. Bonferroni over the q outputs: a right model is rejected with probability at most
// `residual_alpha` (1 %; measured in tests/diagnostics/audit_residual_check_test.cpp and
// audit_acceptance_slow_test.cpp). It does not see a residual offset or drift (removed per
// window) nor structure not coherent with r.
//
// Acceptance is sequential (forward selection), up to `max_effects` (3): each round takes, of
// its significant findings whose extended residual passes the residual check (below), the one
// the fewest others beat head to head (audit_rivals.hpp: the validation improvement of one over
// the other's replay, noise whitened, above `rival_margin`; ties: the best score), or the
// significant finding of best score when none passes (a further effect is still missing: the
// head-to-head test assumes one of the two is right; on a maglev record at 1.5 ms a force law
// scored 83.7 against the true sensor nonlinearity's 82.4 and left a residual the check
// rejected), and lists it first in its round; the
// next round searches
// the remaining effects on top of the effects taken (same screening, fit, significance test
// against the previous extended model, residual check). The search ends when no candidate of a round is significant.
// Then cause = the first effect taken and `causes` all of them in order when the last extended model passes the
// residual check and the first effect taken predicts the validation segment better, by a z of `foil_margin`, than
// every significant out-of-catalogue foil (audit_foils.hpp: one coil's inductance, a sensor offset, fitted on the
// nominal model); "unexplained" when either fails, or when nothing is significant but the nominal residual fails the
// check; "none" when nothing is significant and the nominal residual passes. Before either, the last model (extended,
// or nominal when nothing was taken) is checked for an amplifier gain that varies over the record
// (audit_gain_drift.hpp, at `drift_alpha`): when it does, the cause is "unexplained" (the catalogue's effects are
// constant), and audit.json names the amplifier. On data where the nominal model is right a
// catalogue cause is named with probability at most `false_acceptance` and "unexplained" with at most `residual_alpha`
// + `drift_alpha`;
// with one right effect, a false second one is added with probability at most `false_acceptance`. Besides: the plant
// FRF ratio measured / model (audit_frf.hpp), the nominal residual's correlation with each excitation, and its
// dependence on amplitude (audit_amplitude.hpp). audit.json adds "ambiguous_with" [{cause, effect, channel,
// z_cause_over_it, z_it_over_cause}] (AuditResult::ambiguous_with), "out_of_catalogue" [{mismatch, unit, value, z,
// cause_over_it_z, nrmse2_reduction}] (the foils), "out_of_catalogue_beats_cause" (the foil's name, or null) and
// "gain_drift" {method, determinable, reason, parts, amplifiers [{channel, gain_error, standard_error,
// heterogeneity_chi2, heterogeneity_p, slope_z, slope_p, p_value}], p_value, alpha, varies, channel}.
//
// audit.json has the contract's keys exactly ("causes" [{effect, channel, finding}] in the
// order accepted, empty unless cause is a catalogue effect; "finding" the index into
// "findings"), plus these additive ones: per finding "round" (1-based search round; later
// rounds are fitted on top of the effects taken before), "significant", "accepted",
// "significance" {z, p_value, nrmse2_reduction, z_threshold}, "residual_check" (below),
// "head_to_head" [{effect, channel, z_over_it, z_it_over_this, one_step_z_over_it,
// one_step_z_it_over_this}] (a significant finding whose residual passes the check against
// every other such one of its round, audit_rivals.hpp, the one-step z's null for a family
// without one-step predictions; empty otherwise); "refuted_by" ({effect, one_step_z_over_this,
// one_step_z_this_over_it} or null, AuditFinding::refuted_by); the nominal model's
// "residual_check"; "unexplained_after" (the effects taken provisionally when
// cause is unexplained); "residual_check" objects are {determinable, reason, window, windows,
// excited_bins, p_value, consistent, null_replicas, outputs: {"y": {coherence_mean, coherence_z,
// coherence_p}}} (coherence_mean: mean multiple coherence with r over the excited bins, p / K
// expected under noise; null_replicas: on a rounded record, the replicas whose coherence with r
// the rounding alone gives was subtracted, audit_rounding_null.hpp); "acceptance" {rule, false_acceptance_probability,
// z_threshold, residual_rule, residual_alpha}; "frf_ratio" {estimator, segment, lines, nominal|extended: {"y/u":
// {frequency_hz, magnitude, phase_deg}}} (null when the validation segment is too short);
// "residual_excitation_correlation" {"y": {"r1": max |corr|}}; "amplitude_dependence" {method, determinable, reason,
// spread, parts [{begin, end, excitation_rms, log_ratio, log_ratio_se}], z, dependent}; "clamped_samples" {count,
// estimation, validation, left_out_of}: the samples where a controller clamp acted (in the
// record and in each segment), which no fit, score or statistic counts (NRMSE, the fits'
// residuals, z, the residual check's windows, the correlation with r, the spectra, the FRF
// ratio's and the amplitude dependence's Welch segments).
#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_amplitude.hpp"
#include "diagnostics/audit/audit_fit.hpp"
#include "diagnostics/audit/audit_foils.hpp"
#include "diagnostics/audit/audit_frf.hpp"
#include "diagnostics/audit/audit_gain_drift.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "diagnostics/audit/audit_residual_check.hpp"
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
  double residual_alpha = 0.01;         // P(the residual check rejects a right model)
  int max_effects = 3;                  // effects accepted at most (sequentially), 1 to 3
  // On a record logged at a coarse resolution (audit_rounding.hpp) the replay follows the
  // logged rounding (audit_replay.hpp), and its residual is no longer noise independent of the
  // model: within half a step the replay runs open loop, and any candidate that reshapes that
  // drift improves it "significantly". A finding there must also lower nrmse_total by at least
  // this fraction of the model it extends; in [0, 1).
  double rounded_min_improvement = 0.1;
  // On a rounded record, the residual check subtracts the coherence with r that the rounding
  // alone gives, from this many replicas of the record made from the checked model
  // (audit_rounding_null.hpp); at least 1.
  int rounding_replicas = 8;
  double foil_margin = 1.5;  // z by which a cause must beat every significant foil (audit_foils.hpp)
  // z by which a significant finding must beat another head to head to displace it
  // (audit_rivals.hpp): a right finding is displaced by a given wrong one with probability at
  // most P(N(0, 1) > rival_margin).
  double rival_margin = 3.0;
  // A rival of an accepted effect is named with it (AuditResult::ambiguous_with) unless the
  // cause beats it by z > rival_margin and by more than 1 / ambiguity_ratio times the rival's z
  // over the cause; in (0, 1]. The head to head's z are not N(0, 1) under the right model on rig
  // records (the replay's rounding floor): on the maglev table the right effect over a wrong one
  // that differs physically read z 3.0-1218 and the wrong one back 0.05-0.15 of that (one pair
  // 0.66: sensor_nonlinearity over force_law at 1.5 ms), while effects that a measured operating
  // point makes equal to first order (a sensor offset or gain and a force law's exponents)
  // read 0.75-0.91 of it both ways.
  double ambiguity_ratio = 0.5;
  // The gain drift test (audit_gain_drift.hpp) of the last model: parts of the record, and the
  // probability that it finds a constant gain varying.
  int drift_segments = 8;
  double drift_alpha = 0.001;
  FitOptions fit;
};

// One significant finding's validation improvement over another of its round, both ways
// (audit_rivals.hpp).
struct RivalTest {
  std::string effect;
  int channel = 0;
  double z_over = 0.0;   // this finding over the rival
  double z_under = 0.0;  // the rival over this finding
  // The same on the family's one-step predictions (audit_rivals.hpp); NaN when it has none.
  double z_one_step_over = NAN, z_one_step_under = NAN;
};

struct AuditFinding {
  sim::Effect effect;           // fitted; channel 0 means none (null in audit.json)
  Eigen::VectorXd nrmse_after;  // per output, validation segment
  double nrmse_total_before = 0.0, nrmse_total_after = 0.0;
  double score = 0.0;        // test.z less AuditOptions::complexity_penalty per parameter beyond one
  ImprovementTest test;      // validation improvement against noise (against the previous round's model)
  double z_threshold = 0.0;  // the z this finding needed (Bonferroni over its round)
  bool significant = false;  // z above the threshold, reduction > 0, nrmse_total lowered
  ResidualCheck residual;    // the extended model's validation residual against noise
  int round = 1;             // search round: fitted on top of the effects taken in earlier rounds
  bool accepted = false;
  std::vector<RivalTest> rivals;  // a significant finding whose residual passes: against the others
  int rival_losses = 0;           // how many of them beat it head to head
  // Taken: a significant finding of its round whose residual failed the check but whose one-step
  // prediction (audit_rivals.hpp) beats this one's as a cause beats an ambiguous rival
  // (AuditOptions::ambiguity_ratio): the record refutes this model's equation, so the audit
  // names no cause (unexplained). Empty when none does; z both ways.
  std::string refuted_by;
  double refuted_z = 0.0, refuted_z_back = 0.0;
  std::string evidence;
};

struct AuditResult {
  std::string plant_model;  // the family whose catalogue the findings come from
  std::vector<std::string> outputs, inputs;
  Eigen::VectorXd baseline_nrmse;      // nominal model, validation segment
  double baseline_total = 0.0;         // mean of the per-output NRMSE
  std::vector<AuditFinding> findings;  // fitted candidates by round; in each, the one taken first, then by score
  std::string cause = "none";          // the first of `causes`, "none" or "unexplained"
  std::vector<std::string> causes;     // every accepted effect in the order accepted
  // Rivals of an accepted effect that the head to head does not separate from it
  // (AuditOptions::ambiguity_ratio): the record names them as much as the cause (audit.json
  // "ambiguous_with").
  struct Ambiguity {
    std::string cause, rival;
    int channel = 0;                     // the rival's
    double z_over = 0.0, z_under = 0.0;  // the cause over the rival and back, the deciding z's
  };
  std::vector<Ambiguity> ambiguous_with;
  double false_acceptance = 0.0;     // AuditOptions::false_acceptance
  double z_threshold = 0.0;          // the z a finding of the first round needed to be accepted
  double residual_alpha = 0.0;       // AuditOptions::residual_alpha
  ResidualCheck nominal_check;       // the nominal model's validation residual against noise
  Segment estimation, validation;    // both leave out the samples where a controller clamp acted
  Eigen::Index clamped_samples = 0;  // of the record (controller.output_limits, state_limits)
  bool rounded = false;              // the record is logged at a coarse resolution (audit_rounding.hpp)
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
  std::vector<sim::Effect> extended_effects;     // the accepted effects in order, or empty
  std::vector<sim::Effect> unexplained_effects;  // taken provisionally when cause is unexplained
  // The family's out-of-catalogue foils (audit_foils.hpp), fitted on the nominal model when a
  // round took an effect, and the first significant one the first effect taken does not beat
  // significantly (then the cause is unexplained); empty when none.
  std::vector<FoilFinding> foils;
  std::string foil_beats_cause;
  // Whether an amplifier's gain varies over the record, on the last model (the extended one, or
  // the nominal when nothing was taken); when it varies the cause is unexplained.
  GainDrift gain_drift;
};

// Error/InsufficientData when the experiment cannot be audited (no controller, no
// excitation, too short, a model without a catalogue, a nominal model that cannot be replayed).
AuditResult run_audit(const Experiment& measured, const AuditOptions& options = {});

// audit.json exactly as the contract has it.
nlohmann::json audit_json(const AuditResult& result, const std::string& experiment_file,
                          const std::string& extended_model_file);
// The extended model: nominal parameters plus the accepted effects (in order) and their fit.
nlohmann::json extended_model_json(const Experiment& measured, const AuditResult& result);

}  // namespace ambid::diag
