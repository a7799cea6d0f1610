#pragma once
// Test systems for the time-domain identifier tests: random discrete systems with chosen
// poles, innovation models built from a chosen predictor, and a plain closed-loop simulation
// (plant + contract-form controller or full-state feedback) written out sample by sample, so
// the identifier is checked against data it did not generate itself. Seeded randomness only.
#include <algorithm>
#include <complex>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/linalg.hpp"

namespace ambid::ident::testing {

inline Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng, double scale = 1.0) {
  std::normal_distribution<double> n(0.0, scale);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = n(rng);
  return m;
}

// A real matrix with the given eigenvalues (complex ones in conjugate pairs: list each pair
// once, as the member with positive imaginary part), in random well-conditioned coordinates.
inline Eigen::MatrixXd matrix_with_eigenvalues(const std::vector<std::complex<double>>& poles, std::mt19937_64& rng) {
  Eigen::Index n = 0;
  for (const auto& z : poles) n += z.imag() != 0.0 ? 2 : 1;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  Eigen::Index k = 0;
  for (const auto& z : poles) {
    if (z.imag() != 0.0) {
      J(k, k) = z.real();
      J(k, k + 1) = z.imag();
      J(k + 1, k) = -z.imag();
      J(k + 1, k + 1) = z.real();
      k += 2;
    } else {
      J(k, k) = z.real();
      k += 1;
    }
  }
  // T = Q (I + 0.3 G): orthogonal times a moderate perturbation, condition number a few.
  const Eigen::MatrixXd Q = linalg::qr_q(random_matrix(n, n, rng));
  const Eigen::MatrixXd T =
      Q * (Eigen::MatrixXd::Identity(n, n) + 0.3 * random_matrix(n, n, rng) / std::sqrt(double(n)));
  return T * J * linalg::inverse(T);
}

// Three significant digits in scientific notation (for RecordProperty).
inline std::string sci(double v) {
  std::ostringstream s;
  s.precision(3);
  s << std::scientific << v;
  return s.str();
}

inline double spectral_radius(const Eigen::MatrixXd& A) { return linalg::spectral_radius(A); }

// The scale s > 0 at which spectral_radius(A0 + s M) = target, by bisection from s = 0
// (requires spectral_radius(A0) < target).
inline double scale_to_radius(const Eigen::MatrixXd& A0, const Eigen::MatrixXd& M, double target) {
  double lo = 0.0, hi = 1.0;
  while (spectral_radius(A0 + hi * M) < target) hi *= 2.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (spectral_radius(A0 + mid * M) < target ? lo : hi) = mid;
  }
  return hi;
}

// Eigenvalues sorted by (real, imag) for comparison.
inline std::vector<std::complex<double>> sorted_eigenvalues(const Eigen::MatrixXd& A) {
  const Eigen::VectorXcd e = linalg::eigenvalues(A);
  std::vector<std::complex<double>> v(e.data(), e.data() + e.size());
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
    if (std::abs(a.real() - b.real()) > 1e-6) return a.real() < b.real();
    return a.imag() < b.imag();
  });
  return v;
}

// Largest |lambda_i - mu_i| / |lambda_i| over the sorted eigenvalues.
inline double eigenvalue_error(const Eigen::MatrixXd& A, const Eigen::MatrixXd& Ahat) {
  const auto a = sorted_eigenvalues(A), b = sorted_eigenvalues(Ahat);
  if (a.size() != b.size()) return 1e300;
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, std::abs(a[i] - b[i]) / std::abs(a[i]));
  return e;
}

// Largest ||X_k - Y_k||_F / max_k ||X_k||_F over k in [first, last] for two sequences of
// C A^(k-1) B style products given as lambdas-free vectors.
inline double max_relative_error(const std::vector<Eigen::MatrixXd>& truth, const std::vector<Eigen::MatrixXd>& est,
                                 std::size_t first, std::size_t last) {
  double e = 0.0;
  for (std::size_t k = first; k <= last; ++k) {
    const double nt = truth[k].norm();
    e = std::max(e, (truth[k] - est[k]).norm() / (nt > 0 ? nt : 1.0));
  }
  return e;
}

