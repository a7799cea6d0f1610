#pragma once
// Order selection for the rational fit by validation misfit (with the AIC reported alongside).
//
// Every candidate (n, m = n - relative degree) is fitted on the even-numbered lines and scored
// on the odd-numbered ones (validation misfit: mean |w (G_model - G)|^2, about 1 at the noise
// level with noise weights). The chosen candidate is the one with the fewest parameters (then
// the lowest n) whose validation misfit is within
//   best * (1 + parsimony) + floor,   floor = parsimony with noise weights (the noise level is
//                                     1), negligible_misfit otherwise,
// of the best candidate: a higher order must earn its parameters by explaining more than the
// noise. The chosen order is then refitted on all lines.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "identifier/frequency_domain/rational_fit.hpp"

namespace ambid::ident {

struct OrderSearchOptions {
  int min_denominator_degree = 1;
  int max_denominator_degree = 6;
  std::vector<int> relative_degrees = {0, 1, 2};  // n - m, each >= 0
  double parsimony = 0.1;
  double negligible_misfit = 1e-10;  // relative / uniform weighting: misfits below are "exact"
  RationalFitOptions fit;            // weighting, compensation, iterations (degrees ignored)
};

struct OrderCandidate {
  int numerator_degree = 0, denominator_degree = 0, parameters = 0;
  bool ok = false;
  std::string failure;  // why the fit failed, when !ok
  double estimation_misfit = 0.0, validation_misfit = 0.0;
  double aic = 0.0;  // on the estimation lines (informative)
};

struct OrderSelection {
  std::vector<OrderCandidate> candidates;
  std::size_t chosen = 0;  // index into candidates
  RationalFit fit;         // the chosen order fitted on all lines
};

// Throws Error for bad options and InsufficientData when no candidate could be fitted.
OrderSelection select_rational_order(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& response,
                                     const Eigen::VectorXd& variance, const OrderSearchOptions& options);

}  // namespace ambid::ident
