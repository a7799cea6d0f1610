#pragma once
// Change detection on normalised estimates z = (value - baseline mean) / sigma_eff
// (baseline.hpp), which are N(0, 1) while nothing changes and N(delta, 1) after a step of
// delta standard deviations. Two detectors with hysteresis, so that an alarm neither flaps nor
// lingers:
//
// Cusum — two-sided CUSUM for steps (Page 1954):
//   S+[n] = max(0, S+[n-1] + z[n] - k),  S-[n] = max(0, S-[n-1] - z[n] - k)
//   raised when S+ or S- exceeds h; while raised both are capped at h; cleared (and reset to 0)
//   after `clear_windows` consecutive windows with max(S+, S-) < clear_level. Back at the
//   baseline the statistic falls by about k per window, so an alarm clears about
//   (h - clear_level)/k + clear_windows windows after the change went away.
//   Run lengths (Siegmund's approximation, cusum_arl below), one-sided, for z of
//   mean mu, with Delta = mu - k and b = h + 1.166 (the 1.166 corrects for the overshoot of a
//   discrete walk):
//       ARL(mu) = (exp(-2 Delta b) + 2 Delta b - 1) / (2 Delta^2)     (b^2 when Delta = 0)
//   - false-alarm rate: ARL0 = ARL(0) of each side; two-sided 1/ARL0 = 1/ARL+ + 1/ARL-, so
//     ARL0 = ARL(0)/2 = (exp(2kb) - 2kb - 1)/(4 k^2); false alarms per window ~ 1/ARL0 for
//     each monitored parameter (P parameters of a plant: ~P/ARL0 per window for the plant).
//     k = 0.5, h = 4: 169 windows; h = 10: 7.1e4; h = 12 (default): 5.2e5.
//   - detection delay of a step of delta > k (windows from the first changed one to the
//     alarm, both included, starting from S = 0): ARL(delta) ~ (h + 1.166)/(delta - k)
//     - 1/(2 (delta - k)^2), at least one window; a step delta > h + k alarms in its first
//     window. For delta - k >> 1 the formula runs a few tenths of a window short of the
//     discrete truth (k = 0.5, h = 8, delta = 4: 2.6 against 2.8 simulated).
//   k is best at half the step to detect fastest; h sets ARL0 (exponentially) and the delay
//   (linearly).
//   A learned baseline mean is itself uncertain (standard error mean_sigma): its error is a
//   permanent shift of z and shortens ARL0 sharply (k = 0.5, h = 12: a 0.3 sigma error cuts
//   ARL0 from 5.2e5 to about 2.4e3). The monitor therefore raises k, per window, by
//   baseline_allowance * mean_sigma / sigma_eff: an error of up to baseline_allowance standard
//   errors then leaves ARL0 at least at the formula's value for k; delays use the raised k.
//
// SlopeTest — weighted least-squares slope of the last `window` values against time, with
// weights 1/sigma_eff^2, and its statistic T = slope / sd(slope) (sd from the sigmas, so T is
// N(0, 1) under H0 and needs no baseline). Raised when |T| > threshold, cleared after
// `clear_windows` consecutive windows with |T| < clear_threshold.
//   For equally spaced windows, consecutive T have correlation 1 - 3/W (W = window), and the
//   false alarms come in clumps; the clump rate gives (Siegmund & Yakir's approximation for a
//   locally Brownian Gaussian sequence, slope_test_arl0):
//       ARL0 ~ 1 / (2 theta c phi(c) nu(c sqrt(2 theta))),   theta = 3/W, c = threshold,
//   phi the normal density and nu(x) = (2/x)(Phi(x/2) - 1/2) / ((x/2) Phi(x/2) + phi(x/2)).
//   W = 20, c = 2.5: 171 windows; W = 50, c = 5 (default): 3.1e6.
//   Detection: a drift of r sigma_eff per window gives E[T] = r sqrt(W (W^2 - 1)/12) once the
//   whole window is on the ramp (slope_test_expected_statistic gives E[T] while the ramp
//   enters the window); drifts slower than threshold / sqrt(W (W^2 - 1)/12) (0.049 sigma per
//   window for W = 50, c = 5) are left to the CUSUM, which catches them as a growing step.
#include <cstddef>
#include <deque>

namespace ambid::diag {

struct CusumConfig {
  double k = 0.5;   // reference value, in sigma_eff
  double h = 12.0;  // decision interval
  double clear_level = 6.0;
  std::size_t clear_windows = 5;
  double baseline_allowance = 2.0;  // k is raised by this many standard errors of the baseline mean
  // Throws Error unless k >= 0, h > 0, 0 <= clear_level < h, clear_windows >= 1,
  // baseline_allowance >= 0, all finite.
  void validate() const;
};

class Cusum {
 public:
  explicit Cusum(const CusumConfig& config);
  // One normalised estimate; k_raise (>= 0) is added to k for this window.
  void update(double z, double k_raise = 0.0);
  bool alarmed() const { return alarmed_; }
  // +1 when the raised alarm is for an increase, -1 for a decrease; 0 when not alarmed.
  int direction() const;
  // Windows since the alarm was raised (1 in the window that raised it). 0 when not alarmed.
  std::size_t alarm_windows() const { return alarm_windows_; }
  double upper() const { return upper_; }
  double lower() const { return lower_; }

 private:
  void reset();

  CusumConfig config_;
  double upper_ = 0.0, lower_ = 0.0;
  bool alarmed_ = false;
  std::size_t alarm_windows_ = 0;
  std::size_t clean_windows_ = 0;
};

struct SlopeConfig {
  std::size_t window = 50;
  double threshold = 5.0;
  double clear_threshold = 3.0;
  std::size_t clear_windows = 5;
  // Throws Error unless window >= 3, 0 <= clear_threshold < threshold, clear_windows >= 1.
  void validate() const;
};

class SlopeTest {
 public:
  explicit SlopeTest(const SlopeConfig& config);
  // Times must increase strictly (Error otherwise); sigma_eff > 0.
  void update(double time, double value, double sigma_eff);
  // True once `window` values are in; statistic(), slope() and level() need it.
  bool ready() const { return points_.size() == config_.window; }
  double statistic() const { return statistic_; }
  double slope() const { return slope_; }  // value units per second
  // The fitted line at the latest time: the drift-corrected current level.
  double level() const { return level_; }
  double level_sigma() const { return level_sigma_; }
  // Fitted change over the window: slope * (latest time - first time).
  double change_over_window() const;
  bool alarmed() const { return alarmed_; }

 private:
  struct Point {
    double time, value, weight;
  };
  void fit();

  SlopeConfig config_;
  std::deque<Point> points_;
  double statistic_ = 0.0, slope_ = 0.0, level_ = 0.0, level_sigma_ = 0.0;
  bool alarmed_ = false;
  std::size_t clean_windows_ = 0;
};

// The formulas above.
// One-sided CUSUM (reference k, interval h) on N(mean, 1): average run length (Siegmund).
double cusum_arl(double k, double h, double mean);
// Two-sided: 1 / (1/ARL+(mean) + 1/ARL-(mean)), the lower side seeing -mean.
double two_sided_cusum_arl(double k, double h, double mean);
// Average number of windows (statistics evaluated) before |T| first exceeds threshold under
// H0, equally spaced windows.
double slope_test_arl0(std::size_t window, double threshold);
// E[T] when a ramp of `rate` sigma_eff per window began `windows_on_ramp` windows ago
// (the first ramp value is `rate` above the baseline), equally spaced windows.
double slope_test_expected_statistic(std::size_t window, double rate, std::size_t windows_on_ramp);

}  // namespace ambid::diag
