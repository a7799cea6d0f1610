#pragma once
// The diagnostics engine: takes windows of identified physical parameters, watches every
// parameter of every plant (series_monitor.hpp), names the fault behind the parameters that
// moved (fault_isolation.hpp), decides the level of each (alert_policy.hpp) and returns an
// alert whenever the level, fault or channel of a parameter changes. Every window, the
// baselines it learns and the alerts it raises are written to the trend store in one
// transaction per call.
//
// What persists across a restart: the history, the baselines and the alerts. The detectors
// start again from the stored baselines (a lasting change is raised again within the delays
// of change_detection.hpp); a baseline still being learned is learned again from new windows.
//
// The same data identified again (a replayed recording looping, a simulation restarted at its
// first seed) gives bit-identical estimates: such a window is stored with the history but not
// given to the detectors, which assume every window is a new, independent look at the plant
// (a replayed 0.5 s record gave R1 16.75 ohm, -1.6 baseline sigmas, in 966 windows in a row and
// raised "R1 5 % below baseline" on a bearing that never changed). The last
// kRememberedWindows windows of each plant are remembered.
//
// A WARN or ERROR is raised once confirm_windows judged windows in a row agree on it
// (alert_policy.hpp, "Confirmation"; 1 by default: at once).
//
// Not thread-safe: one thread at a time.
#include <cstddef>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "diagnostics/alert.hpp"
#include "diagnostics/fault_isolation.hpp"
#include "diagnostics/monitor/alert_policy.hpp"
#include "diagnostics/monitor/series_monitor.hpp"
#include "diagnostics/trend_store.hpp"

namespace ambid::diag {

struct EngineConfig {
  MonitorConfig monitor;
  AlertPolicy policy;
  IsolationConfig isolation;
  void validate() const;
};

class DiagnosticsEngine {
 public:
  static constexpr std::size_t kRememberedWindows = 4096;  // per plant, for repeated data

  // The store must outlive the engine.
  DiagnosticsEngine(TrendStore& store, const EngineConfig& config = {});

  // Windows in time order per plant and parameter. Each window also marks STALE the other
  // parameters of its plant that have had no estimate for longer than the stale timeout.
  // Throws Error for an invalid window, an unmonitored parameter, a time that does not
  // follow the previous estimate of its parameter, or a store failure; then nothing of the
  // call is kept, neither in the engine nor in the store.
  //
  // An estimate that has not converged (its sigma beyond MonitorConfig::unconverged_sigma_ratio
  // times the baseline's) is stored with the history but not given to the detectors; the call's
  // notes() say so when a parameter starts or stops being judged.
  std::vector<Alert> process(std::span<const EstimateWindow> windows);
  std::vector<Alert> process(const EstimateWindow& window) { return process(std::span(&window, 1)); }

  // Marks STALE every parameter without an estimate since now - stale_timeout (`now` on the
  // clock of the window times). Stores and returns the alerts.
  std::vector<Alert> check_stale(double now);

  // Marks STALE, at `time`, every parameter of the plant not STALE yet because its estimates
  // stopped for `reason` (e.g. the identifier's windows keep failing), before any timeout; a
  // plant without estimates yet gets its family's monitored parameters (plant_families.hpp).
  // Each comes back with its next estimate ("estimates resumed"). Stores and returns the alerts.
  std::vector<Alert> mark_stale(const std::string& plant_id, double time, const std::string& reason);

  // Gives a baseline explicitly (stored at once, stamped `time`); detection of the parameter
  // starts again from it.
  void set_baseline(const std::string& plant_id, const std::string& parameter, const Baseline& baseline, double time);

  // Of the last process() call: "plant P: R1 not judged: sigma 0.52 is 2.3x the baseline's 0.22
  // (the estimate has not converged)", "plant P: R1 judged again (sigma 0.25)"; empty when no
  // parameter changed between judged and not.
  const std::vector<std::string>& notes() const { return notes_; }

  // The current level of a parameter; Error when the engine has not seen it.
  Level level(const std::string& plant_id, const std::string& parameter) const;

 private:
  struct Series {
    Series(SeriesMonitor m, const ParameterRole& r)
        : monitor(std::move(m)), role(r), fault(r.fault), channel(r.channel) {}
    SeriesMonitor monitor;
    ParameterRole role;
    std::optional<double> last_time;  // empty until the first estimate
    double last_value = 0.0;
    Level level = Level::ok;  // as last reported (OK until an alert says otherwise)
    std::string fault;
    std::optional<int> channel;
    Level episode = Level::ok;          // highest level raised since last OK
    bool unconverged = false;           // its last estimate was not judged (MonitorConfig::unconverged_sigma_ratio)
    std::optional<double> judged_time;  // of its last estimate given to the detectors
    // Confirmation (AlertPolicy::confirm_windows): the cause of a WARN or ERROR the last judged
    // windows named and how many in a row named it with their estimate on its side.
    std::string pending_fault;
    std::optional<int> pending_channel;
    std::size_t pending_windows = 0;
  };
  using Key = std::pair<std::string, std::string>;  // plant id, parameter
  using SeriesMap = std::map<Key, Series>;

  Series& series(SeriesMap& map, const std::string& plant_id, const std::string& parameter) const;
  std::string convergence_note(const std::string& plant_id, const ParameterEstimate& e, const Series& s,
                               bool converged) const;
  void mark_stale(SeriesMap& map, const std::optional<std::string>& plant_id, double now,
                  std::vector<Alert>& alerts) const;
  void evaluate(SeriesMap& map, const std::string& plant_id, double time, std::vector<Alert>& alerts) const;
  // Counts a judged window of `s` towards confirming a WARN or ERROR of `fault`, `channel` at
  // the detector's `level` (value units), or breaks the run; true once confirmed.
  bool confirmed(Series& s, Level candidate, const std::string& fault, std::optional<int> channel, double level,
                 double time) const;

  // Hashes of the estimates of a plant's recent windows, oldest first.
  struct SeenWindows {
    std::deque<std::size_t> order;
    std::unordered_set<std::size_t> hashes;
  };

  TrendStore& store_;
  EngineConfig config_;
  SeriesMap series_;
  std::map<std::string, SeenWindows> seen_;  // by plant id
  std::vector<std::string> notes_;           // of the last process() call
};

}  // namespace ambid::diag
