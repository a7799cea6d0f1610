#pragma once
// The joint autoregression that whitens the closed-loop noise of the audit's outputs before a
// comparison of two replays (the improvement test of audit_significance.hpp on whitened
// signals): in closed loop the sensor noise, the process force and the current noise are fed
// around the loop, so the residuals of x, i1 and i2 are coloured and share most of their noise.
// Each output is predicted from the past of all outputs and from the outputs before it at the
// same sample; the prediction error of that noise model, applied alike to the measurement and
// every replay, weighs a difference between two models by the noise's own spectrum, with the
// part of each output's noise that the others predict taken out. A fixed filter changes the
// test's power, not its validity (the improvement test estimates the remaining noise
// covariance itself).
#include <vector>

#include <Eigen/Core>

#include "diagnostics/audit/audit_replay.hpp"

namespace ambid::diag {

// Order of the autoregression.
constexpr Eigen::Index kWhiteningOrder = 20;

struct NoiseWhitening {
  // Per output j the coefficients of its regressors (lagged outputs, then the earlier outputs at
  // the same sample); empty: no whitening (the segment was too short to fit it).
  std::vector<Eigen::VectorXd> ar;
  // The samples a clamp acted on (Segment::left_out of the record): set to zero before the
  // filter, so that what was logged there reaches no whitened sample after them either.
  Segment left_out;
  // y_j[k] less its prediction by the noise model from y itself (samples x outputs).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& signal) const;
};

// e_j[k] = sum_{i=1..order} sum_l a e_l[k - i] + sum_{l<j} c e_l[k] + white, fitted by QR to the
// rows of `residual` (deviations, whole record) in `segment` (its left-out samples are zero
// there, as everywhere in the audit's sums).
NoiseWhitening fit_noise_whitening(const Eigen::MatrixXd& residual, const Segment& segment,
                                   Eigen::Index order = kWhiteningOrder);

}  // namespace ambid::diag
