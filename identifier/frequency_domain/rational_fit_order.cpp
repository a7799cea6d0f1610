#include "identifier/frequency_domain/rational_fit_order.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "identifier/frequency_domain/rational_fit_detail.hpp"

namespace ambid::ident {
namespace {

template <class V>
V every_other(const V& v, Eigen::Index first) {
  if (v.size() == 0) return v;
  V out((v.size() - first + 1) / 2);
  for (Eigen::Index i = 0; i < out.size(); ++i) out(i) = v(first + 2 * i);
  return out;
}

}  // namespace

OrderSelection select_rational_order(const Eigen::VectorXd& f, const Eigen::VectorXcd& G, const Eigen::VectorXd& var,
                                     const OrderSearchOptions& o) {
  if (o.min_denominator_degree < 1 || o.max_denominator_degree < o.min_denominator_degree)
    throw Error("rational order search: need 1 <= min <= max denominator degree, got " +
                std::to_string(o.min_denominator_degree) + ", " + std::to_string(o.max_denominator_degree));
  if (o.relative_degrees.empty()) throw Error("rational order search: no relative degree to try");
  for (int rd : o.relative_degrees)
    if (rd < 0) throw Error("rational order search: relative degree must be >= 0, got " + std::to_string(rd));
  if (!(o.parsimony >= 0.0) || !(o.negligible_misfit >= 0.0))
    throw Error("rational order search: parsimony and negligible_misfit must be >= 0");
  if (G.size() != f.size() || (var.size() != 0 && var.size() != f.size()))
    throw Error("rational order search: frequency, response and variance sizes differ");

  const Eigen::VectorXd f_est = every_other(f, 0), f_val = every_other(f, 1);
  const Eigen::VectorXcd G_est = every_other(G, 0), G_val = every_other(G, 1);
  const Eigen::VectorXd v_est = every_other(var, 0), v_val = every_other(var, 1);

  OrderSelection out;
  FitWeighting weighting = o.fit.weighting;
  if (weighting == FitWeighting::automatic) weighting = var.size() ? FitWeighting::noise : FitWeighting::relative;
  for (int n = o.min_denominator_degree; n <= o.max_denominator_degree; ++n) {
    for (int rd : o.relative_degrees) {
      const int m = n - rd;
      if (m < 0) continue;
      OrderCandidate c;
      c.numerator_degree = m;
      c.denominator_degree = n;
      c.parameters = m + 1 + n;
      RationalFitOptions fo = o.fit;
      fo.numerator_degree = m;
      fo.denominator_degree = n;
      fo.weighting = weighting;
      try {
        const RationalFit fit = fit_rational(f_est, G_est, v_est, fo);
        // Validation on the other lines, with the same compensation and weighting.
        const detail::FitData val = detail::prepare_fit_data(f_val, G_val, v_val, fo);
        // The model is evaluated at s = j w (its own scale is the estimation set's).
        double s = 0.0;
        for (Eigen::Index k = 0; k < val.x.size(); ++k) {
          const std::complex<double> s_k = val.x(k) * val.w0;
          s += std::norm(val.w(k) * (fit.model.evaluate(s_k) - val.g(k)));
        }
        c.validation_misfit = s / static_cast<double>(val.x.size());
        c.estimation_misfit = fit.misfit;
        const double K = static_cast<double>(fit.lines);
        c.aic = weighting == FitWeighting::noise
                    ? K * fit.misfit + 2.0 * c.parameters
                    : 2.0 * K * std::log(std::max(fit.misfit, 1e-300)) + 2.0 * c.parameters;
        c.ok = std::isfinite(c.validation_misfit);
        if (!c.ok) c.failure = "validation misfit is not finite";
      } catch (const Error& e) {
        c.ok = false;
        c.failure = e.what();
      }
      out.candidates.push_back(c);
    }
  }

  double best = std::numeric_limits<double>::infinity();
  for (const auto& c : out.candidates)
    if (c.ok) best = std::min(best, c.validation_misfit);
  if (!std::isfinite(best)) throw InsufficientData("rational order search: no candidate order could be fitted");
  const double floor = weighting == FitWeighting::noise ? o.parsimony : o.negligible_misfit;
  const double threshold = best * (1.0 + o.parsimony) + floor;
  bool found = false;
  for (std::size_t i = 0; i < out.candidates.size(); ++i) {
    const auto& c = out.candidates[i];
    if (!c.ok || c.validation_misfit > threshold) continue;
    if (!found) {
      out.chosen = i;
      found = true;
      continue;
    }
    const auto& b = out.candidates[out.chosen];
    if (c.parameters < b.parameters || (c.parameters == b.parameters && c.denominator_degree < b.denominator_degree))
      out.chosen = i;
  }
  RationalFitOptions fo = o.fit;
  fo.numerator_degree = out.candidates[out.chosen].numerator_degree;
  fo.denominator_degree = out.candidates[out.chosen].denominator_degree;
  fo.weighting = weighting;
  out.fit = fit_rational(f, G, var, fo);
  return out;
}

}  // namespace ambid::ident
