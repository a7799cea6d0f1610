#include "services/daemons/alert_message.hpp"

#include <algorithm>

#include "diagnostics/fault_isolation.hpp"

namespace ambid::daemons {

bus::Alert to_message(const diag::Alert& a) {
  bus::Alert m;
  m.plant_id = a.plant_id;
  m.fault = a.fault;
  m.channel = a.channel.value_or(0);
  m.time = a.time;
  m.level = static_cast<bus::AlertLevel>(a.level);
  m.parameter = a.parameter;
  m.value = a.value;
  m.baseline = a.baseline.value_or(0.0);
  m.message = a.message.substr(0, bus::limits::text_length);
  return m;
}

diag::EstimateWindow estimate_window(const bus::IdentifiedModel& model, diag::Source source) {
  const std::vector<std::string>& monitored = diag::monitored_amb1dof_parameters();
  diag::EstimateWindow w;
  w.time = model.time;
  w.plant_id = model.plant_id;
  w.source = source;
  for (const bus::Estimate& e : model.physical)
    if (std::find(monitored.begin(), monitored.end(), e.name) != monitored.end())
      w.estimates.push_back({e.name, e.value, e.sigma});
  return w;
}

diag::Source to_source(bus::SourceKind kind) {
  switch (kind) {
    case bus::SourceKind::replay:
      return diag::Source::replay;
    case bus::SourceKind::rig:
      return diag::Source::rig;
    case bus::SourceKind::sim:
      break;
  }
  return diag::Source::sim;
}

std::string_view level_name(bus::AlertLevel level) { return diag::to_string(static_cast<diag::Level>(level)); }

}  // namespace ambid::daemons
