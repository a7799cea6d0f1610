#include "diagnostics/monitor/series_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace ambid::diag {

void MonitorConfig::validate() const {
  if (learning_windows < kMinLearningWindows)
    throw Error("monitor: learning_windows must be at least " + std::to_string(kMinLearningWindows) + ", got " +
                std::to_string(learning_windows));
  if (!(unconverged_sigma_ratio > 1.0))
    throw Error("monitor: unconverged_sigma_ratio must be > 1, got " + std::to_string(unconverged_sigma_ratio));
  cusum.validate();
  slope.validate();
}

SeriesMonitor::SeriesMonitor(const MonitorConfig& config, std::optional<Baseline> baseline)
    : config_(config), baseline_(std::move(baseline)), cusum_(config.cusum), slope_(config.slope) {
  config_.validate();
  if (baseline_) baseline_->validate();
}

bool SeriesMonitor::update(double time, double value, double sigma) {
  if (!std::isfinite(time) || !std::isfinite(value) || !(sigma >= 0.0) || !std::isfinite(sigma))
    throw Error("monitor: estimate at t=" + std::to_string(time) +
                " needs a finite value and a non-negative sigma, got " + std::to_string(value) + " +- " +
                std::to_string(sigma));
  if (last_time_ && !(time > *last_time_))
    throw Error("monitor: estimate at t=" + std::to_string(time) + " does not follow t=" + std::to_string(*last_time_));
  last_time_ = time;
  if (!baseline_) {
    learn_values_.push_back(value);
    learn_sigmas_.push_back(sigma);
    if (learn_values_.size() < config_.learning_windows) return false;
    baseline_ = learn_baseline(learn_values_, learn_sigmas_);
    learn_values_.clear();
    learn_sigmas_.clear();
    return true;
  }
  const double sigma_eff = baseline_->sigma_eff(sigma);
  if (!(sigma_eff > 0.0))
    throw Error("monitor: estimate at t=" + std::to_string(time) +
                " reports sigma 0 and the baseline learned no "
                "extra spread: no sigma_eff to test it with");
  const bool was_step = cusum_.alarmed();
  cusum_.update(baseline_->z(value, sigma), config_.cusum.baseline_allowance * baseline_->mean_sigma / sigma_eff);
  // The edges of a step look like a steep slope to the slope test for a whole window; once a
  // step has come and gone it starts afresh, so the step's return is not reported as a drift.
  if (was_step && !cusum_.alarmed()) slope_ = SlopeTest(config_.slope);
  slope_.update(time, value, sigma_eff);
  recent_.push_back({value, sigma_eff, baseline_->z(value, sigma)});
  if (recent_.size() > config_.slope.window) recent_.pop_front();
  return false;
}

bool SeriesMonitor::converged(double sigma) const {
  return !baseline_ || !(sigma > config_.unconverged_sigma_ratio * baseline_->reported_sigma) ||
         baseline_->reported_sigma == 0.0;
}

SeriesStatus SeriesMonitor::status() const {
  SeriesStatus s;
  if (!baseline_) {
    s.learned_windows = learn_values_.size();
    return s;
  }
  s.learning = false;
  if (recent_.empty()) {
    s.level = baseline_->mean;
    return s;
  }
  const double mean = baseline_->mean;
  if (cusum_.alarmed()) {
    // The change point: of the recent windows, the last m whose normalised sum, in the
    // direction of the alarm, is largest relative to sqrt(m) (the GLR estimate for a step of
    // unknown size); the level is their mean.
    s.change = Change::step;
    s.step_windows = cusum_.alarm_windows();
    const double direction = cusum_.direction();
    double z_sum = 0.0, best = -std::numeric_limits<double>::infinity();
    std::size_t m = 1;
    for (std::size_t i = 1; i <= recent_.size(); ++i) {
      z_sum += direction * recent_[recent_.size() - i].z;
      const double score = z_sum / std::sqrt(static_cast<double>(i));
      if (score > best) {
        best = score;
        m = i;
      }
    }
    double sum = 0.0, variance = 0.0;
    for (std::size_t i = recent_.size() - m; i < recent_.size(); ++i) {
      sum += recent_[i].value;
      variance += recent_[i].sigma_eff * recent_[i].sigma_eff;
    }
    s.level = sum / static_cast<double>(m);
    s.relative_sigma = std::sqrt(variance) / static_cast<double>(m) / std::abs(mean);
  } else if (slope_.alarmed()) {
    s.change = Change::drift;
    s.level = slope_.level();
    s.relative_sigma = slope_.level_sigma() / std::abs(mean);
  } else {
    s.level = recent_.back().value;
    s.relative_sigma = recent_.back().sigma_eff / std::abs(mean);
  }
  s.relative = baseline_->relative_change(s.level);
  if (slope_.ready()) s.drift_relative = slope_.change_over_window() / mean;
  return s;
}

}  // namespace ambid::diag