inline std::vector<Eigen::MatrixXd> markov_of(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                              const Eigen::MatrixXd& C, const Eigen::MatrixXd& D, int count) {
  std::vector<Eigen::MatrixXd> y{D};
  Eigen::MatrixXd AkB = B;
  for (int k = 1; k <= count; ++k) {
    y.push_back(C * AkB);
    AkB = A * AkB;
  }
  return y;
}

// Discrete LQR gain by Riccati iteration (test-local, independent of plant_sim).
inline Eigen::MatrixXd lqr_gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                                const Eigen::MatrixXd& R) {
  Eigen::MatrixXd X = Q;
  for (int it = 0; it < 20000; ++it) {
    const Eigen::MatrixXd S = R + B.transpose() * X * B;
    const Eigen::MatrixXd K = linalg::ldlt_solve(S, B.transpose() * X * A);
    const Eigen::MatrixXd Xn = A.transpose() * X * (A - B * K) + Q;
    const double d = (Xn - X).norm();
    X = 0.5 * (Xn + Xn.transpose());
    if (d <= 1e-14 * X.norm()) break;
  }
  return linalg::ldlt_solve(R + B.transpose() * X * B, B.transpose() * X * A);
}

// Plant x[k+1] = A x + B u + G e + w, y = C x + D u + e (innovation form when w = 0).
struct Plant {
  Eigen::MatrixXd A, B, C, D, G;
};

// Contract-form controller reading [u; y]: xc[k+1] = Ac xc + Bc [u; y], uf = Cc xc + Dc [u; y].
struct Controller {
  Eigen::MatrixXd A, B, C, D;
};

struct LoopData {
  Eigen::MatrixXd y, u, uf;
};

// Runs the loop u = uf + r for r.rows() samples. Either `controller` (when F is empty) or
// full-state feedback uf = -F x. e: innovation noise (samples x outputs), w: process noise
// (samples x states); both may be empty.
inline LoopData run_loop(const Plant& plant, const Controller* controller, const Eigen::MatrixXd& F,
                         const Eigen::MatrixXd& r, const Eigen::MatrixXd& e = {}, const Eigen::MatrixXd& w = {},
                         const Eigen::VectorXd& x0 = {}) {
  const Eigen::Index N = r.rows(), m = plant.B.cols(), p = plant.C.rows(), n = plant.A.rows();
  LoopData d{Eigen::MatrixXd(N, p), Eigen::MatrixXd(N, m), Eigen::MatrixXd(N, m)};
  Eigen::VectorXd x = x0.size() ? x0 : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd xc = controller ? Eigen::VectorXd::Zero(controller->A.rows()) : Eigen::VectorXd();
  for (Eigen::Index k = 0; k < N; ++k) {
    const Eigen::VectorXd ek = e.size() ? Eigen::VectorXd(e.row(k).transpose()) : Eigen::VectorXd::Zero(p);
    Eigen::VectorXd uf;
    Eigen::VectorXd y0 = plant.C * x + ek;  // y without the D u part
    if (F.size()) {
      uf = -F * x;
    } else {
      // D u feeds y; the controller reads y only through Dc's y columns, which must then be zero
      // when plant D != 0 (no algebraic loop in these tests).
      uf = controller->C * xc + controller->D.rightCols(p) * y0;
    }
    const Eigen::VectorXd u = uf + r.row(k).transpose();
    const Eigen::VectorXd y = y0 + plant.D * u;
    d.y.row(k) = y.transpose();
    d.u.row(k) = u.transpose();
    d.uf.row(k) = uf.transpose();
    if (controller && !F.size()) {
      Eigen::VectorXd v(m + p);
      v << u, y;
      xc = controller->A * xc + controller->B * v;
    }
    x = plant.A * x + plant.B * u + plant.G * ek;
    if (w.size()) x += w.row(k).transpose();
  }
  return d;
}

}  // namespace ambid::ident::testing
