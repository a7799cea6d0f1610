#include "identifier/families/amb1dof_prediction_error.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <ceres/jet.h>  // dual numbers for the automatic derivatives; the solver is nonlinear_least_squares.hpp
#include <Eigen/LU>     // closed-form fixed-size 3x3 inverse only (kalman_predictor_gain)

#include "core/error.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/nonlinear_least_squares.hpp"
#include "identifier/time_domain/least_squares.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;
using Vector9 = Eigen::Matrix<double, 9, 1>;
const std::string kWho = "prediction-error identification";
constexpr int kTaylorTerms = 12;          // of expm after scaling to norm <= 0.25: truncation < 1e-16
constexpr int kWeightingIterations = 15;  // pass 1 only sets the output weights

inline double scalar_part(double x) { return x; }
template <typename T, int N>
double scalar_part(const ceres::Jet<T, N>& x) {
  return x.a;
}

// [Ad Bd] of the zero-order hold: [Ad Bd; 0 I] = expm([A B; 0 0] T), scaling and squaring
// with a Taylor series (templated for the automatic derivatives).
template <typename T>
void zero_order_hold(const Eigen::Matrix<T, 4, 4>& A, const Eigen::Matrix<T, 4, 3>& B, double sample_time,
                     Eigen::Matrix<T, 4, 4>& Ad, Eigen::Matrix<T, 4, 3>& Bd) {
  using M7 = Eigen::Matrix<T, 7, 7>;
  M7 M = M7::Zero();
  M.template topLeftCorner<4, 4>() = A * T(sample_time);
  M.template topRightCorner<4, 3>() = B * T(sample_time);
  double norm = 0.0;  // 1-norm of the values
  for (int j = 0; j < 7; ++j) {
    double column = 0.0;
    for (int i = 0; i < 7; ++i) column += std::abs(scalar_part(M(i, j)));
    norm = std::max(norm, column);
  }
  const int squarings = norm > 0.25 ? static_cast<int>(std::ceil(std::log2(norm / 0.25))) : 0;
  M /= T(std::ldexp(1.0, squarings));
  M7 E = M7::Identity(), term = M7::Identity();
  for (int k = 1; k <= kTaylorTerms; ++k) {
    term = (term * M) / T(double(k));
    E += term;
  }
  for (int s = 0; s < squarings; ++s) E = (E * E).eval();
  Ad = E.template topLeftCorner<4, 4>();
  Bd = E.template topRightCorner<4, 3>();
}

template <typename T>
void structure_matrices(const T* v, const T* w, Eigen::Matrix<T, 4, 4>& A, Eigen::Matrix<T, 4, 3>& B) {
  A.setZero();
  A(0, 1) = T(1.0);
  A(1, 0) = v[0];
  A(1, 2) = v[1];
  A(1, 3) = -v[2];
  A(2, 1) = -v[3];
  A(2, 2) = -v[4];
  A(3, 1) = v[5];
  A(3, 3) = -v[6];
  B.setZero();
  B(2, 0) = v[7];
  B(3, 1) = v[8];
  B(1, 2) = w[0];
  B(2, 2) = w[1];
  B(3, 2) = w[2];
}

// What the residual needs; the parameters are scaled: v = v0 .* p_v, w = w_scale .* p_w,
// x0 = x_scale .* p_x, K = K0 + k_scale .* p_k (all of order one or less at the solution).
struct Record {
  const Eigen::MatrixXd& y;
  const Eigen::MatrixXd& u;
  double sample_time;
  Vector9 v0;
  Eigen::Vector3d w_scale;
  Eigen::Vector4d x_scale;
  Eigen::Matrix<double, 4, 3> K0, k_scale;
  Eigen::Vector3d weight;  // per output
};

constexpr int kGains = 12;  // K, row-major

// Residuals weight_j e[t, j], index 3 t + j, of the one-step predictor.
class PredictionResidual {
 public:
  explicit PredictionResidual(const Record& record) : d_(record) {}

