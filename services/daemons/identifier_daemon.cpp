#include "services/daemons/identifier_daemon.hpp"

#include <unistd.h>

#include <array>
#include <cmath>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "services/daemons/continuous_estimator.hpp"
#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/foreign_models.hpp"
#include "services/daemons/identify_window.hpp"
#include "services/daemons/sample_gap_report.hpp"
#include "services/daemons/served_plants.hpp"
#include "services/daemons/window_failures.hpp"
#include "services/daemons/window_steps.hpp"

namespace ambid::daemons {
namespace {

struct IdentifierConfig {
  WindowSettings windows{.window = 0.25, .settle = 0.25};
  ident::IdentifyOptions identify = window_identify_options(kDefaultDaemonMethod);
  WindowFailureRule failures;
  std::optional<ContinuousSettings> continuous;  // method rpem: one estimator, windows = publish periods
};

IdentifierConfig identifier_config(const nlohmann::json& j) {
  reject_unknown_keys(j, "identifier config",
                      {"plants", "method", "window", "settle", "transient_samples", "failing_consecutive",
                       "failing_recent", "failing_fraction", "publish_rate", "forgetting", "carry", "jackknife"});
  IdentifierConfig c;
  c.windows.window = config_value(j, "window", c.windows.window);
  c.windows.settle = config_value(j, "settle", c.windows.settle);
  if (!(c.windows.settle >= 0))
    throw Error("identifier config: settle must be >= 0 s, got " + std::to_string(c.windows.settle));
  c.identify = window_identify_options(config_value<std::string>(j, "method", kDefaultDaemonMethod),
                                       Eigen::Index(config_value(j, "transient_samples", 0)));
  // okid/closed-loop/projection report no uncertainty without it, and the diagnostics then
  // judge every window by the scatter of the baseline's, whatever the excitation of the window.
  const int jackknife = config_value(j, "jackknife", 0);
  if (jackknife < 0 || jackknife == 1)
    throw Error("identifier config: jackknife must be 0 (no uncertainty) or >= 2 segments, got " +
                std::to_string(jackknife));
  c.identify.jackknife_segments = jackknife;
  if (!(c.windows.window > 0))
    throw Error("identifier config: window must be > 0 s, got " + std::to_string(c.windows.window));
  if (c.identify.method == "rpem") {
    const double rate = config_value(j, "publish_rate", 1.0 / c.windows.window);
    if (!(rate > 0) || !std::isfinite(rate))
      throw Error("identifier config: publish_rate must be > 0 Hz, got " + std::to_string(rate));
    c.windows.window = 1.0 / rate;
    c.continuous = ContinuousSettings{};
    double& forgetting = c.continuous->recursive.forgetting;
    forgetting = config_value(j, "forgetting", forgetting);
    if (!(forgetting > 0 && forgetting <= 1))
      throw Error("identifier config: forgetting must be in (0, 1], got " + std::to_string(forgetting));
    c.continuous->carry = config_value(j, "carry", c.continuous->carry);
    if (!(c.continuous->carry > 0 && c.continuous->carry <= 1))
      throw Error("identifier config: carry must be in (0, 1], got " + std::to_string(c.continuous->carry));
  } else if (j.contains("publish_rate") || j.contains("forgetting") || j.contains("carry")) {
    throw Error("identifier config: publish_rate, forgetting and carry are for method rpem only (method " +
                c.identify.method + " publishes once per window)");
  }
  // Signed, so that a negative value is named instead of wrapping around.
  const auto count = [&](const char* key, std::size_t fallback) {
    const int n = config_value(j, key, int(fallback));
    if (n < 1) throw Error(std::string("identifier config: ") + key + " must be >= 1, got " + std::to_string(n));
    return std::size_t(n);
  };
  c.failures.consecutive = count("failing_consecutive", c.failures.consecutive);
  c.failures.recent = count("failing_recent", c.failures.recent);
  c.failures.fraction = config_value(j, "failing_fraction", c.failures.fraction);
  c.failures.validate();
  return c;
}

std::string host_name() {
  std::array<char, 256> name{};
  return gethostname(name.data(), name.size() - 1) == 0 ? std::string(name.data()) : std::string("localhost");
}

}  // namespace

int run_identifier_daemon(const DaemonOptions& options) {
  const nlohmann::json json = load_config(options.config);
  const IdentifierConfig config = identifier_config(json);
  const ServedPlants served(json, options.plant_id, "identifier config");

  auto bus = options.connect();
  // One plant: its node as before; several: the process's own node, plus one per plant.
  const std::string node =
      served.single() ? options.plant_id + "/identifier" : "identifier@" + host_name() + ":" + std::to_string(getpid());
  DaemonRuntime runtime(*bus, "identifier", node, options.metrics_port);
  auto samples = bus->reader<bus::PlantSamples>();
  auto descriptions = bus->reader<bus::PlantDescription>();
  auto models = bus->writer<bus::IdentifiedModel>();
  auto echoes = bus->reader<bus::IdentifiedModel>();
  prometheus::Histogram& identification_seconds =
      runtime.metrics.histogram("ambid_identification_seconds", "wall time of one window's identification",
                                {0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5});
  prometheus::Counter& samples_in =
      runtime.metrics.counter("ambid_samples_received_total", "samples in the batches taken from the bus", {});
  // Samples that never reach an identification, by why: a refused batch, the partial window
  // a sequence gap or a record's end discards, a window the method could not identify.
  const std::string dropped_help = "samples that reached no identification";
  prometheus::Counter& dropped_unidentified =
      runtime.metrics.counter("ambid_samples_dropped_total", dropped_help, {{"reason", "unidentified"}});
  prometheus::Counter& served_twice = runtime.metrics.counter(
      "ambid_foreign_models_total", "models of a served plant published by another identifier", {});
  WindowSteps steps(runtime, dropped_help);
  // Everything the identifier keeps is per plant (windows, failure rule, model numbers).
  struct Plant {
    DescribedWindows window;
    WindowFailures failures;
    SampleGapReport gaps;                           // holes in the samples
    std::optional<ContinuousEstimator> continuous;  // method rpem
    std::uint64_t seq = 0;
    bool served_twice = false;
  };
  std::map<std::string, Plant> plants;
  auto plant = [&](const std::string& id) -> Plant& {
    auto it = plants.find(id);
    if (it == plants.end()) {
      it = plants
               .emplace(id, Plant{DescribedWindows(config.windows), WindowFailures(config.failures, runtime.metrics),
                                  SampleGapReport(*bus, runtime, id), std::nullopt})
               .first;
      if (config.continuous) it->second.continuous.emplace(*config.continuous);
      runtime.add_node(id + "/identifier");
      if (!served.single()) runtime.log("serving plant " + id);
    }
    return it->second;
  };
  for (const std::string& id : served.listed()) plant(id);
  ForeignModels foreign;
  runtime.ready((config.continuous ? "continuous, published every " : "windows of ") +
                std::to_string(config.windows.window) + " s, method " + config.identify.method + ", " +
                served.describe() + "; plant description from the bus");
  while (runtime.running()) {
    bus->wait(std::chrono::milliseconds(100));
    for (const bus::PlantDescription& d : descriptions->take())
      if (served.serves(d.plant_id)) steps.describe(plant(d.plant_id).window, d, served.single() ? "" : d.plant_id);
    for (const bus::PlantSamples& batch : samples->take()) {
      if (!served.serves(batch.plant_id)) continue;
      Plant& p = plant(batch.plant_id);
      const std::string plant_node = batch.plant_id + "/identifier";
      runtime.metrics.received.Increment();
      samples_in.Increment(double(batch.count));
      p.gaps.check(batch);
      const std::vector<DescribedWindows::Step> added = p.window.add(batch);
      steps.report(added, served.single() ? "" : batch.plant_id);
      for (const DescribedWindows::Step& s : added)
        if (s.event == DescribedWindows::Event::dropped_no_description)
          p.gaps.dropped(s.samples, s.from, s.to, s.reason);
      while (p.window.full()) {
        const Experiment w = p.window.take();
        try {
          const auto start = std::chrono::steady_clock::now();
          // Only published models are numbered: a gap in seq is a model a consumer missed.
          bus::IdentifiedModel model = p.continuous ? p.continuous->identify(w, batch.plant_id, p.seq)
                                                    : identify_window(w, batch.plant_id, p.seq, config.identify);
          ++p.seq;
          identification_seconds.Observe(seconds_since(start));
          models->write(model);
          foreign.published(model);
          runtime.metrics.published.Increment();
          if (p.failures.identified() == WindowFailures::Change::cleared) {
            runtime.set_health(plant_node, bus::AlertLevel::ok, p.failures.message());
            runtime.log(batch.plant_id + ": " + p.failures.message());
          } else if (p.failures.failing()) {
            runtime.set_health(plant_node, bus::AlertLevel::warn, p.failures.message());  // its counts move on
          }
        } catch (const Error& e) {
          const ident::WindowFailure failure = ident::window_failure(e);
          runtime.metrics.rejected.Increment();
          dropped_unidentified.Increment(double(w.samples()));
          runtime.log(batch.plant_id + ": window ending " + std::to_string(w.t(w.samples() - 1)) +
                      " s not identified (" + failure.reason + "): " + failure.message);
          const WindowFailures::Change change = p.failures.failed(failure);
          // While failing, Health follows every failed window (its counts and last reason).
          if (p.failures.failing()) runtime.set_health(plant_node, bus::AlertLevel::warn, p.failures.message());
          if (change == WindowFailures::Change::started) runtime.log(batch.plant_id + ": " + p.failures.message());
        }
      }
    }
    for (const bus::IdentifiedModel& m : echoes->take()) {
      if (!served.serves(m.plant_id) || !foreign.foreign(m)) continue;
      served_twice.Increment();
      Plant& p = plant(m.plant_id);
      if (p.served_twice) continue;
      p.served_twice = true;  // warned once; the plant stays served (which one should stop is the operator's call)
      const std::string message = "plant " + m.plant_id +
                                  " is served twice: another identifier publishes its models too (divide the "
                                  "plant ids between the identifiers' \"plants\" lists)";
      runtime.log(message);
      runtime.set_health(bus::AlertLevel::warn, message);
      if (node != m.plant_id + "/identifier")
        runtime.set_health(m.plant_id + "/identifier", bus::AlertLevel::warn, message);
    }
  }
  return 0;
}

}  // namespace ambid::daemons
