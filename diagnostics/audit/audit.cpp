#include "diagnostics/audit.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "diagnostics/audit/audit_mode_search.hpp"
#include "diagnostics/audit/audit_residual_check.hpp"
#include "diagnostics/audit/audit_rivals.hpp"
#include "diagnostics/audit/audit_rounding.hpp"
#include "diagnostics/audit/audit_rounding_null.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace {

struct Candidate {
  sim::Effect start;
  double cost = 0.0;  // estimation cost at the start
};

double total(const Eigen::VectorXd& per_output) { return per_output.mean(); }

// Per row of `segment`: a controller clamp acted there (empty when none did anywhere).
std::vector<bool> left_out_rows(const Segment& segment) {
  if (segment.left_out.empty()) return {};
  return std::vector<bool>(segment.left_out.begin() + segment.begin, segment.left_out.begin() + segment.end);
}

// The residual check of `residual` (whole record, deviations) of the model with `effects` on
// the validation segment, leaving out the windows that hold a clamped sample; on a rounded
// record against the rounding's own coherence with r (audit_rounding_null.hpp).
ResidualCheck validation_check(const Experiment& measured, const std::vector<sim::Effect>& effects,
                               const Eigen::MatrixXd& residual, const AuditResult& r, const AuditOptions& options) {
  const Segment& v = r.validation;
  std::vector<NullReplica> replicas;
  if (r.rounded)
    for (NullReplica& replica : rounding_replicas(measured, effects, options.rounding_replicas))
      replicas.push_back(
          {replica.residual.middleRows(v.begin, v.size()), replica.excitation.middleRows(v.begin, v.size())});
  return residual_check(residual.middleRows(v.begin, v.size()), measured.r_deviation().middleRows(v.begin, v.size()),
                        options.residual_alpha, left_out_rows(v), replicas);
}

// The strongest line over the outputs' residuals, each normalised by its measured spread.
Line residual_line(const Eigen::MatrixXd& residual, const Eigen::MatrixXd& measured, double dt, double f_lo,
                   double f_hi) {
  Line best;
  for (Eigen::Index j = 0; j < residual.cols(); ++j) {
    const double spread = (measured.col(j).array() - measured.col(j).mean()).matrix().norm();
    const Line l = strongest_line(residual.col(j) / spread, dt, f_lo, f_hi);
    if (l.amplitude > best.amplitude) best = l;
  }
  return best;
}

// Starting values of every candidate but the flexible mode (audit_mode_search.hpp):
// switching parameters at +-1 and +-0.3 times their scale (within range), the frequency of a
// harmonic from the residual's strongest line.
std::vector<sim::Effect> starts_of(const std::vector<sim::EffectSpec>& catalogue, const sim::EffectSpec& spec,
                                   int channel, double harmonic_f) {
  std::vector<sim::Effect> starts;
  for (const auto& p : spec.parameters) {
    std::map<std::string, double> shape;
    if (spec.name == "harmonic_disturbance") shape["f"] = harmonic_f;
    if (channel) shape["channel"] = channel;
    if (!p.switches) continue;
    for (double size : {1.0, -1.0, 0.3, -0.3}) {
      if (size * p.scale < p.lower || size * p.scale > p.upper) continue;
      auto values = shape;
      values[p.name] = size * p.scale;
      starts.push_back(sim::make_effect(catalogue, spec.name, values));
    }
  }
  return starts;
}