  template <typename T>
  bool operator()(const T* p_v, const T* p_w, const T* p_x, const T* p_k, T* residual) const {
    T v[9], w[3];
    for (int i = 0; i < 9; ++i) v[i] = T(d_.v0(i)) * p_v[i];
    for (int i = 0; i < 3; ++i) w[i] = T(d_.w_scale(i)) * p_w[i];
    Eigen::Matrix<T, 4, 4> A, Ad;
    Eigen::Matrix<T, 4, 3> B, Bd, K;
    structure_matrices(v, w, A, B);
    zero_order_hold(A, B, d_.sample_time, Ad, Bd);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) K(i, j) = T(d_.K0(i, j)) + T(d_.k_scale(i, j)) * p_k[3 * i + j];
    T x[4], x_next[4], e[3];
    for (int i = 0; i < 4; ++i) x[i] = T(d_.x_scale(i)) * p_x[i];
    for (Index t = 0; t < d_.y.rows(); ++t) {
      e[0] = T(d_.y(t, 0)) - x[0];
      e[1] = T(d_.y(t, 1)) - x[2];
      e[2] = T(d_.y(t, 2)) - x[3];
      const double u0 = d_.u(t, 0), u1 = d_.u(t, 1);
      for (int i = 0; i < 4; ++i)
        x_next[i] = Ad(i, 0) * x[0] + Ad(i, 1) * x[1] + Ad(i, 2) * x[2] + Ad(i, 3) * x[3] + Bd(i, 0) * u0 +
                    Bd(i, 1) * u1 + Bd(i, 2) + K(i, 0) * e[0] + K(i, 1) * e[1] + K(i, 2) * e[2];
      for (int j = 0; j < 3; ++j) {
        residual[3 * t + j] = T(d_.weight(j)) * e[j];
        if (!std::isfinite(scalar_part(residual[3 * t + j]))) return false;  // the predictor diverged
      }
      std::copy(x_next, x_next + 4, x);
    }
    return true;
  }

 private:
  const Record& d_;
};

// [p_v (9), p_w (3), p_x (4), p_k (kGains)]; all 1, 0 at the start (the start's own model).
constexpr int kParameters = 9 + 3 + 4 + kGains;
using Parameters = Eigen::Matrix<double, kParameters, 1>;

Parameters start_parameters() {
  Parameters p = Parameters::Zero();
  p.head<9>().setOnes();
  return p;
}

int residual_count(const Record& record) { return static_cast<int>(3 * record.y.rows()); }

// The residuals at p and, with `jacobian`, their derivatives by forward-mode automatic
// differentiation: one dual number per parameter, as Ceres' AutoDiffCostFunction does.
bool prediction_residuals(const PredictionResidual& f, int count, const double* p, double* residuals,
                          double* jacobian) {
  if (jacobian == nullptr) return f(p, p + 9, p + 12, p + 16, residuals);
  using Jet = ceres::Jet<double, kParameters>;
  Jet q[kParameters];
  for (int i = 0; i < kParameters; ++i) q[i] = Jet(p[i], i);
  std::vector<Jet> r(static_cast<std::size_t>(count));
  if (!f(q, q + 9, q + 12, q + 16, r.data())) return false;
  for (int i = 0; i < count; ++i) {
    residuals[i] = r[std::size_t(i)].a;
    for (int j = 0; j < kParameters; ++j) jacobian[i * kParameters + j] = r[std::size_t(i)].v(j);
  }
  return true;
}

// The residuals at p without derivatives (empty when the predictor diverges).
std::vector<double> residuals_at(const Record& record, const Parameters& p) {
  std::vector<double> e(std::size_t(residual_count(record)));
  if (!PredictionResidual(record)(p.data(), p.data() + 9, p.data() + 12, p.data() + 16, e.data())) e.clear();
  return e;
}

