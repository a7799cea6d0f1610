#include "identifier/frf_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_periodic.hpp"
#include "identifier/frequency_domain/frf_stepped_sine.hpp"
#include "identifier/frequency_domain/rational_fit_order.hpp"
#include "identifier/frf_welch.hpp"

namespace ambid::ident {
namespace {

const nlohmann::json* excitation_description(const Experiment& e) {
  const nlohmann::json& extra = e.extra.json();
  if (!extra.is_object()) return nullptr;
  const auto it = extra.find("excitation");
  if (it == extra.end() || !it->is_object()) return nullptr;
  return &*it;
}

std::string text(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

double number(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

bool in_band(double f, const FrfAnalysisOptions& o) { return f >= o.f_min && (o.f_max <= 0.0 || f <= o.f_max); }

// The periodic estimator's options from a multisine / periodic PRBS description, or nullopt
// (with a note) when the description does not allow a period-exact analysis.
std::optional<PeriodicFrfOptions> periodic_options(const Experiment& e, const nlohmann::json& d,
                                                   const FrfAnalysisOptions& o, Eigen::Index* periods,
                                                   std::vector<std::string>& notes) {
  const std::string kind = text(d, "kind");
  const double N_value = number(d, "period_samples", 0.0);
  const auto N = static_cast<Eigen::Index>(std::llround(N_value));
  const double described_periods = number(d, "periods", 0.0);
  const auto nr = static_cast<Eigen::Index>(e.r_names.size());
  if (N < 4 || N_value != static_cast<double>(N)) {
    notes.push_back("excitation: no usable period_samples in the description; Welch analysis instead");
    return std::nullopt;
  }
  *periods = std::min<Eigen::Index>(e.samples() / N, static_cast<Eigen::Index>(std::floor(described_periods + 1e-9)));
  PeriodicFrfOptions p;
  p.sample_time = e.sample_time;
  p.period_samples = N;
  const double df = 1.0 / (static_cast<double>(N) * e.sample_time);
  if (kind == "multisine") {
    const auto it = d.find("lines");
    if (it == d.end() || !it->is_array()) {
      notes.push_back("excitation: the multisine description has no lines; Welch analysis instead");
      return std::nullopt;
    }
    for (const auto& k : *it)
      if (k.is_number_integer() && in_band(static_cast<double>(k.get<Eigen::Index>()) * df, o))
        p.lines.push_back(k.get<Eigen::Index>());
    std::sort(p.lines.begin(), p.lines.end());
    p.lines.erase(std::unique(p.lines.begin(), p.lines.end()), p.lines.end());
    const std::string pattern = text(d, "channel_pattern");
    if (pattern == "hadamard") {
      const auto h = d.find("hadamard");
      p.periods_per_block = h != d.end() && h->is_array() ? static_cast<Eigen::Index>(h->size()) : 0;
      if (p.periods_per_block < nr) {
        notes.push_back("excitation: the hadamard description is missing or too small; Welch analysis instead");
        return std::nullopt;
      }
    } else if (nr > 1) {
      notes.push_back(
          "excitation: the same multisine on every channel cannot separate the plant inputs; Welch analysis instead");
      return std::nullopt;
    }
  } else if (kind == "prbs") {
    if (nr != 1 || *periods < 2) {
      notes.push_back(
          nr != 1 ? "excitation: shifted PRBS channels are not separable period by period; Welch analysis instead"
                  : "excitation: fewer than two whole PRBS periods; Welch analysis instead");
      return std::nullopt;
    }
    for (Eigen::Index k = 1; 2 * k < N; ++k)
      if (in_band(static_cast<double>(k) * df, o)) p.lines.push_back(k);
  } else {
    return std::nullopt;
  }
  if (p.lines.empty()) {
    notes.push_back("excitation: no excited line in the requested band; Welch analysis instead");
    return std::nullopt;
  }
  if (o.transient_periods >= 0) {
    p.transient_periods = o.transient_periods;
  } else {
    p.transient_periods = *periods - 1 >= p.periods_per_block ? 1 : 0;
    if (p.transient_periods == 0)
      notes.push_back("periodic analysis: too few periods to discard one as transient; the first period is used");
  }
  return p;
}

// The stepped-sine estimator's options from the description, or nullopt (with a note) when
// the steps cannot be analysed one by one.
std::optional<SteppedSineFrfOptions> stepped_sine_options(const Experiment& e, const nlohmann::json& d,
                                                          const FrfAnalysisOptions& o,
                                                          std::vector<std::string>& notes) {
  if (text(d, "kind") != "stepped_sine") return std::nullopt;
  if (e.r_names.size() != 1 || e.u_names.size() != 1) {
    notes.push_back("excitation: a stepped sine excites one direction per frequency and cannot separate " +
                    std::to_string(e.u_names.size()) + " plant inputs from " + std::to_string(e.r_names.size()) +
                    " references; Welch analysis instead");
    return std::nullopt;
  }
  const auto steps = d.find("steps");
  const double cycles = number(d, "measure_periods", 0.0);
  if (steps == d.end() || !steps->is_array() || !(cycles >= 1.0) || cycles != std::floor(cycles)) {
    notes.push_back(
        "excitation: the stepped-sine description has no usable steps or measure_periods; Welch analysis instead");
    return std::nullopt;
  }
  SteppedSineFrfOptions s;
  s.sample_time = e.sample_time;
  s.f_min = o.f_min;
  s.f_max = o.f_max;
  for (const auto& step : *steps) {
    const double start = step.is_object() ? number(step, "measure_start_sample", -1.0) : -1.0;
    const double length = step.is_object() ? number(step, "measure_samples", 0.0) : 0.0;
    if (!(start >= 0.0) || !(length >= 2.0)) {
      notes.push_back(
          "excitation: a stepped-sine step without measure_start_sample / measure_samples; Welch analysis instead");
      return std::nullopt;
    }
    s.steps.push_back(
        {static_cast<Eigen::Index>(start), static_cast<Eigen::Index>(length), static_cast<Eigen::Index>(cycles)});
  }
  return s;
}

void fill_pairs(FrfReport& report, const Eigen::MatrixXd* coherence, double confidence) {
  const double factor =
      report.plant.has_variance() ? confidence_radius_factor(confidence, report.plant.variance_dof) : 0.0;
  for (Eigen::Index i = 0; i < report.plant.rows(); ++i) {
    for (Eigen::Index j = 0; j < report.plant.cols(); ++j) {
      PlantPair p;
      p.output = report.output_names[static_cast<std::size_t>(i)];
      p.input = report.input_names[static_cast<std::size_t>(j)];
      p.name = p.output + "/" + p.input;
      p.value = report.plant.element(i, j);
      if (report.plant.has_variance()) {
        p.variance = report.plant.element_variance(i, j);
        p.bound = (factor * p.variance.array()).sqrt().matrix();
      }
      if (coherence != nullptr) p.coherence = coherence->col(i);
      report.pairs.push_back(std::move(p));
    }
  }
}

void fit_pairs(FrfReport& report, const Experiment& e, const FrfAnalysisOptions& o) {
  const double f_top = o.fit_f_max > 0.0 ? o.fit_f_max : 0.1 / e.sample_time;
  std::vector<Eigen::Index> rows;
  for (Eigen::Index l = 0; l < report.frequency_hz.size(); ++l)
    if (report.frequency_hz(l) <= f_top && 2.0 * report.frequency_hz(l) * e.sample_time < 1.0) rows.push_back(l);
  if (rows.size() < 8) {
    report.notes.push_back("rational fit: fewer than 8 lines below " + std::to_string(f_top) + " Hz; no fit");
    return;
  }
  Eigen::VectorXd f(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) f(static_cast<Eigen::Index>(k)) = report.frequency_hz(rows[k]);
  OrderSearchOptions search;
  search.max_denominator_degree = o.fit_max_order;
  search.relative_degrees = {0, 1, 2, 3};
  search.fit.zoh_sample_time = e.sample_time;
  for (const PlantPair& pair : report.pairs) {
    Eigen::VectorXcd g(f.size());
    Eigen::VectorXd v(pair.variance.size() ? f.size() : 0);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      g(static_cast<Eigen::Index>(k)) = pair.value(rows[k]);
      if (v.size()) v(static_cast<Eigen::Index>(k)) = pair.variance(rows[k]);
    }
    if (v.size() && !(v.minCoeff() > 0.0)) v.resize(0);  // noise-free lines: relative weights
    try {
      const OrderSelection sel = select_rational_order(f, g, v, search);
      report.fits.push_back(FittedPair{pair.name, pair.output, pair.input, sel.fit});
    } catch (const Error& err) {
      report.notes.push_back("rational fit of " + pair.name + ": " + err.what());
    }
  }
}

}  // namespace

FrfReport analyse_frf(const Experiment& e, const FrfAnalysisOptions& o) {
  e.validate();
  if (!e.has_excitation())
    throw InsufficientData("frf: the experiment records no excitation r; the closed-loop FRF needs one");
  if (!(o.confidence > 0.0 && o.confidence < 1.0))
    throw Error("frf: confidence must be in (0, 1), got " + std::to_string(o.confidence));
  FrfReport report;
  report.output_names = e.y_names;
  report.input_names = e.u_names;
  report.reference_names = e.r_names;
  Eigen::MatrixXd r = e.r_deviation(), u = e.u_deviation(), y = e.y_deviation();

  const nlohmann::json* d = excitation_description(e);
  report.excitation = d ? text(*d, "kind") : std::string();
  if (report.excitation.empty()) report.excitation = "unknown";

  Eigen::Index periods = 0;
  std::optional<PeriodicFrfOptions> periodic = d ? periodic_options(e, *d, o, &periods, report.notes) : std::nullopt;
  const Eigen::MatrixXd* coherence = nullptr;
  Eigen::MatrixXd welch_coherence;
  if (periodic) {
    const Eigen::Index used = periods * periodic->period_samples;
    const PeriodicFrf p = estimate_periodic_frf(r.topRows(used), u.topRows(used), y.topRows(used), *periodic);
    report.method = "periodic";
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.blocks;
    if (p.blocks < 2) report.notes.push_back("periodic analysis: one block only; no noise bounds");
  } else if (const auto stepped = d ? stepped_sine_options(e, *d, o, report.notes) : std::nullopt) {
    const SteppedSineFrf p = estimate_stepped_sine_frf(r, u, y, *stepped);
    report.method = "stepped_sine";
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.plant.lines();
    report.notes.push_back("stepped sine: one window per frequency; no noise estimate");
  } else {
    WelchFrfOptions w;
    w.sample_time = e.sample_time;
    w.segment_samples = o.segment_samples;
    if (w.segment_samples == 0) {
      w.segment_samples = 64;
      while (w.segment_samples * 2 <= e.samples() / 8) w.segment_samples *= 2;
    }
    w.f_min = o.f_min;
    w.f_max = o.f_max;
    const WelchFrf p = estimate_welch_frf(r, u, y, w);
    report.method = "welch";
    report.plant = p.plant;
    report.plant_direct = p.plant_direct;
    report.output_from_reference = p.output_from_reference;
    report.input_from_reference = p.input_from_reference;
    report.blocks = p.segments;
    welch_coherence = p.output_coherence;
    coherence = &welch_coherence;
  }
  report.frequency_hz = report.plant.frequency_hz;
  fill_pairs(report, coherence, o.confidence);

  if (e.controller) {
    const LoopSignalNames signals{e.y_names, e.u_names, e.r_names};
    try {
      report.sensitivity = input_sensitivity_from_reference(report.input_from_reference, *e.controller, signals);
      report.sensitivity_peaks = sensitivity_peaks(*report.sensitivity, e.u_names, o.iso);
      report.sensitivity_peaks.push_back(max_singular_sensitivity_peak(*report.sensitivity, "sigma_max", o.iso));
    } catch (const Error& err) {
      report.notes.push_back(std::string("sensitivity: ") + err.what());
    }
    try {
      report.controller_check = check_controller(report.plant, report.output_from_reference, *e.controller, signals);
    } catch (const Error& err) {
      report.notes.push_back(std::string("controller check (seed 003 eq. 5): ") + err.what());
    }
  } else {
    report.notes.push_back("no controller recorded: no sensitivity and no controller check");
  }
  if (o.fit) fit_pairs(report, e, o);
  return report;
}

}  // namespace ambid::ident
