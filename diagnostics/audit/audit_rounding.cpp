#include "diagnostics/audit/audit_rounding.hpp"

#include <cmath>

namespace ambid::diag {
namespace {

bool multiples_of(const Eigen::VectorXd& v, double q) {
  for (const double value : v)
    if (std::abs(value / q - std::nearbyint(value / q)) > 1e-6) return false;
  return true;
}

double column_resolution(const Eigen::VectorXd& v) {
  if (v.size() < 2 || !v.allFinite() || v.maxCoeff() == v.minCoeff()) return 0.0;
  for (int power = 3; power >= -12; --power)
    for (const double mantissa : {5.0, 2.0, 1.0}) {
      const double q = mantissa * std::pow(10.0, power);
      if (multiples_of(v, q)) return q;
    }
  return 0.0;
}

}  // namespace

Eigen::VectorXd logging_resolution(const Eigen::MatrixXd& logged) {
  Eigen::VectorXd out(logged.cols());
  for (Eigen::Index j = 0; j < logged.cols(); ++j) out(j) = column_resolution(logged.col(j));
  return out;
}

}  // namespace ambid::diag
