#include "identifier/families/amb1dof_prediction_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/amb1dof_structure.hpp"
#include "identifier/families/amb1dof_predictor.hpp"
#include "identifier/time_domain/levenberg_marquardt.hpp"

namespace ambid::ident {

void refuse_lockstep_excitation(const Eigen::MatrixXd& r, double min_ratio, const std::string& who) {
  if (r.rows() < 2 || !(r.cwiseAbs().maxCoeff() > 0.0)) return;  // no excitation: the noise drives the loop
  const Eigen::MatrixXd centred = r.rowwise() - r.colwise().mean();
  const Eigen::Vector2d power = linalg::symmetric_eigenvalues(centred.transpose() * centred);
  if (!(power(0) > min_ratio * power(1)))
    throw InsufficientData(who + ": r1 and r2 move together (the weaker of their directions carries " +
                           std::to_string(std::max(power(0), 0.0) / power(1)) +
                           " of the stronger's power): the excitation cannot tell the two coils apart");
}

namespace {

// A v whose one-sigma exceeds half its value is not determined by the data.
constexpr double kMaxRelativeSigma = 0.5;

using Index = Eigen::Index;
using pem::Gain;
using pem::Parameters;
using pem::Vector9;
const std::string kPemWho = "prediction-error identification";
constexpr double kWeightingTolerance = 1.0;  // standard errors: close enough to set the weights
constexpr double kNearDamping = 1e-10;

// The predictor gain of the steady-state Kalman filter of (A, C) without process noise and
// with measurement covariance R (Riccati iteration from P0).
Gain kalman_predictor_gain(const Eigen::Matrix4d& A, const Eigen::Matrix<double, 3, 4>& C, const Eigen::Matrix3d& R,
                           Eigen::Matrix4d P) {
  Gain K = Gain::Zero();
  for (int it = 0; it < 20000; ++it) {
    const Eigen::Matrix3d S = C * P * C.transpose() + R;
    // Closed-form 3x3 inverse: up to 20000 steps per record, where a dynamic LU would allocate
    // every step.
    K = A * P * C.transpose() * linalg::inverse_3x3(S);
    Eigen::Matrix4d next = A * P * A.transpose() - K * S * K.transpose();
    next = 0.5 * (next + next.transpose()).eval();
    const double change = (next - P).norm();
    P = next;
    if (change <= 1e-13 * P.norm()) break;
  }
  return K;
}

Eigen::Matrix<double, 3, 4> output_matrix() {
  Eigen::Matrix<double, 3, 4> C = Eigen::Matrix<double, 3, 4>::Zero();
  for (int j = 0; j < 3; ++j) C(j, pem::kMeasured[std::size_t(j)]) = 1.0;
  return C;
}

// The typical size of every state: x, x' (x at the frequency sqrt(|v1|)), i1, i2.
Eigen::Vector4d state_scale(const Vector9& v, const Eigen::Vector3d& spread) {
  return {spread(0), spread(0) * std::sqrt(std::abs(v(0))), spread(1), spread(2)};
}

// theta = origin + scale .* p: p is of order one or less near the solution, which the
// relative quantities of the solver (damping, conditioning) assume.
Parameters parameter_scale(const Vector9& v, const Gain& K, const Eigen::Vector3d& spread) {
  const Eigen::Vector4d xs = state_scale(v, spread);
  Gain ks;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) ks(i, j) = std::max(std::abs(K(i, j)), 1e-3 * xs(i) / spread(j));
  return pem::pack(v.cwiseAbs(),
                   Eigen::Vector3d(std::abs(v(0)) * spread(0), std::abs(v(4)) * spread(1), std::abs(v(6)) * spread(2)),
                   xs, ks);
}

// The first sample, at rest: the initial state the fit starts from.
Eigen::Vector4d first_state(const Eigen::MatrixXd& y) { return {y(0, 0), 0.0, y(0, 1), y(0, 2)}; }

// A cold start: v, no offset, the Kalman predictor gain of v's model.
Parameters cold_start(const Vector9& v, const Eigen::MatrixXd& y, double sample_time, const Eigen::Vector3d& spread) {
  Parameters theta = pem::pack(v, Eigen::Vector3d::Zero(), first_state(y), Gain::Zero());
  const pem::ZeroOrderHold zoh = pem::zero_order_hold(theta, sample_time, false);
  const Eigen::Matrix3d R = (0.1 * spread).cwiseAbs2().asDiagonal();
  const Eigen::Vector4d xs = state_scale(v, spread);
  return pem::pack(v, Eigen::Vector3d::Zero(), first_state(y),
                   kalman_predictor_gain(zoh.Ad, output_matrix(), R, xs.cwiseAbs2().asDiagonal()));
}

std::vector<std::string> parameter_names() {
  std::vector<std::string> names = amb1dof_structure_names();
  for (const char* name : {"w_x''", "w_i1'", "w_i2'", "x0_x", "x0_x'", "x0_i1", "x0_i2"}) names.emplace_back(name);
  for (int i = 0; i < 12; ++i) names.push_back("K" + std::to_string(i / 3 + 1) + std::to_string(i % 3 + 1));
  return names;
}

// The prediction-error problem in the scaled parameters p, each output weighted by 1 / its rms
// prediction error where reweight() last put it; linearise keeps the score J'e of every block
// of consecutive samples (for the covariance).
class Problem {
 public:
  Problem(const pem::Amb1dofPredictor& predictor, const Parameters& origin, const Parameters& scale, Index score_block)
      : predictor_(predictor), origin_(origin), scale_(scale), score_block_(score_block) {}