std::string describe(const AuditFinding& f, const AuditResult& r, const Eigen::VectorXd& correlation) {
  std::ostringstream s;
  s.precision(3);
  s << sim::effect_spec(effect_catalogue_of(r.plant_model, "audit"), f.effect.name).summary;
  if (f.effect.channel) s << " (channel " << f.effect.channel << ")";
  s << ";";
  if (f.round > 1) s << " fitted on top of the effects accepted before (round " << f.round << ");";
  for (std::size_t j = 0; j < r.outputs.size(); ++j)
    s << " " << r.outputs[j] << " NRMSE " << r.baseline_nrmse[Eigen::Index(j)] << " -> "
      << f.nrmse_after[Eigen::Index(j)];
  if (f.effect.name == "harmonic_disturbance" || f.effect.name == "flexible_mode")
    s << "; residual line at " << f.effect.at("f") << " Hz";
  if (f.effect.name == "force_factor")
    s << "; coil " << f.effect.channel << " force factor K" << f.effect.channel << " x " << 1.0 + f.effect.at("dratio");
  s << "; nominal residual |correlation| with r up to " << correlation.maxCoeff();
  s << "; validation improvement z = " << f.test.z << " (accepted above " << f.z_threshold << ")";
  for (const RivalTest& rival : f.rivals) {
    s << "; over " << rival.effect << (rival.channel ? " (channel " + std::to_string(rival.channel) + ")" : "")
      << " z = " << rival.z_over << ", it over this z = " << rival.z_under;
    if (!std::isnan(rival.z_one_step_over))
      s << " (one-step: " << rival.z_one_step_over << ", " << rival.z_one_step_under << ")";
  }
  if (!f.refuted_by.empty())
    s << "; refuted by the one-step prediction of " << f.refuted_by << " (z = " << f.refuted_z << ", this over it "
      << f.refuted_z_back << ")";
  if (f.significant)
    for (const FoilFinding& foil : r.foils)
      s << "; out of the catalogue, " << foil.name << " " << foil.value << " " << foil.unit << " at z = " << foil.test.z
        << " (this effect over it: z = " << foil.rival_gain.z << ")";
  if (f.significant && r.gain_drift.varies)
    s << "; amplifier " << r.gain_drift.channel << "'s gain varies over the record (p = " << r.gain_drift.p_value
      << ")";
  if (f.residual.determinable)
    s << "; extended residual " << (f.residual.consistent ? "consistent with noise" : "NOT consistent with noise")
      << " (mean coherence with r up to " << f.residual.coherence_mean.maxCoeff() << ", p = " << f.residual.p_value
      << ")";
  return s.str();
}

// The z by which one rival beats another: the larger of the replay's and the one-step
// prediction's (NaN: none), as audit_rivals.hpp decides.
double deciding_z(double replay, double one_step) { return std::isnan(one_step) ? replay : std::max(replay, one_step); }

// A fitted finding with its replay over the whole record.
struct Scored {
  AuditFinding finding;
  ReplayedLoop loop;
};

