#include "identifier/frequency_domain/frf_uncertainty.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "identifier/frequency_domain/frf_linalg.hpp"

namespace ambid::ident {

UncertaintyEnvelope uncertainty_envelope(const std::vector<Frf>& cases, const Frf& nominal) {
  nominal.validate();
  if (cases.empty()) throw Error("uncertainty envelope: no cases");
  const Eigen::Index nl = nominal.lines();
  const auto nc = static_cast<Eigen::Index>(cases.size());
  const double tol = 1e-9 * std::max(1.0, nominal.frequency_hz.cwiseAbs().maxCoeff());
  for (std::size_t c = 0; c < cases.size(); ++c) {
    cases[c].validate();
    if (cases[c].lines() != nl || (cases[c].frequency_hz - nominal.frequency_hz).cwiseAbs().maxCoeff() > tol)
      throw Error("uncertainty envelope: case " + std::to_string(c) + " is not on the nominal's frequency lines");
    if (cases[c].rows() != nominal.rows() || cases[c].cols() != nominal.cols())
      throw Error("uncertainty envelope: case " + std::to_string(c) + " is " + std::to_string(cases[c].rows()) + "x" +
                  std::to_string(cases[c].cols()) + ", the nominal " + std::to_string(nominal.rows()) + "x" +
                  std::to_string(nominal.cols()));
  }
  UncertaintyEnvelope out;
  out.frequency_hz = nominal.frequency_hz;
  out.additive.resize(nl, nc);
  out.multiplicative.resize(nl, nc);
  for (Eigen::Index l = 0; l < nl; ++l) {
    const Eigen::MatrixXcd& GN = nominal.value[static_cast<std::size_t>(l)];
    if (!(max_singular_value(GN) > 0.0))
      throw InsufficientData("uncertainty envelope: the nominal is zero at " + std::to_string(nominal.frequency_hz(l)) +
                             " Hz");
    for (Eigen::Index c = 0; c < nc; ++c) {
      const Eigen::MatrixXcd D = cases[static_cast<std::size_t>(c)].value[static_cast<std::size_t>(l)] - GN;
      out.additive(l, c) = max_singular_value(D);
      out.multiplicative(l, c) = max_singular_value(right_solve(D, GN));
    }
  }
  out.additive_envelope = out.additive.rowwise().maxCoeff();
  out.multiplicative_envelope = out.multiplicative.rowwise().maxCoeff();
  return out;
}

}  // namespace ambid::ident
