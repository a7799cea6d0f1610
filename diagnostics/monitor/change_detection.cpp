#include "diagnostics/monitor/change_detection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw Error(what);
}

bool finite_non_negative(double x) { return x >= 0.0 && std::isfinite(x); }

double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi); }
double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// Siegmund & Yakir (2007) approximation of the overshoot correction nu(x).
double overshoot_nu(double x) {
  if (x < 1e-9) return 1.0;
  const double half = 0.5 * x;
  return (2.0 / x) * (normal_cdf(half) - 0.5) / (half * normal_cdf(half) + normal_pdf(half));
}

}  // namespace

void CusumConfig::validate() const {
  require(finite_non_negative(k), "CUSUM: k must be non-negative and finite, got " + std::to_string(k));
  require(h > 0.0 && std::isfinite(h), "CUSUM: h must be positive and finite, got " + std::to_string(h));
  require(finite_non_negative(clear_level) && clear_level < h,
          "CUSUM: clear_level must be in [0, h), got " + std::to_string(clear_level) + " with h " + std::to_string(h));
  require(clear_windows >= 1, "CUSUM: clear_windows must be at least 1");
  require(finite_non_negative(baseline_allowance),
          "CUSUM: baseline_allowance must be non-negative and finite, got " + std::to_string(baseline_allowance));
}

Cusum::Cusum(const CusumConfig& config) : config_(config) { config_.validate(); }

void Cusum::update(double z, double k_raise) {
  require(std::isfinite(z), "CUSUM: normalised estimate is not finite");
  require(finite_non_negative(k_raise), "CUSUM: k raise must be non-negative, got " + std::to_string(k_raise));
  const double k = config_.k + k_raise;
  upper_ = std::max(0.0, upper_ + z - k);
  lower_ = std::max(0.0, lower_ - z - k);
  if (!alarmed_ && std::max(upper_, lower_) > config_.h) alarmed_ = true;
  if (!alarmed_) return;
  ++alarm_windows_;
  upper_ = std::min(upper_, config_.h);
  lower_ = std::min(lower_, config_.h);
  clean_windows_ = std::max(upper_, lower_) < config_.clear_level ? clean_windows_ + 1 : 0;
  if (clean_windows_ >= config_.clear_windows) reset();
}

int Cusum::direction() const {
  if (!alarmed_) return 0;
  return upper_ >= lower_ ? 1 : -1;
}

void Cusum::reset() {
  upper_ = 0.0;
  lower_ = 0.0;
  alarmed_ = false;
  alarm_windows_ = 0;
  clean_windows_ = 0;
}

void SlopeConfig::validate() const {
  require(window >= 3, "slope test: window must be at least 3, got " + std::to_string(window));
  require(threshold > 0.0 && std::isfinite(threshold),
          "slope test: threshold must be positive and finite, got " + std::to_string(threshold));
  require(finite_non_negative(clear_threshold) && clear_threshold < threshold,
          "slope test: clear_threshold must be in [0, threshold), got " + std::to_string(clear_threshold));
  require(clear_windows >= 1, "slope test: clear_windows must be at least 1");
}

SlopeTest::SlopeTest(const SlopeConfig& config) : config_(config) { config_.validate(); }

void SlopeTest::update(double time, double value, double sigma_eff) {
  require(std::isfinite(time) && std::isfinite(value), "slope test: time or value is not finite");
  require(sigma_eff > 0.0 && std::isfinite(sigma_eff),
          "slope test: sigma must be positive and finite, got " + std::to_string(sigma_eff));
  if (!points_.empty() && !(time > points_.back().time))
    throw Error("slope test: time " + std::to_string(time) + " does not follow " + std::to_string(points_.back().time));
  points_.push_back({time, value, 1.0 / (sigma_eff * sigma_eff)});
  if (points_.size() > config_.window) points_.pop_front();
  if (!ready()) return;
  fit();
  if (!alarmed_) {
    alarmed_ = std::abs(statistic_) > config_.threshold;
    return;
  }
  clean_windows_ = std::abs(statistic_) < config_.clear_threshold ? clean_windows_ + 1 : 0;
  if (clean_windows_ >= config_.clear_windows) {
    alarmed_ = false;
    clean_windows_ = 0;
  }
}

void SlopeTest::fit() {
  // Times relative to the first point keep the sums well conditioned for epoch times.
  const double t0 = points_.front().time;
  double sw = 0.0, swt = 0.0, swv = 0.0;
  for (const Point& p : points_) {
    sw += p.weight;
    swt += p.weight * (p.time - t0);
    swv += p.weight * p.value;
  }
  const double t_mean = swt / sw, v_mean = swv / sw;
  double stt = 0.0, stv = 0.0;
  for (const Point& p : points_) {
    const double dt = p.time - t0 - t_mean;
    stt += p.weight * dt * dt;
    stv += p.weight * dt * (p.value - v_mean);
  }
  slope_ = stv / stt;
  statistic_ = slope_ * std::sqrt(stt);
  const double dt_last = points_.back().time - t0 - t_mean;
  level_ = v_mean + slope_ * dt_last;
  level_sigma_ = std::sqrt(1.0 / sw + dt_last * dt_last / stt);
}

double SlopeTest::change_over_window() const { return slope_ * (points_.back().time - points_.front().time); }

double cusum_arl(double k, double h, double mean) {
  require(finite_non_negative(k) && h > 0.0 && std::isfinite(h) && std::isfinite(mean),
          "cusum_arl: need k >= 0, h > 0 and a finite mean");
  const double delta = mean - k;
  const double b = h + 1.166;
  if (std::abs(delta) < 1e-9) return b * b;
  return (std::exp(-2.0 * delta * b) + 2.0 * delta * b - 1.0) / (2.0 * delta * delta);
}

double two_sided_cusum_arl(double k, double h, double mean) {
  return 1.0 / (1.0 / cusum_arl(k, h, mean) + 1.0 / cusum_arl(k, h, -mean));
}

double slope_test_arl0(std::size_t window, double threshold) {
  require(window >= 3 && threshold > 0.0 && std::isfinite(threshold),
          "slope_test_arl0: need window >= 3 and a positive threshold");
  const double theta = 3.0 / static_cast<double>(window);
  const double c = threshold;
  return 1.0 / (2.0 * theta * c * normal_pdf(c) * overshoot_nu(c * std::sqrt(2.0 * theta)));
}

double slope_test_expected_statistic(std::size_t window, double rate, std::size_t windows_on_ramp) {
  require(window >= 3 && std::isfinite(rate), "slope_test_expected_statistic: need window >= 3 and a finite rate");
  const double w = static_cast<double>(window);
  const double centre = (w - 1.0) / 2.0;
  const double sxx = w * (w * w - 1.0) / 12.0;
  double sum = 0.0;
  for (std::size_t j = 0; j < window; ++j) {
    // position j holds the value of ramp index windows_on_ramp - window + j (ramp value r (i+1)).
    const double on_ramp = static_cast<double>(windows_on_ramp) - w + static_cast<double>(j) + 1.0;
    sum += (static_cast<double>(j) - centre) * rate * std::max(0.0, on_ramp);
  }
  return sum / std::sqrt(sxx);
}

}  // namespace ambid::diag