  Parameters theta(const Eigen::VectorXd& p) const { return origin_ + scale_.cwiseProduct(p); }
  const Eigen::Vector3d& weight() const { return weight_; }
  const std::vector<Parameters>& scores() const { return scores_; }

  // With `every` set, each linearisation first re-weights at its point.
  void reweight_every_linearisation(bool every) { every_ = every; }

  // Weights 1 / rms of each output's prediction error at p; false when the predictor diverges.
  bool reweight(const Eigen::VectorXd& p) {
    const std::optional<Eigen::Vector3d> squares = predictor_.squares(theta(p));
    if (!squares) return false;
    for (Index j = 0; j < 3; ++j) {
      const double rms = std::sqrt((*squares)(j) / double(predictor_.scored_samples()));
      if (!(rms > 0.0)) throw InsufficientData(kPemWho + ": output " + std::to_string(j + 1) + " is predicted exactly");
      weight_(j) = 1.0 / rms;
    }
    return true;
  }

  BlockLeastSquares least_squares() {
    BlockLeastSquares ls;
    ls.parameters = pem::kParameters;
    ls.names = parameter_names();
    ls.linearise = [this](const Eigen::VectorXd& p, LeastSquaresAccumulator& rows) {
      if (every_ && !reweight(p)) return false;
      scores_.clear();
      return predictor_.linearise(
          theta(p), weight_, scale_, score_block_,
          [&](const Eigen::Ref<const Eigen::MatrixXd>& J, const Eigen::Ref<const Eigen::VectorXd>& r) {
            rows.add(J, r);
            scores_.push_back(J.transpose() * r);
          });
    };
    ls.cost = [this](const Eigen::VectorXd& p) {
      const std::optional<Eigen::Vector3d> squares = predictor_.squares(theta(p));
      return squares ? 0.5 * squares->dot(weight_.cwiseAbs2()) : std::numeric_limits<double>::infinity();
    };
    return ls;
  }

