#pragma once
// The default ARX order of the ARX -> Markov -> ERA methods (okid, projection, closed-loop):
// an order that grows with the record, as the consistent high-order ARX and predictor-based
// subspace methods require.
//
// An ARX model of finite order q truncates the innovations predictor, whose coefficients decay
// as rho^q (rho: spectral radius of the predictor A - AKC; in closed loop also the controller's
// poles, Lee 1995 sec. 2). The truncation bias is fixed by q; the estimation error falls as
// 1/sqrt(N). The estimate is consistent when q grows with N so that the bias falls faster than
// the standard error, rho^q = o(N^-1/2), i.e. q >= d ln N / (-2 ln rho) with d > 1, while the
// number of parameters stays small against N (Ljung & Wahlberg 1992, Adv. Appl. Prob. 24:412;
// Bauer 2005, Automatica 41:359; Chiuso 2007, Automatica 43:1034 use this lag choice).
// rho is a property of the plant and its noise, unknown beforehand: the rule below is
//   q(N) = ceil(kArxOrderPerLogSample ln N),  at most N / (kArxRowsPerParameter (p + m))
// and kArxOrderPerLogSample = 2 is d / (-2 ln rho) for d = 1.5 and rho = 0.69 (16 on the
// service's 0.25 s windows at 10 kHz, 23 on 8 s). A larger factor fits the bearing's
// nonlinearity as well: at 3 the noise-free 1 V windows of the diagnostics tests err by 1.1 %.
// A predictor with a larger radius needs a larger order (IdentifyOptions::arx_order): the amb1dof bearing
// with sensor noise only has rho ~ 0.996 (the coil mode, whose state the sensor noise hides),
// see identifier/time_domain/ARX_ORDER.md for the error against window and order.
#include <vector>

#include <Eigen/Core>

namespace ambid::ident {

inline constexpr double kArxOrderPerLogSample = 2.0;
inline constexpr Eigen::Index kArxRowsPerParameter = 20;  // equations per ARX coefficient, at least

// q(N) above for `samples` equations, `outputs` p and `inputs` m of the regressors. Throws
// InsufficientData when not even order 1 has kArxRowsPerParameter equations per coefficient,
// Error for outputs < 1 or inputs < 0.
Eigen::Index default_arx_order(Eigen::Index samples, Eigen::Index outputs, Eigen::Index inputs);

// The Markov counts ERA tries in turn by default: the first whose Hankel matrix determines the
// model order (EraOptions::min_gap) is used. 30 (3 ms at 10 kHz) suffices for the bearing at
// low noise; at 0.1 um / 1 mA its 4th state sinks into the noise floor there and needs 100
// (ARX_ORDER.md). The shortest that works keeps ERA closest to the lags the ARX fits directly.
const std::vector<Eigen::Index>& default_markov_counts();

}  // namespace ambid::ident
