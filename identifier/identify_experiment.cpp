#include "identifier/identify_experiment.hpp"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/no_continuous_equivalent.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/families/amb1dof_deadbeat.hpp"
#include "identifier/families/amb1dof_prediction_error.hpp"
#include "identifier/families/amb1dof_realization.hpp"
#include "identifier/plant_families.hpp"
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
// samples at `breaks` (the segment jackknife's joints).
using Realize = DiscreteSystem (*)(const Experiment&, const IdentifyOptions&, const Breaks&);

DiscreteSystem realize_okid(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  const LoopSignals s = signals_of(e);
  ArxOptions ao;
  ao.order = o.arx_order;
  ao.breaks = breaks;
  const ArxModel arx = fit_arx(s.y, s.u, ao);
  EraOptions eo;
  eo.order = model_order(e, o);
  return era(markov_from_arx(arx, o.markov_count).system, e.sample_time, eo).system;
}

// The options the ARX -> Markov -> ERA methods share.
template <typename Options>
Options arx_era_options(const Experiment& e, const IdentifyOptions& o, const Breaks& breaks) {
  Options out;
  out.breaks = breaks;
  out.arx_order = o.arx_order;
  out.markov_count = o.markov_count;
  out.sample_time = e.sample_time;
  out.era.order = model_order(e, o);
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

void fit_realization(Realize realize, const Experiment& e, const IdentifyOptions& o, Model& model) {
  const DiscreteSystem realization = realize(e, o, {});
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
  const Eigen::VectorXd nrmse = closed_loop_nrmse(model.discrete, k, s.r, s.y, validation.controller->initial_state);
  if (!nrmse.allFinite()) {
    add_warning(
        model, "the closed-loop simulation of the model with the recorded controller diverges: fit.nrmse not computed");
    return;
  }
  for (Index j = 0; j < nrmse.size(); ++j) model.fit_nrmse[s.y_names[std::size_t(j)]] = nrmse(j);
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

// Starts from `closed-loop`, `deadbeat-iv` and `deadbeat` (those that succeed), then the
// prediction-error refinement from the best of them.
void fit_pem(const Experiment& e, const IdentifyOptions& o, Model& model) {
  require_four_states(o);
  const LoopSignals s = signals_of(e);
  controller_of(e, s);  // the starts need it without feedthrough: refuse early
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
    add_amb1dof_structure(e, realize_closed_loop(e, o, {}), start);
    return start.parameters;
  });
  try_start("deadbeat-iv", [&] { return identify_amb1dof_deadbeat(e, instrumental_variables(o)).parameters; });
  try_start("deadbeat", [&] { return identify_amb1dof_deadbeat(e, DeadbeatOptions{}).parameters; });
  if (starts.empty()) {
    std::string all;
    for (const auto& f : failures) all += (all.empty() ? "" : "; ") + f;
    throw InsufficientData(kWho + ": method 'pem' found no starting estimate (" + all + ")");
  }
  const Amb1dofPredictionErrorFit fit = fit_amb1dof_prediction_error(s.y, s.u, s.r, e.sample_time, starts);
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
    add_warning(model, "pem: the solver stopped at its iteration limit before converging (" +
                           std::to_string(fit.iterations) + " iterations)");
  model.extra.json()["pem"] = {{"start", start_names[std::size_t(fit.start_index)]},
                               {"iterations", fit.iterations},
                               {"condition_number", fit.condition_number},
                               {"offset", {fit.offset(0), fit.offset(1), fit.offset(2)}},
                               {"residual_rms", {fit.residual_rms(0), fit.residual_rms(1), fit.residual_rms(2)}}};
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
  const Experiment fit = experiment_segment(e, o.skip_samples, e.samples() - validation);
  IdentifyOptions resolved = o;
  if (resolved.arx_order == 0) resolved.arx_order = kDefaultArxOrder;
  if (resolved.markov_count == 0) resolved.markov_count = kDefaultMarkovCount;
  if (resolved.instrument_lags == 0) resolved.instrument_lags = kDefaultInstrumentLags;

  Model model;
  model.plant_model = e.plant.model;
  model.method = o.method;
  model.sample_time = e.sample_time;
  method.fit(fit, resolved, model);
  model.discrete.sample_time = e.sample_time;
  model.extra.json()["samples"] = {{"skipped", o.skip_samples}, {"fit", fit.samples()}, {"validation", validation}};
  if (validation >= 2) validate_on(experiment_segment(e, e.samples() - validation, e.samples()), model);
  model.validate();
  return model;
}

}  // namespace ambid::ident
