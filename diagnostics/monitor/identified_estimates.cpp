#include "diagnostics/identified_estimates.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {

EstimateWindow estimate_window(const std::string& family, const std::map<std::string, double>& physical,
                               const std::map<std::string, double>& uncertainty, double time,
                               const std::string& plant_id, Source source) {
  const std::vector<std::string> names = monitored_parameters(family);
  std::map<std::string, double> monitored;
  for (const std::string& name : names) {
    const auto value = physical.find(name);
    if (value == physical.end()) throw Error("estimate window: no physical value of " + name);
    monitored.emplace(name, value->second);
  }
  const std::vector<ident::Estimate> estimates = ident::with_uncertainty(monitored, uncertainty, "estimate window");
  EstimateWindow w;
  w.time = time;
  w.plant_id = plant_id;
  w.source = source;
  for (const std::string& name : names) {  // in the monitored order
    const auto e = std::find_if(estimates.begin(), estimates.end(), [&](const auto& x) { return x.name == name; });
    w.estimates.push_back({name, e->value, e->sigma});
  }
  w.validate();
  return w;
}

EstimateWindow estimate_window(const ident::WindowIdentification& identification, double time,
                               const std::string& plant_id, Source source) {
  return estimate_window(identification.model.plant_model, identification.model.physical,
                         identification.model.uncertainty, time, plant_id, source);
}

}  // namespace ambid::diag
