#include "identifier/frf_types.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace ambid::ident {

Eigen::VectorXcd Frf::element(Eigen::Index i, Eigen::Index j) const {
  if (i < 0 || i >= rows() || j < 0 || j >= cols())
    throw Error("frf: element (" + std::to_string(i) + ", " + std::to_string(j) + ") outside a " +
                std::to_string(rows()) + "x" + std::to_string(cols()) + " response");
  Eigen::VectorXcd out(static_cast<Eigen::Index>(value.size()));
  for (std::size_t k = 0; k < value.size(); ++k) out(static_cast<Eigen::Index>(k)) = value[k](i, j);
  return out;
}

Eigen::VectorXd Frf::element_variance(Eigen::Index i, Eigen::Index j) const {
  if (!has_variance()) throw Error("frf: this response has no variance");
  if (i < 0 || i >= rows() || j < 0 || j >= cols())
    throw Error("frf: element (" + std::to_string(i) + ", " + std::to_string(j) + ") outside a " +
                std::to_string(rows()) + "x" + std::to_string(cols()) + " response");
  Eigen::VectorXd out(static_cast<Eigen::Index>(variance.size()));
  for (std::size_t k = 0; k < variance.size(); ++k) out(static_cast<Eigen::Index>(k)) = variance[k](i, j);
  return out;
}

void Frf::validate() const {
  const auto n = static_cast<std::size_t>(frequency_hz.size());
  if (value.size() != n)
    throw Error("frf: " + std::to_string(value.size()) + " response matrices for " + std::to_string(n) +
                " frequencies");
  if (!variance.empty() && variance.size() != n)
    throw Error("frf: " + std::to_string(variance.size()) + " variance matrices for " + std::to_string(n) +
                " frequencies");
  if (!(variance_dof >= 0.0) || !std::isfinite(variance_dof))
    throw Error("frf: variance_dof must be >= 0, got " + std::to_string(variance_dof));
  for (std::size_t k = 0; k < n; ++k) {
    const double f = frequency_hz(static_cast<Eigen::Index>(k));
    if (!(f > 0.0) || !std::isfinite(f))
      throw Error("frf: frequency " + std::to_string(k) + " must be positive and finite, got " + std::to_string(f));
    if (k > 0 && !(f > frequency_hz(static_cast<Eigen::Index>(k) - 1)))
      throw Error("frf: frequencies must increase strictly, line " + std::to_string(k) + " has " + std::to_string(f) +
                  " Hz after " + std::to_string(frequency_hz(static_cast<Eigen::Index>(k) - 1)));
    if (value[k].rows() != rows() || value[k].cols() != cols())
      throw Error("frf: line " + std::to_string(k) + " is " + std::to_string(value[k].rows()) + "x" +
                  std::to_string(value[k].cols()) + ", the first line " + std::to_string(rows()) + "x" +
                  std::to_string(cols()));
    if (!value[k].allFinite())
      throw Error("frf: line " + std::to_string(k) + " (" + std::to_string(f) + " Hz) is not finite");
    if (!variance.empty()) {
      if (variance[k].rows() != rows() || variance[k].cols() != cols())
        throw Error("frf: variance of line " + std::to_string(k) + " has the wrong shape");
      if (!variance[k].allFinite() || (variance[k].array() < 0.0).any())
        throw Error("frf: variance of line " + std::to_string(k) + " (" + std::to_string(f) +
                    " Hz) is negative or not finite");
    }
  }
}

double confidence_radius_factor(double confidence, double dof) {
  if (!(confidence > 0.0 && confidence < 1.0))
    throw Error("confidence must be in (0, 1), got " + std::to_string(confidence));
  if (!(dof >= 0.0) || !std::isfinite(dof)) throw Error("degrees of freedom must be >= 0, got " + std::to_string(dof));
  const double alpha = 1.0 - confidence;
  if (dof == 0.0) return -std::log(alpha);
  // P(F(2, nu) > f) = (1 + 2 f / nu)^(-nu / 2).
  return 0.5 * dof * std::expm1(-2.0 / dof * std::log(alpha));
}

}  // namespace ambid::ident
