#include "identifier/identify_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/controller_replay.hpp"
#include "core/error.hpp"
#include "core/no_continuous_equivalent.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/families/amb1dof_deadbeat.hpp"
#include "identifier/families/amb1dof_prediction_error.hpp"
#include "identifier/families/amb1dof_realization.hpp"
#include "identifier/plant_families.hpp"
#include "identifier/time_domain/arx_order.hpp"
#include "identifier/time_domain/closed_loop_id.hpp"
#include "identifier/time_domain/closed_loop_validation.hpp"
#include "identifier/time_domain/loop_signals.hpp"
#include "identifier/time_domain/markov.hpp"
#include "identifier/time_domain/method_fits.hpp"
#include "identifier/time_domain/projection_filter.hpp"
#include "identifier/time_domain/segment_jackknife.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;
const std::string kWho = "identify";

// The structure's signals for a known family, else every signal in the experiment's order.
LoopSignals signals_of(const Experiment& e) {
  const IdentificationFamily* family = find_identification_family(e.plant.model);
  return family ? loop_signals(e, family->y_names, family->u_names, kWho) : loop_signals(e, kWho);
}

// The experiment has one: require() checked it for the methods that need it.
KnownController controller_of(const Experiment& e, const LoopSignals& s) {
  return known_controller(*e.controller, s.u_names, s.y_names);  // refuses feedthrough from u
}

// The ARX -> Markov -> ERA methods refuse a model order whose last Hankel singular value is
// not twice the next: such a state is the noise's, not the plant's (EraOptions::min_gap).
constexpr double kEraMinGap = 2.0;

Index model_order(const Experiment& e, const IdentifyOptions& o) {
  if (o.order < 0) throw Error(kWho + ": order must be >= 0, got " + std::to_string(o.order));
  const IdentificationFamily* family = find_identification_family(e.plant.model);
  return o.order > 0 ? o.order : (family ? family->order : 0);
}

// The families check is identify_experiment's (the registry); the order is the method's own.
void require_four_states(const IdentifyOptions& o) {
  if (o.order != 0 && o.order != 4)
    throw Error(kWho + ": method '" + o.method + "' gives the 4 physical states of amb1dof_voltage; --order " +
                std::to_string(o.order) + " is not possible");
}

void fit_deadbeat_with(const Experiment& e, const IdentifyOptions& o, const DeadbeatOptions& dopt, Model& model) {
  require_four_states(o);
  const Amb1dofIdentification id = identify_amb1dof_deadbeat(e, dopt);
  model.discrete = id.realization.system;
  model.continuous = id.continuous;
  model.parameters = id.parameters;
  model.physical = id.physical;
  for (const auto& [k, v] : id.parameter_uncertainty) model.uncertainty[k] = v;
  for (const auto& [k, v] : id.physical_uncertainty) model.uncertainty[k] = v;
  model.extra.json()["structure_deviation"] = id.structure_deviation;
}

DeadbeatOptions instrumental_variables(const IdentifyOptions& o) {
  DeadbeatOptions dopt;
  dopt.instrument_lags = o.instrument_lags;
  return dopt;
}

using Breaks = std::vector<Index>;
// A realisation of the ARX -> Markov -> ERA methods from the part of the record without the
// samples at `breaks` (the segment jackknife's joints) and without the samples where a
// controller clamp acted (with_clamps).
using Realize = DiscreteSystem (*)(const Experiment&, const IdentifyOptions&, const Breaks&);

// `breaks` plus a break at c and at c + 1 for every sample c where a controller clamp acted:
// the ARX leaves out every equation whose window k-q .. k holds c (ArxOptions::breaks drops
// k in [b, b + q) for a break b), since u[c] is not what the plant received or r[c] is not
// what the loop added (experiment-format.md: not exogenous).
Breaks with_clamps(const Experiment& e, Breaks breaks) {
  const std::vector<bool> clamped = clamped_samples(e).clamped;
  for (std::size_t c = 0; c < clamped.size(); ++c)
    if (clamped[c]) {
      breaks.push_back(Index(c));
      breaks.push_back(Index(c) + 1);
    }
  return breaks;
}

