#pragma once
// Physical realisation through a deadbeat observer/controller model (seed 000, Gosiewski &
// Paszowski, eq. 16-18 and 39-51).
//
// Closed loop with state feedback from an observer and integral action on some outputs:
//   x[k+1] = A x + B u,  y = C x          (plant, C known)
//   e[k+1] = e[k] - E y[k+1]               (integrators, eq. 39)
//   uf = -F x + Fe e,  u = uf + r          (eq. 42, the controller's observer converged)
// The observer/controller outputs yu = [y; uf] = Cbar [x; e], Cbar = [C 0; -F Fe] (eq. 45).
// When #outputs + #inputs = #states + #integrators, Cbar is square and, if invertible, the
// state is read from every sample, [x; e] = Cbar^-1 yu (eq. 46): the ARX model of the
// observer/controller is exact with order one (eq. 47) and gives the physical A, B (eq. 49-51).
//
// Two departures from the printed equations, neither changing the result on consistent data:
// 1. Cbar is singular for a symmetric bearing under a symmetric design (the two coils' gains on
//    x' and on e are then opposite, so [-F(:, x') Fe] has rank one). The integrator state e is
//    however known: it is the controller's own state, e[k] = e[k-1] - E y[k], run on the
//    recorded y. So x is read from [C; -F] x = [y; uf - Fe e] with the left inverse that takes
//    the measured states from y and only the unmeasured ones from the feedback:
//      x = C+ y + N (-F N)+ (uf - Fe e + F C+ y),  N an orthonormal basis of ker C.
//    This needs C of full row rank and -F N of full column rank; it equals Cbar^-1 yu whenever
//    Cbar is invertible.
// 2. Eq. (47) as printed repeats y[k] among its regressors (in yu[k] and in v[k]); the split of
//    that coefficient, i.e. the paper's G_d in A = L11 - G_d C, is not determined by the data.
//    The same equations are solved without the duplicate: x[k+1] = A x[k] + B u[k] by QR least
//    squares, and the one-step deadbeat gain of the observer/controller output is reported:
//      x = M_x [y; uf - Fe e],  Gt = -A M_x  (n x (p + m)),  A + Gt [C; -F] = 0,
//      x[k+1] = B u[k] - Gt [y[k]; uf[k] - Fe e[k]].
// The method assumes the controller's observer has converged to the true state (x_hat = x):
// exact for noise-free data when the observer's model is the plant; biased by the observer's
// model error otherwise (the paper's examples II and III).
#include <Eigen/Core>

#include "core/state_space.hpp"
#include "identifier/time_domain/least_squares.hpp"

namespace ambid::ident {

struct DeadbeatOptions {
  Eigen::Index transient_samples = 0;  // leading samples skipped (observer transient)
  // Estimate a constant c in x[k+1] = A x + B u + c (one more regressor). Data in deviations
  // from the NOMINAL operating point carry an offset when the plant settles elsewhere (e.g. a
  // coil resistance off nominal moves the equilibrium currents); without c that offset biases
  // A and B. c = 0 for data around the true equilibrium.
  bool estimate_offset = true;
  // > 0: instrumental variables (instrumental_variables.hpp) with the instruments
  // r[k], r[k-1], ..., r[k-lags] (r = u - uf, the excitation) and the constant, instead of
  // least squares. Sensor noise reaches both the reconstructed state and, through the
  // controller, u: least squares is then biased; r is independent of the noise, so IV is
  // consistent. The first `lags` equations are dropped.
  Eigen::Index instrument_lags = 0;
  LeastSquaresOptions least_squares;
};

struct DeadbeatRealization {
  DiscreteSystem system;          // A, B, the known C, D = 0: physical coordinates
  Eigen::MatrixXd deadbeat_gain;  // Gt = -A M_x, n x (outputs + inputs)
  Eigen::MatrixXd state_map;      // M_x: x = M_x [y; uf - Fe e], n x (outputs + inputs)
  Eigen::MatrixXd cbar;           // Cbar = [C 0; -F Fe]
  bool cbar_invertible = false;   // eq. (46) applies as printed
  Eigen::VectorXd offset;         // c (zero when not estimated)
  LeastSquaresSolution fit;       // x[k+1]' = [x[k]' u[k]' (1)] theta, theta = [A B (c)]'
  // Covariance of p = [A row by row, B row by row] (n n + n m entries).
  Eigen::MatrixXd parameter_covariance;
};

// y: samples x p, u: samples x m (plant input), uf: samples x m (feedback signal, u - r),
// e: samples x ni (integrator states e[k], empty when ni = 0); C: p x n, F: m x n,
// Fe: m x ni. Throws Error for inconsistent sizes, C without full row rank, or a feedback
// that does not see the unmeasured states (-F N rank deficient); InsufficientData for too
// short or unexciting data.
DeadbeatRealization deadbeat_realization(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, const Eigen::MatrixXd& uf,
                                         const Eigen::MatrixXd& e, const Eigen::MatrixXd& C, const Eigen::MatrixXd& F,
                                         const Eigen::MatrixXd& Fe, double sample_time,
                                         const DeadbeatOptions& options = {});

// Integrator states of the controller run on the recorded outputs: e[k] = e[k-1] - E y[k],
// e[-1] = initial (the controller's integrator state at the first sample; zero when empty).
Eigen::MatrixXd integrator_states(const Eigen::MatrixXd& y, const Eigen::MatrixXd& E,
                                  const Eigen::VectorXd& initial = {});

}  // namespace ambid::ident
