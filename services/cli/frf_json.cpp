// frf.json of `ambid frf`.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "services/cli/frf_output.hpp"

namespace ambid::cli {
namespace {

using nlohmann::json;

json list(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

json complex_pairs(const Eigen::VectorXcd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back({v(i).real(), v(i).imag()});
  return out;
}

json plant_json(const ident::PlantPair& pair, double confidence) {
  json p = {
      {"output", pair.output}, {"input", pair.input}, {"re", list(pair.value.real())}, {"im", list(pair.value.imag())}};
  if (pair.variance.size() > 0) p["noise_std"] = list(pair.variance.cwiseSqrt());
  if (pair.bound.size() > 0) {
    p["bound"] = list(pair.bound);
    p["bound_confidence"] = confidence;
  }
  if (pair.coherence.size() > 0) p["coherence"] = list(pair.coherence);
  return p;
}

// parameters, derived (each value and sigma), misfit, converged.
json structure_json(const ident::StructuredFrfFit& f) {
  json parameters = json::object(), derived = json::object();
  for (std::size_t k = 0; k < f.parameter_names.size(); ++k)
    parameters[f.parameter_names[k]] = {{"value", f.value(Eigen::Index(k))}, {"sigma", f.sigma(Eigen::Index(k))}};
  for (std::size_t k = 0; k < f.derived_names.size(); ++k)
    derived[f.derived_names[k]] = {{"value", f.derived_value(Eigen::Index(k))},
                                   {"sigma", f.derived_sigma(Eigen::Index(k))}};
  return {{"parameters", parameters}, {"derived", derived}, {"misfit", f.misfit}, {"converged", f.converged}};
}

// One settled level: its means, spans [first sample, samples], Welch segments, and its fit (or
// why there is none).
json level_json(const ident::LevelStructuredFit& l) {
  json spans = json::array();
  for (const ident::SettledSpan& s : l.spans) spans.push_back({s.first, s.samples});
  json out = l.fit ? structure_json(*l.fit) : json::object();
  out["operating_point"] = l.operating_point;
  out["spans"] = spans;
  out["samples"] = l.samples;
  out["segment_samples"] = l.segment_samples;
  out["segments"] = l.segments;
  if (!l.note.empty()) out["note"] = l.note;
  return out;
}

json model_json(const ident::FittedPair& fitted, double top_hz) {
  const ident::RationalModel& m = fitted.fit.model;
  const Eigen::VectorXcd poles = m.poles();
  json unstable = json::array();
  json unresolved = json::array();
  for (Eigen::Index i = 0; i < poles.size(); ++i) {
    if (poles(i).real() <= 0.0) continue;
    (pole_in_band(poles(i), top_hz) ? unstable : unresolved).push_back({poles(i).real(), poles(i).imag()});
  }
  return {{"output", fitted.output},
          {"input", fitted.input},
          {"numerator_degree", m.numerator_degree()},
          {"denominator_degree", m.denominator_degree()},
          {"poles", complex_pairs(poles)},
          {"pole_std", list(fitted.fit.pole_std)},
          {"unstable_poles", unstable},                // within the fitted band
          {"unstable_poles_beyond_band", unresolved},  // not resolved by the data
          {"zeros", complex_pairs(m.zeros())},
          {"gain", m.gain()},
          {"weighting", ident::to_string(fitted.fit.weighting)},
          {"misfit", fitted.fit.misfit},
          {"lines", fitted.fit.lines}};
}

// What the periodic analysis detected and used; lines as DFT indices of one period and in Hz.
json periodic_json(const ident::PeriodicExcitation& p, const std::vector<std::string>& references) {
  const double df = 1.0 / p.period_s;
  json lines = json::object();
  for (std::size_t c = 0; c < p.lines.size() && c < references.size(); ++c) {
    json hz = json::array();
    for (const Eigen::Index k : p.lines[c]) hz.push_back(static_cast<double>(k) * df);
    lines[references[c]] = {{"count", p.lines[c].size()}, {"dft_lines", p.lines[c]}, {"frequency_hz", hz}};
  }
  return {{"source", p.source},
          {"estimator", p.estimator},
          {"period_samples", p.period_samples},
          {"period_s", p.period_s},
          {"line_spacing_hz", df},
          {"first_sample", p.first_sample},
          {"whole_periods", p.whole_periods},
          {"transient_periods", p.transient_periods},
          {"periods_per_block", p.periods_per_block},
          {"periods_used", p.periods_used},
          {"lines_per_reference", lines}};
}

}  // namespace

nlohmann::json frf_json(const ident::FrfReport& report, const Experiment& experiment,
                        const std::string& experiment_path, const ident::FrfAnalysisOptions& options) {
  json out = {{"format", "ambid-frf/1"},
              {"experiment", experiment_path},
              {"name", experiment.name},
              {"method", report.method},
              {"excitation", report.excitation},
              {"blocks", report.blocks},
              {"sample_time", experiment.sample_time},
              {"convention", "G(jw) from u to y deviations (SI units); u = K y + r; lag = negative phase"},
              {"frequency_hz", list(report.frequency_hz)}};
  if (report.periodic) out["periodic"] = periodic_json(*report.periodic, report.reference_names);
  out["clamped_samples"] = {{"count", report.clamped_samples},
                            {"blocks_left_out", report.blocks_left_out},
                            {"rule",
                             "no period (and not the one after it), Welch segment or stepped-sine window "
                             "holding a sample where a controller clamp acted is averaged"}};
  json plant = json::object();
  for (const ident::PlantPair& pair : report.pairs) plant[pair.name] = plant_json(pair, options.confidence);
  out["plant"] = plant;
  json direct = json::object();
  for (std::size_t i = 0; i < report.pairs.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i / report.input_names.size());
    const auto c = static_cast<Eigen::Index>(i % report.input_names.size());
    const Eigen::VectorXcd v = report.plant_direct.element(r, c);
    direct[report.pairs[i].name] = {{"re", list(v.real())}, {"im", list(v.imag())}};
  }
  out["plant_direct"] = direct;  // the open-loop formula S_yu S_uu^-1: biased under feedback
  json sensitivity = json::object();
  for (const ident::SensitivityPeak& peak : report.sensitivity_peaks) {
    sensitivity[peak.loop] = {{"peak_db", peak.magnitude_db},
                              {"peak_hz", peak.frequency_hz},
                              {"peak_magnitude", peak.magnitude},
                              {"zone", ident::to_string(peak.zone)}};
  }
  out["sensitivity"] = sensitivity;
  out["iso_14839_limits_db"] = {{"A/B", options.iso.ab_db}, {"B/C", options.iso.bc_db}, {"C/D", options.iso.cd_db}};
  json models = json::object();
  for (const ident::FittedPair& fitted : report.fits)
    models[fitted.name] = model_json(fitted, fit_band_top_hz(experiment, options));
  out["model"] = models;
  if (report.structured || report.levels) {  // the plant family's structure (identifier/frf_analysis.hpp)
    json structure = report.structured ? structure_json(*report.structured) : json::object();
    structure["family"] = experiment.plant.model;
    if (report.levels) {
      const ident::LevelStructuredAnalysis& a = *report.levels;
      json levels = json::array();
      for (const ident::LevelStructuredFit& l : a.levels) levels.push_back(level_json(l));
      structure["level_signal"] = a.level_signal;
      structure["levels"] = levels;
      structure["operating_point"] = experiment.operating_point;
      if (a.at_operating_point) structure["level_at_operating_point"] = *a.at_operating_point;
      if (a.pooled) {
        json derived = json::object();
        for (std::size_t k = 0; k < a.pooled->derived_names.size(); ++k) {
          const auto K = Eigen::Index(k);
          derived[a.pooled->derived_names[k]] = {{"value", a.pooled->derived_value(K)},
                                                 {"sigma", a.pooled->derived_sigma(K)},
                                                 {"birge_ratio", a.pooled->birge_ratio(K)}};
        }
        structure["pooled_at_operating_point"] = {{"derived", derived}, {"levels", a.pooled->levels}};
      }
      if (!a.pooled_note.empty()) structure["pooled_note"] = a.pooled_note;
    }
    out["structure"] = structure;
  }
  out["model_band_hz"] = {report.frequency_hz.size() ? report.frequency_hz(0) : 0.0,
                          fit_band_top_hz(experiment, options)};
  if (report.controller_check && report.controller_check->relative_error.size() > 0) {
    Eigen::VectorXd e = report.controller_check->relative_error;
    std::sort(e.data(), e.data() + e.size());
    out["controller_check"] = {{"median_relative_error", e(e.size() / 2)}, {"max_relative_error", e(e.size() - 1)}};
  }
  out["notes"] = report.notes;
  out["warnings"] = report.warnings;
  return out;
}

bool pole_in_band(std::complex<double> pole, double top_hz) {
  return std::abs(pole) <= 2.0 * std::numbers::pi * top_hz;
}

double fit_band_top_hz(const Experiment& experiment, const ident::FrfAnalysisOptions& options) {
  return options.fit_f_max > 0.0 ? options.fit_f_max : 0.1 / experiment.sample_time;
}

}  // namespace ambid::cli
