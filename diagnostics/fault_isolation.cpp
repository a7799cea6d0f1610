#include "diagnostics/fault_isolation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

constexpr std::string_view kFaults[] = {
    "coil_resistance", "amplifier_gain", "amplifier_bandwidth", "eddy_current",
    "sensor_delay",    "sensor_gain",    "flexible_mode",       "magnetic_saturation",
    "air_gap",         "rotor_mass",     "harmonic_disturbance", "force_factor"};

struct Role {
  std::string_view parameter;
  ParameterRole role;
};

const Role kRoles[] = {
    {"R1", {"coil_resistance", 1, "coil 1 resistance"}},
    {"R2", {"coil_resistance", 2, "coil 2 resistance"}},
    {"kw1", {"amplifier_gain", 1, "amplifier 1 gain"}},
    {"kw2", {"amplifier_gain", 2, "amplifier 2 gain"}},
    {"kr1", {"force_factor", 1, "coil 1 force factor"}},
    {"kr2", {"force_factor", 2, "coil 2 force factor"}},
    {"ks", {"air_gap", std::nullopt, "negative stiffness"}},
};

struct Signature {
  std::string_view fault;
  std::string_view subject;
  std::vector<std::pair<std::string_view, double>> ratios;
};

const std::vector<Signature>& signatures() {
  static const std::vector<Signature> table = {
      {"coil_resistance", "resistance of both coils (R1, R2 alike)", {{"R1", 1.0}, {"R2", 1.0}}},
      {"amplifier_gain", "gain of both amplifiers (kw1, kw2 alike)", {{"kw1", 1.0}, {"kw2", 1.0}}},
      {"sensor_gain", "position sensor gain (kr1, kr2 alike)", {{"kr1", 1.0}, {"kr2", 1.0}}},
      {"rotor_mass", "rotor mass (ks, kr1, kr2 alike)", {{"ks", 1.0}, {"kr1", 1.0}, {"kr2", 1.0}}},
      {"air_gap", "air gap (ks : kr1 : kr2 = 1.5 : 1 : 1)", {{"ks", 1.5}, {"kr1", 1.0}, {"kr2", 1.0}}},
  };
  return table;
}

// How badly the deviations fit the signature: <= 1 fits; infinity when a parameter of the
// signature did not move (is not among the remaining deviations).
double misfit(const Signature& sig, const std::vector<Deviation>& moved,
              const std::vector<bool>& assigned, const IsolationConfig& config) {
  std::vector<const Deviation*> devs;
  for (const auto& [parameter, ratio] : sig.ratios) {
    const auto it = std::find_if(moved.begin(), moved.end(),
                                 [&](const Deviation& d) { return d.parameter == parameter; });
    if (it == moved.end() || assigned[static_cast<std::size_t>(it - moved.begin())])
      return std::numeric_limits<double>::infinity();
    devs.push_back(&*it);
  }
  double sd = 0.0, ss = 0.0;
  for (std::size_t i = 0; i < devs.size(); ++i) {
    sd += sig.ratios[i].second * devs[i]->relative;
    ss += sig.ratios[i].second * sig.ratios[i].second;
  }
  const double scale = sd / ss;
  double worst = 0.0;
  for (std::size_t i = 0; i < devs.size(); ++i) {
    const double expected = scale * sig.ratios[i].second;
    const double allowed = config.tolerance * std::abs(expected) + config.sigma_slack * devs[i]->relative_sigma;
    const double residual = std::abs(devs[i]->relative - expected);
    worst = std::max(worst, allowed > 0.0 ? residual / allowed : std::numeric_limits<double>::infinity());
  }
  return worst;
}

}  // namespace

bool is_known_fault(std::string_view fault) {
  return std::find(std::begin(kFaults), std::end(kFaults), fault) != std::end(kFaults);
}

ParameterRole parameter_role(std::string_view parameter) {
  for (const Role& r : kRoles)
    if (r.parameter == parameter) return r.role;
  throw Error("diagnostics: parameter '" + std::string(parameter) +
              "' is not monitored (monitored: R1, R2, kw1, kw2, kr1, kr2, ks)");
}

void IsolationConfig::validate() const {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw Error("fault isolation: tolerance must be non-negative and finite, got " + std::to_string(tolerance));
  if (!(sigma_slack >= 0.0) || !std::isfinite(sigma_slack))
    throw Error("fault isolation: sigma_slack must be non-negative and finite, got " +
                std::to_string(sigma_slack));
}

std::vector<Isolation> isolate(const std::vector<Deviation>& moved, const IsolationConfig& config) {
  config.validate();
  std::set<std::string_view> seen;
  for (const Deviation& d : moved) {
    parameter_role(d.parameter);
    if (!seen.insert(d.parameter).second)
      throw Error("fault isolation: parameter " + d.parameter + " given twice");
    if (!std::isfinite(d.relative) || !(d.relative_sigma >= 0.0) || !std::isfinite(d.relative_sigma))
      throw Error("fault isolation: deviation of " + d.parameter + " is not finite or has a negative sigma (" +
                  std::to_string(d.relative) + " +- " + std::to_string(d.relative_sigma) + ")");
  }

  std::vector<Isolation> result(moved.size());
  std::vector<bool> assigned(moved.size(), false);
  for (;;) {  // the largest, then best-fitting, signature among the parameters not yet named
    const Signature* best = nullptr;
    double best_misfit = std::numeric_limits<double>::infinity();
    for (const Signature& sig : signatures()) {
      const double m = misfit(sig, moved, assigned, config);
      if (m > 1.0) continue;
      if (!best || sig.ratios.size() > best->ratios.size() ||
          (sig.ratios.size() == best->ratios.size() && m < best_misfit)) {
        best = &sig;
        best_misfit = m;
      }
    }
    if (!best) break;
    for (const auto& [parameter, ratio] : best->ratios) {
      for (std::size_t i = 0; i < moved.size(); ++i) {
        if (moved[i].parameter != parameter) continue;
        result[i] = {moved[i].parameter, std::string(best->fault), std::nullopt, std::string(best->subject), true};
        assigned[i] = true;
      }
    }
  }
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (assigned[i]) continue;
    const ParameterRole role = parameter_role(moved[i].parameter);
    result[i] = {moved[i].parameter, std::string(role.fault), role.channel, std::string(role.subject), false};
  }
  return result;
}

}  // namespace ambid::diag
