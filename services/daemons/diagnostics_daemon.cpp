#include "services/daemons/diagnostics_daemon.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "diagnostics/diagnostics_engine.hpp"
#include "diagnostics/plant_families.hpp"
#include "services/convert/alert.hpp"
#include "services/convert/estimate_window.hpp"
#include "services/convert/plant_description.hpp"
#include "services/convert/source_kind.hpp"
#include "services/daemons/daemon_runtime.hpp"
#include "services/daemons/description_change.hpp"
#include "services/daemons/model_gaps.hpp"
#include "services/daemons/plant_time.hpp"
#include "services/daemons/served_plants.hpp"
#include "services/daemons/window_failures.hpp"

namespace ambid::daemons {
namespace {

struct DiagnosticsConfig {
  std::string store = "ambid-trend.sqlite";
  diag::EngineConfig engine;
  double silence = 3.0;
  diag::RetentionPolicy retention;
  double retention_period = 600.0;  // plant seconds between two passes of the retention
};

constexpr double kDay = 86400.0;
// The identifier daemon's estimator is recursive (rpem): its first windows after a restart or
// a swap rest on little information, and their sigma says so (diag::MonitorConfig).
constexpr double kRecursiveUnconvergedSigmaRatio = 2.0;
// Its first window after an abrupt plant change (a fault, a swap) moves parameters no fault
// moves (kr1 +36 %, kw1 -20 % at the stack's swap to R1 +20 %): a change is named once 3
// judged windows in a row agree on it, 1 s at the stack's 0.5 s windows (alert_policy.hpp).
constexpr int kRecursiveConfirmWindows = 3;

DiagnosticsConfig diagnostics_config(const nlohmann::json& j) {
  reject_unknown_keys(j, "diagnostics config",
                      {"plants", "store", "learning_windows", "persist_windows", "error_fraction", "warn_fraction",
                       "stale_timeout", "silence", "keep_windows_days", "aggregate_bucket", "keep_days",
                       "retention_period", "unconverged_sigma_ratio", "confirm_windows"});
  DiagnosticsConfig c;
  c.store = config_value(j, "store", c.store);
  c.engine.monitor.learning_windows = std::size_t(config_value(j, "learning_windows", 50));
  c.engine.monitor.unconverged_sigma_ratio =
      config_value(j, "unconverged_sigma_ratio", kRecursiveUnconvergedSigmaRatio);
  c.engine.policy.persist_windows = std::size_t(config_value(j, "persist_windows", 100));
  const int confirm = config_value(j, "confirm_windows", kRecursiveConfirmWindows);
  if (confirm < 1)
    throw Error("diagnostics config: confirm_windows must be at least 1, got " + std::to_string(confirm));
  c.engine.policy.confirm_windows = std::size_t(confirm);
  c.engine.policy.error_fraction = config_value(j, "error_fraction", c.engine.policy.error_fraction);
  c.engine.policy.warn_fraction = config_value(j, "warn_fraction", c.engine.policy.warn_fraction);
  c.engine.policy.stale_timeout = config_value(j, "stale_timeout", c.engine.policy.stale_timeout);
  c.silence = config_value(j, "silence", c.silence);
  // Per-window estimates for a week, then hourly aggregates for a year (README: disk use).
  c.retention.aggregate_after = config_value(j, "keep_windows_days", 7.0) * kDay;
  c.retention.bucket = config_value(j, "aggregate_bucket", 3600.0);
  c.retention.max_age = config_value(j, "keep_days", 365.0) * kDay;
  c.retention_period = config_value(j, "retention_period", c.retention_period);
  c.retention.validate();
  if (!(c.retention_period > 0 && std::isfinite(c.retention_period)))
    throw Error("diagnostics config: retention_period must be > 0 s, got " + std::to_string(c.retention_period));
  c.engine.validate();
  if (!(c.silence > 0)) throw Error("diagnostics config: silence must be > 0 s, got " + std::to_string(c.silence));
  return c;
}

}  // namespace

int run_diagnostics_daemon(const DaemonOptions& options) {
  const nlohmann::json json = load_config(options.config);
  const DiagnosticsConfig config = diagnostics_config(json);
  const ServedPlants served(json, options.plant_id, "diagnostics config");
  diag::TrendStore store(config.store);

  auto bus = options.connect();
  // One plant: its node as before; several: the process's own node, plus one per plant.
  DaemonRuntime runtime(*bus, "diagnostics",
                        served.single() ? options.plant_id + "/diagnostics" : "diagnostics@" + std::to_string(getpid()),
                        options.metrics_port);
  auto models = bus->reader<bus::IdentifiedModel>();
  auto sources = bus->reader<bus::PlantSourceState>();
  auto descriptions = bus->reader<bus::PlantDescription>();
  auto health = bus->reader<bus::Health>();
  auto alerts = bus->writer<bus::Alert>();
  runtime.ready("trend store " + config.store + ", " + served.describe());

  std::map<diag::Level, prometheus::Counter*> alerts_by_level;
  for (diag::Level level : {diag::Level::ok, diag::Level::warn, diag::Level::error, diag::Level::stale})
    alerts_by_level[level] = &runtime.metrics.counter("ambid_alerts_total", "alerts raised, by level",
                                                      {{"level", std::string(diag::to_string(level))}});
  auto publish = [&](const std::vector<diag::Alert>& raised) {
    for (const diag::Alert& a : raised) {
      alerts->write(convert::to_message(a));
      runtime.metrics.published.Increment();
      alerts_by_level.at(a.level)->Increment();
      runtime.log(std::string(diag::to_string(a.level)) + " " + a.plant_id + " " + a.parameter + ": " + a.message);
    }
  };
  prometheus::Counter& missed_models = runtime.metrics.counter(
      "ambid_models_missed_total", "identified models never received (a hole in the history)", {});
  // Everything the diagnostics keep is per plant (engine with its baselines and trend state,
  // loop, clock); the trend store is shared, keyed by plant id.
  struct Plant {
    std::unique_ptr<diag::DiagnosticsEngine> engine;
    std::optional<bus::PlantDescription> loop;  // the description in force
    diag::Source source = diag::Source::sim;
    PlantTime plant_time;
    std::optional<double> last_retention;  // plant time of the last retention pass
    ModelGaps gaps;
    std::chrono::steady_clock::time_point last_model = std::chrono::steady_clock::now();
    bool stale = false;
    bool identifier_failing = false;  // its Health says its windows keep failing (window_failures.hpp)
  };
  std::map<std::string, Plant> plants;
  auto plant = [&](const std::string& id) -> Plant& {
    auto it = plants.find(id);
    if (it == plants.end()) {
      it = plants.emplace(id, Plant{}).first;
      it->second.engine = std::make_unique<diag::DiagnosticsEngine>(store, config.engine);
      runtime.add_node(id + "/diagnostics");
      if (!served.single()) runtime.log("serving plant " + id);
    }
    return it->second;
  };
  for (const std::string& id : served.listed()) plant(id);
  // A new loop or bearing (description_change.hpp): the engine starts again with the fault
  // signatures of the new loop, from the stored baselines, or from none for another bearing.
  auto describe = [&](Plant& p, const bus::PlantDescription& d, double time) {
    const DescriptionChange change = classify(p.loop ? &*p.loop : nullptr, d);
    if (change == DescriptionChange::same) return;
    diag::EngineConfig c = config.engine;
    const Experiment header = convert::experiment_header(d);
    try {  // the family's monitored parameters and roles, or the family named as not monitored
      diag::monitored_family(header.plant.model, "diagnostics daemon");
      c.isolation.family = header.plant.model;
    } catch (const Error& e) {
      runtime.metrics.rejected.Increment();
      runtime.log("plant description " + d.description_id + " refused: " + e.what() +
                  "; its models will be refused too");
      runtime.set_health(d.plant_id + "/diagnostics", bus::AlertLevel::error, e.what());
      return;
    }
    try {
      c.isolation.hypotheses = diag::fault_hypotheses(header);
    } catch (const Error& e) {
      runtime.metrics.rejected.Increment();
      runtime.log("plant description " + d.description_id + ": no fault signatures of its loop (" + e.what() +
                  "); those of the family's default loop instead");
    }
    if (change == DescriptionChange::bearing) {
      const std::size_t forgotten = store.forget_baselines(d.plant_id);
      bus::Alert a;
      a.plant_id = d.plant_id;
      a.fault = "new_bearing";
      a.time = time;
      a.message = ("another bearing (" + bearing_difference(*p.loop, d) + "): " + std::to_string(forgotten) +
                   " baselines dropped, learned again")
                      .substr(0, bus::limits::text_length);
      alerts->write(a);
      runtime.metrics.published.Increment();
      runtime.log(d.plant_id + ": " + a.message);
    } else if (change == DescriptionChange::controller) {
      runtime.log(d.plant_id + ": plant description " + d.description_id +
                  ": the same bearing in another loop (controller " + convert::controller_summary(d) +
                  "); fault signatures recomputed, baselines kept");
    }
    p.engine = std::make_unique<diag::DiagnosticsEngine>(store, c);
    p.loop = d;
  };
  auto retain = [&](Plant& p, const std::string& id, double now) {
    if (p.last_retention && now - *p.last_retention < config.retention_period) return;
    p.last_retention = now;
    try {
      const diag::RetentionReport r = store.apply_retention(config.retention, now);
      if (r.estimates_aggregated + r.aggregates_removed + r.alerts_removed > 0)
        runtime.log("retention: " + std::to_string(r.estimates_aggregated) + " window estimates aggregated, " +
                    std::to_string(r.aggregates_removed) + " aggregates and " + std::to_string(r.alerts_removed) +
                    " alerts past their age removed");
    } catch (const Error& e) {  // a full disk: the history stays as it is, the service goes on
      runtime.log("retention failed: " + std::string(e.what()));
      runtime.set_health(id + "/diagnostics", bus::AlertLevel::warn,
                         "trend store retention failed: " + std::string(e.what()));
    }
  };
  // When an identifier's writer is lost: serving one plant, its parameters are stale at once;
  // serving several, those of the plants that got no model within the grace (the others are
  // served by another identifier still running).
  const double lost_grace = served.single() ? 0.0 : std::min(1.0, config.silence / 2);
  std::optional<std::chrono::steady_clock::time_point> lost_at;
  while (runtime.running()) {
    bus->wait(std::chrono::milliseconds(100));
    for (const bus::PlantSourceState& s : sources->take())
      if (served.serves(s.plant_id)) plant(s.plant_id).source = convert::to_source(s.kind);
    for (const bus::PlantDescription& d : descriptions->take()) {
      if (!served.serves(d.plant_id)) continue;
      Plant& p = plant(d.plant_id);
      describe(p, d, p.plant_time.last().value_or(0.0));
    }
    for (const bus::Health& h : health->take()) {
      const auto slash = h.node.rfind("/identifier");
      if (slash == std::string::npos || slash + 11 != h.node.size()) continue;
      const std::string id = h.node.substr(0, slash);
      if (!served.serves(id)) continue;
      Plant& p = plant(id);
      const bool failing = reports_failing_windows(h, id);
      // On the edge only: the next identified window brings the parameters back to OK.
      if (failing && !p.identifier_failing)
        publish(p.engine->mark_stale(id, p.plant_time.last().value_or(0.0), "the identifier's " + h.message));
      p.identifier_failing = failing;
    }
    for (const bus::IdentifiedModel& m : models->take()) {
      if (!served.serves(m.plant_id)) continue;
      Plant& p = plant(m.plant_id);
      const std::string plant_node = m.plant_id + "/diagnostics";
      runtime.metrics.received.Increment();
      const std::optional<double> previous = p.plant_time.last();
      const std::optional<PlantTime::Accepted> at = p.plant_time.accept(m.time, m.window);
      if (!at) continue;  // already processed (a late-joiner replay)
      // value: the plant seconds the hole spans.
      auto history_gap = [&](double seconds, const std::string& message) {
        bus::Alert a;
        a.plant_id = m.plant_id;
        a.fault = "history_gap";
        a.parameter = "all";
        a.level = bus::AlertLevel::warn;
        a.time = at->time;
        a.value = seconds;
        a.message = message.substr(0, bus::limits::text_length);
        alerts->write(a);
        runtime.metrics.published.Increment();
        runtime.log(m.plant_id + ": " + a.message);
        runtime.set_health(plant_node, bus::AlertLevel::warn, a.message);
      };
      if (const std::uint64_t missed = p.gaps.missed(m.seq); missed > 0) {
        // This daemon fell behind or was stopped: the models in between are gone for good.
        missed_models.Increment(double(missed));
        history_gap(double(missed) * m.window, "missed " + std::to_string(missed) + " identified models (seq " +
                                                   std::to_string(m.seq - missed) + " to " + std::to_string(m.seq - 1) +
                                                   ") before plant time " + std::to_string(m.time) +
                                                   " s: a hole in the trend history");
      } else if (p.gaps.restarted() && !at->after_restart && previous && at->time - *previous > 4.0 * m.window) {
        // A restarted identifier numbers from 0 again; the plant ran on meanwhile, unidentified.
        history_gap(at->time - m.window - *previous,
                    "the identifier restarted: no models from plant time " + std::to_string(*previous) + " to " +
                        std::to_string(at->time - m.window) + " s, a hole in the trend history");
      }
      if (at->after_restart) {
        const std::string message = "plant restarted: its model at plant time " + std::to_string(m.time) +
                                    " s continues the history at " + std::to_string(at->time) + " s";
        runtime.log(m.plant_id + ": " + message);
        runtime.set_health(plant_node, bus::AlertLevel::ok, message);
      }
      try {
        diag::EstimateWindow window = convert::estimate_window(m, p.source);
        window.time = at->time;
        publish(p.engine->process(window));
        for (const std::string& note : p.engine->notes()) runtime.log(note);
        retain(p, m.plant_id, at->time);
        p.last_model = std::chrono::steady_clock::now();
        p.stale = false;
      } catch (const Error& e) {
        runtime.metrics.rejected.Increment();
        runtime.log(m.plant_id + ": model " + std::to_string(m.seq) + " refused: " + e.what());
      }
    }
    for (const bus::StatusEvent& e : models->events())
      if (e.kind == bus::StatusKind::liveliness_lost || e.kind == bus::StatusKind::unmatched)
        lost_at = std::chrono::steady_clock::now();
    for (auto& [id, p] : plants) {
      // An identifier went away: stale are the plants it served, those with no model since.
      const bool orphaned = lost_at && p.last_model < *lost_at && seconds_since(*lost_at) >= lost_grace;
      const bool silent = orphaned || seconds_since(p.last_model) > config.silence;
      if (silent && p.plant_time.last() && !p.stale) {
        // The engine's clock is the plant's: the source went silent after the last model.
        publish(
            p.engine->check_stale(std::nextafter(*p.plant_time.last() + config.engine.policy.stale_timeout, INFINITY)));
        p.stale = true;
      }
    }
  }
  return 0;
}

}  // namespace ambid::daemons
