#include "diagnostics/identified_estimates.hpp"

#include "core/error.hpp"

namespace ambid::diag {

const std::vector<std::string>& monitored_amb1dof_parameters() {
  static const std::vector<std::string> names = {"R1", "R2", "kw1", "kw2", "kr1", "kr2", "ks"};
  return names;
}

EstimateWindow estimate_window(const std::map<std::string, double>& physical,
                               const std::map<std::string, double>& uncertainty, double time,
                               const std::string& plant_id, Source source) {
  EstimateWindow w;
  w.time = time;
  w.plant_id = plant_id;
  w.source = source;
  for (const std::string& name : monitored_amb1dof_parameters()) {
    const auto value = physical.find(name);
    if (value == physical.end()) throw Error("estimate window: no physical value of " + name);
    if (uncertainty.empty()) {  // a method without sigmas: the baseline's scatter is the whole sigma_eff
      w.estimates.push_back({name, value->second, 0.0});
      continue;
    }
    const auto sigma = uncertainty.find(name);
    if (sigma == uncertainty.end()) throw Error("estimate window: no uncertainty of " + name);
    w.estimates.push_back({name, value->second, sigma->second});
  }
  w.validate();
  return w;
}

EstimateWindow estimate_window(const ident::Amb1dofIdentification& identification, double time,
                               const std::string& plant_id, Source source) {
  return estimate_window(identification.physical, identification.physical_uncertainty, time, plant_id, source);
}

}  // namespace ambid::diag