DiscreteSystem realize_okid(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  const LoopSignals s = signals_of(e);
  ArxOptions ao;
  ao.order = o.arx_order;
  ao.breaks = with_clamps(e, breaks);
  const ArxModel arx = fit_arx(s.y, s.u, ao);
  EraOptions eo;
  eo.order = model_order(e, o);
  eo.min_gap = kEraMinGap;
  return era(markov_from_arx(arx, o.markov_count).system, e.sample_time, eo).system;
}

// The options the ARX -> Markov -> ERA methods share.
template <typename Options>
Options arx_era_options(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  Options out;
  out.breaks = with_clamps(e, breaks);
  out.arx_order = o.arx_order;
  out.markov_count = o.markov_count;
  out.sample_time = e.sample_time;
  out.era.order = model_order(e, o);
  out.era.min_gap = kEraMinGap;
  return out;
}

DiscreteSystem realize_closed_loop(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  const LoopSignals s = signals_of(e);
  const auto co = arx_era_options<KnownControllerIdOptions>(e, o, breaks);
  return identify_with_known_controller(s.r, s.y, controller_of(e, s), co).plant;
}

// Needs r: without it uf = u and the plant input is not excited independently.
DiscreteSystem realize_projection(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  const LoopSignals s = signals_of(e);
  const auto po = arx_era_options<ProjectionFilterOptions>(e, o, breaks);
  return identify_projection_filter(s.y, s.u, s.uf, po).plant;
}

void add_warning(Model& model, const std::string& warning) {
  if (!model.extra.json().contains("warnings")) model.extra.json()["warnings"] = nlohmann::json::array();
  model.extra.json()["warnings"].push_back(warning);
}

Eigen::Matrix<double, 9, 1> structure_vector(const std::map<std::string, double>& parameters) {
  Eigen::Matrix<double, 9, 1> v;
  for (Index i = 0; i < 9; ++i) v(i) = parameters.at(amb1dof_structure_names()[std::size_t(i)]);
  return v;
}

// Segment jackknife of the parameters and physical quantities of an ARX/ERA method.
void add_jackknife_uncertainty(const IdentificationFamily& family, Realize realize, const Experiment& e,
                               const IdentifyOptions& o, Model& model) {
  std::vector<std::map<std::string, double>> estimates;
  try {
    for (Index i = 0; i < o.jackknife_segments; ++i) {
      const LeaveOneSegmentOut cut = experiment_without_segment(e, i, o.jackknife_segments);
      const Breaks breaks = cut.joint > 0 ? Breaks{cut.joint} : Breaks{};
      Model part;
      family.add_structure(e, realize(cut.experiment, o, breaks), part);
      part.parameters.insert(part.physical.begin(), part.physical.end());
      estimates.push_back(part.parameters);
    }
  } catch (const Error& error) {
    add_warning(model, std::string("no uncertainty: a leave-one-segment-out fit failed: ") + error.what());
    return;
  }
  model.uncertainty = jackknife_sigma(estimates);
  model.extra.json()["uncertainty_method"] = "segment jackknife, " + std::to_string(o.jackknife_segments) + " segments";
}

// `o` with the ARX order of the ARX -> Markov -> ERA methods resolved for the record `e`
// (arx_order.hpp); the jackknife's shorter sub-records keep it.
IdentifyOptions with_arx_order(const Experiment& e, IdentifyOptions o) {
  if (o.arx_order == 0) {
    const LoopSignals s = signals_of(e);
    o.arx_order = default_arx_order(e.samples(), s.y.cols(), s.u.cols());
  }
  return o;
}

// A sampled continuous plant has no eigenvalue on the closed negative real axis (exp(s T) of a
// real s is positive); one there is a state of the noise, not of the plant.
std::optional<double> negative_real_eigenvalue(const DiscreteSystem& realization) {
  for (const std::complex<double>& z : poles(realization))
    if (z.real() <= 0.0 && std::abs(z.imag()) <= 1e-12 * std::max(1.0, std::abs(z))) return z.real();
  return std::nullopt;
}