// Refines p in place; with `jacobian`, the solution carries the residuals and Jacobian at p.
NonlinearLeastSquaresSolution solve(const Record& record, Parameters& p, int max_iterations, bool jacobian = false) {
  const PredictionResidual f(record);
  NonlinearLeastSquares problem;
  problem.residual_count = residual_count(record);
  problem.residuals = [&f, count = problem.residual_count](const double* x, double* r, double* J) {
    return prediction_residuals(f, count, x, r, J);
  };
  NonlinearLeastSquaresOptions o;
  o.max_iterations = max_iterations;
  // The parameters are scaled to order one; changes below 1e-8 are far below any sigma.
  o.function_tolerance = 1e-10;
  o.parameter_tolerance = 1e-8;
  o.gradient_tolerance = 1e-12;
  o.jacobian = jacobian;
  NonlinearLeastSquaresSolution solution = solve_nonlinear_least_squares(problem, p, o);
  if (!solution.usable()) throw InsufficientData(kWho + ": the solver failed (" + solution.message + ")");
  p = solution.x;
  return solution;
}

// The predictor gain of the steady-state Kalman filter of (A, C) without process noise and
// with measurement covariance R (Riccati iteration from P0).
Eigen::Matrix<double, 4, 3> kalman_predictor_gain(const Eigen::Matrix4d& A, const Eigen::Matrix<double, 3, 4>& C,
                                                  const Eigen::Matrix3d& R, Eigen::Matrix4d P) {
  Eigen::Matrix<double, 4, 3> K = Eigen::Matrix<double, 4, 3>::Zero();
  for (int it = 0; it < 20000; ++it) {
    const Eigen::Matrix3d S = C * P * C.transpose() + R;
    // Closed-form 3x3 inverse, not core/linalg: up to 20000 steps per record, where a dynamic LU
    // would allocate every step.
    K = A * P * C.transpose() * S.inverse();
    Eigen::Matrix4d next = A * P * A.transpose() - K * S * K.transpose();
    next = 0.5 * (next + next.transpose()).eval();
    const double change = (next - P).norm();
    P = next;
    if (change <= 1e-13 * P.norm()) break;
  }
  return K;
}

Record make_record(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, double sample_time, const Vector9& v,
                   const Eigen::Vector3d& spread) {
  Record rec{y,
             u,
             sample_time,
             v,
             Eigen::Vector3d(std::abs(v(0)) * spread(0), std::abs(v(4)) * spread(1), std::abs(v(6)) * spread(2)),
             Eigen::Vector4d(spread(0), spread(0) * std::sqrt(std::abs(v(0))), spread(1), spread(2)),
             Eigen::Matrix<double, 4, 3>::Zero(),
             Eigen::Matrix<double, 4, 3>::Zero(),
             spread.cwiseInverse()};
  Eigen::Matrix4d A, Ad;
  Eigen::Matrix<double, 4, 3> B, Bd;
  const double w0[3] = {0.0, 0.0, 0.0};
  structure_matrices(v.data(), w0, A, B);
  zero_order_hold(A, B, sample_time, Ad, Bd);
  Eigen::Matrix<double, 3, 4> C = Eigen::Matrix<double, 3, 4>::Zero();
  C(0, 0) = C(1, 2) = C(2, 3) = 1.0;
  const Eigen::Matrix3d R = (0.1 * spread).cwiseAbs2().asDiagonal();
  rec.K0 = kalman_predictor_gain(Ad, C, R, rec.x_scale.cwiseAbs2().asDiagonal());
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) rec.k_scale(i, j) = std::max(std::abs(rec.K0(i, j)), 1e-3 * rec.x_scale(i) / spread(j));
  return rec;
}

// Jacobian and residual at the solution: rank and conditioning (QR of the column-equilibrated
// Jacobian, refused beyond max_condition), (J'J)^-1 and the batch-means score covariance S.
struct Curvature {
  Eigen::MatrixXd inverse_gram, score_covariance;
  double condition_number = 0.0;
};

