#include "services/daemons/window_failures.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace ambid::daemons {
namespace {

std::string counts(const std::map<std::string, std::uint64_t>& skipped) {
  std::string s;
  for (const auto& [reason, n] : skipped) s += (s.empty() ? "" : ", ") + reason + " " + std::to_string(n);
  return s;
}

}  // namespace

void WindowFailureRule::validate() const {
  if (consecutive < 1) throw Error("window failure rule: consecutive must be >= 1, got " + std::to_string(consecutive));
  if (recent < 1) throw Error("window failure rule: recent must be >= 1, got " + std::to_string(recent));
  if (!(fraction >= 0.0 && fraction < 1.0))
    throw Error("window failure rule: fraction must be in [0, 1), got " + std::to_string(fraction));
}

WindowFailures::WindowFailures(WindowFailureRule rule, Metrics& metrics) : rule_(rule) {
  rule_.validate();
  for (const std::string& reason : ident::window_failure_reasons()) {
    skipped_[reason] = 0;
    counters_[reason] = &metrics.counter("ambid_windows_unidentified_total",
                                         "windows the method could not identify, by reason", {{"reason", reason}});
  }
}

WindowFailures::Change WindowFailures::identified() {
  consecutive_ = 0;
  recent_.push_back(false);
  return update();
}

WindowFailures::Change WindowFailures::failed(const ident::WindowFailure& failure) {
  ++consecutive_;
  ++skipped_.at(failure.reason);
  counters_.at(failure.reason)->Increment();
  last_ = failure;
  recent_.push_back(true);
  return update();
}

WindowFailures::Change WindowFailures::update() {
  if (recent_.size() > rule_.recent) recent_.pop_front();
  const auto failed = std::size_t(std::count(recent_.begin(), recent_.end(), true));
  // The fraction over the windows seen so far once there are `consecutive` of them: a
  // stream that starts failing does not flap between a failure run and the first success.
  const bool now = consecutive_ >= rule_.consecutive ||
                   (recent_.size() >= rule_.consecutive && double(failed) > rule_.fraction * double(recent_.size()));
  const Change change = now == failing_ ? Change::none : (now ? Change::started : Change::cleared);
  failing_ = now;
  return change;
}

std::string WindowFailures::message() const {
  std::string text;
  if (failing_) {
    const auto failed = std::size_t(std::count(recent_.begin(), recent_.end(), true));
    text = std::string(kFailingWindows) + std::to_string(consecutive_) + " in a row, " + std::to_string(failed) +
           " of the last " + std::to_string(recent_.size()) + " (rule: " + std::to_string(rule_.consecutive) +
           " in a row or more than " + std::to_string(int(std::lround(100 * rule_.fraction))) + " % of " +
           std::to_string(rule_.recent) + "); last " + last_.reason + ": " + last_.message;
  } else {
    text = "windows identified again; skipped so far: " + counts(skipped_);
  }
  return text.substr(0, bus::limits::text_length);
}

bool reports_failing_windows(const bus::Health& health, const std::string& plant_id) {
  return health.node == plant_id + "/identifier" && health.level == bus::AlertLevel::warn &&
         health.message.starts_with(kFailingWindows);
}

}  // namespace ambid::daemons