// One round of the search: every catalogue effect not in `base` screened, the most promising
// fitted on top of `base` (whose replay is `base_loop`), scored on the validation segment and
// tested against `base_loop`; best score first.
std::vector<Scored> search_round(const Experiment& measured, const AuditResult& r, const std::vector<sim::Effect>& base,
                                 const ReplayedLoop& base_loop, double base_total, int round,
                                 const AuditOptions& options) {
  const double dt = measured.sample_time;
  const Eigen::Index N = measured.samples();
  const std::vector<sim::EffectSpec>& catalogue = effect_catalogue_of(r.plant_model, "audit");
  const Eigen::MatrixXd residual = r.measured - base_loop.y;

  // Screening.
  // Zero where a controller clamp acted: the line search sums over the kept samples only.
  const Eigen::MatrixXd est_residual = r.estimation.kept_rows(residual);
  const Eigen::MatrixXd est_measured = r.estimation.kept_rows(r.measured);
  const double nyquist = 0.5 / dt;
  const double harmonic_f = residual_line(est_residual, est_measured, dt, 1.0, 0.9 * nyquist).frequency;
  // A mode shows as a resonance in the position residual: its three strongest peaks join the grid.
  const std::vector<double> mode_f = spectral_peaks(est_residual.col(0), dt, 100.0, 0.9 * nyquist, 3);
  auto with_base = [&](const sim::Effect& e) {
    std::vector<sim::Effect> effects = base;
    effects.push_back(e);
    return effects;
  };
  const std::vector<sim::Effect> data_starts = audit_starts_from_data(measured);

  std::vector<Candidate> candidates;
  std::size_t screened = 0;
  for (const auto& spec : catalogue) {
    if (options.progress)
      options.progress(round == 1 ? std::string("screen the effect catalogue")
                                  : "screen the effect catalogue on top of round " + std::to_string(round - 1),
                       screened++, catalogue.size());
    if (std::any_of(base.begin(), base.end(), [&](const sim::Effect& e) { return e.name == spec.name; })) continue;
    for (int channel : spec.has_channel ? std::vector<int>{1, 2} : std::vector<int>{0}) {
      Candidate best{{}, INFINITY};
      if (spec.name == "flexible_mode") {
        // Matched to the residual of the current model; the search replays the mode alone, so
        // on top of accepted effects its start is costed again with them.
        const ModeStart mode = search_mode_start(measured, r.measured, base_loop.y, r.estimation, mode_f);
        best = {mode.effect,
                base.empty() ? mode.cost : estimation_cost(measured, r.measured, with_base(mode.effect), r.estimation)};
      }
      std::vector<sim::Effect> starts = starts_of(catalogue, spec, channel, harmonic_f);
      for (const auto& s : data_starts)
        if (s.name == spec.name && s.channel == channel) starts.push_back(s);
      for (const auto& start : starts) {
        const double c = estimation_cost(measured, r.measured, with_base(start), r.estimation);
        if (c < best.cost || best.start.name.empty()) best = {start, c};
      }
      candidates.push_back(best);
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });

  // Fit the most promising candidates, score them on the validation segment.
  const int fitted = std::min<int>(options.fitted_candidates, int(candidates.size()));
  std::vector<Scored> scored;
  for (int c = 0; c < fitted; ++c) {
    if (options.progress) options.progress("fit the best candidates", std::size_t(c), std::size_t(fitted));
    if (!std::isfinite(candidates[std::size_t(c)].cost)) continue;
    const EffectFit fit =
        fit_effect(measured, r.measured, candidates[std::size_t(c)].start, r.estimation, options.fit, base);
    AuditFinding f;
    f.effect = fit.effect;
    f.round = round;
    f.nrmse_total_before = base_total;
    ReplayedLoop loop;
    try {
      loop = replay_loop(measured, with_base(fit.effect), N);
    } catch (const InsufficientData&) {
      throw;
    } catch (const Error&) {
      continue;  // fitted on one part, it cannot even be simulated over the whole record
    }
    f.nrmse_after = nrmse(r.measured, loop.y, r.validation);
    f.test = improvement_test(r.measured, base_loop.y, loop.y, r.validation, options.covariance_lags);
    f.nrmse_total_after = total(f.nrmse_after);
    f.score = f.test.z - options.complexity_penalty * double(fit.effect.parameters.size() - 1);
    f.residual = validation_check(measured, with_base(fit.effect), r.measured - loop.y, r, options);
    scored.push_back({std::move(f), std::move(loop)});
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const Scored& a, const Scored& b) { return a.finding.score > b.finding.score; });
  const double threshold = acceptance_threshold(options.false_acceptance, std::max(1, int(scored.size())));
  const double required_total = r.rounded ? (1.0 - options.rounded_min_improvement) * base_total : base_total;
  for (auto& s : scored) {
    s.finding.z_threshold = threshold;
    s.finding.significant =
        s.finding.test.reduction > 0.0 && s.finding.test.z > threshold && s.finding.nrmse_total_after < required_total;
  }
  return scored;
}

// The significant finding of `scored` (best score first) to take (audit_rivals.hpp), each
// rival given its head-to-head tests; end() when none is significant.
std::vector<Scored>::iterator take_among_rivals(const Experiment& measured, const AuditResult& r,
                                                const std::vector<sim::Effect>& base, std::vector<Scored>& scored,
                                                const AuditOptions& options) {
  // The rivals: the significant findings whose residual passes the check (the head-to-head
  // test assumes one of the two is right); when none does (a second effect is still missing),
  // the best score decides.
  std::vector<std::size_t> significant;
  std::vector<const Eigen::MatrixXd*> replays;
  std::vector<OneStepPrediction> one_step;
  for (std::size_t i = 0; i < scored.size(); ++i)
    if (scored[i].finding.significant && scored[i].finding.residual.consistent) {
      significant.push_back(i);
      replays.push_back(&scored[i].loop.y);
      std::vector<sim::Effect> effects = base;
      effects.push_back(scored[i].finding.effect);
      one_step.push_back(audit_one_step_prediction(measured, effects));
    }
  if (significant.empty())
    return std::find_if(scored.begin(), scored.end(), [](const Scored& s) { return s.finding.significant; });
  if (one_step.front().predicted.size() == 0) one_step.clear();  // the family has none
  if (options.progress) options.progress("test the significant findings head to head", 0, 1);
  const RivalChoice choice =
      choose_among_rivals(r.measured, replays, r.validation, options.covariance_lags, options.rival_margin, one_step);
  for (std::size_t a = 0; a < significant.size(); ++a) {
    AuditFinding& f = scored[significant[a]].finding;
    f.rival_losses = choice.losses[a];
    for (std::size_t b = 0; b < significant.size(); ++b)
      if (a != b) {
        const sim::Effect& rival = scored[significant[b]].finding.effect;
        const auto i = Eigen::Index(a), j = Eigen::Index(b);
        RivalTest t{rival.name, rival.channel, choice.z(i, j), choice.z(j, i)};
        if (choice.z_one_step.size()) {
          t.z_one_step_over = choice.z_one_step(i, j);
          t.z_one_step_under = choice.z_one_step(j, i);
        }
        f.rivals.push_back(t);
      }
  }
  return scored.begin() + std::ptrdiff_t(significant[choice.pick]);
}