// realize() with the given Markov count, or without one with default_markov_counts() in turn
// until ERA finds the model order determined and no state on the negative real axis;
// `o.markov_count` becomes the count used. When every determined realisation has such a state
// (a discrete plant that truly has one, or noise no count gets rid of), the last of them is
// returned: a valid discrete model without a continuous equivalent (Model::no_continuous).
// Throws InsufficientData when no count determines the order.
DiscreteSystem realize_determined(Realize realize, const Experiment& e, IdentifyOptions& o) {
  if (o.markov_count > 0) return realize(e, o, {});
  std::string last;
  std::optional<std::pair<DiscreteSystem, Index>> with_negative_state;
  for (const Index count : default_markov_counts()) {
    o.markov_count = count;
    try {
      DiscreteSystem realization = realize(e, o, {});
      if (!negative_real_eigenvalue(realization)) return realization;
      with_negative_state = {std::move(realization), count};
    } catch (const UndeterminedOrder& error) {
      last = error.what();
    }
  }
  if (with_negative_state) {
    o.markov_count = with_negative_state->second;
    return with_negative_state->first;
  }
  throw InsufficientData(kWho + ": the data do not determine a model of this order: with " +
                         std::to_string(o.markov_count) + " Markov parameters (the most tried) " + last);
}

void fit_realization(Realize realize, const Experiment& e, const IdentifyOptions& options, Model& model) {
  IdentifyOptions o = with_arx_order(e, options);
  const DiscreteSystem realization = realize_determined(realize, e, o);
  model.extra.json()["arx"] = {{"order", o.arx_order}, {"markov_count", o.markov_count}};
  model.discrete = realization;
  const IdentificationFamily* family = find_identification_family(e.plant.model);
  if (family && family->add_structure && realization.states() == family->order) {
    try {
      family->add_structure(e, realization, model);
    } catch (const NoContinuousEquivalent& error) {
      // The physical coordinates need Ac = logm(A)/T; the discrete model stays valid as it is.
      model.no_continuous = error.what();
      add_warning(model, "no continuous-time model (" + std::string(error.what()) +
                             "): the discrete model is kept in the realisation's coordinates, without parameters");
      return;
    }
    if (o.jackknife_segments > 0) add_jackknife_uncertainty(*family, realize, e, o, model);
  } else {
    add_warning(model, "model in the realisation's coordinates (no physical structure for this plant or order)");
  }
}

void validate_on(const Experiment& validation, Model& model) {
  if (!validation.controller) {
    add_warning(model, "no controller: the model cannot be simulated in closed loop, fit.nrmse not computed");
    return;
  }
  const LoopSignals s = signals_of(validation);
  const KnownController k = known_controller(*validation.controller, s.u_names, s.y_names);
  const Eigen::VectorXd nrmse = closed_loop_nrmse(model.discrete, k, s.r, s.y, validation.controller->initial_state,
                                                  clamped_samples(validation).clamped);
  if (!nrmse.allFinite()) {
    add_warning(
        model, "the closed-loop simulation of the model with the recorded controller diverges: fit.nrmse not computed");
    return;
  }
  for (Index j = 0; j < nrmse.size(); ++j) model.fit_nrmse[s.y_names[std::size_t(j)]] = nrmse(j);
}

Index count_clamped(const Experiment& e) { return clamped_samples(e).clamped_samples; }

// [begin, end) of the longest run of samples of `e` without a controller clamp acting.
std::pair<Index, Index> longest_unclamped_stretch(const Experiment& e) {
  const std::vector<bool> clamped = clamped_samples(e).clamped;
  std::pair<Index, Index> best{0, 0};
  Index begin = 0;
  for (Index k = 0; k <= Index(clamped.size()); ++k) {
    if (k < Index(clamped.size()) && !clamped[std::size_t(k)]) continue;
    if (k - begin > best.second - best.first) best = {begin, k};
    begin = k + 1;
  }
  return best;
}

// What method_registry() requires of the experiment, in this order.
void require(const IdentificationMethod& method, const Experiment& e) {
  const std::vector<std::string> families = families_offering(method.name);
  if (method.family_bound && std::find(families.begin(), families.end(), e.plant.model) == families.end()) {
    std::string list;
    for (const auto& f : families) list += (list.empty() ? "'" : "', '") + f;
    throw Error(kWho + ": method '" + method.name + "' is defined for plant model " + list + "' only, got '" +
                e.plant.model + "'" +
                (find_identification_family(e.plant.model)
                     ? ""
                     : " (known plant models: " + identification_family_names() + ")"));
  }
  if (method.needs_r && !e.has_excitation())
    throw Error(kWho + ": method '" + method.name +
                "' needs the excitation r; the experiment records none (signals.r)");
  if (method.needs_controller && !e.controller)
    throw Error(kWho + ": method '" + method.name +
                "' needs the controller that closed the loop; the experiment has no controller");
}

