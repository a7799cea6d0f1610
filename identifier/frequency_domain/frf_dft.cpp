#include "identifier/frequency_domain/frf_dft.hpp"

#include <complex>
#include <string>

#include <unsupported/Eigen/FFT>

#include "core/error.hpp"

namespace ambid::ident {

std::vector<Eigen::MatrixXcd> period_phasors(const Eigen::MatrixXd& x, Eigen::Index first, Eigen::Index period,
                                             Eigen::Index count, const std::vector<Eigen::Index>& lines) {
  if (period < 2) throw Error("period phasors: period must be at least 2 samples, got " + std::to_string(period));
  if (count < 1) throw Error("period phasors: need at least one period, got " + std::to_string(count));
  if (first < 0 || first + count * period > x.rows())
    throw Error("period phasors: " + std::to_string(count) + " periods of " + std::to_string(period) +
                " samples from sample " + std::to_string(first) + " do not fit in " + std::to_string(x.rows()) +
                " samples");
  for (const Eigen::Index k : lines)
    if (k < 0 || 2 * k > period)
      throw Error("period phasors: line " + std::to_string(k) + " is outside [0, " + std::to_string(period / 2) +
                  "] for a period of " + std::to_string(period) + " samples");

  Eigen::FFT<double> fft;
  std::vector<double> segment(static_cast<std::size_t>(period));
  std::vector<std::complex<double>> spectrum;
  const double scale = 2.0 / static_cast<double>(period);
  const auto nl = static_cast<Eigen::Index>(lines.size());
  std::vector<Eigen::MatrixXcd> out(static_cast<std::size_t>(count), Eigen::MatrixXcd(nl, x.cols()));
  for (Eigen::Index p = 0; p < count; ++p) {
    for (Eigen::Index c = 0; c < x.cols(); ++c) {
      for (Eigen::Index n = 0; n < period; ++n) segment[static_cast<std::size_t>(n)] = x(first + p * period + n, c);
      fft.fwd(spectrum, segment);  // e^{-j 2 pi k n / N}, unscaled
      for (Eigen::Index l = 0; l < nl; ++l)
        out[static_cast<std::size_t>(p)](l, c) =
            scale * spectrum[static_cast<std::size_t>(lines[static_cast<std::size_t>(l)])];
    }
  }
  return out;
}

}  // namespace ambid::ident