Curvature curvature(const NonlinearLeastSquaresSolution& fit, Index samples,
                    const Amb1dofPredictionErrorOptions& options) {
  constexpr Index n = kParameters;
  if (!fit.evaluated) throw InsufficientData(kWho + ": the predictor diverges at the solution");
  const Eigen::MatrixXd& J = fit.jacobian;
  const Eigen::VectorXd& e = fit.residuals;
  std::vector<std::string> names = amb1dof_structure_names();
  for (const char* name : {"w_x''", "w_i1'", "w_i2'", "x0_x", "x0_x'", "x0_i1", "x0_i2"}) names.emplace_back(name);
  for (int i = 0; i < kGains; ++i) names.push_back("K" + std::to_string(i / 3 + 1) + std::to_string(i % 3 + 1));
  LeastSquaresAccumulator qr(n, 1, names);
  Curvature out;
  out.score_covariance = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd rows(3 * options.score_block, n);
  Eigen::VectorXd target(3 * options.score_block);
  for (Index begin = 0; begin < samples; begin += options.score_block) {
    const Index count = std::min(options.score_block, samples - begin);
    rows.setZero();
    Eigen::VectorXd score = Eigen::VectorXd::Zero(n);
    for (Index i = 0; i < 3 * count; ++i) {
      const Index row = 3 * begin + i;
      rows.row(i) = J.row(row);
      target(i) = e(row);
      score += rows.row(i).transpose() * e(row);
    }
    out.score_covariance += score * score.transpose();
    qr.add(rows.topRows(3 * count), target.head(3 * count));
  }
  LeastSquaresOptions lo;
  lo.max_condition = options.max_condition;
  const LeastSquaresSolution solution = qr.solve(lo);  // throws InsufficientData
  out.inverse_gram = solution.inverse_gram;
  out.condition_number = solution.condition_number;
  return out;
}

double rms(const Eigen::VectorXd& x) { return x.norm() / std::sqrt(double(x.size())); }

Eigen::VectorXd output_column(const double* e, Index j, Index samples) {
  return Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<3>>(e + j, samples);
}

}  // namespace