// Whether a significant finding outside the rivals (its residual failed the check) predicts the
// family's one-step outputs decisively better than the taken one, `pick` (AuditFinding::
// refuted_by): e.g. on a record with an amplifier gain at 1.3 ms the gain's finding fails the
// check narrowly (p 0.006) while a sensor nonlinearity passes with the nominal coil, whose
// one-step current prediction is off by 0.92 mA rms against the gain's 0.015 mA.
void check_refutation(const Experiment& measured, const AuditResult& r, const std::vector<sim::Effect>& base,
                      std::vector<Scored>& scored, const AuditOptions& options) {
  AuditFinding& taken = scored.front().finding;
  std::vector<sim::Effect> effects = base;
  effects.push_back(taken.effect);
  const OneStepPrediction own = audit_one_step_prediction(measured, effects);
  if (own.predicted.size() == 0) return;  // the family has none
  for (const Scored& s : scored) {
    if (&s.finding == &taken || !s.finding.significant || s.finding.residual.consistent) continue;
    effects.back() = s.finding.effect;
    const OneStepPrediction other = audit_one_step_prediction(measured, effects);
    const double
        over = improvement_test(own.measured, own.predicted, other.predicted, r.validation, options.covariance_lags).z,
        back = improvement_test(own.measured, other.predicted, own.predicted, r.validation, options.covariance_lags).z;
    if (over > options.rival_margin && back < options.ambiguity_ratio * over && over > taken.refuted_z) {
      taken.refuted_by = s.finding.effect.name;
      taken.refuted_z = over;
      taken.refuted_z_back = back;
    }
  }
}

}  // namespace

