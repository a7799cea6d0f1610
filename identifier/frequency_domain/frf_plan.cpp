#include "identifier/frequency_domain/frf_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace ambid::ident {
namespace {

std::string text(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

double number(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

bool in_band(Eigen::Index k, Eigen::Index N, double T, const FrfAnalysisOptions& o) {
  const double f = static_cast<double>(k) / (static_cast<double>(N) * T);
  return f >= o.f_min && (o.f_max <= 0.0 || f <= o.f_max);
}

std::vector<Eigen::Index> band_lines(const std::vector<Eigen::Index>& lines, Eigen::Index N, double T,
                                     const FrfAnalysisOptions& o) {
  std::vector<Eigen::Index> out;
  for (const Eigen::Index k : lines)
    if (in_band(k, N, T, o)) out.push_back(k);
  return out;
}

std::string samples_text(Eigen::Index n, double T) {
  return std::to_string(n) + " samples (" + std::to_string(static_cast<double>(n) * T) + " s)";
}

// The period the description claims, in samples (times the Hadamard order for the orthogonal
// pattern, whose references repeat only after a whole block), and the whole periods it claims
// within the record; 0 when it claims none.
struct Claim {
  Eigen::Index repeat = 0, period = 0, periods = 0, block = 1;
};
Claim claimed_period(const Experiment& e, const nlohmann::json& d) {
  const double N_value = number(d, "period_samples", 0.0);
  const auto N = static_cast<Eigen::Index>(std::llround(N_value));
  if (N < 1 || N_value != static_cast<double>(N)) return {};
  Claim c;
  c.period = N;
  c.periods =
      std::min<Eigen::Index>(e.samples() / N, static_cast<Eigen::Index>(std::floor(number(d, "periods", 0.0) + 1e-9)));
  const auto h = d.find("hadamard");
  if (text(d, "channel_pattern") == "hadamard" && h != d.end() && h->is_array())
    c.block = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(h->size()));
  c.repeat = N * c.block;
  return c;
}

// Whether the recorded r contradicts the description: it claims a periodic excitation that r
// does not repeat with over the claimed whole periods, or a non-periodic one where r repeats.
std::optional<std::string> contradiction(const Experiment& e, const Eigen::MatrixXd& r, const nlohmann::json& d,
                                         const Periodicity& detected, const FrfAnalysisOptions& o) {
  const std::string kind = text(d, "kind");
  const Claim c = claimed_period(e, d);
  const bool periodic_kind = kind == "multisine" || (kind == "prbs" && number(d, "periods", 0.0) >= 2.0);
  if (periodic_kind && c.periods >= 1 &&
      !repeats_with_shift(r, 0, std::min(r.rows(), c.periods * c.period), c.repeat, o.periodicity.tolerance))
    return "the sidecar describes a " + kind + " repeating every " + samples_text(c.repeat, e.sample_time) +
           " but the recorded r does not repeat with that shift" +
           (detected.periodic() ? " (it repeats every " + samples_text(detected.period_samples, e.sample_time) + ")"
                                : std::string(" (it does not repeat at all)")) +
           "; the description is ignored";
  if (!periodic_kind && !kind.empty() && kind != "stepped_sine" && detected.periodic())
    return "the sidecar describes a non-periodic " + kind + " excitation but the recorded r repeats every " +
           samples_text(detected.period_samples, e.sample_time) + "; the description is ignored";
  return std::nullopt;
}

Eigen::Index transient_periods(const FrfAnalysisOptions& o, Eigen::Index periods, Eigen::Index block,
                               std::vector<std::string>& notes) {
  if (o.transient_periods >= 0) return o.transient_periods;
  if (periods - 1 >= block) return 1;
  notes.push_back("periodic analysis: too few periods to discard one as transient; the first period is used");
  return 0;
}

// `ambid sim`'s multisine as described (its lines and Hadamard blocks), or nullopt with a note
// when the description cannot be used as it is.
std::optional<PeriodicPlan> from_description(const Experiment& e, const nlohmann::json& d, const FrfAnalysisOptions& o,
                                             std::vector<std::string>& notes) {
  const Claim c = claimed_period(e, d);
  const auto nr = static_cast<Eigen::Index>(e.r_names.size());
  if (c.period < 4) return std::nullopt;
  const auto lines = d.find("lines");
  if (lines == d.end() || !lines->is_array()) {
    notes.push_back("excitation description: a multisine without lines; the lines of r are used");
    return std::nullopt;
  }
  if (nr > c.block) {
    notes.push_back("excitation description: " + std::to_string(nr) +
                    " references without an orthogonal pattern; the lines of r are used");
    return std::nullopt;
  }
  PeriodicPlan p;
  PeriodicFrfOptions& q = p.options;
  q.sample_time = e.sample_time;
  q.period_samples = c.period;
  q.periods_per_block = c.block;
  for (const auto& k : *lines)
    if (k.is_number_integer() && in_band(k.get<Eigen::Index>(), c.period, e.sample_time, o))
      q.lines.push_back(k.get<Eigen::Index>());
  std::sort(q.lines.begin(), q.lines.end());
  q.lines.erase(std::unique(q.lines.begin(), q.lines.end()), q.lines.end());
  if (q.lines.empty()) {
    notes.push_back("excitation description: no described line in the requested band");
    return std::nullopt;
  }
  q.transient_periods = transient_periods(o, c.periods, c.block, notes);
  p.end_sample = c.periods * c.period;
  p.summary = {"sidecar",
               c.block > 1 ? "local polynomial" : "exact lines",
               c.period,
               static_cast<double>(c.period) * e.sample_time,
               0,
               c.periods,
               q.transient_periods,
               c.block,
               0,
               std::vector<std::vector<Eigen::Index>>(static_cast<std::size_t>(nr), q.lines)};
  return p;
}

// The periodic analysis of what r shows.
std::optional<PeriodicPlan> from_record(const Experiment& e, const Periodicity& detected, const FrfAnalysisOptions& o,
                                        std::vector<std::string>& notes) {
  const Eigen::Index N = detected.period_samples;
  const double T = e.sample_time;
  PeriodicPlan p;
  PeriodicFrfOptions& q = p.options;
  q.sample_time = T;
  q.period_samples = N;
  q.first_sample = detected.first_sample;
  q.lines = band_lines(detected.all_lines, N, T, o);
  if (q.lines.empty()) {
    notes.push_back("r repeats every " + samples_text(N, T) +
                    " but excites no line in the requested band; Welch analysis instead");
    return std::nullopt;
  }
  const bool several = e.r_names.size() > 1;
  q.transient_model =
      several ? PeriodicFrfOptions::TransientModel::local_polynomial : PeriodicFrfOptions::TransientModel::none;
  q.transient_periods = transient_periods(o, detected.periods, 1, notes);
  if (several) {
    // Steady state after the discarded period: no transient terms; a local rational model of
    // degree 4 over 2 on 13 lines, of the period-mean outputs on the period-mean inputs (G is
    // smooth where the closed loop is not). On amb1dof_voltage with a zippered 5 Hz grid
    // (noise-free) the worst relative error of G below 1 kHz is 6.5e-3; the default polynomial
    // with transient terms on T_yr, T_ur: 1.6 (below 50 Hz, where the loop makes T_ur
    // ill-conditioned), 3.9e-2 above.
    q.local_polynomial.transient = false;
    q.local_polynomial.half_width = 6;
    q.local_polynomial.denominator_degree = 2;
    q.plant_from_period_means = true;
    notes.push_back(
        "periodic analysis: the references excite different lines, so the plant at each line is interpolated "
        "from neighbouring lines (local rational model of the period-mean outputs on the inputs)");
  }
  p.end_sample = detected.first_sample + detected.periods * N;
  p.summary = {"r",
               several ? "local rational" : "exact lines",
               N,
               static_cast<double>(N) * T,
               detected.first_sample,
               detected.periods,
               q.transient_periods,
               1,
               0,
               {}};
  for (const auto& channel : detected.lines) p.summary.lines.push_back(band_lines(channel, N, T, o));
  return p;
}

}  // namespace

const nlohmann::json* excitation_description(const Experiment& e) {
  const nlohmann::json& extra = e.extra.json();
  if (!extra.is_object()) return nullptr;
  const auto it = extra.find("excitation");
  if (it == extra.end() || !it->is_object()) return nullptr;
  return &*it;
}

std::string excitation_kind(const nlohmann::json* d) {
  const std::string kind = d ? text(*d, "kind") : std::string();
  return kind.empty() ? "unknown" : kind;
}

std::optional<PeriodicPlan> plan_periodic(const Experiment& e, const Periodicity& detected, const nlohmann::json* d,
                                          const FrfAnalysisOptions& o, std::vector<std::string>& notes,
                                          std::vector<std::string>& warnings) {
  if (d) {
    const Eigen::MatrixXd r = e.r_deviation();
    if (const auto why = contradiction(e, r, *d, detected, o)) {
      warnings.push_back(*why);
    } else if (text(*d, "kind") == "multisine") {
      if (auto p = from_description(e, *d, o, notes)) return p;
    }
  }
  if (detected.periodic()) return from_record(e, detected, o, notes);
  if (excitation_kind(d) != "stepped_sine")
    notes.push_back("the recorded r does not repeat within the record (relative tolerance " +
                    std::to_string(o.periodicity.tolerance) + "); Welch analysis");
  return std::nullopt;
}

std::optional<SteppedSineFrfOptions> plan_stepped_sine(const Experiment& e, const nlohmann::json* description,
                                                       const FrfAnalysisOptions& o, std::vector<std::string>& notes) {
  if (!description || text(*description, "kind") != "stepped_sine") return std::nullopt;
  const nlohmann::json& d = *description;
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

}  // namespace ambid::ident
