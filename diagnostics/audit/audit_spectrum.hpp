#pragma once
// What the residual of a model says about the missing physics: its spectrum (lines, trends
// with frequency), the frequency of its strongest line, and how much of it is coherent with
// the excitation (a wrong plant) rather than not (a disturbance or noise).
#include <vector>

#include <Eigen/Core>

namespace ambid::diag {

struct Spectrum {
  Eigen::VectorXd frequency;  // Hz, 0 .. Nyquist
  Eigen::MatrixXd power;      // one-sided PSD per column of the input, units^2 / Hz
};

// Welch estimate: Hann windows of `segment_length` samples (a power of two is not needed),
// half overlapping, mean removed per window. Error when the signal is shorter than a window.
Spectrum welch_spectrum(const Eigen::MatrixXd& signals, double sample_time, Eigen::Index segment_length);

struct Line {
  double frequency = 0.0;  // Hz
  double amplitude = 0.0;  // of the best-fitting sinusoid, units of the signal
};
// The sinusoid in [f_lo, f_hi] that best fits `signal`: the largest DFT magnitude on a grid
// of 1/(4 T) (T the record length), searched around the Welch peak. Error for an empty band.
Line strongest_line(const Eigen::VectorXd& signal, double sample_time, double f_lo, double f_hi);

// The frequencies of the `count` largest local maxima of the Welch spectrum (512-sample
// windows) in [f_lo, f_hi], largest first, each refined by strongest_line within one bin.
std::vector<double> spectral_peaks(const Eigen::VectorXd& signal, double sample_time, double f_lo, double f_hi,
                                   int count);

// max over lags 0..max_lag of |correlation coefficient| between residual[k] and excitation[k - lag].
double excitation_correlation(const Eigen::VectorXd& residual, const Eigen::VectorXd& excitation, Eigen::Index max_lag);

}  // namespace ambid::diag