AuditResult run_audit(const Experiment& measured, const AuditOptions& options) {
  require_auditable(measured);
  acceptance_threshold(options.false_acceptance, 1);  // refuses a bad probability before the fits
  if (!(options.estimation_fraction > 0.1 && options.estimation_fraction < 0.9))
    throw Error("audit: estimation_fraction must be in (0.1, 0.9), got " + std::to_string(options.estimation_fraction));
  if (!(options.residual_alpha > 0.0 && options.residual_alpha < 1.0))
    throw Error("audit: residual_alpha must be in (0, 1), got " + std::to_string(options.residual_alpha));
  if (!std::isfinite(options.foil_margin))
    throw Error("audit: foil_margin must be finite, got " + std::to_string(options.foil_margin));
  if (!std::isfinite(options.rival_margin))
    throw Error("audit: rival_margin must be finite, got " + std::to_string(options.rival_margin));
  if (!(options.ambiguity_ratio > 0.0 && options.ambiguity_ratio <= 1.0))
    throw Error("audit: ambiguity_ratio must be in (0, 1], got " + std::to_string(options.ambiguity_ratio));
  if (options.drift_segments < 3)
    throw Error("audit: drift_segments must be at least 3, got " + std::to_string(options.drift_segments));
  if (!(options.drift_alpha > 0.0 && options.drift_alpha < 1.0))
    throw Error("audit: drift_alpha must be in (0, 1), got " + std::to_string(options.drift_alpha));
  if (options.max_effects < 1 || options.max_effects > 3)
    throw Error("audit: max_effects must be 1 to 3, got " + std::to_string(options.max_effects));
  if (options.rounding_replicas < 1)
    throw Error("audit: rounding_replicas must be at least 1, got " + std::to_string(options.rounding_replicas));
  if (!(options.rounded_min_improvement >= 0.0 && options.rounded_min_improvement < 1.0))
    throw Error("audit: rounded_min_improvement must be in [0, 1), got " +
                std::to_string(options.rounded_min_improvement));
  const double dt = measured.sample_time;
  const Eigen::Index N = measured.samples();
  AuditResult r;
  r.plant_model = measured.plant.model;
  r.outputs = measured.y_names;
  r.inputs = measured.u_names;
  r.estimation = {0, Eigen::Index(std::llround(options.estimation_fraction * double(N)))};
  r.validation = {r.estimation.end, N};
  r.rounded = (logging_resolution(measured).array() > 0.0).any();
  const ControllerReplay clamps = clamped_samples(measured);  // not exogenous: no score counts them
  r.clamped_samples = clamps.clamped_samples;
  if (r.clamped_samples > 0) r.estimation.left_out = r.validation.left_out = clamps.clamped;
  r.t = measured.t;
  r.measured = measured.y_deviation();
  ReplayedLoop nominal;
  try {
    nominal = replay_loop(measured, {}, N);
    r.nominal = nominal.y;
  } catch (const InsufficientData&) {
    throw;
  } catch (const Error& e) {
    throw Error(std::string("audit: the nominal model cannot be replayed: ") + e.what());
  }
  r.baseline_nrmse = nrmse(r.measured, r.nominal, r.validation);
  r.baseline_total = total(r.baseline_nrmse);
  const Eigen::MatrixXd residual = r.measured - r.nominal;
  const Eigen::MatrixXd r_dev = measured.r_deviation();
  const Segment record{0, N, r.estimation.left_out};
  const Eigen::MatrixXd kept_residual = record.kept_rows(residual);  // zero where a clamp acted
  r.excitation_correlation.resize(residual.cols(), r_dev.cols());
  for (Eigen::Index j = 0; j < residual.cols(); ++j)
    for (Eigen::Index i = 0; i < r_dev.cols(); ++i)
      r.excitation_correlation(j, i) = excitation_correlation(kept_residual.col(j), r_dev.col(i), 50);
  r.false_acceptance = options.false_acceptance;
  r.residual_alpha = options.residual_alpha;
  r.nominal_check = validation_check(measured, {}, residual, r, options);

  // Sequential acceptance (forward selection): each round searches on top of the effects taken
  // so far and takes the significant finding of best score; the search goes on while a round
  // finds a significant improvement. The residual check judges the last model.
  std::vector<sim::Effect> taken;
  std::vector<std::size_t> taken_findings;
  ReplayedLoop current = nominal, first_loop;
  double current_total = r.baseline_total;
  ResidualCheck current_check = r.nominal_check;
  for (int round = 1; round <= options.max_effects; ++round) {
    std::vector<Scored> scored = search_round(measured, r, taken, current, current_total, round, options);
    if (round == 1)
      r.z_threshold =
          scored.empty() ? acceptance_threshold(options.false_acceptance, 1) : scored.front().finding.z_threshold;
    // Of the significant findings whose residual passes the check, the one the fewest others
    // beat head to head (audit_rivals.hpp; ties: the best score, z less the complexity
    // penalty); when none passes, the best score. Put first.
    auto pick = take_among_rivals(measured, r, taken, scored, options);
    if (pick != scored.end()) {
      std::rotate(scored.begin(), pick, pick + 1);
      pick = scored.begin();
      check_refutation(measured, r, taken, scored, options);
    }
    const std::size_t offset = r.findings.size();
    for (auto& s : scored) r.findings.push_back(s.finding);
    if (pick == scored.end()) break;
    taken.push_back(pick->finding.effect);
    taken_findings.push_back(offset + std::size_t(pick - scored.begin()));
    if (round == 1) first_loop = pick->loop;
    current = std::move(pick->loop);
    current_total = pick->finding.nrmse_total_after;
    current_check = pick->finding.residual;
  }
  // The foils: a catalogue effect is named only when it predicts the validation segment
  // significantly better than every significant mismatch outside the catalogue.
  if (!taken.empty()) {
    if (options.progress) options.progress("fit the out-of-catalogue foils", 0, 1);
    r.foils = fit_foils(measured, r.measured, {}, r.nominal, first_loop.y, r.estimation, r.validation,
                        options.covariance_lags, options.fit);
    for (const FoilFinding& f : r.foils)
      if (f.test.z > r.z_threshold && f.test.reduction > 0.0 && !(f.rival_gain.z > options.foil_margin) &&
          r.foil_beats_cause.empty())
        r.foil_beats_cause = f.name;
  }
  if (options.progress) options.progress("test the amplifier gains for drift", 0, 1);
  r.gain_drift = gain_drift_test(measured, r.measured, taken, current.y, record, r.rounded, options.drift_segments,
                                 options.drift_alpha);
  for (auto& f : r.findings) f.evidence = describe(f, r, r.excitation_correlation.rowwise().maxCoeff());
  const bool refuted = std::any_of(taken_findings.begin(), taken_findings.end(),
                                   [&](std::size_t i) { return !r.findings[i].refuted_by.empty(); });
  if (!taken.empty() && current_check.consistent && r.foil_beats_cause.empty() && !refuted && !r.gain_drift.varies) {
    for (std::size_t i : taken_findings) {
      r.findings[i].accepted = true;
      r.causes.push_back(r.findings[i].effect.name);
      for (const RivalTest& rival : r.findings[i].rivals) {
        const double over = deciding_z(rival.z_over, rival.z_one_step_over),
                     under = deciding_z(rival.z_under, rival.z_one_step_under);
        if (!(over > options.rival_margin && under < options.ambiguity_ratio * over))
          r.ambiguous_with.push_back({r.findings[i].effect.name, rival.effect, rival.channel, over, under});
      }
    }
    r.cause = r.causes.front();
    r.extended_effects = taken;
  } else if (!taken.empty() || !r.nominal_check.consistent || r.gain_drift.varies) {
    r.cause = "unexplained";
    r.unexplained_effects = taken;
  }
  const ReplayedLoop& extended = r.extended_effects.empty() ? nominal : current;
  r.extended = extended.y;
  const Eigen::Index L = std::min<Eigen::Index>(512, r.validation.size());
  r.residual_nominal = welch_spectrum(r.validation.kept_rows(residual), dt, L);
  r.residual_extended = welch_spectrum(r.validation.kept_rows(r.measured - r.extended), dt, L);
  r.frfs = audit_frfs(measured, nominal, extended, r.validation);
  r.amplitude = amplitude_dependence(measured, nominal, record.left_out);
  return r;
}

