// Fit data preparation and the Sanathanan-Koerner iterations.
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/frequency_domain/rational_fit_detail.hpp"

namespace ambid::ident::detail {

std::complex<double> polyval(const Eigen::VectorXd& c, std::complex<double> x) {
  std::complex<double> v = 0.0;
  for (Eigen::Index i = c.size() - 1; i >= 0; --i) v = v * x + c(i);
  return v;
}

std::complex<double> monic_polyval(const Eigen::VectorXd& a_low, std::complex<double> x) {
  std::complex<double> v = 1.0;
  for (Eigen::Index i = a_low.size() - 1; i >= 0; --i) v = v * x + a_low(i);
  return v;
}

FitData prepare_fit_data(const Eigen::VectorXd& f, const Eigen::VectorXcd& G, const Eigen::VectorXd& variance,
                         const RationalFitOptions& o) {
  const Eigen::Index K = f.size();
  if (G.size() != K)
    throw Error("rational fit: " + std::to_string(G.size()) + " responses for " + std::to_string(K) + " frequencies");
  if (variance.size() != 0 && variance.size() != K)
    throw Error("rational fit: " + std::to_string(variance.size()) + " variances for " + std::to_string(K) +
                " frequencies");
  if (o.denominator_degree < 1)
    throw Error("rational fit: denominator degree must be >= 1, got " + std::to_string(o.denominator_degree));
  if (o.numerator_degree < 0 || o.numerator_degree > o.denominator_degree)
    throw Error("rational fit: numerator degree must be in [0, " + std::to_string(o.denominator_degree) + "], got " +
                std::to_string(o.numerator_degree));
  if (!(o.delay >= 0.0) || !std::isfinite(o.delay))
    throw Error("rational fit: delay must be >= 0, got " + std::to_string(o.delay));
  if (!(o.zoh_sample_time >= 0.0) || !std::isfinite(o.zoh_sample_time))
    throw Error("rational fit: zoh_sample_time must be >= 0, got " + std::to_string(o.zoh_sample_time));
  for (Eigen::Index k = 0; k < K; ++k) {
    if (!(f(k) > 0.0) || !std::isfinite(f(k)) || (k > 0 && !(f(k) > f(k - 1))))
      throw Error("rational fit: frequencies must be positive and increasing, line " + std::to_string(k) + " has " +
                  std::to_string(f(k)));
    if (!std::isfinite(G(k).real()) || !std::isfinite(G(k).imag()))
      throw Error("rational fit: response at " + std::to_string(f(k)) + " Hz is not finite");
    if (o.zoh_sample_time > 0.0 && !(2.0 * f(k) * o.zoh_sample_time < 1.0))
      throw Error("rational fit: line " + std::to_string(f(k)) +
                  " Hz is not below the Nyquist frequency of the ZOH sampling");
  }
  const int p = o.numerator_degree + 1 + o.denominator_degree;
  if (K < p)
    throw InsufficientData("rational fit: " + std::to_string(K) + " lines for " + std::to_string(p) + " parameters");

  FitData d;
  d.weighting = o.weighting;
  if (d.weighting == FitWeighting::automatic)
    d.weighting = variance.size() ? FitWeighting::noise : FitWeighting::relative;
  if (d.weighting == FitWeighting::noise && variance.size() == 0)
    throw Error("rational fit: noise weighting needs variances");
  const Eigen::VectorXd omega = 2.0 * std::numbers::pi * f;
  d.w0 = omega.maxCoeff();
  d.x = std::complex<double>(0.0, 1.0) * omega.cast<std::complex<double>>() / d.w0;
  d.g.resize(K);
  d.w.resize(K);
  for (Eigen::Index k = 0; k < K; ++k) {
    std::complex<double> c = std::polar(1.0, omega(k) * o.delay);
    if (o.zoh_sample_time > 0.0) {
      const double T = o.zoh_sample_time;
      const std::complex<double> h = (1.0 - std::polar(1.0, -omega(k) * T)) / std::complex<double>(0.0, omega(k) * T);
      c /= h;
    }
    d.g(k) = G(k) * c;
    switch (d.weighting) {
      case FitWeighting::noise:
        if (!(variance(k) > 0.0) || !std::isfinite(variance(k)))
          throw Error("rational fit: variance at " + std::to_string(f(k)) + " Hz must be positive, got " +
                      std::to_string(variance(k)));
        d.w(k) = 1.0 / std::sqrt(variance(k) * std::norm(c));
        break;
      case FitWeighting::relative:
        if (!(std::abs(d.g(k)) > 0.0))
          throw Error("rational fit: relative weighting with a zero response at " + std::to_string(f(k)) + " Hz");
        d.w(k) = 1.0 / std::abs(d.g(k));
        break;
      default:
        d.w(k) = 1.0;
    }
  }
  return d;
}

double weighted_misfit(const FitData& d, const Eigen::VectorXd& b, const Eigen::VectorXd& a_low) {
  double s = 0.0;
  for (Eigen::Index k = 0; k < d.x.size(); ++k)
    s += std::norm(d.w(k) * (polyval(b, d.x(k)) / monic_polyval(a_low, d.x(k)) - d.g(k)));
  return s / static_cast<double>(d.x.size());
}

Coefficients sanathanan_koerner(const FitData& d, int m, int n, int iterations, double tolerance, int* used) {
  const Eigen::Index K = d.x.size();
  const Eigen::Index nb = m + 1, na = n, p = nb + na;
  Coefficients c;
  c.a_low = Eigen::VectorXd::Zero(na);
  Eigen::VectorXcd Dprev = Eigen::VectorXcd::Ones(K);
  int it = 0;
  for (; it < std::max(1, iterations); ++it) {
    Eigen::MatrixXd A(2 * K, p);
    Eigen::VectorXd rhs(2 * K);
    for (Eigen::Index k = 0; k < K; ++k) {
      if (!(std::abs(Dprev(k)) > 1e-300))
        throw InsufficientData("rational fit: the SK denominator vanished at a data line (a pole on the axis)");
      const std::complex<double> scale = d.w(k) / Dprev(k);
      std::complex<double> xi = 1.0;
      for (Eigen::Index i = 0; i <= std::max<Eigen::Index>(m, n); ++i) {
        if (i < nb) {
          const std::complex<double> v = scale * xi;
          A(2 * k, i) = v.real();
          A(2 * k + 1, i) = v.imag();
        }
        if (i < na) {
          const std::complex<double> v = -scale * d.g(k) * xi;
          A(2 * k, nb + i) = v.real();
          A(2 * k + 1, nb + i) = v.imag();
        }
        if (i == n) {
          const std::complex<double> v = scale * d.g(k) * xi;
          rhs(2 * k) = v.real();
          rhs(2 * k + 1) = v.imag();
        }
        xi *= d.x(k);
      }
    }
    Eigen::VectorXd colnorm = A.colwise().norm().transpose();
    for (Eigen::Index j = 0; j < p; ++j) {
      if (!(colnorm(j) > 0.0)) throw InsufficientData("rational fit: a regressor column is zero");
      A.col(j) /= colnorm(j);
    }
    const linalg::RankedSolution<Eigen::VectorXd> ls = linalg::qr_solve(A, rhs, 1e-13);
    if (ls.rank < p)
      throw InsufficientData("rational fit: the least-squares problem of order (" + std::to_string(m) + ", " +
                             std::to_string(n) + ") is rank deficient (rank " + std::to_string(ls.rank) + " of " +
                             std::to_string(p) + ")");
    const Eigen::VectorXd theta = (ls.x.array() / colnorm.array()).matrix();
    const Eigen::VectorXd a_new = theta.tail(na);
    const double change = (a_new - c.a_low).norm() / (1.0 + a_new.norm());
    c.b = theta.head(nb);
    c.a_low = a_new;
    for (Eigen::Index k = 0; k < K; ++k) Dprev(k) = monic_polyval(c.a_low, d.x(k));
    if (it > 0 && change < tolerance) {
      ++it;
      break;
    }
  }
  if (used) *used = it;
  return c;
}

}  // namespace ambid::ident::detail
