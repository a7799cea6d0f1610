#include "identifier/time_domain/residual_independence.hpp"

#include <cmath>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;
const std::string kWho = "residual independence";

// Columns of `x` without their means.
Eigen::MatrixXd centred(const Eigen::MatrixXd& x) { return x.rowwise() - x.colwise().mean(); }

}  // namespace

ResidualIndependence residual_independence(const Eigen::MatrixXd& e, const std::vector<std::string>& e_names,
                                           const Eigen::MatrixXd& r, const std::vector<std::string>& r_names,
                                           Index lags) {
  const Index N = e.rows();
  if (r.rows() != N || Index(e_names.size()) != e.cols() || Index(r_names.size()) != r.cols())
    throw Error(kWho + ": needs as many samples of e (" + std::to_string(N) + ") as of r (" + std::to_string(r.rows()) +
                ") and a name for every column");
  if (lags < 1) throw Error(kWho + ": lags must be >= 1, got " + std::to_string(lags));
  if (N <= 2 * lags)
    throw Error(kWho + ": " + std::to_string(N) + " samples are too few for " + std::to_string(lags) + " lags");
  if (!e.allFinite() || !r.allFinite()) throw Error(kWho + ": e and r must be finite");
  const Eigen::MatrixXd ec = centred(e), rc = centred(r);
  ResidualIndependence out;
  out.lags = lags;
  auto test = [&](Index j, const Eigen::MatrixXd& partners, Index i, const std::string& partner, double& largest,
                  std::string& where, double* correlation) {
    for (Index k = 1; k <= lags; ++k) {
      const auto now = ec.col(j).tail(N - k);
      const auto past = partners.col(i).head(N - k);
      const double norms = now.norm() * past.norm();
      if (!(norms > 0.0)) continue;
      const double z = std::sqrt(double(N - k)) * now.dot(past) / norms;
      ++out.correlations;
      if (std::abs(z) <= largest) continue;
      largest = std::abs(z);
      if (correlation) *correlation = now.dot(past) / norms;
      where = "e_" + e_names[std::size_t(j)] + " with " + partner + " at lag " + std::to_string(k);
    }
  };
  for (Index j = 0; j < e.cols(); ++j) {
    test(j, ec, j, "itself", out.whiteness_z, out.whiteness_worst, nullptr);
    for (Index i = 0; i < r.cols(); ++i) test(j, rc, i, r_names[std::size_t(i)], out.z, out.worst, &out.correlation);
  }
  return out;
}

}  // namespace ambid::ident
