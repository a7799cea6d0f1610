#pragma once
// When the identifier's windows keep failing. Every window's outcome goes in (identified, or
// not with its reason, ident::window_failure); out come the skipped windows counted by reason
// (the metric ambid_windows_unidentified_total{reason}, and Health) and whether the windows
// are failing, by a configurable rule:
//   failing while the last `consecutive` windows all failed, or more than `fraction` of the
//   last `recent` windows failed (of those seen so far, once there are `consecutive`);
// it clears when neither holds any more (windows are identified again).
// The identifier daemon turns "failing" into Health WARN naming the reason. The parameters'
// alerts belong to the diagnostics daemon (architecture.md: identifier -> models ->
// diagnostics -> alerts): it reads that Health (reports_failing_windows) and marks the
// parameters STALE (diag::DiagnosticsEngine::mark_stale); their next estimate clears them.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <string_view>

#include "identifier/identify_window.hpp"
#include "services/bus/messages.hpp"
#include "services/daemons/metrics.hpp"

namespace ambid::daemons {

struct WindowFailureRule {
  std::size_t consecutive = 4;  // 1 s of the default 0.25 s windows
  std::size_t recent = 20;
  double fraction = 0.5;
  // Throws Error naming the value unless consecutive >= 1, recent >= 1, 0 <= fraction < 1.
  void validate() const;
};

class WindowFailures {
 public:
  enum class Change { none, started, cleared };

  // Registers ambid_windows_unidentified_total{reason} for every reason in `metrics`.
  WindowFailures(WindowFailureRule rule, Metrics& metrics);

  // One window's outcome; returns whether it started or cleared the failing state.
  Change identified();
  Change failed(const ident::WindowFailure& failure);

  bool failing() const { return failing_; }
  // Skipped windows by reason, every reason of ident::window_failure_reasons() listed.
  const std::map<std::string, std::uint64_t>& skipped() const { return skipped_; }
  // For Health: while failing, kFailingWindows + counts, the rule and the last failure; after
  // it cleared, "windows identified again" + the skipped counts. Fits bus::limits::text_length.
  std::string message() const;

 private:
  Change update();

  WindowFailureRule rule_;
  std::deque<bool> recent_;  // the last rule_.recent outcomes, true: failed
  std::size_t consecutive_ = 0;
  bool failing_ = false;
  std::map<std::string, std::uint64_t> skipped_;
  std::map<std::string, prometheus::Counter*> counters_;
  ident::WindowFailure last_;
};

// How the identifier's failing-windows Health message starts.
inline constexpr std::string_view kFailingWindows = "windows not identified: ";

// True when `health` is the identifier of `plant_id` (node PLANT_ID/identifier) in WARN for
// failing windows.
bool reports_failing_windows(const bus::Health& health, const std::string& plant_id);

}  // namespace ambid::daemons