// The plant input the controller's output clamps let through, as replay applies them
// (experiment-format.md): the recorded u (the command) clamped into controller.output_limits;
// deviations, in the columns of s.u.
Eigen::MatrixXd applied_input(const Experiment& e, const LoopSignals& s) {
  Eigen::MatrixXd u = s.u;
  const Eigen::VectorXd op = e.operating_values(s.u_names);
  for (std::size_t i = 0; e.controller && i < e.controller->output_limits.size(); ++i) {
    const auto it = std::find(s.u_names.begin(), s.u_names.end(), e.controller->outputs[i]);
    if (it == s.u_names.end()) continue;
    const Index j = it - s.u_names.begin();
    const Limit& limit = e.controller->output_limits[i];
    u.col(j) = (u.col(j).array() + op(j)).cwiseMax(limit.lo).cwiseMin(limit.hi) - op(j);
  }
  return u;
}

// The samples where a controller clamp acted leave their prediction errors out of pem's cost.
Amb1dofPredictionErrorOptions pem_options(const Experiment& e) {
  Amb1dofPredictionErrorOptions o;
  const ControllerReplay clamps = clamped_samples(e);
  if (clamps.clamped_samples > 0) o.clamped = clamps.clamped;
  return o;
}

// Starts from `closed-loop`, `deadbeat-iv`, `deadbeat` (those that succeed) and the nominal
// model, then the prediction-error refinement from the best of them; or from
// options.pem_warm_start alone.
Amb1dofPredictionErrorFit pem_fit(const Experiment& e, const IdentifyOptions& o, const LoopSignals& s,
                                  std::string& start_name) {
  if (o.pem_warm_start) {
    start_name = "warm";
    return fit_amb1dof_prediction_error_from(s.y, applied_input(e, s), s.r, e.sample_time, *o.pem_warm_start,
                                             pem_options(e));
  }
  std::vector<std::string> start_names, failures;
  std::vector<Eigen::Matrix<double, 9, 1>> starts;
  auto try_start = [&](const std::string& name, auto&& estimate) {
    try {
      const Eigen::Matrix<double, 9, 1> v = structure_vector(estimate());
      // One unusable start must not sink the others (the fit refuses such starts).
      if (!v.allFinite() || (v.array() == 0.0).any()) throw Error("v1..v9 not finite or with a zero entry");
      starts.push_back(v);
      start_names.push_back(name);
    } catch (const Error& error) {
      failures.push_back(name + ": " + error.what());
    }
  };
  try_start("closed-loop", [&] {
    Model start;
    IdentifyOptions co = with_arx_order(e, o);
    add_amb1dof_structure(e, realize_determined(realize_closed_loop, e, co), start);
    return start.parameters;
  });
  try_start("deadbeat-iv", [&] { return identify_amb1dof_deadbeat(e, instrumental_variables(o)).parameters; });
  try_start("deadbeat", [&] { return identify_amb1dof_deadbeat(e, DeadbeatOptions{}).parameters; });
  // The sidecar's nominal model: the only start without data-driven bias, and the one that
  // remains when a short window leaves closed-loop far off and the deadbeat starts do not
  // apply (a decentralised controller).
  try {
    starts.push_back(amb1dof_nominal_structure(e, kWho));
    start_names.push_back("nominal");
  } catch (const Error& error) {
    failures.push_back(std::string("nominal: ") + error.what());
  }
  if (starts.empty()) {
    std::string all;
    for (const auto& f : failures) all += (all.empty() ? "" : "; ") + f;
    throw InsufficientData(kWho + ": method 'pem' found no starting estimate (" + all + ")");
  }
  Amb1dofPredictionErrorFit fit =
      fit_amb1dof_prediction_error(s.y, applied_input(e, s), s.r, e.sample_time, starts, pem_options(e));
  start_name = start_names[std::size_t(fit.start_index)];
  return fit;
}

}  // namespace

