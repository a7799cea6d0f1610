#pragma once
// Whether an amplifier's gain varies over the record (issue 17: a slowly varying gain is outside
// the catalogue, whose effects are constant; a gain oscillating about its nominal value fits no
// constant effect, and its error is not coherent with r in a window, so neither the improvement
// test nor the residual check sees it).
//
// Method: the record is cut into `segments` + 1 equal parts, the first left out (the start from
// the operating point, where the replay's sensitivity is largest and any model error shows most:
// under PID with a fitted eddy current, the first part's gain had a third of the others' standard
// error and pulled the mean), and, per amplifier, the gain error is fitted in each part alone, linearised about the
// checked model (its replay y and the replay with that amplifier's gain raised by kProbe, whose difference over kProbe
// is the sensitivity S): theta_s = <e, S>_s / <S, S>_s, e = y_meas - y. Both are first whitened by the joint
// autoregression of the noise (audit_whitening.hpp) fitted to the residual left after a first,
// unwhitened per-part fit; outputs weighted by the inverse variance of their whitened residual;
// the standard error of each theta_s from the whitened residual's auto/cross-covariances (lag
// window kDriftLags, the improvement test's estimator, audit_significance.hpp). A constant gain,
// right or wrong, gives the same theta in every part: Q = sum_s (theta_s - mean)^2 / se_s^2 is
// chi-square with segments - 1 degrees of freedom (Wilson-Hilferty tail), and the weighted
// slope of theta_s against time (a monotone drift, e.g. thermal) is standard normal. Per
// amplifier p = 2 min(p_Q, p_slope), over the amplifiers p = n min(p); the gain varies when
// p < alpha. The fits see the whole record (nothing is fitted on it beyond the per-part gains).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "diagnostics/audit/audit_replay.hpp"
#include "plant_sim/effects.hpp"

namespace ambid::diag {

struct GainDriftChannel {
  int channel = 0;                      // 1-based amplifier (0: the family's one amplifier)
  Eigen::VectorXd gain;                 // fitted gain error per part (dkw, V/V), relative to the checked model
  Eigen::VectorXd se;                   // its standard error
  double q = 0.0, q_p = 1.0;            // heterogeneity chi-square and its upper tail
  double slope_z = 0.0, slope_p = 1.0;  // trend of the gain over time: z and two-sided p
  double p_value = 1.0;                 // 2 min(q_p, slope_p), at most 1
};

struct GainDrift {
  bool determinable = false;
  std::string reason;  // why not, when not determinable
  int segments = 0;
  std::vector<GainDriftChannel> channels;
  double p_value = 1.0;  // smallest channel p times the number of channels, at most 1
  double alpha = 0.0;    // the test's probability of finding a constant gain varying
  bool varies = false;   // p_value < alpha
  int channel = 0;       // the amplifier of the smallest p when it varies
};

// `measured_y`: the record's deviations; `model_y` the replay of the checked model (the nominal
// sidecar with `effects`); `record`: the samples scored (its left_out: where a clamp acted).
// Not determinable (and not varying) when the family has no amplifier_gain effect, the record
// is logged at a coarse resolution (`rounded`: its replay follows the logged rounding, whose
// residual is no noise), or the parts hold fewer than 200 kept samples each. Error for
// segments < 3 or alpha outside (0, 1).
GainDrift gain_drift_test(const Experiment& measured, const Eigen::MatrixXd& measured_y,
                          const std::vector<sim::Effect>& effects, const Eigen::MatrixXd& model_y,
                          const Segment& record, bool rounded, int segments, double alpha);

}  // namespace ambid::diag
