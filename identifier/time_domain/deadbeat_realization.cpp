#include "identifier/time_domain/deadbeat_realization.hpp"

#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/time_domain/instrumental_variables.hpp"

namespace ambid::ident {
namespace {}  // namespace

Eigen::MatrixXd integrator_states(const Eigen::MatrixXd& y, const Eigen::MatrixXd& E, const Eigen::VectorXd& initial) {
  const Eigen::Index ni = E.rows();
  if (E.cols() != y.cols())
    throw Error("integrator states: E is " + dims(E) + " but y has " + std::to_string(y.cols()) + " channels");
  if (initial.size() != 0 && initial.size() != ni)
    throw Error("integrator states: initial state has " + std::to_string(initial.size()) + " entries, expected " +
                std::to_string(ni));
  Eigen::MatrixXd e(y.rows(), ni);
  Eigen::VectorXd s = initial.size() ? initial : Eigen::VectorXd::Zero(ni);
  for (Eigen::Index k = 0; k < y.rows(); ++k) {
    s -= E * y.row(k).transpose();
    e.row(k) = s.transpose();
  }
  return e;
}

DeadbeatRealization deadbeat_realization(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, const Eigen::MatrixXd& uf,
                                         const Eigen::MatrixXd& e, const Eigen::MatrixXd& C, const Eigen::MatrixXd& F,
                                         const Eigen::MatrixXd& Fe, double sample_time,
                                         const DeadbeatOptions& options) {
  const Eigen::Index N = y.rows(), p = y.cols(), m = u.cols(), n = C.cols(), ni = Fe.cols();
  if (u.rows() != N || uf.rows() != N || uf.cols() != m)
    throw Error("deadbeat realisation: y " + dims(y) + ", u " + dims(u) + " and uf " + dims(uf) +
                " must have the same samples and uf one column per input");
  if (C.rows() != p || F.rows() != m || F.cols() != n || Fe.rows() != m)
    throw Error("deadbeat realisation: C " + dims(C) + ", F " + dims(F) + ", Fe " + dims(Fe) + " do not fit " +
                std::to_string(p) + " outputs and " + std::to_string(m) + " inputs");
  if (ni > 0 && (e.rows() != N || e.cols() != ni))
    throw Error("deadbeat realisation: integrator states e are " + dims(e) + ", expected " + std::to_string(N) + "x" +
                std::to_string(ni));
  if (!(sample_time > 0.0)) throw Error("deadbeat realisation: sample_time must be positive");
  if (options.transient_samples < 0 || options.transient_samples >= N)
    throw Error("deadbeat realisation: transient_samples " + std::to_string(options.transient_samples) +
                " out of range for " + std::to_string(N) + " samples");
  if (!y.allFinite() || !u.allFinite() || !uf.allFinite() || (ni > 0 && !e.allFinite()))
    throw Error("deadbeat realisation: non-finite sample");

  DeadbeatRealization out;
  out.cbar = Eigen::MatrixXd::Zero(p + m, n + ni);
  out.cbar.topLeftCorner(p, n) = C;
  out.cbar.bottomLeftCorner(m, n) = -F;
  out.cbar.bottomRightCorner(m, ni) = Fe;
  out.cbar_invertible = p + m == n + ni && linalg::rank(out.cbar) == n + ni;

  // Left inverse of [C; -F] taking the measured states from y: x = C+ y + N (-F N)+ (...).
  const Eigen::Index c_rank = linalg::rank(C);
  if (c_rank != p)
    throw Error("deadbeat realisation: the output matrix C (" + dims(C) + ") must have full row rank, rank " +
                std::to_string(c_rank));
  const Eigen::MatrixXd Cp = linalg::pseudo_inverse(C).pinv;  // n x p
  const Eigen::MatrixXd Nc = linalg::null_space(C);           // n x (n - p)
  const Eigen::MatrixXd Fz = -F * Nc;                         // m x (n - p)
  Eigen::MatrixXd Fzp = Eigen::MatrixXd::Zero(n - p, m);
  if (n > p) {
    linalg::PseudoInverse fz_inverse = linalg::pseudo_inverse(Fz);
    if (fz_inverse.rank != n - p)
      throw Error("deadbeat realisation: the feedback does not observe the unmeasured states (-F N has rank " +
                  std::to_string(fz_inverse.rank) + " of " + std::to_string(n - p) +
                  "): the outputs and the feedback do not determine the state");
    Fzp = std::move(fz_inverse.pinv);
  }
  out.state_map.resize(n, p + m);
  out.state_map << Cp + Nc * Fzp * F * Cp, Nc * Fzp;
  const Eigen::MatrixXd& Mx = out.state_map;

  // x[k] for every sample, then x[k+1] on [x[k]; u[k]].
  const Eigen::Index k0 = options.transient_samples;
  Eigen::MatrixXd yu(N - k0, p + m);
  yu << y.bottomRows(N - k0), uf.bottomRows(N - k0);
  if (ni > 0) yu.rightCols(m) -= e.bottomRows(N - k0) * Fe.transpose();
  const Eigen::MatrixXd X = yu * Mx.transpose();  // (N - k0) x n
  const bool affine = options.estimate_offset;
  const Eigen::Index regs = n + m + (affine ? 1 : 0);
  std::vector<std::string> names;
  for (Eigen::Index j = 0; j < n; ++j) names.push_back("x" + std::to_string(j + 1) + "[k]");
  for (Eigen::Index j = 0; j < m; ++j) names.push_back("u" + std::to_string(j + 1) + "[k]");
  if (affine) names.push_back("constant");
  const Eigen::Index lags = options.instrument_lags;
  if (lags < 0) throw Error("deadbeat realisation: instrument_lags must be >= 0, got " + std::to_string(lags));
  const Eigen::Index rows = N - k0 - 1 - lags;  // equations for k = k0 + lags .. N - 2
  if (rows < 1) throw InsufficientData("deadbeat realisation: needs at least two samples after the transient");
  Eigen::MatrixXd phi(rows, regs);
  phi.leftCols(n) = X.middleRows(lags, rows);
  phi.middleCols(n, m) = u.middleRows(k0 + lags, rows);
  if (affine) phi.col(n + m).setOnes();
  if (lags == 0) {
    LeastSquaresAccumulator acc(regs, n, names);
    acc.add(phi, X.bottomRows(rows));
    out.fit = acc.solve(options.least_squares);
  } else {
    const Eigen::MatrixXd r = u - uf;
    Eigen::MatrixXd instruments(rows, m * (lags + 1) + (affine ? 1 : 0));
    for (Eigen::Index j = 0; j <= lags; ++j) instruments.middleCols(j * m, m) = r.middleRows(k0 + lags - j, rows);
    if (affine) instruments.rightCols(1).setOnes();
    out.fit = solve_instrumental_variables(phi, X.bottomRows(rows), instruments, names, options.least_squares);
  }

  const Eigen::MatrixXd thetaT = out.fit.theta.transpose();  // n x regs = [A B (c)]
  out.system.A = thetaT.leftCols(n);
  out.system.B = thetaT.middleCols(n, m);
  out.offset = affine ? Eigen::VectorXd(thetaT.col(n + m)) : Eigen::VectorXd::Zero(n);
  out.system.C = C;
  out.system.D = Eigen::MatrixXd::Zero(p, m);
  out.system.sample_time = sample_time;
  out.deadbeat_gain = -out.system.A * Mx;

  // Cov(A(i, j), A(k, l)) = Sigma(i, k) G(j, l) with the regressor index of B entries offset by n.
  const Eigen::Index np = n * (n + m);
  out.parameter_covariance.resize(np, np);
  auto index = [&](Eigen::Index row, Eigen::Index reg) {
    return reg < n ? row * n + reg : n * n + row * m + (reg - n);
  };
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n + m; ++j)
      for (Eigen::Index k = 0; k < n; ++k)
        for (Eigen::Index l = 0; l < n + m; ++l)
          out.parameter_covariance(index(i, j), index(k, l)) = out.fit.covariance(j, i, l, k);
  return out;
}

}  // namespace ambid::ident
