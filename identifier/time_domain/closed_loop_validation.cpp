#include "identifier/time_domain/closed_loop_validation.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

Eigen::VectorXd state_or_zero(const Eigen::VectorXd& x, Index n, const char* what) {
  if (x.size() == 0) return Eigen::VectorXd::Zero(n);
  if (x.size() != n)
    throw Error(std::string("closed-loop validation: ") + what + " has " + std::to_string(x.size()) + " entries for " +
                std::to_string(n) + " states");
  return x;
}

}  // namespace

Eigen::MatrixXd replay_controller(const KnownController& k, const Eigen::MatrixXd& u, const Eigen::MatrixXd& y,
                                  const Eigen::VectorXd& initial) {
  if (u.rows() != y.rows() || k.B.cols() != u.cols() + y.cols())
    throw Error("closed-loop validation: controller reads " + std::to_string(k.B.cols()) + " signals, data have " +
                std::to_string(u.cols()) + " inputs and " + std::to_string(y.cols()) + " outputs");
  const Index m = u.cols();
  Eigen::VectorXd xc = state_or_zero(initial, k.A.rows(), "the controller's initial state");
  Eigen::MatrixXd states(u.rows(), k.A.rows());
  for (Index t = 0; t < u.rows(); ++t) {
    xc = k.A * xc + k.B.leftCols(m) * u.row(t).transpose() + k.B.rightCols(y.cols()) * y.row(t).transpose();
    states.row(t) = xc.transpose();
  }
  return states;
}

Eigen::MatrixXd simulate_closed_loop(const DiscreteSystem& plant, const KnownController& k, const Eigen::MatrixXd& r,
                                     const Eigen::VectorXd& x0, const Eigen::VectorXd& xc0,
                                     const Eigen::VectorXd& constant) {
  plant.validate();
  const Index m = plant.inputs(), p = plant.outputs();
  if (plant.D.cwiseAbs().maxCoeff() != 0.0)
    throw Error("closed-loop validation: the plant model has D != 0 (an algebraic loop with the controller)");
  if (r.cols() != m || k.B.cols() != m + p || k.C.rows() != m)
    throw Error("closed-loop validation: the controller (" + std::to_string(k.B.cols()) + " inputs, " +
                std::to_string(k.C.rows()) + " outputs) and r (" + std::to_string(r.cols()) +
                " columns) do not fit a plant with " + std::to_string(m) + " inputs and " + std::to_string(p) +
                " outputs");
  Eigen::VectorXd x = state_or_zero(x0, plant.states(), "the plant's initial state");
  Eigen::VectorXd xc = state_or_zero(xc0, k.A.rows(), "the controller's initial state");
  const Eigen::VectorXd g = state_or_zero(constant, plant.states(), "the constant term");
  Eigen::MatrixXd y(r.rows(), p);
  for (Index t = 0; t < r.rows(); ++t) {
    const Eigen::VectorXd yt = plant.C * x;
    const Eigen::VectorXd ut = k.C * xc + k.D.rightCols(p) * yt + r.row(t).transpose();
    y.row(t) = yt.transpose();
    x = plant.A * x + plant.B * ut + g;
    xc = k.A * xc + k.B.leftCols(m) * ut + k.B.rightCols(p) * yt;
  }
  return y;
}

Eigen::VectorXd closed_loop_nrmse(const DiscreteSystem& plant, const KnownController& k, const Eigen::MatrixXd& r,
                                  const Eigen::MatrixXd& y, const Eigen::VectorXd& xc0,
                                  const std::vector<bool>& left_out) {
  const Index n = plant.states(), p = y.cols(), N = y.rows();
  if (r.rows() != N || p != plant.outputs() || (!left_out.empty() && Index(left_out.size()) != N))
    throw Error("closed-loop validation: y has " + std::to_string(N) + " samples x " + std::to_string(p) +
                " outputs, r " + std::to_string(r.rows()) + " samples, the model " + std::to_string(plant.outputs()) +
                " outputs, the mask of left-out samples " + std::to_string(left_out.size()) + " entries");
  Eigen::VectorXd kept = Eigen::VectorXd::Ones(N);  // 0 where a sample is left out
  for (std::size_t i = 0; i < left_out.size(); ++i)
    if (left_out[i]) kept(Index(i)) = 0.0;
  if (kept.sum() < 2.0)
    throw InsufficientData("closed-loop validation: fewer than two samples without a controller clamp to score");
  Eigen::VectorXd spread(p);
  for (Index j = 0; j < p; ++j) {
    const double mean = y.col(j).dot(kept) / kept.sum();
    spread(j) = ((y.col(j).array() - mean) * kept.array()).matrix().norm();
    if (!(spread(j) > 0.0))
      throw InsufficientData("closed-loop validation: output " + std::to_string(j + 1) +
                             " does not vary over the validation segment (nrmse undefined)");
  }
  // The response is affine in x0 and the constant term g: y_model = y_forced + sum_i x0_i y_x0_i
  // + sum_i g_i y_g_i.
  // Each output is weighted by its spread so that the fit balances channels of different units.
  const Eigen::MatrixXd forced = simulate_closed_loop(plant, k, r, {}, xc0);
  const Eigen::MatrixXd zero_r = Eigen::MatrixXd::Zero(N, r.cols());
  const Eigen::VectorXd zero_xc = Eigen::VectorXd::Zero(k.A.rows());
  Eigen::MatrixXd free(N * p, 2 * n);
  for (Index i = 0; i < 2 * n; ++i) {
    const Eigen::VectorXd unit = Eigen::VectorXd::Unit(n, i % n), zero = Eigen::VectorXd::Zero(n);
    const Eigen::MatrixXd yi = i < n ? simulate_closed_loop(plant, k, zero_r, unit, zero_xc)
                                     : simulate_closed_loop(plant, k, zero_r, zero, zero_xc, unit);
    for (Index j = 0; j < p; ++j) free.block(j * N, i, N, 1) = yi.col(j).cwiseProduct(kept) / spread(j);
  }
  Eigen::VectorXd residual(N * p);
  for (Index j = 0; j < p; ++j) residual.segment(j * N, N) = (y.col(j) - forced.col(j)).cwiseProduct(kept) / spread(j);
  Eigen::VectorXd nrmse(p);
  if (!forced.allFinite() || !free.allFinite()) {
    nrmse.setConstant(std::numeric_limits<double>::infinity());
    return nrmse;
  }
  const Eigen::VectorXd x0 = linalg::qr_solve(free, residual).x;
  const Eigen::VectorXd e = residual - free * x0;
  for (Index j = 0; j < p; ++j) nrmse(j) = e.segment(j * N, N).norm();
  return nrmse;
}

}  // namespace ambid::ident
