#pragma once
// A covariance kept as P = U D U' (U unit upper triangular, D > 0 diagonal) for recursive
// least squares and the recursive prediction-error method: Bierman's scalar measurement update
// (Bierman 1977, "Factorization Methods for Discrete Sequential Estimation", sec. V.3) and
// exponential forgetting P <- P / lambda. Updating the factors instead of P keeps P symmetric
// and positive definite in floating point over any number of samples (a plain P update loses
// both within ~1e5 samples at lambda < 1), at the same O(n^2) cost per measurement.
#include <Eigen/Core>

namespace ambid::ident {

class UdCovariance {
 public:
  // P0 = diag(initial) (every entry > 0 and finite, else Error). Forgetting never lets D_i grow
  // beyond `ceiling` times its initial value: without excitation in some direction
  // P / lambda^t would grow without bound (estimator windup) and one burst would then throw
  // the estimate far off.
  explicit UdCovariance(const Eigen::VectorXd& initial, double ceiling = 1.0);

  Eigen::Index size() const { return d_.size(); }

  // P <- P / lambda, 0 < lambda <= 1.
  void forget(double lambda);

  // P <- c P (c > 0).
  void scale(double c);

  // P <- P + c a a', c >= 0 (a random walk of the parameters along a: Agee & Turner 1972, as
  // Bierman 1977 sec. VI.3; O(n^2), and U, D stay a factorisation with D > 0).
  void add(double c, Eigen::Ref<Eigen::VectorXd> a);

  // Measurement z = h' theta + noise of variance r > 0: P <- P - P h h' P / (h' P h + r); the
  // gain P_before h / (h' P h + r) is written to `gain` (size n). Returns h' P h + r.
  double update(const Eigen::Ref<const Eigen::VectorXd>& h, double r, Eigen::Ref<Eigen::VectorXd> gain);

  Eigen::MatrixXd covariance() const;  // U D U'
  Eigen::VectorXd variances() const;   // its diagonal
  const Eigen::VectorXd& d() const { return d_; }
  const Eigen::MatrixXd& u() const { return u_; }

 private:
  Eigen::MatrixXd u_;
  Eigen::VectorXd d_, ceiling_, f_, v_;
};

}  // namespace ambid::ident
