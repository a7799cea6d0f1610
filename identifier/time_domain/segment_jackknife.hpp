#pragma once
// Delete-a-group jackknife over contiguous segments of a record: the uncertainty of an
// estimator that reports none (the ARX -> Markov -> ERA methods).
//   The record is cut into K segments of equal length; estimate i uses the record without
//   segment i (the other K - 1 joined end to end);
//   s^2 = (K - 1) / K * sum_i (theta_i - mean theta)^2,
// and the reported sigma = s * t(K - 1) / 2, where t(K - 1) is the two-sided 95.45 % quantile
// of Student's t with K - 1 degrees of freedom: s is itself an estimate from K - 1 degrees of
// freedom, so (theta - truth) / s is t-distributed, and +-2 sigma covers what +-2 standard
// errors cover for a normal error (the 2 of the alert policy's margin). Factor 1.65 at K = 4,
// 1.21 at K = 8, 1.09 at K = 16. Without it a window whose K segments happened to agree
// reported a sigma several times too small (s < 0.3 of the truth in 3.4 % of windows at
// K = 4), and the diagnostics took its ordinary error for a many-sigma step (issue 18 soak:
// false R2 ERRORs on windows of weak excitation).
// Assumption: the estimator is smooth in the data and the errors of segments much longer than
// the loop's memory are nearly independent. A joint between two segments disturbs as many
// regression rows as the model's memory (the ARX order): those rows are left out
// (ArxOptions::breaks), since with little noise they would dominate the fit.
#include <map>
#include <string>
#include <vector>

#include "core/experiment.hpp"

namespace ambid::ident {

// The samples of `experiment` without segment `segment` of `segments` (the rest joined; t
// renumbered uniformly from the first sample), and the sample where the two pieces meet (0
// when the dropped segment is the first or the last: no joint). The controller's initial
// state is kept (the methods that use this only read y, u and r). Throws Error for segment
// out of [0, segments) or segments < 2, InsufficientData when a segment would be shorter
// than 2 samples.
struct LeaveOneSegmentOut {
  Experiment experiment;
  Eigen::Index joint = 0;
};
LeaveOneSegmentOut experiment_without_segment(const Experiment& experiment, Eigen::Index segment,
                                              Eigen::Index segments);

// sigma of every key from the leave-one-out estimates (all with the same keys; at least 2).
// Throws Error for fewer than 2 estimates or mismatched keys.
std::map<std::string, double> jackknife_sigma(const std::vector<std::map<std::string, double>>& leave_one_out);

// The x with P(|T| <= x) = probability for Student's t with `dof` degrees of freedom (closed
// form of the distribution for integer dof, Abramowitz & Stegun 26.7.3-4, solved by bisection).
// Throws Error for dof < 1 or probability outside (0, 1).
double student_t_two_sided_quantile(double probability, int dof);

}  // namespace ambid::ident
