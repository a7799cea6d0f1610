#include "diagnostics/audit/audit_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "core/error.hpp"

namespace ambid::diag {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double dft_magnitude(const Eigen::VectorXd& s, double f, double dt) {
  std::complex<double> sum = 0.0;
  const std::complex<double> step = std::polar(1.0, -kTwoPi * f * dt);
  std::complex<double> phasor = 1.0;
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    sum += s[k] * phasor;
    phasor *= step;
    if ((k & 1023) == 1023) phasor /= std::abs(phasor);  // keep the recursion on the unit circle
  }
  return std::abs(sum);
}

}  // namespace

Spectrum welch_spectrum(const Eigen::MatrixXd& signals, double sample_time, Eigen::Index segment_length) {
  const Eigen::Index L = segment_length, N = signals.rows();
  if (L < 8 || N < L)
    throw Error("audit: spectrum needs at least one window of " + std::to_string(L) + " samples, got " +
                std::to_string(N));
  Eigen::VectorXd window(L);
  for (Eigen::Index k = 0; k < L; ++k) window[k] = 0.5 - 0.5 * std::cos(kTwoPi * double(k) / double(L));
  const double window_power = window.squaredNorm();
  const Eigen::Index bins = L / 2 + 1, hop = L / 2;
  Spectrum s;
  s.frequency = Eigen::VectorXd::LinSpaced(bins, 0.0, double(bins - 1) / (double(L) * sample_time));
  s.power = Eigen::MatrixXd::Zero(bins, signals.cols());
  // DFT by the recurrence of each bin's twiddle: O(L^2) per window, fine for L ~ 512.
  Eigen::MatrixXcd twiddle(bins, L);
  for (Eigen::Index b = 0; b < bins; ++b)
    for (Eigen::Index k = 0; k < L; ++k) twiddle(b, k) = std::polar(1.0, -kTwoPi * double(b * k % L) / double(L));
  int windows = 0;
  for (Eigen::Index start = 0; start + L <= N; start += hop, ++windows) {
    Eigen::MatrixXd block = signals.middleRows(start, L);
    block.rowwise() -= block.colwise().mean();
    const Eigen::MatrixXcd spectrum = twiddle * (window.asDiagonal() * block).cast<std::complex<double>>();
    s.power += spectrum.cwiseAbs2();
  }
  s.power *= 2.0 * sample_time / (window_power * windows);
  s.power.row(0) *= 0.5;
  return s;
}

Line strongest_line(const Eigen::VectorXd& signal, double sample_time, double f_lo, double f_hi) {
  const Eigen::Index L = std::min<Eigen::Index>(512, signal.size());
  const Spectrum s = welch_spectrum(signal, sample_time, L);
  Eigen::Index best = -1;
  for (Eigen::Index b = 1; b < s.frequency.size(); ++b)
    if (s.frequency[b] >= f_lo && s.frequency[b] <= f_hi && (best < 0 || s.power(b, 0) > s.power(best, 0))) best = b;
  if (best < 0)
    throw Error("audit: no spectral line between " + std::to_string(f_lo) + " and " + std::to_string(f_hi) + " Hz");
  const double bin = s.frequency[1], T = double(signal.size()) * sample_time;
  const Eigen::VectorXd centred = signal.array() - signal.mean();
  double f_best = s.frequency[best], m_best = -1.0;
  for (double f = s.frequency[best] - bin; f <= s.frequency[best] + bin; f += 0.25 / T) {
    const double m = dft_magnitude(centred, f, sample_time);
    if (m > m_best) m_best = m, f_best = f;
  }
  return {f_best, 2.0 * m_best / double(signal.size())};
}

std::vector<double> spectral_peaks(const Eigen::VectorXd& signal, double sample_time, double f_lo, double f_hi,
                                   int count) {
  const Spectrum s = welch_spectrum(signal, sample_time, std::min<Eigen::Index>(512, signal.size()));
  std::vector<Eigen::Index> maxima;
  const Eigen::VectorXd p = s.power.col(0);
  for (Eigen::Index b = 1; b + 1 < p.size(); ++b)
    if (s.frequency[b] >= f_lo && s.frequency[b] <= f_hi && p[b] >= p[b - 1] && p[b] >= p[b + 1]) maxima.push_back(b);
  std::sort(maxima.begin(), maxima.end(), [&](Eigen::Index a, Eigen::Index b) { return p[a] > p[b]; });
  std::vector<double> peaks;
  const double bin = s.frequency[1];
  for (std::size_t i = 0; i < maxima.size() && int(i) < count; ++i)
    peaks.push_back(
        strongest_line(signal, sample_time, s.frequency[maxima[i]] - bin, s.frequency[maxima[i]] + bin).frequency);
  if (peaks.empty()) peaks.push_back(0.5 * (f_lo + f_hi));
  return peaks;
}

double excitation_correlation(const Eigen::VectorXd& residual, const Eigen::VectorXd& excitation,
                              Eigen::Index max_lag) {
  const Eigen::Index N = std::min(residual.size(), excitation.size());
  const Eigen::VectorXd e = residual.head(N).array() - residual.head(N).mean();
  const Eigen::VectorXd r = excitation.head(N).array() - excitation.head(N).mean();
  const double scale = e.norm() * r.norm();
  if (!(scale > 0.0)) return 0.0;
  double best = 0.0;
  for (Eigen::Index lag = 0; lag <= max_lag && lag < N; ++lag)
    best = std::max(best, std::abs(e.tail(N - lag).dot(r.head(N - lag))) / scale);
  return best;
}

}  // namespace ambid::diag
