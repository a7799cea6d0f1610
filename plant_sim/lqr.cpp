#include "plant_sim/lqr.hpp"

#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "plant_sim/dare.hpp"

namespace ambid::sim {

LqrGain dlqr(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
             const Eigen::MatrixXd& N) {
  LqrGain out;
  out.X = solve_dare(A, B, Q, R, N);
  Eigen::MatrixXd cross = A.transpose() * out.X * B;
  if (N.size() != 0) cross += N;
  out.K = linalg::ldlt_solve(R + B.transpose() * out.X * B, cross.transpose());
  out.closed_loop_poles = linalg::eigenvalues(A - B * out.K);
  return out;
}

ObserverGain predictor_gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& C, const Eigen::MatrixXd& W,
                            const Eigen::MatrixXd& V) {
  LqrGain dual;
  try {
    dual = dlqr(A.transpose(), C.transpose(), W, V);
  } catch (const Error& e) {
    throw Error(std::string("observer gain (dual DARE with A := A', B := C', Q := W, R := V; "
                            "not stabilisable means (C, A) not detectable): ") +
                e.what());
  }
  ObserverGain out;
  out.L = dual.K.transpose();
  out.P = dual.X;
  out.observer_poles = linalg::eigenvalues(A - out.L * C);
  return out;
}

}  // namespace ambid::sim
