#include "diagnostics/audit/maglev_starts.hpp"

#include "core/error.hpp"
#include "identifier/families/maglev_greybox.hpp"
#include "plant_sim/maglev_effects.hpp"

namespace ambid::diag {

std::vector<sim::Effect> maglev_audit_starts(const Experiment& measured) {
  ident::MaglevGreyBoxFit fit;
  try {
    ident::MaglevGreyBoxInput in;
    in.sample_time = measured.sample_time;
    in.x = measured.signal("x");
    in.i = measured.signal("i");
    in.u = measured.signal("u");
    in.x0 = measured.operating_value("x");
    in.i0 = measured.operating_value("i");
    in.nominal = measured.plant.parameters;
    fit = ident::fit_maglev_greybox(in);
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
      {{"dn_i", fit.value.at("n_i") - nominal.at("n_i")}, {"dn_x", fit.value.at("n_x") - nominal.at("n_x")}});
  add("coil_resistance", {{"dR", fit.value.at("R") - nominal.at("R")}});
  return starts;
}

}  // namespace ambid::diag
