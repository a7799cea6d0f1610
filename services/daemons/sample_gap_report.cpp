#include "services/daemons/sample_gap_report.hpp"

namespace ambid::daemons {

SampleGapReport::SampleGapReport(bus::Bus& bus, DaemonRuntime& runtime, std::string plant_id)
    : runtime_(runtime),
      plant_id_(std::move(plant_id)),
      alerts_(bus.writer<bus::Alert>()),
      missed_(runtime.metrics.counter("ambid_samples_missed_total", "samples never received (a hole in the history)",
                                      {})) {}

void SampleGapReport::check(const bus::PlantSamples& batch) {
  const std::optional<SampleGap> gap = gaps_.check(batch);
  if (gap) raise(std::size_t(gap->samples), gap->from, gap->to, gap->message());
}

void SampleGapReport::dropped(std::size_t samples, double from, double to, const std::string& reason) {
  raise(samples, from, to,
        "dropped " + std::to_string(samples) + " samples (plant time " + std::to_string(from) + " to " +
            std::to_string(to) + " s): " + reason + ": a hole in the identified history");
}

void SampleGapReport::raise(std::size_t samples, double from, double to, const std::string& message) {
  bus::Alert a;
  a.plant_id = plant_id_;
  a.fault = "history_gap";
  a.parameter = "samples";
  a.level = bus::AlertLevel::warn;
  a.time = to;
  a.value = to - from;  // s of plant time never identified
  a.message = message.substr(0, bus::limits::text_length);
  alerts_->write(a);
  runtime_.metrics.published.Increment();
  missed_.Increment(double(samples));
  runtime_.log(a.message);
  runtime_.set_health(plant_id_ + "/identifier", bus::AlertLevel::warn, a.message);
}

}  // namespace ambid::daemons
