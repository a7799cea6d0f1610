#include "diagnostics/audit/maglev_starts.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/model_file.hpp"
#include "diagnostics/audit/audit_quantisation.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/plant_families.hpp"
#include "plant_sim/maglev_effects.hpp"

namespace ambid::diag {

namespace {

// Index of signal `name` in `names`, or -1.
Eigen::Index signal(const std::vector<std::string>& names, const char* name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : Eigen::Index(it - names.begin());
}

}  // namespace

std::vector<sim::Effect> maglev_audit_starts(const Experiment& measured) {
  std::vector<sim::Effect> starts;
  const auto& catalogue = sim::maglev_effect_catalogue();
  const auto add = [&](const char* effect, const std::map<std::string, double>& values) {
    try {
      starts.push_back(sim::make_effect(catalogue, effect, values));
    } catch (const Error&) {
      // outside the catalogue's physical range: not a start
    }
  };
  // A reading late by whole samples.
  for (const double samples : {1.0, 2.0}) add("sensor_delay", {{"delay", samples * measured.sample_time}});
  // The DAC's step as the current reads it, over the catalogue's range.
  const Eigen::Index u = signal(measured.u_names, "u"), i = signal(measured.y_names, "i");
  const auto& step = sim::effect_spec(catalogue, "actuator_quantisation").parameters.front();
  if (u >= 0 && i >= 0 && measured.samples() >= 10)
    add("actuator_quantisation",
        {{"step", screen_dac_step(measured.u.col(u), measured.y.col(i), 0.01 * step.upper, step.upper).step}});

  Model fit;
  try {
    const ident::IdentificationFamily* family = ident::find_identification_family(measured.plant.model);
    if (!family || !family->greybox) return starts;
    family->greybox(measured, ident::IdentifyOptions{}, fit);
  } catch (const Error&) {
    return starts;  // InsufficientData included: the catalogue's own starts remain
  }
  const auto& nominal = measured.plant.parameters;
  add("force_law",
      {{"dn_i", fit.physical.at("n_i") - nominal.at("n_i")}, {"dn_x", fit.physical.at("n_x") - nominal.at("n_x")}});
  add("coil_resistance", {{"dR", fit.physical.at("R") - nominal.at("R")}});
  // The grey-box fit holds kw: an amplifier's gain reads as the resistance with the same
  // steady current, kw / R = kw' / R_nominal; the validation then tells the two by the coil's
  // pole R / L, which only the resistance moves.
  add("amplifier_gain", {{"dkw", nominal.at("kw") * (nominal.at("R") / fit.physical.at("R") - 1.0)}});
  // Read in the sensor's distance, the mechanics linearised at the measured point are
  // y'' = (n_x g / gap0) dy - s (n_i g / i0) di with gap0 = (x0 - offset) / s: an offset reads
  // as the gap exponent n_x x0 / (x0 - offset), a scale s as both exponents times s. The
  // replay's cost is rough in these (the followed rounding): from the catalogue's sizes their
  // fits stopped near where they started (0.2 mm for a 0.3 mm offset).
  const double x0 = measured.operating_value("x");
  add("sensor_offset", {{"dy", x0 * (1.0 - nominal.at("n_x") / fit.physical.at("n_x"))}});
  add("sensor_gain", {{"dgain", fit.physical.at("n_i") / nominal.at("n_i") - 1.0}});
  return starts;
}

}  // namespace ambid::diag