 private:
  const pem::Amb1dofPredictor& predictor_;
  Parameters origin_, scale_;
  Index score_block_;
  Eigen::Vector3d weight_ = Eigen::Vector3d::Ones();
  bool every_ = false;
  std::vector<Parameters> scores_;
};

double rms(const Eigen::VectorXd& x) { return x.norm() / std::sqrt(double(x.size())); }

// The checks both entry points share; returns the spread (rms about the mean) of every output.
Eigen::Vector3d checked_spread(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, const Eigen::MatrixXd& r,
                               double sample_time, const Amb1dofPredictionErrorOptions& options) {
  const Index N = y.rows();
  if (y.cols() != 3 || u.cols() != 2 || r.cols() != 2 || u.rows() != N || r.rows() != N)
    throw Error(kPemWho + ": needs y = [x, i1, i2], u and r at [u1, u2] with equal samples, got y " +
                std::to_string(N) + " x " + std::to_string(y.cols()) + ", u " + std::to_string(u.rows()) + " x " +
                std::to_string(u.cols()) + ", r " + std::to_string(r.rows()) + " x " + std::to_string(r.cols()));
  if (!(sample_time > 0.0) || !std::isfinite(sample_time))
    throw Error(kPemWho + ": sample time must be finite and > 0");
  if (!y.allFinite() || !u.allFinite() || !r.allFinite())
    throw Error(kPemWho + ": y, u and r must be finite (a NaN or infinite sample)");
  if (options.score_block < 1 || options.min_blocks < 1)
    throw Error(kPemWho + ": score_block and min_blocks must be >= 1");
  if (options.max_iterations < 0 || !(options.step_tolerance > 0.0))
    throw Error(kPemWho + ": max_iterations must be >= 0 and step_tolerance > 0");
  if (options.residual_lags < 1 || !(options.max_residual_z > 0.0) || !(options.max_residual_correlation >= 0.0))
    throw Error(kPemWho + ": residual_lags must be >= 1, max_residual_z > 0 and max_residual_correlation >= 0");
  if (!(options.min_excitation_ratio >= 0.0 && options.min_excitation_ratio < 1.0))
    throw Error(kPemWho + ": min_excitation_ratio must be in [0, 1)");
  if (N < options.score_block * options.min_blocks)
    throw InsufficientData(kPemWho + ": " + std::to_string(N) + " samples; the uncertainty needs at least " +
                           std::to_string(options.min_blocks) + " blocks of " + std::to_string(options.score_block));
  if (!(r.cwiseAbs().maxCoeff() > 0.0))
    throw InsufficientData(kPemWho + ": the excitation r is zero: nothing but noise drives the loop");
  // r1 and r2 in lockstep (a chirp on both inputs, a multisine period of the Hadamard pattern)
  // excite one direction of the two coils; the other is driven by the sensor noise alone and
  // the fit reads it through the model error, with a sigma that does not cover it: in the
  // soak (soak_slow_test.cpp) such windows of an unchanged bearing read R1 +38 % at 1.5-3
  // sigmas, window after window, and raised false step ERRORs.
  refuse_lockstep_excitation(r, options.min_excitation_ratio, kPemWho);
  Eigen::Vector3d spread;
  for (Index j = 0; j < 3; ++j) {
    spread(j) = rms(y.col(j).array() - y.col(j).mean());
    if (!(spread(j) > 0.0))
      throw InsufficientData(kPemWho + ": output " + std::to_string(j + 1) + " of [x, i1, i2] does not vary");
  }
  return spread;
}

void check_start(const Vector9& v) {
  if (!v.allFinite() || (v.array() == 0.0).any())
    throw Error(kPemWho + ": a starting v1..v9 is not finite or has a zero entry");
}

// Refines the ranked starts (the next one when the solver cannot evaluate a start) and fills
// the fit: estimates, rank and conditioning, sandwich covariance, continuous and discrete model.
Amb1dofPredictionErrorFit refine(const pem::Amb1dofPredictor& predictor, const Eigen::MatrixXd& r,
                                 const std::vector<Parameters>& starts, const std::vector<std::size_t>& order,
                                 bool weighting_pass, const Eigen::Vector3d& spread, double sample_time,
                                 const Amb1dofPredictionErrorOptions& options) {
  // Cold: pass 1 re-weights the outputs by their rms at every step (the fixed point is the
  // maximum-likelihood estimate for independent Gaussian errors) and stops within
  // kWeightingTolerance standard errors; pass 2 keeps the weights of its end and converges to
  // step_tolerance (re-weighting at every step converges only linearly). Fixed weights from a
  // cold start instead crawl on noise-free records, where the predictor of x approaches a
  // deadbeat one. Warm: the start is near the solution, its rms are the weights of pass 2.
  LevenbergMarquardtOptions first, second;
  first.max_iterations = second.max_iterations = options.max_iterations;
  first.step_tolerance = std::max(kWeightingTolerance, options.step_tolerance);
  second.step_tolerance = options.step_tolerance;
  // Near the solution: almost Gauss-Newton from the first step (damping of the order of the
  // column norms would hold back the weakly determined directions, cond(J) ~ 1e4..1e6).
  second.initial_damping = kNearDamping;
  std::string failure;
  for (const std::size_t index : order) {
    const Parameters& start = starts[index];
    const Parameters scale = parameter_scale(start.head<9>(), pem::gain_of(start), spread);
    Problem problem(predictor, start, scale, options.score_block);
    std::optional<LevenbergMarquardtResult> solution;
    int iterations = 0;
    double start_cost = 0.0;
    try {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(pem::kParameters);
      if (weighting_pass) {
        problem.reweight_every_linearisation(true);
        const LevenbergMarquardtResult pass = levenberg_marquardt(problem.least_squares(), p, first);
        problem.reweight_every_linearisation(false);
        iterations = pass.iterations;
        start_cost = pass.initial_cost;
        p = pass.p;
      } else if (!problem.reweight(p)) {
        throw InsufficientData(kPemWho + ": the predictor of the start diverges");
      }
      solution = levenberg_marquardt(problem.least_squares(), p, second);
      if (!weighting_pass) start_cost = solution->initial_cost;
    } catch (const InsufficientData& error) {
      failure += (failure.empty() ? "" : "; ") + std::string(error.what());
      continue;
    }
    const Parameters theta = problem.theta(solution->p);
    const std::optional<Eigen::MatrixXd> errors = predictor.errors(theta);
    if (!errors) throw InsufficientData(kPemWho + ": the predictor diverges at the solution");
    const ResidualIndependence check =
        residual_independence(*errors, {"x", "i1", "i2"}, r, {"r1", "r2"}, options.residual_lags);
    if (check.z > options.max_residual_z && std::abs(check.correlation) > options.max_residual_correlation) {
      failure += (failure.empty() ? "" : "; ") + kPemWho + ": the prediction errors still hold the past r (" +
                 check.worst + ": z = " + std::to_string(check.z) + ", correlation " +
                 std::to_string(check.correlation) + ")";
      continue;
    }
    Amb1dofPredictionErrorFit fit;
    fit.residual_check = check;
    fit.start_index = static_cast<int>(index);
    fit.iterations = iterations + solution->iterations;
    fit.converged = solution->converged;
    fit.termination = solution->message;
    fit.start_cost = start_cost;
    fit.final_cost = solution->final_cost;

    // Rank and conditioning of the column-equilibrated Jacobian (throws InsufficientData), and
    // the sandwich (J'J)^-1 S (J'J)^-1 of the scaled parameters.
    LeastSquaresOptions so;
    so.max_condition = options.max_condition;
    const LeastSquaresSolution curvature = solution->rows.solve(so);
    fit.condition_number = curvature.condition_number;
    Eigen::MatrixXd score_covariance = Eigen::MatrixXd::Zero(pem::kParameters, pem::kParameters);
    for (const Parameters& g : problem.scores()) score_covariance += g * g.transpose();
    const Eigen::MatrixXd cov_p = curvature.inverse_gram * score_covariance * curvature.inverse_gram;
    fit.v = theta.head<9>();
    fit.offset = theta.segment<3>(9);
    fit.initial_state = theta.segment<4>(pem::kInitial);
    fit.predictor_gain = pem::gain_of(theta);
    fit.covariance = scale.head<9>().asDiagonal() * cov_p.topLeftCorner<9, 9>() * scale.head<9>().asDiagonal();
    // What the data must support is v; the nuisance directions (the initial state, which the
    // predictor forgets within a few samples) may be far weaker than any v.
    for (Index i = 0; i < 9; ++i) {
      const double relative = std::sqrt(fit.covariance(i, i)) / std::abs(fit.v(i));
      if (!(relative <= kMaxRelativeSigma))
        throw InsufficientData(kPemWho + ": the data do not determine v" + std::to_string(i + 1) + " (one sigma " +
                               std::to_string(100.0 * relative) + " % of its value)");
    }
    const std::optional<Eigen::Vector3d> squares = predictor.squares(theta);  // the scored samples only
    if (!squares) throw InsufficientData(kPemWho + ": the predictor diverges at the solution");
    fit.residual_rms = (*squares / double(predictor.scored_samples())).cwiseSqrt();
    fit.scored_samples = predictor.scored_samples();

    Eigen::Matrix4d A;
    Eigen::Matrix<double, 4, 3> B;
    pem::structure_matrices(fit.v, Eigen::Vector3d::Zero(), A, B);
    fit.continuous.A = A;
    fit.continuous.B = B.leftCols(2);
    fit.continuous.C = output_matrix();
    fit.continuous.D = Eigen::MatrixXd::Zero(3, 2);
    fit.discrete = c2d_zoh(fit.continuous, sample_time);
    return fit;
  }
  throw InsufficientData(failure);
}

}  // namespace

