#pragma once
// A plant family's physical structure fitted to the measured plant FRF (`ambid frf`): the
// structure G(s; theta) of the family's linearisation at the record's operating point
// (plant_families.hpp, `frf_structure`) adjusted to every OUTPUT/INPUT pair by the grey-box
// FRF fit (frf_grey_box.hpp: exact ZOH equivalent, noise weights where the FRF has variances),
// and the quantities the family derives from theta (the maglev's unstable pole) with their
// one-sigma uncertainty through the fit's covariance (central differences).
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/experiment.hpp"
#include "core/state_space.hpp"
#include "identifier/frf_types.hpp"

namespace ambid::ident {

struct FrfStructure {
  std::vector<std::string> parameter_names;
  std::vector<std::string> derived_names;
  // The starting theta from the record's header (plant parameters, operating point).
  Eigen::VectorXd (*start)(const Experiment& header) = nullptr;
  // The linear model (the family's y, u signals in the FRF's order) of theta.
  ContinuousSystem (*model)(const Eigen::VectorXd& theta) = nullptr;
  // The derived quantities of theta, in derived_names order.
  Eigen::VectorXd (*derived)(const Eigen::VectorXd& theta) = nullptr;
  // The output whose level sets the operating point (the maglev's gap "x"): records of
  // reference steps are fitted level by level (frf_levels.hpp). Empty: one fit of the record.
  std::string level_signal;
  // theta at the operating point `to` from theta at `from` by the family's law (each a map of
  // the y and u means), for the estimate at the operating point pooled over the levels
  // (frf_levels.hpp); null: none.
  Eigen::VectorXd (*transport)(const Eigen::VectorXd& theta, const std::map<std::string, double>& from,
                               const std::map<std::string, double>& to) = nullptr;
};

struct StructuredFrfFit {
  std::vector<std::string> parameter_names, derived_names;
  Eigen::VectorXd value, sigma;                  // theta
  Eigen::MatrixXd covariance;                    // of theta
  Eigen::VectorXd derived_value, derived_sigma;  // the derived quantities
  double misfit = 0.0;                           // mean |w e|^2 (frf_grey_box.hpp)
  bool converged = false;
};

// Fits `structure` to `plant` (outputs x inputs in the family's order). Throws Error for sizes
// that do not match the structure and InsufficientData when the fit leaves theta undetermined
// (no covariance).
StructuredFrfFit fit_structured_frf(const Experiment& header, const Frf& plant, const FrfStructure& structure);

}  // namespace ambid::ident