namespace {

// Magnitude and phase (deg) of every element of a ratio FRF, keyed "output/input", on the
// lines where the measured element is well determined (audit_frf.hpp).
nlohmann::json ratio_json(const ident::Frf& ratio, const AuditResult& r) {
  nlohmann::json pairs = nlohmann::json::object();
  for (Eigen::Index i = 0; i < ratio.rows(); ++i)
    for (Eigen::Index j = 0; j < ratio.cols(); ++j) {
      std::vector<double> frequency, magnitude, phase;
      for (Eigen::Index k : determined_lines(r.frfs, i, j)) {
        const std::complex<double> v = ratio.value[std::size_t(k)](i, j);
        frequency.push_back(ratio.frequency_hz[k]);
        magnitude.push_back(std::abs(v));
        phase.push_back(std::arg(v) * 180.0 / 3.141592653589793);
      }
      pairs[r.outputs[std::size_t(i)] + "/" + r.inputs[std::size_t(j)]] = {
          {"frequency_hz", frequency}, {"magnitude", magnitude}, {"phase_deg", phase}};
    }
  return pairs;
}

nlohmann::json check_json(const ResidualCheck& c, const AuditResult& r) {
  nlohmann::json outputs = nlohmann::json::object();
  for (std::size_t j = 0; j < r.outputs.size() && c.determinable; ++j) {
    const auto i = Eigen::Index(j);
    outputs[r.outputs[j]] = {
        {"coherence_mean", c.coherence_mean[i]}, {"coherence_z", c.coherence_z[i]}, {"coherence_p", c.coherence_p[i]}};
  }
  nlohmann::json j = {{"determinable", c.determinable},
                      {"window", c.window},
                      {"windows", c.windows},
                      {"excited_bins", c.bins},
                      {"p_value", c.p_value},
                      {"consistent", c.consistent},
                      {"outputs", outputs},
                      {"null_replicas", c.null_replicas}};
  if (!c.determinable) j["reason"] = c.reason;
  return j;
}

nlohmann::json rivals_json(const AuditFinding& f) {
  nlohmann::json rivals = nlohmann::json::array();
  for (const RivalTest& rival : f.rivals)
    rivals.push_back(
        {{"effect", rival.effect},
         {"channel", rival.channel ? nlohmann::json(rival.channel) : nlohmann::json(nullptr)},
         {"z_over_it", rival.z_over},
         {"z_it_over_this", rival.z_under},
         {"one_step_z_over_it",
          std::isnan(rival.z_one_step_over) ? nlohmann::json(nullptr) : nlohmann::json(rival.z_one_step_over)},
         {"one_step_z_it_over_this",
          std::isnan(rival.z_one_step_under) ? nlohmann::json(nullptr) : nlohmann::json(rival.z_one_step_under)}});
  return rivals;
}

nlohmann::json drift_json(const GainDrift& d) {
  nlohmann::json amplifiers = nlohmann::json::array();
  for (const GainDriftChannel& c : d.channels)
    amplifiers.push_back({{"channel", c.channel ? nlohmann::json(c.channel) : nlohmann::json(nullptr)},
                          {"gain_error", std::vector<double>(c.gain.begin(), c.gain.end())},
                          {"standard_error", std::vector<double>(c.se.begin(), c.se.end())},
                          {"heterogeneity_chi2", c.q},
                          {"heterogeneity_p", c.q_p},
                          {"slope_z", c.slope_z},
                          {"slope_p", c.slope_p},
                          {"p_value", c.p_value}});
  nlohmann::json j = {
      {"method",
       "amplifier gain error fitted per part of the record (linearised about the last model, noise whitened); "
       "heterogeneity chi-square and slope over the parts"},
      {"determinable", d.determinable},
      {"parts", d.segments},
      {"amplifiers", amplifiers},
      {"p_value", d.p_value},
      {"alpha", d.alpha},
      {"varies", d.varies},
      {"channel", d.varies && d.channel ? nlohmann::json(d.channel) : nlohmann::json(nullptr)}};
  if (!d.determinable) j["reason"] = d.reason;
  return j;
}

nlohmann::json effect_json(const sim::Effect& e) {
  return {{"effect", e.name},
          {"channel", e.channel ? nlohmann::json(e.channel) : nlohmann::json(nullptr)},
          {"parameters", e.parameters}};
}

}  // namespace

