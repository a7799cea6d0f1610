#include "diagnostics/audit/maglev_starts.hpp"

#include "core/error.hpp"
#include "core/model_file.hpp"
#include "identifier/identify_experiment.hpp"
#include "identifier/plant_families.hpp"
#include "plant_sim/maglev_effects.hpp"

namespace ambid::diag {

std::vector<sim::Effect> maglev_audit_starts(const Experiment& measured) {
  Model fit;
  try {
    const ident::IdentificationFamily* family = ident::find_identification_family(measured.plant.model);
    if (!family || !family->greybox) return {};
    family->greybox(measured, ident::IdentifyOptions{}, fit);
  } catch (const Error&) {
    return {};  // InsufficientData included: the catalogue's own starts remain
  }
  const auto& nominal = measured.plant.parameters;
  std::vector<sim::Effect> starts;
  const auto add = [&](const char* effect, const std::map<std::string, double>& values) {
    try {
      starts.push_back(sim::make_effect(sim::maglev_effect_catalogue(), effect, values));
    } catch (const Error&) {
      // outside the catalogue's physical range: not a start
    }
  };
  add("force_law",
      {{"dn_i", fit.physical.at("n_i") - nominal.at("n_i")}, {"dn_x", fit.physical.at("n_x") - nominal.at("n_x")}});
  add("coil_resistance", {{"dR", fit.physical.at("R") - nominal.at("R")}});
  return starts;
}

}  // namespace ambid::diag
