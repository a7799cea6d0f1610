#include "diagnostics/fault_isolation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace {

// The effect vocabulary of experiment-format.md (maglev1coil_voltage's additions last) and
// force_factor.
constexpr std::string_view kFaults[] = {
    "coil_resistance", "amplifier_gain", "amplifier_bandwidth",  "eddy_current",
    "sensor_delay",    "sensor_gain",    "flexible_mode",        "magnetic_saturation",
    "air_gap",         "rotor_mass",     "harmonic_disturbance", "force_factor",
    "force_law",       "sensor_offset",  "sensor_nonlinearity",  "actuator_quantisation"};

// The weighted least-squares fit of some hypotheses to the deviations.
struct Fit {
  std::vector<std::size_t> hypotheses;
  Eigen::VectorXd scale;      // per hypothesis: its relative change
  Eigen::MatrixXd predicted;  // deviations x hypotheses: scale_h * signature_h,p
  Eigen::VectorXd sigma;      // per deviation, widened by the model tolerance
  Eigen::VectorXd residual;   // per deviation, in sigmas
  double rss = std::numeric_limits<double>::infinity();
  bool valid = false;
};

Fit fit(const std::vector<Deviation>& d, const std::vector<FaultHypothesis>& hyp, std::vector<std::size_t> chosen,
        const IsolationConfig& config) {
  const auto n = static_cast<Eigen::Index>(d.size()), k = static_cast<Eigen::Index>(chosen.size());
  Eigen::MatrixXd S(n, k);
  Eigen::VectorXd y(n), base_var(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Deviation& dev = d[static_cast<std::size_t>(i)];
    y(i) = dev.relative;
    base_var(i) = dev.relative_sigma * dev.relative_sigma + config.sigma_floor * config.sigma_floor;
    for (Eigen::Index j = 0; j < k; ++j) S(i, j) = hyp[chosen[static_cast<std::size_t>(j)]].signature.at(dev.parameter);
  }
  Fit f;
  f.hypotheses = std::move(chosen);
  Eigen::VectorXd var = base_var;
  // Twice: the second pass widens each sigma by the model tolerance of its predicted change.
  for (int pass = 0; pass < 2; ++pass) {
    f.scale = Eigen::VectorXd::Zero(k);
    if (k > 0) {
      const Eigen::VectorXd w = var.cwiseSqrt().cwiseInverse();
      const linalg::RankedSolution<Eigen::VectorXd> ls =
          linalg::qr_solve(Eigen::MatrixXd(w.asDiagonal() * S), Eigen::VectorXd(w.cwiseProduct(y)));
      if (ls.rank < k) return f;  // the hypotheses are not distinguishable on these parameters
      f.scale = ls.x;
    }
    f.predicted = S * f.scale.asDiagonal();
    const Eigen::VectorXd total = f.predicted.rowwise().sum();
    var = base_var + (config.tolerance * total).cwiseAbs2();
    f.sigma = var.cwiseSqrt();
    f.residual = (y - total).cwiseQuotient(f.sigma);
  }
  f.rss = f.residual.squaredNorm();
  f.valid = true;
  return f;
}

std::size_t unexplained(const Fit& f, const std::vector<Deviation>& d, double slack) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i].moved && std::abs(f.residual(static_cast<Eigen::Index>(i))) > slack) ++count;
  return count;
}

// How well the hypotheses' own parameters agree with what moved: +1 for each that moved,
// -1 for each that did not (or is not among the deviations).
int own_agreement(const Fit& f, const std::vector<Deviation>& d, const std::vector<FaultHypothesis>& hyp) {
  int score = 0;
  for (std::size_t h : f.hypotheses)
    for (const std::string& own : hyp[h].own) {
      const auto it = std::find_if(d.begin(), d.end(), [&](const Deviation& dev) { return dev.parameter == own; });
      score += it != d.end() && it->moved ? 1 : -1;
    }
  return score;
}

}  // namespace

bool is_known_fault(std::string_view fault) {
  return std::find(std::begin(kFaults), std::end(kFaults), fault) != std::end(kFaults);
}

void IsolationConfig::validate() const {
  for (const auto& [name, value] :
       {std::pair{"tolerance", tolerance}, {"sigma_floor", sigma_floor}, {"ambiguity", ambiguity}})
    if (!(value >= 0.0) || !std::isfinite(value))
      throw Error(std::string("fault isolation: ") + name + " must be non-negative and finite, got " +
                  std::to_string(value));
  if (!(sigma_slack > 0.0) || !std::isfinite(sigma_slack))
    throw Error("fault isolation: sigma_slack must be positive and finite, got " + std::to_string(sigma_slack));
  if (max_faults < 1) throw Error("fault isolation: max_faults must be at least 1");
  for (const FaultHypothesis& h : hypotheses) {
    if (!is_known_fault(h.fault)) throw Error("fault isolation: hypothesis of unknown fault '" + h.fault + "'");
    for (const std::string& p : monitored_parameters(family)) {
      const auto it = h.signature.find(p);
      if (it == h.signature.end() || !std::isfinite(it->second))
        throw Error("fault isolation: hypothesis '" + h.subject + "' has no finite signature of " + p);
    }
  }
}

