// RationalModel: evaluation, poles, zeros, gain, realisation.
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/frequency_domain/rational_fit.hpp"
#include "identifier/frequency_domain/rational_fit_detail.hpp"

namespace ambid::ident {
namespace {

// Roots of sum c_i x^i (ascending, c.back() != 0) by the companion matrix.
Eigen::VectorXcd roots(const Eigen::VectorXd& c) {
  const Eigen::Index n = c.size() - 1;
  if (n < 1) return Eigen::VectorXcd(0);
  if (c(n) == 0.0) throw Error("rational model: leading coefficient is zero");
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  companion.topRightCorner(n - 1, n - 1).setIdentity();
  companion.row(n - 1) = -c.head(n).transpose() / c(n);
  return linalg::eigenvalues(companion);
}

void check(const RationalModel& m) {
  if (m.denominator.size() < 2) throw Error("rational model: the denominator degree must be at least 1");
  if (m.numerator.size() < 1) throw Error("rational model: the numerator is empty");
  if (m.denominator(m.denominator.size() - 1) != 1.0) throw Error("rational model: the denominator must be monic");
  if (!(m.frequency_scale > 0.0) || !std::isfinite(m.frequency_scale))
    throw Error("rational model: frequency_scale must be positive, got " + std::to_string(m.frequency_scale));
}

}  // namespace

std::complex<double> RationalModel::evaluate(std::complex<double> s) const {
  check(*this);
  const std::complex<double> x = s / frequency_scale;
  return detail::polyval(numerator, x) / detail::polyval(denominator, x);
}

Eigen::VectorXcd RationalModel::poles() const {
  check(*this);
  return roots(denominator) * frequency_scale;
}

Eigen::VectorXcd RationalModel::zeros() const {
  check(*this);
  return roots(numerator) * frequency_scale;
}

double RationalModel::gain() const {
  check(*this);
  const int m = numerator_degree(), n = denominator_degree();
  return numerator(m) * std::pow(frequency_scale, n - m);
}

ContinuousSystem RationalModel::realization() const {
  check(*this);
  const int m = numerator_degree(), n = denominator_degree();
  if (m > n)
    throw Error("rational model: improper (numerator degree " + std::to_string(m) + " > " + std::to_string(n) + ")");
  const auto N = static_cast<Eigen::Index>(n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(N + 1);
  b.head(numerator.size()) = numerator;
  const double d = b(N);  // direct feed-through (m == n)
  const Eigen::VectorXd c = b.head(N) - d * denominator.head(N);
  ContinuousSystem sys;
  sys.A = Eigen::MatrixXd::Zero(N, N);
  if (N > 1) sys.A.topRightCorner(N - 1, N - 1).setIdentity();
  sys.A.row(N - 1) = -denominator.head(N).transpose();
  sys.A *= frequency_scale;
  sys.B = Eigen::MatrixXd::Zero(N, 1);
  sys.B(N - 1, 0) = frequency_scale;
  sys.C = c.transpose();
  sys.D = Eigen::MatrixXd::Constant(1, 1, d);
  return sys;
}

std::string to_string(FitWeighting weighting) {
  switch (weighting) {
    case FitWeighting::automatic:
      return "automatic";
    case FitWeighting::noise:
      return "noise";
    case FitWeighting::relative:
      return "relative";
    case FitWeighting::uniform:
      return "uniform";
  }
  return "?";
}

}  // namespace ambid::ident