namespace detail {

void fit_deadbeat(const Experiment& e, const IdentifyOptions& o, Model& model) {
  fit_deadbeat_with(e, o, DeadbeatOptions{}, model);
}

void fit_deadbeat_iv(const Experiment& e, const IdentifyOptions& o, Model& model) {
  fit_deadbeat_with(e, o, instrumental_variables(o), model);
}

void fit_okid(const Experiment& e, const IdentifyOptions& o, Model& model) {
  fit_realization(realize_okid, e, o, model);
}

void fit_closed_loop(const Experiment& e, const IdentifyOptions& o, Model& model) {
  fit_realization(realize_closed_loop, e, o, model);
}

void fit_projection(const Experiment& e, const IdentifyOptions& o, Model& model) {
  fit_realization(realize_projection, e, o, model);
}

// The family's own (require() checked that the family offers greybox).
void fit_greybox(const Experiment& e, const IdentifyOptions& o, Model& model) {
  find_identification_family(e.plant.model)->greybox(e, o, model);
}

void fit_pem(const Experiment& e, const IdentifyOptions& o, Model& model) {
  require_four_states(o);
  const LoopSignals s = signals_of(e);
  controller_of(e, s);  // the starts need it without feedthrough: refuse early
  std::string start_name;
  const Amb1dofPredictionErrorFit fit = pem_fit(e, o, s, start_name);
  model.discrete = fit.discrete;
  model.continuous = fit.continuous;
  const Amb1dofNominal nominal = amb1dof_nominal(e, kWho);
  const Eigen::Matrix<double, 9, 1> scale = amb1dof_physical_scale(nominal.L1, nominal.L2, nominal.m);
  for (Index i = 0; i < 9; ++i) {
    const std::string& v = amb1dof_structure_names()[std::size_t(i)];
    const std::string& q = amb1dof_physical_names()[std::size_t(i)];
    const double sigma = std::sqrt(std::max(0.0, fit.covariance(i, i)));
    model.parameters[v] = fit.v(i);
    model.physical[q] = fit.v(i) * scale(i);
    model.uncertainty[v] = sigma;
    model.uncertainty[q] = sigma * scale(i);
  }
  model.extra.json()["structure_deviation"] = 0.0;  // the structure of eq. (4) by construction
  if (!fit.converged)
    add_warning(model, "pem: the solver stopped before converging after " + std::to_string(fit.iterations) +
                           " iterations: " + fit.termination);
  nlohmann::json gain = nlohmann::json::array();
  for (Index i = 0; i < 4; ++i)
    gain.push_back({fit.predictor_gain(i, 0), fit.predictor_gain(i, 1), fit.predictor_gain(i, 2)});
  model.extra.json()["pem"] = {{"start", start_name},
                               {"scored_samples", fit.scored_samples},
                               {"iterations", fit.iterations},
                               {"converged", fit.converged},
                               {"condition_number", fit.condition_number},
                               {"offset", {fit.offset(0), fit.offset(1), fit.offset(2)}},
                               {"predictor_gain", std::move(gain)},
                               {"residual_rms", {fit.residual_rms(0), fit.residual_rms(1), fit.residual_rms(2)}},
                               {"residual_check",
                                {{"z", fit.residual_check.z},
                                 {"correlation", fit.residual_check.correlation},
                                 {"worst", fit.residual_check.worst},
                                 {"whiteness_z", fit.residual_check.whiteness_z},
                                 {"whiteness_worst", fit.residual_check.whiteness_worst},
                                 {"lags", fit.residual_check.lags},
                                 {"correlations", fit.residual_check.correlations},
                                 {"max_z", Amb1dofPredictionErrorOptions{}.max_residual_z},
                                 {"max_correlation", Amb1dofPredictionErrorOptions{}.max_residual_correlation}}}};
}

}  // namespace detail

void require_method_inputs(const Experiment& e, const std::string& method) {
  require(identification_method(method, kWho), e);
}

Experiment experiment_segment(const Experiment& e, Index begin, Index end) {
  if (begin < 0 || end > e.samples() || end - begin < 2)
    throw Error(kWho + ": segment [" + std::to_string(begin) + ", " + std::to_string(end) + ") of a record of " +
                std::to_string(e.samples()) + " samples");
  Experiment s = e;
  const Index n = end - begin;
  s.t = e.t.segment(begin, n);
  s.y = e.y.middleRows(begin, n);
  s.u = e.u.middleRows(begin, n);
  if (e.r.size() > 0) s.r = e.r.middleRows(begin, n);
  if (e.controller && begin > 0) {
    const LoopSignals all = loop_signals(e, kWho);
    const KnownController k = known_controller(*e.controller, all.u_names, all.y_names);
    const Eigen::MatrixXd states =
        replay_controller(k, all.u.topRows(begin), all.y.topRows(begin), e.controller->initial_state);
    s.controller->initial_state = states.row(begin - 1).transpose();
  }
  return s;
}

