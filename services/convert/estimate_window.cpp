#include "services/convert/estimate_window.hpp"

#include <algorithm>
#include <vector>

#include "diagnostics/plant_families.hpp"

namespace ambid::convert {

diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source) {
  const std::vector<std::string> monitored = diag::monitored_parameters(model.plant_model);
  diag::EstimateWindow w;
  w.time = model.time;
  w.plant_id = model.plant_id;
  w.source = source;
  for (const bus::Estimate& e : model.physical)
    if (std::find(monitored.begin(), monitored.end(), e.name) != monitored.end())
      w.estimates.push_back({e.name, e.value, e.sigma});
  return w;
}

}  // namespace ambid::convert