Amb1dofPredictionErrorFit fit_amb1dof_prediction_error(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                       const Eigen::MatrixXd& r, double sample_time,
                                                       const std::vector<Vector9>& v_starts,
                                                       const Amb1dofPredictionErrorOptions& options) {
  const Index N = y.rows();
  if (y.cols() != 3 || u.cols() != 2 || r.cols() != 2 || u.rows() != N || r.rows() != N)
    throw Error(kWho + ": needs y = [x, i1, i2], u and r at [u1, u2] with equal samples, got y " + std::to_string(N) +
                " x " + std::to_string(y.cols()) + ", u " + std::to_string(u.rows()) + " x " +
                std::to_string(u.cols()) + ", r " + std::to_string(r.rows()) + " x " + std::to_string(r.cols()));
  if (!(sample_time > 0.0) || !std::isfinite(sample_time)) throw Error(kWho + ": sample time must be finite and > 0");
  if (!y.allFinite() || !u.allFinite() || !r.allFinite())
    throw Error(kWho + ": y, u and r must be finite (a NaN or infinite sample)");
  if (v_starts.empty()) throw Error(kWho + ": needs at least one starting v1..v9");
  for (const Vector9& v : v_starts)
    if (!v.allFinite() || (v.array() == 0.0).any())
      throw Error(kWho + ": a starting v1..v9 is not finite or has a zero entry");
  if (options.score_block < 1 || options.min_blocks < 1)
    throw Error(kWho + ": score_block and min_blocks must be >= 1");
  if (N < options.score_block * options.min_blocks)
    throw InsufficientData(kWho + ": " + std::to_string(N) + " samples; the uncertainty needs at least " +
                           std::to_string(options.min_blocks) + " blocks of " + std::to_string(options.score_block));
  if (!(r.cwiseAbs().maxCoeff() > 0.0))
    throw InsufficientData(kWho + ": the excitation r is zero: nothing but noise drives the loop");
  Eigen::Vector3d spread;
  for (Index j = 0; j < 3; ++j) {
    spread(j) = rms(y.col(j).array() - y.col(j).mean());
    if (!(spread(j) > 0.0))
      throw InsufficientData(kWho + ": output " + std::to_string(j + 1) + " of [x, i1, i2] does not vary");
  }
  std::vector<Record> records;  // one per start (the scales depend on it); never reallocated
  records.reserve(v_starts.size());
  for (const Vector9& v : v_starts) records.push_back(make_record(y, u, sample_time, v, spread));
  Amb1dofPredictionErrorFit fit;

  // The start whose predictor has the lowest cost goes on (the next one if it fails).
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const std::vector<double> e = residuals_at(records[i], start_parameters());
    const double cost = 0.5 * Eigen::Map<const Eigen::VectorXd>(e.data(), Index(e.size())).squaredNorm();
    if (!e.empty() && std::isfinite(cost)) ranked.emplace_back(cost, i);
  }
  if (ranked.empty()) throw InsufficientData(kWho + ": the predictor of every starting model diverges");
  std::sort(ranked.begin(), ranked.end());

  // Pass 1 weights the outputs by their spread; pass 2 by the rms of their pass-1 prediction
  // error (maximum likelihood for independent Gaussian errors), which the covariance assumes.
  Parameters p = start_parameters();
  std::string failure;
  for (const auto& [cost, index] : ranked) {
    (void)cost;
    p = start_parameters();
    try {
      fit.iterations += solve(records[index], p, kWeightingIterations).iterations;
      fit.start_index = static_cast<int>(index);
      failure.clear();
      break;
    } catch (const InsufficientData& error) {
      failure = error.what();
    }
  }
  if (!failure.empty()) throw InsufficientData(failure);
  Record& record = records[std::size_t(fit.start_index)];
  {
    const std::vector<double> e = residuals_at(record, p);
    if (e.empty()) throw InsufficientData(kWho + ": the predictor diverges after the weighting pass");
    for (Index j = 0; j < 3; ++j) {
      const double unweighted = rms(output_column(e.data(), j, N)) / record.weight(j);
      if (!(unweighted > 0.0)) throw InsufficientData(kWho + ": output " + std::to_string(j + 1) + " fits exactly");
      record.weight(j) = 1.0 / unweighted;
    }
  }
  const NonlinearLeastSquaresSolution solution = solve(record, p, options.max_iterations, true);
  fit.iterations += solution.iterations;
  fit.converged = solution.termination == Termination::converged;
  fit.start_cost = solution.initial_cost;
  fit.final_cost = solution.final_cost;

  const Curvature c = curvature(solution, N, options);
  fit.condition_number = c.condition_number;
  const Eigen::MatrixXd cov_p = c.inverse_gram * c.score_covariance * c.inverse_gram;
  for (Index i = 0; i < 9; ++i) fit.v(i) = record.v0(i) * p(i);
  for (Index i = 0; i < 3; ++i) fit.offset(i) = record.w_scale(i) * p(9 + i);
  for (Index i = 0; i < 4; ++i) fit.initial_state(i) = record.x_scale(i) * p(12 + i);
  for (Index i = 0; i < 4; ++i)
    for (Index j = 0; j < 3; ++j) fit.predictor_gain(i, j) = record.K0(i, j) + record.k_scale(i, j) * p(16 + 3 * i + j);
  fit.covariance = record.v0.asDiagonal() * cov_p.topLeftCorner<9, 9>() * record.v0.asDiagonal();
  for (Index j = 0; j < 3; ++j)
    fit.residual_rms(j) = rms(output_column(solution.residuals.data(), j, N)) / record.weight(j);
  Eigen::Matrix4d A;
  Eigen::Matrix<double, 4, 3> B;
  const double w0[3] = {0.0, 0.0, 0.0};
  structure_matrices(fit.v.data(), w0, A, B);
  fit.continuous.A = A;
  fit.continuous.B = B.leftCols(2);
  fit.continuous.C = Eigen::MatrixXd::Zero(3, 4);
  fit.continuous.C(0, 0) = fit.continuous.C(1, 2) = fit.continuous.C(2, 3) = 1.0;
  fit.continuous.D = Eigen::MatrixXd::Zero(3, 2);
  fit.discrete = c2d_zoh(fit.continuous, sample_time);
  return fit;
}

}  // namespace ambid::ident
