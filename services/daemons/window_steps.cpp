#include "services/daemons/window_steps.hpp"

#include "core/error.hpp"

namespace ambid::daemons {

WindowSteps::WindowSteps(DaemonRuntime& runtime, const std::string& help)
    : runtime_(runtime),
      rejected_(runtime.metrics.counter("ambid_samples_dropped_total", help, {{"reason", "rejected"}})),
      gap_(runtime.metrics.counter("ambid_samples_dropped_total", help, {{"reason", "gap"}})),
      record_end_(runtime.metrics.counter("ambid_samples_dropped_total", help, {{"reason", "record_end"}})),
      no_description_(runtime.metrics.counter("ambid_samples_dropped_total", help, {{"reason", "no_description"}})),
      description_change_(
          runtime.metrics.counter("ambid_samples_dropped_total", help, {{"reason", "description_change"}})) {}

void WindowSteps::report(const std::vector<DescribedWindows::Step>& steps, const std::string& plant) {
  using Event = DescribedWindows::Event;
  const std::string at = plant.empty() ? std::string{} : plant + ": ";
  for (const DescribedWindows::Step& s : steps) {
    switch (s.event) {
      case Event::added:
        break;
      case Event::waiting:
        if (!waiting_logged_) runtime_.log(at + "samples wait: " + s.reason);
        waiting_logged_ = true;
        break;
      case Event::rejected:
        runtime_.metrics.rejected.Increment();
        rejected_.Increment(double(s.samples));
        runtime_.log(at + "batch rejected: " + s.reason);
        runtime_.set_health(bus::AlertLevel::warn, at + "samples rejected: " + s.reason);
        break;
      case Event::gap:
        gap_.Increment(double(s.samples));
        if (s.samples > 0) runtime_.log(at + std::to_string(s.samples) + " samples dropped: " + s.reason);
        break;
      case Event::record_end:
        record_end_.Increment(double(s.samples));
        break;
      case Event::dropped_no_description:
        no_description_.Increment(double(s.samples));
        runtime_.log(at + std::to_string(s.samples) + " samples dropped: " + s.reason);
        runtime_.set_health(bus::AlertLevel::warn, at + "samples dropped: " + s.reason);
        break;
      case Event::description_change:
        description_change_.Increment(double(s.samples));
        waiting_logged_ = false;
        runtime_.log(at + "windows restart: " + s.reason);
        break;
    }
  }
}

void WindowSteps::describe(DescribedWindows& windows, const bus::PlantDescription& d, const std::string& plant) {
  const std::string at = plant.empty() ? std::string{} : plant + ": ";
  try {
    report(windows.describe(d), plant);
  } catch (const Error& e) {
    runtime_.metrics.rejected.Increment();
    runtime_.log(at + std::string("plant description refused: ") + e.what());
    runtime_.set_health(bus::AlertLevel::warn, at + std::string("plant description refused: ") + e.what());
  }
}

}  // namespace ambid::daemons