nlohmann::json audit_json(const AuditResult& r, const std::string& experiment_file,
                          const std::string& extended_model_file) {
  auto per_output = [&](const Eigen::VectorXd& v) {
    nlohmann::json j = nlohmann::json::object();
    for (std::size_t i = 0; i < r.outputs.size(); ++i) j[r.outputs[i]] = v[Eigen::Index(i)];
    return j;
  };
  nlohmann::json findings = nlohmann::json::array();
  for (const auto& f : r.findings)
    findings.push_back(
        {{"effect", f.effect.name},
         {"channel", f.effect.channel ? nlohmann::json(f.effect.channel) : nlohmann::json(nullptr)},
         {"parameters", f.effect.parameters},
         {"nrmse_total_before", f.nrmse_total_before},
         {"nrmse_total_after", f.nrmse_total_after},
         {"evidence", f.evidence},
         {"round", f.round},
         {"significant", f.significant},
         {"accepted", f.accepted},
         {"significance",
          {{"z", f.test.z},
           {"p_value", f.test.p_value},
           {"nrmse2_reduction", f.test.reduction},
           {"z_threshold", f.z_threshold}}},
         {"residual_check", check_json(f.residual, r)},
         {"head_to_head", rivals_json(f)},
         {"refuted_by", f.refuted_by.empty() ? nlohmann::json(nullptr)
                                             : nlohmann::json({{"effect", f.refuted_by},
                                                               {"one_step_z_over_this", f.refuted_z},
                                                               {"one_step_z_this_over_it", f.refuted_z_back}})}});
  nlohmann::json causes = nlohmann::json::array();
  for (std::size_t i = 0; i < r.findings.size(); ++i)
    if (r.findings[i].accepted) {
      nlohmann::json c = effect_json(r.findings[i].effect);
      c.erase("parameters");
      c["finding"] = i;
      causes.push_back(c);
    }
  nlohmann::json unexplained_after = nlohmann::json::array();
  for (const auto& e : r.unexplained_effects) unexplained_after.push_back(effect_json(e));
  nlohmann::json ambiguous = nlohmann::json::array();
  for (const auto& a : r.ambiguous_with)
    ambiguous.push_back({{"cause", a.cause},
                         {"effect", a.rival},
                         {"channel", a.channel ? nlohmann::json(a.channel) : nlohmann::json(nullptr)},
                         {"z_cause_over_it", a.z_over},
                         {"z_it_over_cause", a.z_under}});
  nlohmann::json foils = nlohmann::json::array();
  for (const auto& f : r.foils)
    foils.push_back({{"mismatch", f.name},
                     {"unit", f.unit},
                     {"value", f.value},
                     {"z", f.test.z},
                     {"cause_over_it_z", f.rival_gain.z},
                     {"nrmse2_reduction", f.test.reduction}});
  nlohmann::json correlation = nlohmann::json::object();
  for (std::size_t j = 0; j < r.outputs.size(); ++j)
    for (Eigen::Index i = 0; i < r.excitation_correlation.cols(); ++i)
      correlation[r.outputs[j]]["r" + std::to_string(i + 1)] = r.excitation_correlation(Eigen::Index(j), i);
  const AmplitudeDependence& a = r.amplitude;
  auto per_pair = [&](const auto& m) {
    nlohmann::json j = nlohmann::json::object();
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index k = 0; k < m.cols(); ++k)
        j[r.outputs[std::size_t(i)] + "/" + r.inputs[std::size_t(k)]] = m(i, k);
    return j;
  };
  nlohmann::json parts = nlohmann::json::array();
  for (const auto& p : a.parts)
    parts.push_back({{"begin", p.samples.begin},
                     {"end", p.samples.end},
                     {"excitation_rms", p.excitation_rms},
                     {"log_ratio", per_pair(p.log_ratio)},
                     {"log_ratio_se", per_pair(p.log_ratio_se)}});
  nlohmann::json amplitude = {
      {"method", "median log|G_meas / G_nominal| per contiguous part, highest vs lowest excitation rms"},
      {"determinable", a.determinable},
      {"spread", a.spread},
      {"parts", parts},
      {"z", a.determinable ? per_pair(a.z) : nlohmann::json(nullptr)},
      {"dependent", a.dependent}};
  if (!a.determinable) amplitude["reason"] = a.reason;
  nlohmann::json frf_ratio = nullptr;
  const ident::Frf& f = r.frfs.ratio_nominal;
  if (f.lines() > 0)
    frf_ratio = {{"estimator", "indirect closed-loop Welch G = S_yr S_ur^+, measured / model, element by element"},
                 {"segment", "validation"},
                 {"lines", "inputs coherent with r (>= 0.5) and var G_meas / |G_meas|^2 <= 0.01"},
                 {"nominal", ratio_json(f, r)},
                 {"extended", ratio_json(r.frfs.ratio_extended, r)}};
  return {{"format", "ambid-audit/1"},
          {"experiment", experiment_file},
          {"baseline", {{"nrmse", per_output(r.baseline_nrmse)}, {"nrmse_total", r.baseline_total}}},
          {"cause", r.cause},
          {"causes", causes},
          {"findings", findings},
          {"extended_model", extended_model_file},
          {"frf_ratio", frf_ratio},
          {"residual_excitation_correlation", correlation},
          {"amplitude_dependence", amplitude},
          {"clamped_samples",
           {{"count", r.clamped_samples},
            {"estimation", r.estimation.size() - Eigen::Index(r.estimation.kept().sum())},
            {"validation", r.validation.size() - Eigen::Index(r.validation.kept().sum())},
            {"left_out_of",
             "every statistic: NRMSE (baseline, screening, fits, findings), the fits' residuals, the improvement z, "
             "the residual check (windows holding one), the residual's correlation with r and its spectra (set to "
             "zero there), the FRF ratio and amplitude dependence (Welch segments holding one)"}}},
          {"acceptance",
           {{"rule", "validation improvement z above the Bonferroni threshold over the fitted findings"},
            {"false_acceptance_probability", r.false_acceptance},
            {"z_threshold", r.z_threshold},
            {"residual_rule",
             "the extended model's validation residual passes the residual check (multiple coherence with r over the "
             "excited bins against its null law) at residual_alpha; otherwise cause is unexplained"},
            {"residual_alpha", r.residual_alpha}}},
          {"residual_check", check_json(r.nominal_check, r)},
          {"unexplained_after", unexplained_after},
          {"ambiguous_with", ambiguous},
          {"out_of_catalogue", foils},
          {"gain_drift", drift_json(r.gain_drift)},
          {"out_of_catalogue_beats_cause",
           r.foil_beats_cause.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.foil_beats_cause)}};
}

nlohmann::json extended_model_json(const Experiment& measured, const AuditResult& r) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : r.extended_effects) effects.push_back(effect_json(e));
  const Eigen::VectorXd fit = nrmse(r.measured, r.extended, r.validation);
  nlohmann::json per_output = nlohmann::json::object();
  for (std::size_t i = 0; i < r.outputs.size(); ++i) per_output[r.outputs[i]] = fit[Eigen::Index(i)];
  return {{"format", "ambid-extended-model/1"},
          {"plant_model", measured.plant.model},
          {"sample_time", measured.sample_time},
          {"parameters", measured.plant.parameters},
          {"effects", effects},
          {"fit", {{"segment", "validation"}, {"nrmse", per_output}}}};
}

}  // namespace ambid::diag
