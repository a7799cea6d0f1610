#pragma once
// Prediction-error refinement (direct method, innovations form) of the seed 000 structure
// parameters v1..v9 of `amb1dof_voltage` (amb1dof_structure.hpp) from closed-loop data.
//
// Model: the structure of eq. (4) sampled with a zero-order hold, with constant terms w of the
// x'', i1', i2' rows (the shift of the operating point, e.g. a hot coil settles at other bias
// currents) and a free predictor gain K (4 x 3):
//   x^[t+1] = Ad(v) x^[t] + Bd(v) u[t] + g(v, w) + K (y[t] - C x^[t]),   x^[0] = x0 (fitted)
// The residual is the one-step prediction error  e[t] = y[t] - C x^[t]  of every output,
// weighted by 1 / its rms (cold start: re-weighted at every step until within one standard
// error, whose fixed point is the maximum-likelihood estimate for independent Gaussian errors
// of each output, then with those weights held to convergence; warm start: the weights of the
// start held). Levenberg-Marquardt with exact derivatives minimises it (amb1dof_predictor.hpp: the forward
// sensitivity recursion of the predictor; levenberg_marquardt.hpp in time_domain/: steps by
// QR of the Jacobian streamed in row blocks, never J'J), until the Gauss-Newton step is below
// `step_tolerance` standard errors.
// Cold start: from the given starting estimate whose predictor has the lowest cost (the next
// one if the solver fails or its solution fails the residual check); K starts from the Kalman gain of the starting
// model (Riccati iteration, no process noise): a stable predictor even though the plant is unstable. Warm start: from a
// previous fit's v, w and K (pem_warm_start.hpp). x0 starts at the first sample (x' = 0) and is fitted either way (the
// errors are linear in it).
//
// Consistency in closed loop (the direct prediction-error method): the innovations form with
// a free K contains the true noise model (white sensor noise, and process noise through the
// plant's own states), so the prediction errors of the true model are white and independent
// of the past u and y, however strongly the controller feeds the noise back; least squares on
// the equation error is biased exactly by that feedback. u is the recorded plant input (it
// needs no noise model of its own: the controller's output is known exactly).
// Nothing here stabilises the identified plant: only the predictor A - K C is stable.
// Noise-free data determine no noise model: K is then set by the model error alone (the true
// plant's nonlinearity) and tends to a deadbeat predictor; the fit takes 30-50 steps, and at
// small excitation the Jacobian becomes ill-conditioned (v2, v3 against K) and is refused.
//
// Uncertainty (one sigma): the sandwich  H^-1 S H^-1,  H^-1 = (J'J)^-1 from the QR factor of
// the column-equilibrated Jacobian (which also decides rank and conditioning) and S the
// covariance of the score J'e from sums over blocks of consecutive samples (batch means).
// Assumption: the prediction errors are stationary and correlated over much less than a
// block; for white prediction errors S = sigma^2 J'J and this is the usual (J'J)^-1 sigma^2.
// It does not include a model-structure error (e.g. the nonlinearity at large excitation).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/pem_warm_start.hpp"
#include "identifier/time_domain/residual_independence.hpp"

