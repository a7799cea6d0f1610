#include "identifier/frequency_domain/frf_structured.hpp"

#include <cmath>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_grey_box.hpp"

namespace ambid::ident {

StructuredFrfFit fit_structured_frf(const Experiment& header, const Frf& plant, const FrfStructure& s) {
  const Eigen::VectorXd start = s.start(header);
  if (start.size() != Eigen::Index(s.parameter_names.size()))
    throw Error("structured FRF fit: the start has " + std::to_string(start.size()) + " parameters, the structure " +
                std::to_string(s.parameter_names.size()));
  GreyBoxOptions options;
  options.sample_time = header.sample_time;
  const GreyBoxFit fit = fit_grey_box(plant, s.model, start, options);
  if (fit.covariance.size() == 0)
    throw InsufficientData("structured FRF fit: the lines do not determine the structure's parameters");
  StructuredFrfFit out;
  out.parameter_names = s.parameter_names;
  out.derived_names = s.derived_names;
  out.value = fit.parameters;
  out.sigma = fit.standard_deviation;
  out.covariance = fit.covariance;
  out.misfit = fit.misfit;
  out.converged = fit.converged;
  out.derived_value = s.derived(fit.parameters);
  // Jacobian of the derived quantities by central differences, then J P J'.
  const Eigen::Index n = fit.parameters.size();
  Eigen::MatrixXd J(out.derived_value.size(), n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const double h = 1e-6 * std::max(std::abs(fit.parameters(c)), 1e-12);
    Eigen::VectorXd up = fit.parameters, down = fit.parameters;
    up(c) += h;
    down(c) -= h;
    J.col(c) = (s.derived(up) - s.derived(down)) / (2 * h);
  }
  out.derived_sigma = (J * fit.covariance * J.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  return out;
}

}  // namespace ambid::ident
