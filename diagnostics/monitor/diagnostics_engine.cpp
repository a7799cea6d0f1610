#include "diagnostics/diagnostics_engine.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.hpp"
#include "diagnostics/plant_families.hpp"

namespace ambid::diag {
namespace {

Alert make_alert(double time, const std::string& plant_id, const std::string& parameter, Level level, std::string fault,
                 std::optional<int> channel, double value, const std::optional<Baseline>& baseline,
                 std::string message) {
  Alert a;
  a.time = time;
  a.plant_id = plant_id;
  a.level = level;
  a.fault = std::move(fault);
  a.channel = channel;
  a.parameter = parameter;
  a.value = value;
  if (baseline) a.baseline = baseline->mean;
  a.message = std::move(message);
  return a;
}

// The parameters and exact values of a window's estimates (FNV-1a over their bytes).
std::size_t estimates_hash(const EstimateWindow& w) {
  std::size_t h = 14695981039346656037ull;
  const auto mix = [&](const void* data, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
  };
  for (const ParameterEstimate& e : w.estimates) {
    mix(e.parameter.data(), e.parameter.size() + 1);
    mix(&e.value, sizeof e.value);
  }
  return h;
}

}  // namespace

std::string DiagnosticsEngine::convergence_note(const std::string& plant_id, const ParameterEstimate& e,
                                                const Series& s, bool converged) const {
  const double reference = s.monitor.baseline() ? s.monitor.baseline()->reported_sigma : 0.0;
  char text[160];
  if (converged)
    std::snprintf(text, sizeof text, "plant %s: %s judged again (sigma %.3g, the baseline's %.3g)", plant_id.c_str(),
                  e.parameter.c_str(), e.sigma, reference);
  else
    std::snprintf(text, sizeof text,
                  "plant %s: %s not judged: sigma %.3g is %.2gx the baseline's %.3g (the estimate has not converged)",
                  plant_id.c_str(), e.parameter.c_str(), e.sigma, e.sigma / reference, reference);
  return text;
}

void EngineConfig::validate() const {
  monitor.validate();
  policy.validate();
  isolation.validate();
}

DiagnosticsEngine::DiagnosticsEngine(TrendStore& store, const EngineConfig& config) : store_(store), config_(config) {
  config_.validate();
}

DiagnosticsEngine::Series& DiagnosticsEngine::series(SeriesMap& map, const std::string& plant_id,
                                                     const std::string& parameter) const {
  const Key key{plant_id, parameter};
  auto it = map.find(key);
  if (it == map.end()) {
    const ParameterRole role = parameter_role(config_.isolation.family, parameter);
    it = map.emplace(key, Series(SeriesMonitor(config_.monitor, store_.baseline(plant_id, parameter)), role)).first;
  }
  return it->second;
}

std::vector<Alert> DiagnosticsEngine::process(std::span<const EstimateWindow> windows) {
  for (const EstimateWindow& w : windows) {
    w.validate();
    for (const ParameterEstimate& e : w.estimates) parameter_role(config_.isolation.family, e.parameter);
  }
  SeriesMap next = series_;
  Batch batch;
  std::vector<std::string> notes;
  batch.windows.assign(windows.begin(), windows.end());
  std::vector<std::pair<std::string, std::size_t>> new_hashes;  // remembered once stored
  for (const EstimateWindow& w : windows) {
    const std::size_t hash = estimates_hash(w);
    const auto seen = seen_.find(w.plant_id);
    const bool repeated =
        (seen != seen_.end() && seen->second.hashes.count(hash)) ||
        std::find(new_hashes.begin(), new_hashes.end(), std::pair(w.plant_id, hash)) != new_hashes.end();
    if (!repeated) new_hashes.emplace_back(w.plant_id, hash);
    for (const ParameterEstimate& e : w.estimates) {
      Series& s = series(next, w.plant_id, e.parameter);
      const bool converged = s.monitor.converged(e.sigma);
      if (!repeated && converged != !s.unconverged) notes.push_back(convergence_note(w.plant_id, e, s, converged));
      if (!repeated) s.unconverged = !converged;
      if (!repeated && converged) {
        if (s.monitor.update(w.time, e.value, e.sigma))
          batch.baselines.push_back({w.plant_id, e.parameter, *s.monitor.baseline(), w.time});
        s.judged_time = w.time;
      }
      s.last_time = w.time;
      s.last_value = e.value;
    }
    mark_stale(next, w.plant_id, w.time, batch.alerts);
    evaluate(next, w.plant_id, w.time, batch.alerts);
  }
  store_.write(batch);
  series_ = std::move(next);
  notes_ = std::move(notes);
  for (const auto& [plant_id, hash] : new_hashes) {
    SeenWindows& seen = seen_[plant_id];
    seen.order.push_back(hash);
    seen.hashes.insert(hash);
    if (seen.order.size() > kRememberedWindows) {
      seen.hashes.erase(seen.order.front());
      seen.order.pop_front();
    }
  }
  return batch.alerts;
}

std::vector<Alert> DiagnosticsEngine::check_stale(double now) {
  if (!std::isfinite(now)) throw Error("diagnostics: staleness check time is not finite");
  SeriesMap next = series_;
  Batch batch;
  mark_stale(next, std::nullopt, now, batch.alerts);
  if (!batch.alerts.empty()) store_.write(batch);
  series_ = std::move(next);
  return batch.alerts;
}

std::vector<Alert> DiagnosticsEngine::mark_stale(const std::string& plant_id, double time, const std::string& reason) {
  if (!std::isfinite(time)) throw Error("diagnostics: staleness time is not finite");
  SeriesMap next = series_;
  const bool seen = std::any_of(next.begin(), next.end(), [&](const auto& s) { return s.first.first == plant_id; });
  if (!seen)
    for (const std::string& parameter : monitored_parameters(config_.isolation.family))
      series(next, plant_id, parameter);
  Batch batch;
  for (auto& [key, s] : next) {
    if (key.first != plant_id || s.level == Level::stale) continue;
    s.level = Level::stale;
    s.fault = std::string(s.role.fault);
    s.channel = s.role.channel;
    batch.alerts.push_back(make_alert(time, plant_id, key.second, Level::stale, s.fault, s.channel, s.last_value,
                                      s.monitor.baseline(), stale_message(s.role.subject, reason)));
  }
  if (!batch.alerts.empty()) store_.write(batch);
  series_ = std::move(next);
  return batch.alerts;
}

void DiagnosticsEngine::mark_stale(SeriesMap& map, const std::optional<std::string>& plant_id, double now,
                                   std::vector<Alert>& alerts) const {
  for (auto& [key, s] : map) {
    if (plant_id && key.first != *plant_id) continue;
    if (!s.last_time || s.level == Level::stale) continue;
    const double silent_for = now - *s.last_time;
    if (!(silent_for > config_.policy.stale_timeout)) continue;
    s.level = Level::stale;
    s.fault = std::string(s.role.fault);
    s.channel = s.role.channel;
    alerts.push_back(make_alert(now, key.first, key.second, Level::stale, s.fault, s.channel, s.last_value,
                                s.monitor.baseline(),
                                stale_message(s.role.subject, silent_for, config_.policy.stale_timeout)));
  }
}

void DiagnosticsEngine::evaluate(SeriesMap& map, const std::string& plant_id, double time,
                                 std::vector<Alert>& alerts) const {
  struct Current {
    const Key* key;
    Series* series;
    SeriesStatus status;
    Level level;
  };
  std::vector<Current> current;
  std::vector<Deviation> deviations;
  for (auto& [key, s] : map) {
    if (key.first != plant_id) continue;
    if (s.level == Level::stale && s.last_time != time) continue;  // still silent
    const SeriesStatus status = s.monitor.status();
    const Level level = config_.policy.level(status, s.episode);
    current.push_back({&key, &s, status, level});
    // Every parameter past learning enters the fit: one a fault predicts to move and that did
    // not speaks against that fault.
    if (!status.learning)
      deviations.push_back(
          {key.second, status.relative, status.relative_sigma, level == Level::warn || level == Level::error});
  }
  const std::vector<Isolation> isolations = isolate(deviations, config_.isolation);

  for (Current& c : current) {
    Series& s = *c.series;
    const auto isolation = std::find_if(isolations.begin(), isolations.end(),
                                        [&](const Isolation& i) { return i.parameter == c.key->second; });
    std::string fault(s.role.fault);
    std::optional<int> channel = s.role.channel;
    if (isolation != isolations.end()) {
      fault = isolation->fault;
      channel = isolation->channel;
    }
    const bool confirmed_now = confirmed(s, c.level, fault, channel, c.status.level, time);
    if (c.level == s.level && fault == s.fault && channel == s.channel) continue;
    if (c.level != Level::ok && !confirmed_now) continue;  // the last alert holds meanwhile
    s.episode = c.level == Level::ok ? Level::ok : std::max(s.episode, c.level);
    const bool changed = isolation != isolations.end();
    alerts.push_back(make_alert(time, plant_id, c.key->second, c.level, fault, channel,
                                changed ? c.status.level : s.last_value, s.monitor.baseline(),
                                changed
                                    ? change_message(*isolation, c.status, config_.policy, config_.monitor.slope.window)
                                    : ok_message(s.role.subject, c.status, s.level, config_.monitor.learning_windows)));
    s.level = c.level;
    s.fault = std::move(fault);
    s.channel = channel;
  }
}

bool DiagnosticsEngine::confirmed(Series& s, Level candidate, const std::string& fault, std::optional<int> channel,
                                  double level, double time) const {
  if (candidate != Level::warn && candidate != Level::error) {
    s.pending_windows = 0;
    return true;
  }
  if (s.judged_time == time) {
    // On the changed side: nearer the detector's level than the baseline mean.
    const double mean = s.monitor.baseline()->mean;
    const bool on_its_side = (s.last_value - 0.5 * (mean + level)) * (level - mean) > 0.0;
    if (!on_its_side) {
      s.pending_windows = 0;
    } else if (s.pending_windows > 0 && s.pending_fault == fault && s.pending_channel == channel) {
      ++s.pending_windows;
    } else {
      s.pending_fault = fault;
      s.pending_channel = channel;
      s.pending_windows = 1;
    }
  }
  return config_.policy.confirm_windows == 1 || (s.pending_windows >= config_.policy.confirm_windows &&
                                                 s.pending_fault == fault && s.pending_channel == channel);
}

void DiagnosticsEngine::set_baseline(const std::string& plant_id, const std::string& parameter,
                                     const Baseline& baseline, double time) {
  baseline.validate();
  const ParameterRole role = parameter_role(config_.isolation.family, parameter);
  Batch batch;
  batch.baselines.push_back({plant_id, parameter, baseline, time});
  store_.write(batch);
  const Key key{plant_id, parameter};
  auto it = series_.find(key);
  if (it == series_.end()) {
    series_.emplace(key, Series(SeriesMonitor(config_.monitor, baseline), role));
  } else {
    it->second.monitor = SeriesMonitor(config_.monitor, baseline);
  }
}

Level DiagnosticsEngine::level(const std::string& plant_id, const std::string& parameter) const {
  const auto it = series_.find({plant_id, parameter});
  if (it == series_.end())
    throw Error("diagnostics: no estimate of " + parameter + " of plant '" + plant_id + "' seen yet");
  return it->second.level;
}

}  // namespace ambid::diag
