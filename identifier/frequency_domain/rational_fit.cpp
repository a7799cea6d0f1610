#include "identifier/frequency_domain/rational_fit.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/frequency_domain/rational_fit_detail.hpp"

namespace ambid::ident {
namespace {

// First-order standard deviation sqrt(E|dp|^2) of every root p of the monic denominator
// from the covariance of its low coefficients: dp = -sum_i p^i da_i / D'(p) (scaled p).
Eigen::VectorXd pole_std(const RationalModel& model, const Eigen::MatrixXd& cov_a) {
  const Eigen::VectorXcd poles = model.poles();
  const Eigen::Index n = model.denominator_degree();
  Eigen::VectorXd out(poles.size());
  for (Eigen::Index r = 0; r < poles.size(); ++r) {
    if (cov_a.size() == 0) {
      out(r) = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const std::complex<double> p = poles(r) / model.frequency_scale;
    std::complex<double> dD = 0.0, pi = 1.0;
    for (Eigen::Index i = 1; i <= n; ++i) {
      dD += static_cast<double>(i) * model.denominator(i) * pi;
      pi *= p;
    }
    Eigen::VectorXcd g(n);
    pi = 1.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      g(i) = -pi / dD;
      pi *= p;
    }
    const double var = (g.transpose() * cov_a.cast<std::complex<double>>() * g.conjugate())(0, 0).real();
    out(r) = model.frequency_scale * std::sqrt(std::max(0.0, var));
  }
  return out;
}

}  // namespace

RationalFit fit_rational(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& response,
                         const Eigen::VectorXd& variance, const RationalFitOptions& options) {
  const detail::FitData data = detail::prepare_fit_data(frequency_hz, response, variance, options);
  const int m = options.numerator_degree, n = options.denominator_degree;
  RationalFit out;
  out.weighting = data.weighting;
  out.lines = data.x.size();
  out.parameters = m + 1 + n;
  detail::Coefficients c =
      detail::sanathanan_koerner(data, m, n, options.sk_iterations, options.sk_tolerance, &out.sk_iterations);
  if (options.refine) out.refined = detail::refine_output_error(data, c, options.refine_iterations);

  out.model.numerator = c.b;
  out.model.denominator.resize(n + 1);
  out.model.denominator << c.a_low, 1.0;
  out.model.frequency_scale = data.w0;
  out.misfit = detail::weighted_misfit(data, c.b, c.a_low);

  const Eigen::MatrixXd J = detail::output_error_jacobian(data, c);
  Eigen::MatrixXd cov = linalg::qr_inverse_gram(J, 1e-14);  // empty when J is rank deficient
  if (cov.size() != 0 && data.weighting != FitWeighting::noise) {
    const double dof = static_cast<double>(2 * out.lines - out.parameters);
    const double s2 =
        dof > 0.0 ? 2.0 * out.misfit * static_cast<double>(out.lines) / dof : std::numeric_limits<double>::quiet_NaN();
    cov *= s2;
  }
  out.parameter_covariance = cov;
  out.pole_std = pole_std(out.model, cov.size() ? Eigen::MatrixXd(cov.bottomRightCorner(n, n)) : Eigen::MatrixXd());
  return out;
}

}  // namespace ambid::ident