PemWarmStart amb1dof_cold_start(const Vector9& v, const Eigen::Vector3d& spread, double sample_time) {
  check_start(v);
  if (!spread.allFinite() || !(spread.minCoeff() > 0.0))
    throw Error(kPemWho + ": the spread of every output must be finite and > 0");
  const Parameters theta = cold_start(v, Eigen::MatrixXd::Zero(1, 3), sample_time, spread);
  PemWarmStart start;
  start.v = v;
  start.predictor_gain = pem::gain_of(theta);
  return start;
}

Amb1dofPredictionErrorFit fit_amb1dof_prediction_error(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                       const Eigen::MatrixXd& r, double sample_time,
                                                       const std::vector<Vector9>& v_starts,
                                                       const Amb1dofPredictionErrorOptions& options) {
  const Eigen::Vector3d spread = checked_spread(y, u, r, sample_time, options);
  if (v_starts.empty()) throw Error(kPemWho + ": needs at least one starting v1..v9");
  for (const Vector9& v : v_starts) check_start(v);
  const pem::Amb1dofPredictor predictor(y, u, sample_time, options.clamped);

  // The start whose predictor has the lowest cost goes on (the next one if it fails).
  std::vector<Parameters> starts;
  std::vector<std::pair<double, std::size_t>> ranked;
  for (const Vector9& v : v_starts) {
    starts.push_back(cold_start(v, y, sample_time, spread));
    const std::optional<Eigen::Vector3d> squares = predictor.squares(starts.back());
    const double cost = squares ? squares->dot(spread.cwiseAbs2().cwiseInverse()) : 0.0;
    if (squares && std::isfinite(cost)) ranked.emplace_back(cost, starts.size() - 1);
  }
  if (ranked.empty()) throw InsufficientData(kPemWho + ": the predictor of every starting model diverges");
  std::sort(ranked.begin(), ranked.end());
  std::vector<std::size_t> order;
  for (const auto& entry : ranked) order.push_back(entry.second);
  return refine(predictor, r, starts, order, true, spread, sample_time, options);
}

Amb1dofPredictionErrorFit fit_amb1dof_prediction_error_from(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                            const Eigen::MatrixXd& r, double sample_time,
                                                            const PemWarmStart& start,
                                                            const Amb1dofPredictionErrorOptions& options) {
  const Eigen::Vector3d spread = checked_spread(y, u, r, sample_time, options);
  check_start(start.v);
  if (!start.offset.allFinite() || !start.predictor_gain.allFinite())
    throw Error(kPemWho + ": the warm start's offset or predictor gain is not finite");
  const pem::Amb1dofPredictor predictor(y, u, sample_time, options.clamped);
  const Parameters theta = pem::pack(start.v, start.offset, first_state(y), start.predictor_gain);
  if (!predictor.squares(theta))
    throw InsufficientData(kPemWho + ": the predictor of the warm start diverges on this record");
  return refine(predictor, r, {theta}, {0}, false, spread, sample_time, options);
}

}  // namespace ambid::ident