namespace ambid::ident {

// InsufficientData naming `who` when r = [r1, r2] moves in lockstep (a chirp or a multisine on
// both inputs): the weaker direction of its centred power carries at most `min_ratio` of the
// stronger's, so one direction of the two coils is driven by the sensor noise alone. A zero or
// one-sample r passes (its own checks say more).
void refuse_lockstep_excitation(const Eigen::MatrixXd& r, double min_ratio, const std::string& who);

struct Amb1dofPredictionErrorOptions {
  int max_iterations = 60;       // Levenberg-Marquardt iterations per pass (of two)
  double step_tolerance = 0.05;  // converged: the Gauss-Newton step is below this many standard errors
  // Of the column-equilibrated Jacobian; beyond it: InsufficientData. Its weakest directions are
  // usually the initial state's (short windows), so the bound guards the numerics (QR keeps
  // ~16 - 12 digits); whether the data support v is checked on v's own sigmas.
  double max_condition = 1e12;
  Eigen::Index score_block = 100;  // samples per block of the score covariance (10 ms at 10 kHz)
  Eigen::Index min_blocks = 10;    // fewer blocks in the record: InsufficientData
  // The power of r in its weaker direction (the smaller eigenvalue of the 2 x 2 scatter of r1,
  // r2) relative to the stronger: below it r1 and r2 move in lockstep up to round-off (a chirp
  // on both inputs, a multisine period of the Hadamard pattern) and the record cannot tell the
  // coils apart: InsufficientData. Independent PRBS on both inputs: ~1.
  double min_excitation_ratio = 1e-6;
  // The residual check (time_domain/residual_independence.hpp): the prediction errors'
  // correlation with the past r at lags 1..residual_lags. A solution whose largest |z| exceeds
  // max_residual_z with a correlation beyond max_residual_correlation is refused and the next
  // start tried (a wrong local minimum: one window of a PID loop read ks, kr1, kr2 -102 %).
  // The correlation bound lets a right linear model of the nonlinear bearing pass on
  // noise-free records, where any deterministic model error is significant. Weak as a guard
  // (measured on a 1 s LQR record at 0.1 um / 1 mA, models held at their start): kw1 +50 %
  // gives z 19, correlation -0.16, ks, kr1, kr2 of the wrong sign z 5.4, correlation 0.04, and
  // R1 +30 % passes: the free predictor gain K absorbs most of a wrong plant model. at 1 V the
  // nonlinearity alone gives z 7-10, correlation 0.05-0.07 (e_i1 with r1 at lag 15, LQR and
  // observer loops, 2 s), z 19-23, correlation ~0.13-0.16 (e_i2 with r2 at lag 15, PID and
  // lead-lag loops). Whiteness is reported, not required: the same nonlinearity makes
  // noise-free errors coloured (z 100-140 at lags 1-2).
  Eigen::Index residual_lags = 20;
  double max_residual_z = 5.0;
  double max_residual_correlation = 0.2;
  // Per sample, or empty: a controller clamp acted (the recorded u is not what the plant got);
  // the prediction error whose prediction used that u is left out of the cost
  // (amb1dof_predictor.hpp).
  std::vector<bool> clamped;
};

struct Amb1dofPredictionErrorFit {
  Eigen::Matrix<double, 9, 1> v;               // v1..v9
  Eigen::Matrix<double, 9, 9> covariance;      // of v
  Eigen::Vector3d offset;                      // w: constant terms of the x'', i1', i2' rows
  Eigen::Vector4d initial_state;               // x0 = [x, x', i1, i2] at the first sample
  Eigen::Matrix<double, 4, 3> predictor_gain;  // K
  ContinuousSystem continuous;                 // Ac(v), Bc(v), C = [x, i1, i2], D = 0
  DiscreteSystem discrete;                     // its zero-order hold at the sample time
  Eigen::Vector3d residual_rms;                // prediction error per output [x, i1, i2], SI units
  double condition_number = 0.0;               // column-equilibrated Jacobian at the solution
  int iterations = 0;                          // accepted Levenberg-Marquardt steps
  int start_index = 0;                         // the start that went on (0 for a warm start)
  bool converged = false;                      // false: stopped at max_iterations or without progress
  std::string termination;                     // why the solver stopped
  double start_cost = 0.0, final_cost = 0.0;   // weighted 0.5 sum e^2: at the start (its weights), at the end
  ResidualIndependence residual_check;         // of the prediction errors at the solution
  Eigen::Index scored_samples = 0;             // whose prediction error is in the cost
};

// y: samples x 3 ([x, i1, i2] deviations), u: samples x 2 ([u1, u2] deviations, the recorded
// plant input), r: samples x 2 (the excitation; only checked to be non-zero: without it the
// data would be fitted to noise through the free offsets and initial state), v_starts the
// starting v1..v9 (e.g. least-squares estimates; every entry non-zero). Throws Error for
// inconsistent sizes or no start, InsufficientData when the record is too short for the score
// covariance, when r is zero, when an output does not vary, when the solver fails from every
// start (or every start's predictor diverges), when every solution fails the residual check
// (the message names the largest correlation and its z) or when the Jacobian is rank deficient or ill-conditioned (the
// data do not determine v).
Amb1dofPredictionErrorFit fit_amb1dof_prediction_error(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                       const Eigen::MatrixXd& r, double sample_time,
                                                       const std::vector<Eigen::Matrix<double, 9, 1>>& v_starts,
                                                       const Amb1dofPredictionErrorOptions& options = {});

// The same from a previous fit (warm start); the checks of y, u and r are the same, and the
// start must be finite with every v non-zero (Error otherwise).
Amb1dofPredictionErrorFit fit_amb1dof_prediction_error_from(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u,
                                                            const Eigen::MatrixXd& r, double sample_time,
                                                            const PemWarmStart& start,
                                                            const Amb1dofPredictionErrorOptions& options = {});

// The cold start of a model v (every entry non-zero): no offset, and the predictor gain of the
// steady-state Kalman filter of v's model without process noise and with each output's noise
// a tenth of its `spread` (rms about the mean, > 0): a stable predictor although the plant is
// unstable. The batch method starts from it, the recursive one (amb1dof_recursive_pem.hpp) too.
PemWarmStart amb1dof_cold_start(const Eigen::Matrix<double, 9, 1>& v, const Eigen::Vector3d& spread,
                                double sample_time);

}  // namespace ambid::ident
