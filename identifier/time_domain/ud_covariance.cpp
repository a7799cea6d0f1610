#include "identifier/time_domain/ud_covariance.hpp"

#include <cmath>

#include "core/error.hpp"

namespace ambid::ident {

UdCovariance::UdCovariance(const Eigen::VectorXd& initial, double ceiling) {
  if (initial.size() == 0 || !initial.allFinite() || !(initial.minCoeff() > 0.0))
    throw Error("UD covariance: the initial variances must be finite and > 0");
  if (!(ceiling >= 1.0) || !std::isfinite(ceiling)) throw Error("UD covariance: the ceiling must be finite and >= 1");
  const Eigen::Index n = initial.size();
  u_ = Eigen::MatrixXd::Identity(n, n);
  d_ = initial;
  ceiling_ = ceiling * initial;
  f_.resize(n);
  v_.resize(n);
}

void UdCovariance::forget(double lambda) {
  if (!(lambda > 0.0 && lambda <= 1.0)) throw Error("UD covariance: forgetting factor must be in (0, 1]");
  if (lambda == 1.0) return;
  d_ = (d_ / lambda).cwiseMin(ceiling_);
}

void UdCovariance::scale(double c) {
  if (!(c > 0.0) || !std::isfinite(c)) throw Error("UD covariance: a scale must be finite and > 0");
  d_ *= c;
}

void UdCovariance::add(double c, Eigen::Ref<Eigen::VectorXd> a) {
  if (!(c >= 0.0) || a.size() != size()) throw Error("UD covariance: a random walk needs c >= 0 and a of size n");
  // The columns from the last: a's part along column j goes into D_j, the rest on to the columns before.
  for (Eigen::Index j = size() - 1; j >= 0 && c > 0.0; --j) {
    const double s = a(j);
    if (s == 0.0) continue;
    const double d = d_(j) + c * s * s;
    const double beta = c * s / d;
    c *= d_(j) / d;
    d_(j) = d;
    double* column = u_.col(j).data();
    for (Eigen::Index i = 0; i < j; ++i) {
      a(i) -= s * column[i];
      column[i] += beta * a(i);
    }
  }
}

double UdCovariance::update(const Eigen::Ref<const Eigen::VectorXd>& h, double r, Eigen::Ref<Eigen::VectorXd> gain) {
  const Eigen::Index n = size();
  // f = U' h, v = D f (U unit upper triangular, column-major: column j holds U(0..j-1, j)).
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* column = u_.col(j).data();
    double s = h(j);
    for (Eigen::Index i = 0; i < j; ++i) s += column[i] * h(i);
    f_(j) = s;
    v_(j) = d_(j) * s;
  }
  double alpha = r + v_(0) * f_(0);
  d_(0) *= r / alpha;
  gain(0) = v_(0);
  for (Eigen::Index j = 1; j < n; ++j) {
    const double beta = alpha;
    alpha += v_(j) * f_(j);
    const double lambda = -f_(j) / beta;
    d_(j) *= beta / alpha;
    double* column = u_.col(j).data();
    for (Eigen::Index i = 0; i < j; ++i) {
      const double previous = column[i];
      column[i] = previous + gain(i) * lambda;
      gain(i) += previous * v_(j);
    }
    gain(j) = v_(j);
  }
  gain /= alpha;
  return alpha;
}

Eigen::MatrixXd UdCovariance::covariance() const { return u_ * d_.asDiagonal() * u_.transpose(); }

Eigen::VectorXd UdCovariance::variances() const {
  Eigen::VectorXd out(size());
  for (Eigen::Index i = 0; i < size(); ++i) out(i) = u_.row(i).cwiseAbs2().dot(d_);
  return out;
}

}  // namespace ambid::ident
