#include "identifier/frequency_domain/frf_grey_box.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/linalg.hpp"
#include "identifier/frequency_domain/freq_response.hpp"
#include "identifier/nonlinear_least_squares.hpp"

namespace ambid::ident {
namespace {

// Real residuals sqrt(2) w (G_model - G) (real and imaginary parts of every element and line)
// for scaled parameters x (theta = scale .* x); false when the model refuses the parameters.
struct Residuals {
  const Frf& frf;
  const std::function<ContinuousSystem(const Eigen::VectorXd&)>& model;
  Eigen::VectorXd scale;
  std::vector<Eigen::MatrixXd> weight;
  double sample_time;

  int count() const { return static_cast<int>(2 * frf.lines() * frf.rows() * frf.cols()); }

  bool operator()(const double* x, double* r) const {
    const Eigen::VectorXd theta = scale.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, scale.size()));
    try {
      const ContinuousSystem c = model(theta);
      if (c.outputs() != frf.rows() || c.inputs() != frf.cols())
        throw Error("grey-box fit: the model has " + std::to_string(c.outputs()) + " outputs and " +
                    std::to_string(c.inputs()) + " inputs, the FRF " + std::to_string(frf.rows()) + "x" +
                    std::to_string(frf.cols()));
      const DiscreteSystem d = sample_time > 0.0 ? c2d_zoh(c, sample_time) : DiscreteSystem{};
      Eigen::Index n = 0;
      for (Eigen::Index l = 0; l < frf.lines(); ++l) {
        const double w = 2.0 * std::numbers::pi * frf.frequency_hz(l);
        const Eigen::MatrixXcd G = sample_time > 0.0 ? freq_response(d, w) : freq_response(c, w);
        const auto li = static_cast<std::size_t>(l);
        for (Eigen::Index i = 0; i < G.rows(); ++i)
          for (Eigen::Index j = 0; j < G.cols(); ++j) {
            const std::complex<double> e = std::sqrt(2.0) * weight[li](i, j) * (G(i, j) - frf.value[li](i, j));
            r[n++] = e.real();
            r[n++] = e.imag();
          }
      }
    } catch (const InsufficientData&) {
      throw;
    } catch (const Error&) {
      return false;
    }
    return true;
  }
};

// The residuals and their central differences in the scaled parameters (all of order one).
class GreyBoxCost {
 public:
  explicit GreyBoxCost(const Residuals& r) : r_(r) {}
  bool operator()(const double* parameters, double* residuals, double* jacobian) const {
    if (!r_(parameters, residuals)) return false;
    if (jacobian == nullptr) return true;
    const int p = static_cast<int>(r_.scale.size()), m = r_.count();
    std::vector<double> x(parameters, parameters + p), rp(static_cast<std::size_t>(m)), rm(static_cast<std::size_t>(m));
    for (int k = 0; k < p; ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[static_cast<std::size_t>(k)]));
      const double x0 = x[static_cast<std::size_t>(k)];
      x[static_cast<std::size_t>(k)] = x0 + h;
      if (!r_(x.data(), rp.data())) return false;
      x[static_cast<std::size_t>(k)] = x0 - h;
      if (!r_(x.data(), rm.data())) return false;
      x[static_cast<std::size_t>(k)] = x0;
      for (int i = 0; i < m; ++i)
        jacobian[i * p + k] = (rp[static_cast<std::size_t>(i)] - rm[static_cast<std::size_t>(i)]) / (2.0 * h);
    }
    return true;
  }

 private:
  const Residuals& r_;
};

}  // namespace

GreyBoxFit fit_grey_box(const Frf& frf, const std::function<ContinuousSystem(const Eigen::VectorXd&)>& model,
                        const Eigen::VectorXd& initial, const GreyBoxOptions& o) {
  frf.validate();
  if (frf.lines() < 1) throw Error("grey-box fit: the FRF has no lines");
  if (initial.size() < 1) throw Error("grey-box fit: no parameters");
  if (!(o.sample_time >= 0.0)) throw Error("grey-box fit: sample_time must be >= 0");
  for (Eigen::Index k = 0; k < initial.size(); ++k)
    if (!(initial(k) != 0.0) || !std::isfinite(initial(k)))
      throw Error("grey-box fit: initial parameter " + std::to_string(k) + " must be finite and non-zero, got " +
                  std::to_string(initial(k)));
  if (o.sample_time > 0.0 && !(2.0 * frf.frequency_hz.maxCoeff() * o.sample_time < 1.0))
    throw Error("grey-box fit: lines above the Nyquist frequency of sample_time");

  const bool noise = o.use_variance && frf.has_variance();
  Residuals res{frf, model, initial.cwiseAbs(), {}, o.sample_time};
  Eigen::MatrixXd rms = Eigen::MatrixXd::Zero(frf.rows(), frf.cols());
  for (const auto& v : frf.value) rms += v.cwiseAbs2();
  rms = (rms / static_cast<double>(frf.lines())).cwiseSqrt();
  for (Eigen::Index l = 0; l < frf.lines(); ++l) {
    Eigen::MatrixXd w(frf.rows(), frf.cols());
    for (Eigen::Index i = 0; i < w.rows(); ++i)
      for (Eigen::Index j = 0; j < w.cols(); ++j) {
        const double s = noise ? std::sqrt(frf.variance[static_cast<std::size_t>(l)](i, j)) : rms(i, j);
        if (!(s > 0.0))
          throw InsufficientData("grey-box fit: element (" + std::to_string(i) + ", " + std::to_string(j) + ") has " +
                                 (noise ? "zero variance" : "no response") + " at " +
                                 std::to_string(frf.frequency_hz(l)) + " Hz");
        w(i, j) = 1.0 / s;
      }
    res.weight.push_back(w);
  }

  NonlinearLeastSquares problem;
  problem.residuals = GreyBoxCost(res);
  problem.residual_count = res.count();
  NonlinearLeastSquaresOptions so;
  so.max_iterations = o.max_iterations;
  so.function_tolerance = 1e-14;
  so.gradient_tolerance = 1e-14;
  so.parameter_tolerance = 1e-12;
  so.jacobian = true;  // for the covariance
  const NonlinearLeastSquaresSolution solution =
      solve_nonlinear_least_squares(problem, Eigen::VectorXd::Ones(initial.size()), so);

  GreyBoxFit out;
  out.converged = solution.termination == Termination::converged;
  out.iterations = solution.iterations;
  out.parameters = res.scale.cwiseProduct(solution.x);

  // Jacobian at the solution, covariance by QR.
  const int m = res.count(), p = static_cast<int>(initial.size());
  if (!solution.evaluated) throw Error("grey-box fit: the model refuses the fitted parameters");
  const Eigen::MatrixXd& J = solution.jacobian;
  const Eigen::VectorXd& r = solution.residuals;
  out.misfit = r.squaredNorm() / static_cast<double>(m);  // = mean |w e|^2 over elements and lines
  Eigen::MatrixXd cov = linalg::qr_inverse_gram(J);       // empty when J is rank deficient
  if (cov.size() != 0) {
    if (!noise) cov *= m > p ? r.squaredNorm() / static_cast<double>(m - p) : 0.0;
    out.covariance = res.scale.asDiagonal() * cov * res.scale.asDiagonal();
    out.standard_deviation = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  return out;
}

}  // namespace ambid::ident