Model identify_experiment(const Experiment& e, const IdentifyOptions& o) {
  const IdentificationMethod& method = identification_method(o.method, kWho);
  if (!(o.validation_fraction >= 0.0 && o.validation_fraction <= 0.9))
    throw Error(kWho + ": validation fraction must be in [0, 0.9], got " + std::to_string(o.validation_fraction));
  if (o.skip_samples < 0 || o.arx_order < 0 || o.markov_count < 0 || o.instrument_lags < 0)
    throw Error(kWho + ": skip_samples, arx_order, markov_count and instrument_lags must be >= 0");
  if (o.jackknife_segments < 0 || o.jackknife_segments == 1)
    throw Error(kWho + ": jackknife segments must be 0 (no uncertainty) or >= 2, got " +
                std::to_string(o.jackknife_segments));
  e.validate();
  require(method, e);
  const Index usable = e.samples() - o.skip_samples;
  const Index validation = static_cast<Index>(std::floor(o.validation_fraction * double(usable)));
  if (usable - validation < 2)
    throw InsufficientData(kWho + ": " + std::to_string(e.samples()) + " samples, " + std::to_string(o.skip_samples) +
                           " skipped, leave nothing to fit");
  Experiment fit = experiment_segment(e, o.skip_samples, e.samples() - validation);
  const Index fit_clamped = count_clamped(fit);
  std::string clamp_handling = "none in the fit window";
  const IdentificationFamily* family = find_identification_family(e.plant.model);
  const bool keeps_clamped = method.family_bound && family && family->keeps_clamped;
  if (fit_clamped > 0 && !method.leaves_out_clamped.empty()) {
    clamp_handling = method.leaves_out_clamped;
  } else if (fit_clamped > 0 && keeps_clamped) {
    clamp_handling = "kept: method '" + o.method + "' fits the plant's own equations on the u the plant got";
  } else if (fit_clamped > 0) {
    const auto [begin, end] = longest_unclamped_stretch(fit);
    if (end - begin < 2)
      throw InsufficientData(kWho + ": a controller clamp acts in " + std::to_string(fit_clamped) + " of the " +
                             std::to_string(fit.samples()) + " samples of the fit window: no stretch without one");
    clamp_handling = "method '" + o.method +
                     "' cannot leave single samples out: fitted on the longest stretch without a clamp, samples [" +
                     std::to_string(o.skip_samples + begin) + ", " + std::to_string(o.skip_samples + end) +
                     ") of the record";
    fit = experiment_segment(fit, begin, end);
  }
  IdentifyOptions resolved = o;
  if (resolved.instrument_lags == 0) resolved.instrument_lags = kDefaultInstrumentLags;

  Model model;
  model.plant_model = e.plant.model;
  model.method = o.method;
  model.sample_time = e.sample_time;
  try {
    method.fit(fit, resolved, model);
  } catch (const InsufficientData& error) {
    if (fit_clamped == 0 || !method.leaves_out_clamped.empty() || keeps_clamped) throw;
    throw InsufficientData(std::string(error.what()) + " (" + clamp_handling + ")");
  }
  model.discrete.sample_time = e.sample_time;
  model.extra.json()["samples"] = {{"skipped", o.skip_samples}, {"fit", fit.samples()}, {"validation", validation}};
  if (fit_clamped > 0)
    add_warning(model, std::to_string(fit_clamped) +
                           " samples of the fit window have a controller "
                           "clamp acting (not exogenous): " +
                           clamp_handling);
  Index validation_clamped = 0;
  if (validation >= 2) {
    const Experiment scored = experiment_segment(e, e.samples() - validation, e.samples());
    validation_clamped = count_clamped(scored);
    validate_on(scored, model);
  }
  model.extra.json()["clamped_samples"] = {
      {"fit_window", fit_clamped},
      {"fit", clamp_handling},
      {"validation", validation_clamped},
      {"validation_scoring", "left out of fit.nrmse and of the initial-state fit"}};
  model.validate();
  return model;
}

}  // namespace ambid::ident
