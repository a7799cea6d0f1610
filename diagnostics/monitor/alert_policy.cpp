#include "diagnostics/monitor/alert_policy.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

constexpr double kErrorMargin = 2.0;  // standard errors of a level (alert_policy.hpp)

// "20", "5.0", "0.032": whole percent from 10 % on, one decimal from 1 %, two significant
// digits below: a parameter estimated to 1e-4 (an amplifier gain) alarms on changes that one
// decimal would print as "0.0 %".
std::string percent(double fraction) {
  const double p = std::abs(fraction) * 100.0;
  char text[32];
  std::snprintf(text, sizeof text, p >= 10.0 ? "%.0f" : p >= 1.0 ? "%.1f" : "%.2g", p);
  return text;
}

std::string signed_percent(double fraction) { return (fraction < 0.0 ? "-" : "+") + percent(fraction); }

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", s);
  return text;
}

}  // namespace

void AlertPolicy::validate() const {
  if (!(error_fraction > 0.0) || !std::isfinite(error_fraction))
    throw Error("alert policy: error_fraction must be positive and finite, got " + std::to_string(error_fraction));
  if (!(warn_fraction >= 0.0 && warn_fraction < error_fraction))
    throw Error("alert policy: warn_fraction must be at least 0 and below error_fraction, got " +
                std::to_string(warn_fraction));
  if (persist_windows < 1) throw Error("alert policy: persist_windows must be at least 1");
  if (confirm_windows < 1) throw Error("alert policy: confirm_windows must be at least 1");
  if (!(stale_timeout > 0.0) || !std::isfinite(stale_timeout))
    throw Error("alert policy: stale_timeout must be positive and finite, got " + std::to_string(stale_timeout));
}

Level AlertPolicy::level(const SeriesStatus& status, Level episode) const {
  if (status.learning || status.change == Change::none || std::abs(status.relative) < warn_fraction) return Level::ok;
  const bool large = std::abs(status.relative) + kErrorMargin * status.relative_sigma >= error_fraction;
  const bool persistent = status.change == Change::step && status.step_windows >= persist_windows;
  const Level now = large || persistent ? Level::error : Level::warn;
  return episode == Level::error ? Level::error : now;
}

std::string change_message(const Isolation& isolation, const SeriesStatus& status, const AlertPolicy& policy,
                           std::size_t slope_window) {
  std::string text = isolation.subject;
  if (isolation.shared) text += ": " + isolation.parameter;
  text += " " + percent(status.relative) + " % " + (status.relative >= 0.0 ? "above" : "below") + " baseline";
  if (status.change == Change::drift)
    return text + " (drifting: " + signed_percent(status.drift_relative) + " % over the last " +
           std::to_string(slope_window) + " windows)";
  if (status.step_windows >= policy.persist_windows && std::abs(status.relative) < policy.error_fraction)
    return text + " (step, persisting " + std::to_string(status.step_windows) + " windows)";
  return text + " (step)";
}

std::string ok_message(std::string_view subject, const SeriesStatus& status, Level previous,
                       std::size_t learning_windows) {
  std::string text(subject);
  if (status.learning)
    text += ": learning baseline (" + std::to_string(status.learned_windows) + " of " +
            std::to_string(learning_windows) + " windows)";
  else
    text += previous == Level::warn || previous == Level::error ? " back within baseline" : " within baseline";
  if (previous == Level::stale) text += " (estimates resumed)";
  return text;
}

std::string stale_message(std::string_view subject, double silent_for, double timeout) {
  return std::string(subject) + ": no estimate for " + seconds(silent_for) + " s (timeout " + seconds(timeout) + " s)";
}

std::string stale_message(std::string_view subject, std::string_view reason) {
  return std::string(subject) + ": no estimate: " + std::string(reason);
}

}  // namespace ambid::diag
