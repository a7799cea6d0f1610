#pragma once
// The baseline of one parameter of one plant: its nominal value and how much its estimates
// scatter when nothing changes. Change detection works on z = (value - mean) / sigma_eff.
//
// Learned from the first N windows:
//   mean           arithmetic mean of the N values
//   reported_sigma median of the N reported sigmas (what the identifier claims)
//   observed       1.4826 * median absolute deviation of the values (robust scatter, = sd for
//                  Gaussian values, unmoved by a few outliers)
//   extra_spread   tau = sqrt(max(0, observed^2 - reported_sigma^2)): scatter the reported
//                  sigmas do not explain (operating conditions, model error); 0 when the
//                  identifier's sigmas are honest or pessimistic
//   mean_sigma     max(observed, reported_sigma) / sqrt(N), the standard error of the mean
// and then sigma_eff = sqrt(max(sigma, reported_sigma)^2 + tau^2) for an estimate reporting
// sigma: the reported uncertainty of that window, never below the baseline's median, widened
// by the scatter it does not account for. The floor: a window's sigma is itself an estimate
// (pem's sandwich from 50 score blocks of a 0.5 s window scatters by 16-24 % between windows
// of one record), and its low values are overconfident. The stack's bearing, 111 windows of
// 0.5 s: the third with the lowest sigmas reported 0.79 of the median and erred by 0.90, the
// highest third 1.23 and 1.27; the two thirds of the windows where pem stopped at its
// iteration limit reported ~10 % less than the converged ones and erred as much (z sd
// 1.13-1.16 for five of the seven parameters, against 0.95-1.20 converged). Weighted by an unfloored 1/sigma^2, such
// windows inflate the detectors' statistics (noisy_sigma_test.cpp, sigmas scattering 22 %: the slope test's T had
// sd 1.10, 0.93 floored): a cause of false drift alarms (issue 18 item 8; the stack's 5-minute event itself was not
// reproduced). Floored, a window may claim more uncertainty than the baseline's typical one, never less. Without
// identifier sigmas (sigma = 0, e.g. the closed-loop method reports none): reported_sigma = 0, tau = observed, and
// sigma_eff = observed is the whole uncertainty, the window-to-window scatter of the baseline; that needs
// kMinSpreadLearningWindows windows and a non-zero scatter. Given explicitly (a data sheet, a commissioning
// measurement): the mean and optionally tau, with mean_sigma = 0.
#include <cstddef>
#include <span>
#include <string_view>

namespace ambid::diag {

enum class BaselineOrigin { learned, given };
std::string_view to_string(BaselineOrigin origin);  // "learned", "given"
BaselineOrigin parse_baseline_origin(std::string_view text);

struct Baseline {
  double mean = 0.0;
  double extra_spread = 0.0;
  double mean_sigma = 0.0;
  double reported_sigma = 0.0;  // 0 when given
  std::size_t windows = 0;      // 0 when given
  BaselineOrigin origin = BaselineOrigin::given;

  // Throws Error when mean is zero or not finite (changes are relative to it), or a spread is
  // negative or not finite.
  void validate() const;
  double sigma_eff(double sigma) const;
  double z(double value, double sigma) const { return (value - mean) / sigma_eff(sigma); }
  double relative_change(double value) const { return (value - mean) / mean; }
};

// Throws Error for a zero mean or a negative or non-finite extra spread.
Baseline given_baseline(double mean, double extra_spread = 0.0);

constexpr std::size_t kMinLearningWindows = 5;
constexpr std::size_t kMinSpreadLearningWindows = 6;  // when no window reports a sigma

// Learns from values[i] with reported sigmas[i]. Throws InsufficientData for fewer than
// kMinLearningWindows windows (kMinSpreadLearningWindows, or no scatter at all, when the median
// reported sigma is 0) and Error for unequal lengths, a non-finite value, a negative sigma, or
// a zero mean.
Baseline learn_baseline(std::span<const double> values, std::span<const double> sigmas);

}  // namespace ambid::diag
