#pragma once
// Whether the validation residual of an (extended) model is consistent with noise
// (experiment-format.md: "white enough, uncorrelated with r"), the audit's check of an accepted
// model before it names a cause.
//
// The audit replays models in closed loop driven by r (simulation error), so even the right
// model leaves the closed-loop response to sensor and process noise: a coloured residual whose
// level and colour only the data can tell. The check asks a question whose null distribution
// does not depend on that colour: per output, in non-overlapping Hann windows of L samples (K
// of them), the multiple coherence C_b of the residual with the p excitations on every other
// bin b where r has power (>= 1 % of its strongest bin). C_b is the part of the residual
// spectrum coherent with r over its whole power, the rest being the incoherent noise floor,
// bin by bin, so it needs no noise level. When the residual is noise independent of r,
// C_b ~ Beta(p_b, K - p_b) (Gaussian residual, independent windows; bins two apart under
// Hann are nearly independent; p_b the rank of the excitations' cross-spectrum in the bin,
// which a multisine with the same line in both excitations makes 1), and T = sum_b C_b has
// mean sum p_b / K and variance sum p_b (K - p_b) / (K^2 (K + 1)); its upper tail is taken from a scaled chi-square
// with those moments (Wilson-Hilferty). Unmodelled structure driven by r (a wrong plant) raises C_b over the excited
// band. The residual is consistent with noise when the smallest of the q p-values is at least alpha / q (Bonferroni): a
// right model is rejected with probability at most alpha. Not covered: structure not coherent with r (a periodic force
// is the catalogue's harmonic_disturbance; a spectral-line test against neighbouring bins was tried and rejected
// resonant closed-loop noise spectra, so it is not used).
//
// Noise that r itself carries: an excitation reconstructed from a rounded record (r = u - C y_logged,
// audit_rounding.hpp) holds the controller's answer to the logger's rounding, -C q, while a right model's residual
// holds q: the two are correlated, and the residual of a right model is coherent with r (at 1.3 ms the rig's
// derivative gain makes -C q as strong as the excitation: mean coherence 0.46 on a clean record). Then the check
// takes `null_replicas`: residuals and excitations of M records made from the model itself with the same rounding
// (audit_rounding_null.hpp). Their mean cross-spectrum per bin is what noise alone gives; it is subtracted from the
// record's before the coherence is formed. The estimate of a cross-spectrum from K windows scatters about its mean
// with variance S_ee S_rr / K whatever the coherence (Gaussian signals), so the corrected C_b keeps the null law
// above, scaled by 1 + 1/M for the replicas' own scatter. That law assumes Gaussian residuals
// in independent windows; the rounding is neither (on a rig record at 1.3 ms, each of 8 replicas
// checked against the other seven's mean read z from -3.6 to +4.5 under it, and the true model
// of a one-sample delay was rejected at p 5e-10). With at least 3 replicas the check therefore
// also measures the null's spread: T_m of each replica against the others' mean, and the
// record's T against their mean and standard deviation with Student's t of M - 1 degrees of
// freedom; an output's p-value (and z) is that of the two laws that gives the larger p.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ambid::diag {

// A record made from the model with the known noise of the record (e.g. its rounding), replayed like the record:
// residual (samples x outputs) and excitation (samples x excitations), the same samples as the checked residual.
struct NullReplica {
  Eigen::MatrixXd residual, excitation;
};

struct ResidualCheck {
  bool determinable = false;                       // the segment held at least kMinWindows windows
  std::string reason;                              // why not, when not determinable
  Eigen::Index window = 0, windows = 0, bins = 0;  // L, K, excited bins used
  // Per output: mean multiple coherence with r over the excited bins (H0 mean p_b / K), its z
  // and one-sided p-value (with null replicas, under the law that gives the larger p).
  Eigen::VectorXd coherence_mean, coherence_z, coherence_p;
  double p_value = 1.0;    // smallest p-value times q (at most 1)
  bool consistent = true;  // p_value >= alpha (or not determinable)
  int null_replicas = 0;   // records whose mean cross-spectrum with r was subtracted (0: none)
};

// `residual` (samples x outputs) and `excitation` (samples x excitations): the validation
// segment, deviations. `left_out` (per sample, or empty): where a controller clamp acted; the
// windows holding one are left out. `null_replicas` (or none): see above. Not determinable (and consistent) when
// fewer than 16 windows of 64 samples fit or remain. Error for mismatched rows or columns, no excitation, or alpha
// outside (0, 1).
ResidualCheck residual_check(const Eigen::MatrixXd& residual, const Eigen::MatrixXd& excitation, double alpha,
                             const std::vector<bool>& left_out = {},
                             const std::vector<NullReplica>& null_replicas = {});

}  // namespace ambid::diag
