#pragma once
// Kalman gain of an identified model from its gain Markov parameters by least squares
// (Lee 1995 eq. 4.35).
//
// Innovation model (Lee 2.3/2.4): x[k+1] = A x + B u + A K e,  y = C x + D u + e.
// Its gain Markov parameters are N_k = C A^(k-1) (A K) = C A^k K, k >= 1.
//   predictor gain  AK:  [C; C A; ...; C A^(k-1)] AK = [N_1; ...; N_k]
//   filter gain     K :  [C A; ...; C A^k]        K  = [N_1; ...; N_k]      (4.35)
// Both are solved by QR least squares (never the normal equations of 4.35 as printed).
// Lee's Appendix B kalman.m returns AK; here both are returned under explicit names.
#include <Eigen/Core>

#include "identifier/time_domain/least_squares.hpp"
#include "identifier/time_domain/markov.hpp"

namespace ambid::ident {

struct KalmanGainEstimate {
  Eigen::MatrixXd predictor_gain;  // AK: xhat[k+1] = A xhat + B u + AK (y - C xhat - D u)
  Eigen::MatrixXd filter_gain;     // K (4.35), AK = A K; empty when A is singular (K not unique)
  LeastSquaresSolution fit;        // of the predictor gain
};

// gain: N_0 .. N_J with J >= count; count >= 1 blocks enter (default J when 0). Throws Error
// on inconsistent sizes and InsufficientData when [C; ...; C A^(count-1)] does not have full
// column rank (the model is not observable within count steps).
KalmanGainEstimate kalman_gain_from_markov(const Eigen::MatrixXd& A, const Eigen::MatrixXd& C,
                                           const MarkovSequence& gain, Eigen::Index count = 0,
                                           const LeastSquaresOptions& options = {});

}  // namespace ambid::ident
