#pragma once
// Whether a fitted extension predicts the validation segment better than noise alone explains
// (experiment-format.md: cause "none" unless an extension improves the model "beyond what
// noise explains").
//
// With e0 = y_meas - y_nominal, d = y_extended - y_nominal on the validation segment and the
// contract's per-output weights w_j = 1 / ||y_meas,j - mean||^2, the reduction of the weighted
// residual sum of squares (sum over outputs of NRMSE^2) is
//   S0 - S1 = sum_j w_j (||e0_j||^2 - ||e0_j - d_j||^2) = 2 sum_j w_j e0_j . d_j - ||d||_w^2.
// d is fitted on the estimation segment only, so under H0 (the nominal model is right: e0 is
// zero-mean noise, independent of d) z = sum_j w_j e0_j . d_j / sigma is standard normal, with
//   sigma^2 = sum_{j,l} w_j w_l sum_{|h|<=M} (1 - |h|/(M+1)) gamma_jl(h) sum_k d_j[k] d_l[k+h],
// gamma the residual auto-/cross-covariances (coloured, closed-loop noise: the effective
// degrees of freedom, not the sample count, set the spread). gamma is estimated from the
// extended model's residual e0 - d, which is noise under H0 and, for a right effect, also
// under H1 (for a wrong one it still holds model error, which only makes the test stricter).
// P(z > z_obs | H0) is the false-acceptance probability of one candidate.
#include <Eigen/Core>

#include "diagnostics/audit/audit_replay.hpp"

namespace ambid::diag {

struct ImprovementTest {
  double reduction = 0.0;  // S0 - S1 (sum over outputs of NRMSE^2 before minus after)
  double z = 0.0;          // standardised improvement under H0
  double p_value = 1.0;    // one-sided P(z >= z_obs | H0)
};

// measured, nominal, extended: deviations (samples x outputs), at least validation.end rows.
// `max_lag` M of the covariance sum (clamped to a quarter of the segment). The samples the
// segment leaves out (a controller clamp acted) count in no sum. Error when the
// segment does not fit the signals or a measured output is constant there.
ImprovementTest improvement_test(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& nominal,
                                 const Eigen::MatrixXd& extended, const Segment& validation, Eigen::Index max_lag);

// The z above which a candidate is accepted when the best of `candidates` is tested at overall
// false-acceptance probability `alpha` (Bonferroni: alpha / candidates each). Error for alpha
// outside (0, 1) or candidates < 1.
double acceptance_threshold(double alpha, int candidates);

}  // namespace ambid::diag
