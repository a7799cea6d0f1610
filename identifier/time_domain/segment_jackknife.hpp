#pragma once
// Delete-a-group jackknife over contiguous segments of a record: the uncertainty of an
// estimator that reports none (the ARX -> Markov -> ERA methods).
//   The record is cut into K segments of equal length; estimate i uses the record without
//   segment i (the other K - 1 joined end to end);
//   sigma^2 = (K - 1) / K * sum_i (theta_i - mean theta)^2.
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

}  // namespace ambid::ident
