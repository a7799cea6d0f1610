#pragma once
// An alert about one monitored parameter of one plant, as experiment-format.md "Diagnosis"
// specifies it, with the levels of ROS diagnostic_msgs/DiagnosticStatus (OK=0, WARN=1,
// ERROR=2, STALE=3).
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace ambid::diag {

enum class Level { ok = 0, warn = 1, error = 2, stale = 3 };

std::string_view to_string(Level level);  // "OK", "WARN", "ERROR", "STALE"
// Throws Error naming the text and the accepted names.
Level parse_level(std::string_view text);

struct Alert {
  double time = 0.0;  // seconds, time of the estimate window (or the staleness check) that raised it
  std::string plant_id;
  Level level = Level::ok;
  std::string fault;               // effect vocabulary name (fault_isolation.hpp)
  std::optional<int> channel;      // 1-based coil/amplifier; empty for both channels or none
  std::string parameter;           // the physical parameter the alert is about: R1, kw1, ...
  double value = 0.0;              // its current level (estimate of the changed value)
  std::optional<double> baseline;  // empty while the baseline is still being learned
  std::string message;             // e.g. "coil 1 resistance 20 % above baseline (step)"

  bool operator==(const Alert&) const = default;
};

// {"time", "plant_id", "level", "fault", "channel", "parameter", "value", "baseline",
// "message"}; an empty channel or baseline is null.
nlohmann::json to_json(const Alert& alert);
// Throws Error naming the missing or malformed key; unknown keys are ignored.
Alert alert_from_json(const nlohmann::json& j);

}  // namespace ambid::diag