std::vector<Isolation> isolate(const std::vector<Deviation>& deviations, const IsolationConfig& config) {
  config.validate();
  std::set<std::string_view> seen;
  for (const Deviation& d : deviations) {
    parameter_role(config.family, d.parameter);
    if (!seen.insert(d.parameter).second) throw Error("fault isolation: parameter " + d.parameter + " given twice");
    if (!std::isfinite(d.relative) || !(d.relative_sigma >= 0.0) || !std::isfinite(d.relative_sigma))
      throw Error("fault isolation: deviation of " + d.parameter + " is not finite or has a negative sigma (" +
                  std::to_string(d.relative) + " +- " + std::to_string(d.relative_sigma) + ")");
  }
  const bool any_moved = std::any_of(deviations.begin(), deviations.end(), [](const Deviation& d) { return d.moved; });
  if (!any_moved) return {};
  const std::vector<FaultHypothesis>& hyp =
      config.hypotheses.empty() ? default_fault_hypotheses(config.family) : config.hypotheses;

  // Fewest faults first: every set of k hypotheses, k = 1, 2, ... max_faults, until one set
  // leaves no moved parameter unexplained.
  Fit current = fit(deviations, hyp, {}, config);
  for (std::size_t k = 1; k <= std::min(config.max_faults, hyp.size()); ++k) {
    if (unexplained(current, deviations, config.sigma_slack) == 0) break;
    std::vector<Fit> candidates;
    std::vector<std::size_t> chosen(k);
    for (std::size_t i = 0; i < k; ++i) chosen[i] = i;
    for (;;) {  // the combinations of k of the hypotheses, in lexicographic order
      Fit f = fit(deviations, hyp, chosen, config);
      if (f.valid) candidates.push_back(std::move(f));
      std::size_t i = k;
      while (i > 0 && chosen[i - 1] == hyp.size() - k + i - 1) --i;
      if (i == 0) break;
      ++chosen[i - 1];
      for (std::size_t j = i; j < k; ++j) chosen[j] = chosen[j - 1] + 1;
    }
    if (candidates.empty()) continue;
    double best_rss = std::numeric_limits<double>::infinity();
    for (const Fit& f : candidates) best_rss = std::min(best_rss, f.rss);
    const Fit* best = nullptr;
    int best_agreement = 0;
    for (const Fit& f : candidates) {
      if (f.rss > best_rss + config.ambiguity) continue;
      const int agreement = own_agreement(f, deviations, hyp);
      if (!best || agreement > best_agreement || (agreement == best_agreement && f.rss < best->rss)) {
        best = &f;
        best_agreement = agreement;
      }
    }
    // A further fault only when it explains more of what moved.
    if (unexplained(*best, deviations, config.sigma_slack) < unexplained(current, deviations, config.sigma_slack))
      current = *best;
  }

  std::vector<Isolation> result;
  for (std::size_t i = 0; i < deviations.size(); ++i) {
    const Deviation& d = deviations[i];
    if (!d.moved) continue;
    const auto row = static_cast<Eigen::Index>(i);
    // The hypothesis predicting most of this parameter's change, if more than one sigma of it.
    std::optional<std::size_t> named;
    double largest = 1.0;
    if (std::abs(current.residual(row)) <= config.sigma_slack) {
      for (Eigen::Index j = 0; j < current.predicted.cols(); ++j) {
        const double share = std::abs(current.predicted(row, j)) / current.sigma(row);
        if (share > largest) {
          largest = share;
          named = current.hypotheses[static_cast<std::size_t>(j)];
        }
      }
    }
    if (!named) {
      const ParameterRole role = parameter_role(config.family, d.parameter);
      result.push_back({d.parameter, std::string(role.fault), role.channel, std::string(role.subject), false});
      continue;
    }
    const FaultHypothesis& h = hyp[*named];
    // The hypothesis is this parameter's own fault under its own name: the alert needs no more.
    const bool own = h.own.size() == 1 && h.own.front() == d.parameter &&
                     h.subject == parameter_role(config.family, d.parameter).subject;
    result.push_back({d.parameter, h.fault, h.channel, h.subject, !own});
  }
  return result;
}

}  // namespace ambid::diag
